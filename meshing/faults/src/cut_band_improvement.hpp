// Quality of the tetrahedra a fault cut made (docs/dipping-faults.md, steps 5 and 6). Internal to
// ugs_meshing: fault_cut.cpp calls it on its element arrays before writing the mesh back.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <vector>

#include "ugs/formats/mesh.hpp"

namespace ugs {

// Smallest dihedral angle and shortest edge of each input tetrahedron (on its input nodes),
// computed the first time they are asked for: the cut and its band ask for a few thousand of the
// millions (computing them all cost about a second at the thesis scale). The tetrahedra are read
// from the input's element arrays (4 node indices each, numbered across the arrays in order), which
// must stay unchanged while this is used: a copy of the 3.1 million was 50 MB to allocate and fill.
class InputTetShape {
public:
  InputTetShape(std::vector<Point3> nodes, std::vector<std::span<const std::uint32_t>> tet_arrays);
  double quality(std::uint32_t p) const;
  double min_edge(std::uint32_t p) const;

private:
  std::array<std::uint32_t, 4> tet(std::uint32_t p) const;
  static constexpr double kUnknown = -std::numeric_limits<double>::infinity();
  std::vector<Point3> nodes_;
  std::vector<std::span<const std::uint32_t>> arrays_;
  std::vector<std::uint32_t> first_;  // per array: the number of its first tetrahedron
  mutable std::vector<double> quality_, min_edge_;
};

// A tetrahedral mesh as flat arrays: nodes, tetrahedra (positive volume) with their block,
// triangles (boundary and other groups) with their group; groups from `first_fault_group` on are
// faults (no tetrahedron may have its four nodes on one of them: ugs-faultinsert would tear it).
struct ElementSoup {
  std::vector<Point3>& nodes;
  std::vector<std::array<std::uint32_t, 4>>& tets;
  std::vector<std::uint32_t>& tet_block;
  std::vector<std::uint32_t>& tet_parent;  // the input tetrahedron each one comes from
  std::vector<std::array<std::uint32_t, 3>>& tris;
  std::vector<std::uint32_t>& tri_group;
  std::uint32_t first_fault_group;
  const InputTetShape& parent;                // the input tetrahedra (by tet_parent)
  double bound_deg;                           // see score() in the .cpp and FaultCutOptions::bound_deg
  // Appends the tetrahedra holding a node to `out` (any order): the caller's incidences, so that
  // finding the band needs no scan of the millions of tetrahedra.
  std::function<void(std::uint32_t node, std::vector<std::uint32_t>& out)> tets_at;
};

// A tetrahedron a change of the cut may make or leave: positive volume and a volume ratio
// (tet_volume_ratio, ugs-solve's test) above kKeptRatio, a hundred times the solver's limit, so
// that no change of the cut leaves a tetrahedron ugs-solve refuses, or one near it. The input's
// thinnest tetrahedra (a 0.5 m pinch-out layer under a 2 km plan triangle) have ratios of 1e-6 and more.
inline constexpr double kKeptRatio = 100 * kDegenerateTetRatio;
inline bool kept_volume(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return tet_signed_volume(a, b, c, d) > 0 && tet_volume_ratio(a, b, c, d) > kKeptRatio;
}

struct BandImprovement {
  std::size_t collapsed = 0;  // nodes merged into a neighbour across a short edge
  std::size_t moved = 0;      // node moves by smoothing
};

// Improves the band of tetrahedra holding a node numbered `first_new` or above (the cut's nodes).
// Every change keeps each node on all its surfaces (the planes of its triangles and of the faces
// between materials, within `tol`) and feature lines (a group's boundary or crease), so the
// model, its groups, the material volumes and the faults keep their shape exactly; and every
// change raises the worst quality among the tetrahedra it touches, with positive volumes (quality:
// smallest dihedral angle over min(bound_deg, that of the input tetrahedron)).
//  1. Collapse: a cut node is merged into a neighbour across an edge shorter than `ratio` times
//     the longest edge of the tetrahedron (the shortest edge of its input tetrahedron when both
//     nodes are on a fault, so that the fault keeps the layering's resolution), when the neighbour lies on all the node's
//     surfaces and lines and the result stays conforming (no face of three tetrahedra, no element
//     twice, no tetrahedron with its four nodes on one fault). Merged nodes are deleted (the nodes
//     from `first_new` on are renumbered).
//  2. Smoothing: a node of a band tetrahedron below that bound, or with a dihedral angle below
//     `smooth_below_deg`, moves toward the mean of its neighbours, within its surfaces, by the largest of 1, 1/2, 1/4,
//     1/8 of the way that raises the smallest dihedral angle of its tetrahedra.
BandImprovement improve_cut_band(ElementSoup soup, std::size_t first_new, double ratio, double smooth_below_deg, double tol);

}  // namespace ugs
