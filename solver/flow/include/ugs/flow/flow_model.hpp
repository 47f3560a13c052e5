// The discrete flow model of thesis eq. 3.35 on a flow sub-mesh: pressure form
//   div(K grad p) = S_s dp/dt,   S_s = gamma_w (n beta + c_M)
// on linear tetrahedra, with K diagonal per material (Kx, Ky, Kz, Table 4.2) and c_M from the
// compressibility law at the initial effective vertical stress of each element (eq. 4.1).
//
// What is assembled, in volumes of water (m3) and pressures (Pa):
//   conductance matrix  A_ij = sum_e V_e grad N_i . (K_e / gamma_w) grad N_j     [m3 / (s Pa)]
//   lumped storage      m_i  = sum_e V_e (n_e beta + c_M,e) / 4                   [m3 / Pa]
// over the aquifer tetrahedra only (materials of no pool). Pool tetrahedra have every node on the
// pool's pressure schedule, so they never enter an equation; they only decide which nodes are
// Dirichlet nodes. The reaction at those nodes is then the water leaving the aquifer into the
// pool, and the change of stored water (sum m_i dp_i) balances it exactly.
//
// Nodes joined by `tie:<fault>` line elements (ugs-submesh, across non-barrier interface
// elements of a faulted parent mesh) share one unknown.
#pragma once
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "ugs/formats/case_file.hpp"
#include "ugs/formats/mesh.hpp"
#include "ugs/solver/initial_state.hpp"

namespace ugs::flow {

inline constexpr std::uint32_t kNoDof = std::numeric_limits<std::uint32_t>::max();

// Flow properties of one mesh material.
struct FlowMaterial {
  std::string name;                  // without "mat:"
  int pool = -1;                     // index of the pool it belongs to, -1 for an aquifer material
  std::array<double, 3> K{};         // hydraulic conductivity [m/s] along x, y, z (aquifers); for
  double porosity = 0;               // a material with fields: their volume-weighted means
  std::size_t tets = 0;              // tetrahedra in the mesh
  double cm_min = 0, cm_max = 0;     // range of c_M over its tetrahedra [1/Pa] (for reports)
};

struct FlowPool {
  std::string name;
  std::string where;                 // file:line of its [[pool]] table
  std::vector<std::uint32_t> dofs;   // sorted unknowns on its schedule
};

// Compressed sparse rows, symmetric, both triangles stored, columns sorted per row.
struct CsrMatrix {
  std::size_t n = 0;
  std::vector<std::size_t> row_start;  // n + 1
  std::vector<std::uint32_t> col;
  std::vector<double> val;
};

struct FlowModel {
  std::size_t num_nodes = 0;                    // mesh nodes
  std::vector<std::uint32_t> dof_of_node;       // kNoDof for nodes in no tetrahedron
  std::size_t num_dofs = 0;
  std::vector<FlowMaterial> materials;
  std::vector<FlowPool> pools;
  std::vector<int> pool_of_dof;                 // -1 for free unknowns
  std::vector<double> storage;                  // m_i [m3/Pa], aquifer tetrahedra only
  // A = sum over materials of A_m, all on one pattern: conductance_by_material[m] holds the
  // values of material m (empty for pool materials), so a calibration rescales a material
  // without reassembling.
  CsrMatrix pattern;                            // val unused
  std::vector<std::vector<double>> conductance_by_material;
  std::vector<double> k_multiplier;             // per material, 1 unless calibrating

  // A with the current multipliers.
  std::vector<double> conductance_values() const;
  // Water stored in excess of the initial state for a pressure change dp per unknown [m3].
  double stored_water(const std::vector<double>& dp) const;
};

struct FlowModelOptions {
  // Pools to simulate, by name; empty: every pool of the case with a material in the mesh.
  std::vector<std::string> pools;
  std::string mesh_name = "mesh";  // for error messages
};

// Specific storage divided by gamma_w, s = n beta + c_M [1/Pa], of a material at the elevation z
// (c_M from the material's law at the initial effective vertical stress there, floored at
// sigma_z_min_MPa; eq. 3.23 for law = "linear"; docs/flow.md).
// `init` is the case's initial state (initial_state_of), as ugs-solve's.
double storage_coefficient(const CaseFile& c, const InitialState& init, const MaterialSpec& m, double z);
// Initial effective vertical stress magnitude [Pa] at elevation z (compression positive) in the
// material m: S_v - biot p0 with the material's Biot coefficient and gas column, as the mechanics'.
double initial_effective_vertical_stress(const CaseFile& c, const InitialState& init, const MaterialSpec& m, double z);

// Builds the model; InputError for materials without conductivity or porosity, pool materials
// missing from the mesh, nodes claimed by two pools, or interface elements in the mesh.
FlowModel build_flow_model(const Mesh& mesh, const CaseFile& c, const FlowModelOptions& options = {});

}  // namespace ugs::flow
