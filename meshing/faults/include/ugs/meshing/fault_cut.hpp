// Dipping faults made of tetrahedron faces (docs/dipping-faults.md): a conforming cut of a
// tetrahedral mesh by the planar panels of fault surfaces (fault_traces.hpp: a trace, a dip, a dip
// direction and a depth range, or listric pieces down-dip; or a triangulated surface, each triangle
// a panel: docs/faults.md, "Faults as surfaces").
//
// Each panel is a convex polygon Q = plane P ∩ half-spaces (depth limits, the vertical planes
// through the trace's vertices along the dip, and for a fault that ends against another the other
// fault's plane). The cut, per panel:
//   1. every edge crossing P of every tetrahedron whose section by P meets Q is bisected at P;
//   2. for each bounding half-space, every edge lying in P that crosses its plane near Q is
//      bisected there, so that the edges of Q are mesh edges.
// An edge is bisected in every element holding it (tetrahedra and triangle groups alike), and an
// element with several marked edges bisects them in increasing order of their node pair, so two
// elements sharing a face split it the same way: the mesh stays conforming, every child keeps its
// parent's orientation and material, and its volume is a positive fraction of the parent's.
// New nodes lie on P up to rounding, so the faces lying in P with their centroid inside Q cover
// Q ∩ model exactly. They become the triangle group fault:<name>, normals down and against the dip
// direction (side 1 = hanging wall, as ugs-faultinsert orients them). Last, a tetrahedron with all
// four nodes on one fault (where it bends, or a sliver between two of its faces; ugs-faultinsert
// would have to tear it apart) has its longest edge off the fault bisected at its midpoint.
#pragma once
#include <string>
#include <vector>

#include "ugs/formats/mesh.hpp"
#include "ugs/meshing/fault_traces.hpp"

namespace ugs {

struct CutHalfSpace {
  Point3 m{};      // inside: m . x <= d
  double d = 0;
};

struct CutPanel {
  Point3 n{};      // unit normal of the plane n . x = c, pointing down and against the dip direction
  double c = 0;
  std::vector<CutHalfSpace> bounds;
  std::size_t piece = 0, segment = 0;
};

// The panels of a trace (of a fault given as a surface: one per triangle, bounded by the planes
// through its edges, cut_surface_panels.cpp). A fault with `ends_against` is extended past the other fault (found in
// `all` by name) along its last segment at that end and bounded by the other fault's plane.
// InputError (naming the fault) when the other fault is missing or the two run parallel.
std::vector<CutPanel> fault_cut_panels(const FaultTrace& trace, const std::vector<FaultTrace>& all);

// Is x inside panel p (its plane within `tol`, and every bound)?
bool panel_contains(const CutPanel& p, const Point3& x, double tol);

struct FaultCutOptions {
  // m: a node this close to a plane lies on it; 0 = 1e-7 of the model's diagonal (5 mm at 50 km).
  // Not rounding level: one panel's cut spills into its neighbour's region with nodes off the
  // neighbour's plane by angle x distance (1e-4 m for nearly collinear trace segments), and a cut
  // next to such a node splits all its edges that close to it: coincident nodes, zero volumes.
  double tolerance = 0;
  // Before each cut (a panel's plane, each of its limits), where an edge crosses the plane within
  // snap * its length of a node, the node is moved onto the plane within the surfaces it lies on
  // (triangle groups, material interfaces, earlier panels; docs/dipping-faults.md), when its
  // tetrahedra stay positive and keep at least half their smallest dihedral angle: fewer slivers.
  // 0 = never.
  double snap = 0.2;
  // After the cut (docs/dipping-faults.md, steps 5-6), a node it made is merged into a neighbour
  // across an edge shorter than collapse * the longest edge of the tetrahedron (between two nodes of
  // a fault: * the shortest edge of the input tetrahedron, so that the fault keeps the layering's
  // resolution) — two cuts that met at a small angle — and the nodes of the cut's tetrahedra with a dihedral angle below
  // smooth_below_deg are smoothed; both within the nodes' surfaces and only where the worst
  // tetrahedron touched gets better. 0 = never.
  double collapse = 0.35;
  double smooth_below_deg = 10;
  // The quality bound (docs/dipping-faults.md, "Mesh quality"): a tetrahedron holding a node the
  // cut made should keep a smallest dihedral angle of at least min(bound_deg, that of the input
  // tetrahedron it comes from) (the reference), and must keep bound_fraction of it (the bound).
  // The collapse and the smoothing raise the worst ratio to the reference they touch.
  double bound_deg = 2.0;
  double bound_fraction = 0.1;
};

struct FaultCutReport {
  std::string name;
  std::size_t panels = 0;
  std::size_t triangles = 0;      // faces in fault:<name>
  double area = 0;                // m2
  double max_distance = 0;        // m: of the faces' nodes from their panel's plane
  double max_angle_deg = 0;       // between the faces' normals and their panel's normal
  double zmin = 0, zmax = 0;      // extent of the faces
  std::size_t boundary_faces = 0; // faces in a panel lying on the model's boundary (not kept)
};

struct FaultCutSummary {
  std::vector<FaultCutReport> faults;
  std::size_t nodes_before = 0, nodes_after = 0;
  std::size_t tetrahedra_before = 0, tetrahedra_after = 0;
  std::size_t untorn = 0;
  std::size_t snapped = 0;        // nodes moved onto a panel's plane or limit (edges bisected so
                                  // that no tetrahedron has four nodes on one fault: untorn)
  std::size_t collapsed = 0;       // nodes merged into a neighbour across a short edge
  std::size_t smoothed = 0;        // node moves by smoothing
  std::size_t band_tetrahedra = 0;     // tetrahedra holding a node the cut made
  double band_min_dihedral_deg = 180;  // their smallest dihedral angle
  std::size_t band_below_reference = 0;  // of them below min(bound_deg, their input tetrahedron's)
  std::size_t band_below_bound = 0;      // of them below bound_fraction of that
  double tolerance = 0;
};

// Cuts the mesh's tetrahedra and triangles (other element types are kept as they are and must not
// use a cut edge) and adds a triangle group fault:<name> per trace. Element tags are renumbered
// 1.. in block order, new nodes get tags above the largest. InputError naming the fault when the
// group already exists, or its surface does not cross the mesh.
FaultCutSummary cut_faults(Mesh& mesh, const std::vector<FaultTrace>& traces, const FaultCutOptions& options = {});

}  // namespace ugs
