// GOCAD TSurf (.ts) triangulated surfaces as SKUA-GOCAD, Petrel, RMS and Move export them: one or
// more TSurf objects, each one or more TFACE parts of VRTX/PVRTX/ATOM/PATOM vertices and TRGL
// triangles. Properties, borders and display settings are read past. GDAL 3.6 has no reader.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace ugs {

struct TriangulatedSurface {
  std::string path;
  std::vector<std::array<double, 3>> vertices;          // x, y, elevation (z up, m)
  std::vector<std::size_t> vertex_line;                 // line of each vertex's VRTX/PVRTX
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into vertices, in the file's order
  std::vector<std::size_t> triangle_line;               // line of each TRGL
  std::size_t objects = 0, faces = 0;                   // TSurf objects and TFACE parts read
  std::size_t merged_vertices = 0;                      // VRTX at the same x, y, z as an earlier one, merged
  bool depth_positive = false;                          // ZPOSITIVE Depth: the file's z was negated
};

// Reads every TSurf object of the file. Vertices at exactly the same coordinates are merged (the
// count says how many: the caller reports it). Throws InputError "file:line: ..." for a TRGL naming
// a vertex that does not exist or the same vertex twice, a vertex id given twice, an axis unit other
// than metres, an unknown keyword inside a TFACE, an object without END, or no triangle at all.
TriangulatedSurface read_gocad_tsurf(const std::string& path);

}  // namespace ugs
