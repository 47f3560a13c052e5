// The mechanical model as the solver sees it, built once (on rank 0) from the mesh and the case
// file: the tetrahedra with their materials, the constitutive laws, the boundary conditions and
// the geostatic initial state. Every check of the input happens here and throws ugs::InputError
// naming the case file line or the mesh group at fault.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "ugs/fem/material_point.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/mesh.hpp"
#include "ugs/solver/initial_state.hpp"

namespace ugs::mech {

// The geostatic initial state (ugs/solver/initial_state.hpp): the case's mechanical earth model.
using ugs::InitialState;

struct Model {
  std::vector<Point3> x;                           // node coordinates, mesh order
  std::vector<fem::Material> materials;
  // Tetrahedra in output order (formats/field.hpp: blocks of tetrahedra in mesh order).
  std::vector<std::array<std::uint32_t, 4>> tets;  // mesh node indices
  std::vector<std::int32_t> tet_material;          // index into materials
  std::vector<std::uint64_t> tet_tags;             // element tags (stable through the pipeline)
  // Per mesh node: bit c set = displacement component c prescribed; its value in `prescribed`
  // (zero unless a test sets it: fixed boundaries and rollers prescribe zero).
  std::vector<std::uint8_t> fixed;
  std::vector<std::array<double, 3>> prescribed;
  InitialState initial;
  // Per material: {k_Hmax, k_hmin} of its elements' initial stress ([[material]] k0 / k_Hmax / k_hmin,
  // else the [initial_stress] ones).
  std::vector<std::array<double, 2>> material_k;
  // Per material: the gas column of the pool holding it (GasColumn{}: water), for the initial pore
  // pressure of its elements.
  std::vector<GasColumn> material_gas;
  // Per mesh node: the consistent nodal force [N] of the [[boundary_traction]] entries, the change of
  // the boundary traction from the initial state's sigma_0 n (boundary_traction.cpp); a constant load.
  std::vector<std::array<double, 3>> traction_force;
  std::vector<std::uint32_t> top_nodes;            // nodes of bnd:top (sorted), for the surface table
  std::vector<std::array<std::uint32_t, 3>> top_triangles;

  std::size_t num_nodes() const { return fixed.size(); }
  bool has_hypoplastic() const;
};

// Builds the model. Checks: a [[material]] for every mat:<name> group that has tetrahedra, valid
// (positive definite) elastic parameters, the boundary groups named by the case exist, rollers sit on
// planes normal to x, y or z, no interface elements (faults need the faulted solver).
Model build_model(const Mesh& mesh, const CaseFile& cs);
// The same, keeping a faulted mesh's interface elements out of the model (the fault contact,
// ugs_contact, takes them) when `allow_interface_elements` is set.
Model build_model(const Mesh& mesh, const CaseFile& cs, bool allow_interface_elements);

// The nodal forces of the case's [[boundary_traction]] entries on `model` (its tets, materials,
// material_k and initial state set): for each triangle of bnd:<group>, outward normal n (away from
// the tetrahedron it bounds), the traction change dt(x) = t - sigma_0(x) n with sigma_0 the initial
// total stress of that tetrahedron's material (sigma'_0 - alpha p0 I), integrated exactly for
// dt linear over the triangle: f_i = A/12 (2 dt_i + dt_j + dt_k). `in_situ` entries add nothing.
// InputError: a group the mesh lacks (naming the bnd: groups it has), a triangle that bounds no
// tetrahedron.
std::vector<std::array<double, 3>> boundary_traction_forces(const Mesh& mesh, const CaseFile& cs, const Model& model);

// fem::Material from a case [[material]] (InputError at its line when invalid).
fem::Material material_from_spec(const MaterialSpec& spec, const CaseFile& cs);

}  // namespace ugs::mech
