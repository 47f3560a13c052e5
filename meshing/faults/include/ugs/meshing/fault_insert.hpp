// Fault insertion (thesis 3.5.2, Fig. 3.3): the `fault:<name>` triangle groups of a tetrahedral
// mesh become zero-thickness interface elements on duplicated nodes, so the two sides of a fault
// can slide or open. A mesh transformation kept apart from the physics (PyLith's cohesive cells,
// GEOS's fracture generation); docs/faults.md is the user-facing description.
//
// Splitting rule: for each node of an inserted fault, the tetrahedra around it are grouped into
// sets connected through faces that are not faces of an inserted fault; each set gets its own copy
// of the node. The set holding the tetrahedron with the lowest element tag keeps the original node;
// the others get new tags above the mesh's largest, in increasing order of (original tag, set). One
// set means a tip node (buried fault edge): it is not split and appears on both sides with the same
// id. Faults reaching the model boundary split through; T- and X-junctions get one copy per sector.
//
// Interface elements: one 6-node prism (Gmsh type 6) per fault triangle, with the triangle's
// element tag, in the dim-3 physical group `fault:<name>` (the dim-2 triangle group is removed).
// Nodes 1-3 lie on side 1, nodes 4-6 are their twins on side 2, and the normal
// (x2 - x1) x (x3 - x1) points from side 1 to side 2 (the thesis' Gamma_T to Gamma_B). Over each
// connected part of a fault the orientation is propagated across shared edges, then chosen so that
// the mean normal agrees with the fault's reference normal when one is given (trace files: down
// and against the dip direction, i.e. side 1 = hanging wall), otherwise so that it points down
// (n_z < 0); vertical parts (|n_z| <= 1e-3) point south (n_y < 0), or west (n_x < 0) when they
// strike north-south. A part whose mean normal vanishes (closed surface) follows its lowest-tag triangle.
//
// Every other element touching a split node (boundary triangles, other triangle groups, lines,
// points, interface elements of faults inserted earlier) takes the copies of the tetrahedron with
// the lowest tag among those holding all its nodes; for a prism, each side separately.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ugs/formats/mesh.hpp"

namespace ugs {

struct FaultInsertOptions {
  std::string source;                              // the mesh's name, for messages
  // Faults to insert ("F1" or "fault:F1"); empty: every fault triangle group of the mesh.
  std::vector<std::string> only;
  // Reference normals (side 1 -> side 2) by fault name, e.g. from trace files.
  std::map<std::string, Point3> reference_normals;
};

struct FaultSummary {
  std::string name;
  std::size_t triangles = 0;                       // = interface elements
  double area = 0;                                 // m2
  std::size_t nodes = 0;                           // distinct nodes of its triangles
  std::size_t duplicated_nodes = 0;                // nodes whose two sides got different ids
  std::size_t tip_nodes = 0;                       // nodes with one id on both sides (= nodes - duplicated)
  std::size_t junction_nodes = 0;                  // nodes shared with other inserted faults
  std::map<std::string, std::size_t> meets;        // other inserted fault -> shared nodes
  std::size_t parts = 0;                           // connected parts (through shared edges)
  std::size_t unsplit_triangles = 0;               // triangles none of whose nodes is split
  Point3 normal{};                                 // area-weighted mean unit normal, side 1 -> side 2
};

struct FaultInsertReport {
  std::vector<FaultSummary> faults;                // in insertion order
  std::size_t new_nodes = 0;                       // copies created (tags above the input's maximum)
  std::size_t renumbered_elements = 0;             // other elements moved to a copy
  std::size_t unattached_elements = 0;             // elements on split nodes but in no tetrahedron (kept)
};

// Names (without "fault:") of the mesh's fault triangle groups and of faults already inserted
// (groups holding interface prisms), in physical-group order.
std::vector<std::string> fault_triangle_groups(const Mesh& mesh);
std::vector<std::string> fault_interface_groups(const Mesh& mesh);

// Inserts the faults. InputError (naming the fault) for: unknown names, faults that already have
// interface elements, fault triangles that are not faces of two tetrahedra (the fault does not
// follow mesh faces, or lies on the model boundary), repeated or shared triangles, non-manifold
// edges, non-orientable faults, tetrahedra with all four nodes on one fault, and tetrahedra on the
// same side of a fault triangle. On error the mesh is left unchanged.
FaultInsertReport insert_faults(Mesh& mesh, const FaultInsertOptions& options = {});

}  // namespace ugs
