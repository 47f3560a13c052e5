// Faults given as surfaces (docs/faults.md, "Faults as surfaces"): a GOCAD TSurf (one or several
// TFACEs; properties ignored) or fault sticks (IRAP classic lines, one polyline per stick)
// interpolated into triangles between consecutive sticks. The triangles are checked (a 2-manifold
// with one orientation, no triangle of zero area, no self-intersection) and never mended silently:
// what was cleaned (vertices at one point merged) is said in `cleaned`.
#pragma once
#include <string>
#include <vector>

#include "ugs/formats/fault_sticks.hpp"
#include "ugs/formats/gocad_tsurf.hpp"
#include "ugs/formats/mesh.hpp"

namespace ugs {

struct FaultSurfaceInput {
  TriangulatedSurface mesh;          // coordinates as in the file (the model's CRS), elevation up
  std::string format;                // "GOCAD TSurf" or "fault sticks"
  std::vector<std::string> cleaned;  // what was mended, for the user
};

// Reads a fault surface: a file whose first word is GOCAD is a TSurf, any other one fault sticks.
// InputError "file:line: ..." for bad input (the readers' errors, check_fault_surface's).
FaultSurfaceInput read_fault_surface(const std::string& path);

// The sticks' surface: each stick oriented like the one before it (the first one downward), and
// consecutive sticks joined by a strip of triangles that keeps every stick point, advancing along
// the stick whose next point comes first by fraction of its length. Points at the same x, y, z on
// two sticks (sticks meeting at a fault tip) are merged (cleaned says it). InputError naming the
// lines for two consecutive sticks that cross (the strip between them folds back, or doubles back
// against the strip before it).
FaultSurfaceInput sticks_surface(const FaultSticks& sticks);

// A fault surface's checks: check_surface_topology, no triangle of zero area (1e-12 of its longest
// edge squared), check_surface_self_intersections.
void check_fault_surface(const TriangulatedSurface& s);

// The unit normal of the surface's side 1 -> side 2 orientation: the sum of the triangles' area
// normals, turned to point down (and for a vertical surface toward -y, then -x), as the trace
// surfaces' (fault_traces.hpp). +1 or -1: the factor that turns each triangle's own normal (from
// its corners' order) into that orientation.
double surface_orientation(const TriangulatedSurface& s);
// That normal itself (unit): ugs-faultinsert's reference normal for the fault.
Point3 surface_reference_normal(const TriangulatedSurface& s);

}  // namespace ugs
