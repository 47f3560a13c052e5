// Structured tetrahedral meshes of a box: the test bed of the verification cases (oedometer,
// Geertsma, aquifers, patch tests). Each hexahedral cell is split into six tetrahedra along its
// main diagonal (Kuhn split), which is conforming between neighbours; boundary faces are tagged
// bnd:west|east|south|north|bottom|top.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "ugs/formats/mesh.hpp"

namespace ugs {

struct BoxMeshSpec {
  // Node coordinates along each axis, strictly increasing (graded spacing allowed).
  std::vector<double> x, y, z;
  // Material name of a cell from its centroid; default: every cell is "rock".
  std::function<std::string(const Point3& centroid)> material;
};

// Evenly spaced coordinates lo, ..., hi in n intervals.
std::vector<double> linspace(double lo, double hi, int n);
// Coordinates from lo to hi whose spacing grows geometrically by `ratio` from `first` at lo.
std::vector<double> graded(double lo, double hi, double first, double ratio);

// Builds the mesh; materials become mat:<name> groups in first-seen order.
Mesh make_box_mesh(const BoxMeshSpec& spec);

}  // namespace ugs
