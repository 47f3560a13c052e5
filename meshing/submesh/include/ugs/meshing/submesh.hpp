// Sub-meshes for flow (thesis 4.2.1, Fig. 4.5): the tetrahedra of some materials, optionally only
// those whose centroid lies inside a plan polygon, cut along faults named as flow barriers.
//
// What the sub-mesh keeps and adds (docs/flow.md):
// - node and element tags of the parent, so results map back by tag; volume entities and physical
//   groups keep their parent tags (material ids stay valid);
// - parent triangles (boundary and fault groups) that are faces of kept tetrahedra;
// - no interface elements (6-node prisms) and no points or lines of the parent.
// Barriers (`fault:<name>` groups):
// - as triangles of an unfaulted mesh: the nodes on them are duplicated for every extra group of
//   tetrahedra around the node that the barrier separates (connected components of the tetrahedra
//   around the node, joined across faces that are not barrier faces; the group with the lowest element
//   tag keeps the node, as in ugs-faultinsert), so nothing flows across while flow still goes around
//   a fault's edge. Duplicates get tags above the parent's largest node tag
//   and one `twin:<fault>` line element each: node 1 the parent node, node 2 its duplicate.
// - as interface prisms of a faulted mesh: the two sides already have their own nodes; the prisms
//   are dropped and nothing joins the sides.
// Interface prisms of faults that are NOT barriers are replaced by `tie:<fault>` line elements
// joining each node to its twin across the fault: ugs-flow gives tied nodes one unknown, so water
// crosses those faults as in the continuous mesh (thesis: the flow meshes have no interface elements).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "ugs/formats/mesh.hpp"

namespace ugs {

struct SubmeshSpec {
  // Materials by name ("aquifer_pool_c" or "mat:aquifer_pool_c") or physical tag ("4"); empty: all.
  std::vector<std::string> materials;
  // Plan polygon(s) as closed rings of (x, y); a tetrahedron is kept when its centroid is inside by
  // the even-odd rule over all rings (holes and several parts work). Empty: no clipping.
  std::vector<std::vector<std::array<double, 2>>> rings;
  // Fault names ("F1" or "fault:F1") that flow must not cross.
  std::vector<std::string> barriers;
};

struct SubmeshReport {
  std::vector<std::string> materials;         // names kept, in parent order
  std::size_t tetrahedra = 0, nodes = 0, triangles = 0;
  std::size_t duplicated_nodes = 0;           // new nodes behind barriers given as triangles
  std::size_t tied_pairs = 0;                 // tie:<fault> lines across non-barrier interface prisms
  std::size_t dropped_interface_elements = 0;
  std::size_t clipped_tetrahedra = 0;         // of the chosen materials, outside the polygon
};

// InputError for unknown materials or barriers, and when nothing is left to keep.
Mesh extract_submesh(const Mesh& parent, const SubmeshSpec& spec, SubmeshReport* report = nullptr);

// Even-odd point-in-polygon test over all rings.
bool inside_rings(const std::vector<std::vector<std::array<double, 2>>>& rings, double x, double y);

}  // namespace ugs
