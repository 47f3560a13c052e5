// Fault faces from traces: the faces of the tetrahedra lying on each trace's surface
// (fault_traces.hpp) become a `fault:<name>` triangle group, ready for insert_faults().
//
// A face lies on the surface when its three nodes and its centroid are within the tolerance of one
// panel's plane, inside the panel along the trace. It is selected when its centroid lies between
// top and bottom and between the trace's ends (the mid-depth rule of ugs-meshgen): faces straddling
// a limit go to the side holding most of them. Coverage = area of the surface inside the model that
// the faces on it cover (straddling faces count for their part inside the limits) / area of the
// surface inside the model (the exact section of the tetrahedra by the panels).
#pragma once
#include <string>
#include <vector>

#include "ugs/formats/mesh.hpp"
#include "ugs/meshing/fault_traces.hpp"

namespace ugs {

struct FaultSelectOptions {
  std::string source;          // the mesh's name, for messages
  double tolerance = 0;        // m; 0: 1 % of the shortest tetrahedron edge at each node
  double min_coverage = 0.99;  // below it: InputError
};

struct FaultSelection {
  std::string name;
  bool from_mesh = false;      // the mesh already has fault:<name> triangles: they are used as they are
  std::size_t triangles = 0;   // selected (or found in the mesh)
  double area_inside = 0;      // m2 of the trace surface inside the model
  double covered = 0;          // m2 of it on mesh faces
  double coverage = 0;         // covered / area_inside, at most 1
  double max_deviation = 0;    // from_mesh: largest distance of the group's nodes from the trace surface
                               // extended up and down (depth limits are resolved by the mesh), m
  double zmin = 0, zmax = 0;   // from_mesh: the group's extent in z
  std::size_t beyond_depth = 0;  // from_mesh: its triangles lying wholly above top or below bottom
};

// Adds a fault:<name> triangle group for each trace without one in the mesh (oriented along the
// trace's reference normal, new element tags above the largest). InputError (naming the fault) when
// a fault already has interface elements, its depth range lies outside the mesh, its surface does
// not cross the mesh, or mesh faces cover less than min_coverage of it. The mesh is changed only
// when every trace succeeded.
std::vector<FaultSelection> select_fault_faces(Mesh& mesh, const std::vector<FaultTrace>& traces,
                                               const FaultSelectOptions& options = {});

}  // namespace ugs
