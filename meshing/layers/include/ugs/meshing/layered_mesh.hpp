// Layered tetrahedral mesh from a plan and a stack of surfaces (what ugs-meshgen builds).
//
// Node columns: above each plan node, one node per level (the surfaces and the sub-layer
// boundaries between them, top to bottom). Where a unit has zero thickness at a column (a
// pinch-out) the levels inside it coincide and are one node.
//
// Prism split: the prism of plan triangle (a, b, c) in one sub-layer is cut into three tetrahedra so
// that on the side face between columns i and j the diagonal joins the bottom node of min(i, j) to
// the top node of max(i, j) (columns numbered in plan node tag order). Two prisms sharing a side
// face therefore cut it the same way, and the three diagonals of one prism never form a cycle.
// With columns sorted v0 < v1 < v2 the tetrahedra are
//   (B0, B1, B2, T2), (B0, B1, T1, T2), (B0, T0, T1, T2),
// each of volume area * h_i / 3 with h_i the height of the prism's edge at v2, v1, v0: a tetrahedron
// whose edge has collapsed (h_i = 0) has repeated nodes and is dropped; the others are positive,
// and the prism's volume is exactly area * (h0 + h1 + h2) / 3.
//
// Boundary triangles (outward normals): bnd:top, bnd:bottom, and on the outer vertical faces
// bnd:east|west|north|south by the direction of the face's outward horizontal normal n: east/west
// where |n_x| > |n_y|, north/south otherwise (a 45-degree face goes north or south).
// Fault triangles: vertical faces above the plan edges of each fault whose mid-depth lies within
// the fault's depth range, normal to the right of the trace's direction.
#pragma once
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "ugs/formats/mesh.hpp"
#include "ugs/meshing/plan.hpp"

namespace ugs {

struct UnitLayers {
  std::string name;
  int layers = 1;      // sub-layers, >= 1
  double bias = 1.0;   // thickness ratio of successive sub-layers, top to bottom, > 0
};

// Elevations of the sub-layer boundaries of one unit as fractions of its thickness from its top:
// 0 = f_0 < f_1 < ... < f_n = 1 with f_{k+1} - f_k = bias * (f_k - f_{k-1}).
std::vector<double> sublayer_fractions(int layers, double bias);

struct VerticalFault {
  std::string name;                                  // group fault:<name>
  double top = std::numeric_limits<double>::infinity();
  double bottom = -std::numeric_limits<double>::infinity();
  std::vector<std::array<std::uint32_t, 2>> edges;   // plan columns, oriented along the trace
};

struct LayeredMeshInput {
  const Plan* plan = nullptr;
  // Elevations, [surface][column], top to bottom; already ordered (z[i+1] <= z[i]) and with
  // pinched-out units collapsed to exactly zero thickness (see surface_stack.hpp).
  std::vector<std::vector<double>> surfaces;
  std::vector<UnitLayers> units;                     // surfaces.size() - 1
  std::vector<std::string> materials;                // names, without the "mat:" prefix
  std::vector<std::vector<std::uint32_t>> material_of;  // [unit][triangle] -> index into materials
  std::vector<VerticalFault> faults;
};

struct LayeredMeshStats {
  std::size_t columns = 0, levels = 0;               // levels per column (surfaces and sub-layer boundaries)
  std::size_t nodes = 0, merged_nodes = 0;           // merged = columns * levels - nodes
  std::size_t tetrahedra = 0, dropped_tetrahedra = 0;  // dropped: repeated nodes at pinch-outs
  std::vector<std::size_t> pinched_columns;          // per unit: columns where it has zero thickness
};

// Builds the mesh: nodes tagged 1..N column by column (plan tag order, top to bottom), tetrahedra
// first then boundary and fault triangles. Throws InputError when a fault edge is not an edge of
// the plan triangles, std::invalid_argument for inconsistent input.
Mesh build_layered_mesh(const LayeredMeshInput& in, LayeredMeshStats* stats = nullptr);

}  // namespace ugs
