// Checks of a triangulated surface read from a file (GOCAD TSurf horizons and faults, fault sticks
// turned into triangles): each failure is an InputError naming the file and the line of the
// triangle (or vertex) at fault, so that the user can find it in the exporting package.
#pragma once
#include <cstdint>
#include <string>

#include "ugs/formats/error.hpp"
#include "ugs/formats/gocad_tsurf.hpp"

namespace ugs {

// "vertex of line L (x, y, z)" for messages.
std::string vertex_at(const TriangulatedSurface& s, std::uint32_t v);
// InputError at "file:line" of triangle t.
InputError at_triangle(const TriangulatedSurface& s, std::size_t t, const std::string& what);

// A 2-manifold with one orientation: no edge shared by more than two triangles (non-manifold edge),
// neighbours running their shared edge opposite ways (consistent orientation), no vertex where two
// fans of triangles meet only at the vertex (two sheets touching at a point).
void check_surface_topology(const TriangulatedSurface& s);

// No two triangles intersect other than along their shared edges and vertices (CGAL Polygon Mesh
// Processing, self_intersections, exact predicates); the first pair in file order is named. Call
// after check_surface_topology (CGAL needs a manifold).
void check_surface_self_intersections(const TriangulatedSurface& s);

}  // namespace ugs
