// The 2D plan a layered mesh is extruded from: the triangles of a Gmsh 2D mesh (from ugs-mesh2d or
// any other mesher) as columns (plan nodes) and counter-clockwise triangles, with its named line
// groups (fault:<name>, section:<name>, trace:<name>) and triangle groups (region:<name>).
//
// Columns are numbered in increasing order of the plan's node tags, so "global plan node numbers"
// and column indices order the same way (the prism split rule relies on that order).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "ugs/formats/mesh.hpp"
#include "ugs/meshing/xy.hpp"

namespace ugs {

struct PlanLineGroup {
  std::string name;                                  // physical name, e.g. "fault:overthrust_north"
  std::vector<std::array<std::uint32_t, 2>> edges;   // column pairs, in the line elements' order
};

struct Plan {
  std::string source;                                // file name, for messages
  std::vector<std::uint64_t> node_tags;              // per column, strictly increasing
  std::vector<XY> xy;                                // per column
  std::vector<std::array<std::uint32_t, 3>> triangles;  // column indices, counter-clockwise
  std::vector<std::uint64_t> triangle_tags;          // the plan's element tags
  std::vector<PlanLineGroup> lines;                  // named line groups, in the plan's order
  std::vector<std::string> provenance;               // the plan's $UgsProvenance lines

  std::size_t num_columns() const { return xy.size(); }
  double area(std::size_t t) const;                  // > 0
  XY centroid(std::size_t t) const;
  const PlanLineGroup* find_line_group(const std::string& name) const;
};

// Extracts the plan from a 2D mesh and checks it: at least one triangle; no tetrahedra; no
// degenerate, duplicate or inverted triangles (orientation opposite to the others); every edge
// used by at most two triangles, in opposite directions; no two columns at the same x, y.
// z of the plan nodes is ignored. Throws InputError naming `source`, the element and x, y.
Plan plan_from_mesh(const Mesh& mesh, const std::string& source);

}  // namespace ugs
