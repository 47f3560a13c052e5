// Horizons as geological modelling packages deliver them, evaluated at the plan's columns
// (docs/meshing.md, "Horizons from Petrel, RMS, SKUA-GOCAD, Move"): IRAP classic ASCII and CPS-3
// ASCII grids (formats/), ZMAP+ grids through GDAL's ZMap driver, GOCAD TSurf triangulated
// surfaces. Grids are interpolated bilinearly in their cells, exactly as geo::sample_raster does
// between pixel centres, so one surface gives the same elevations whichever format carries it;
// TSurf linearly on its triangles.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "ugs/formats/gocad_tsurf.hpp"
#include "ugs/formats/horizon_grid.hpp"
#include "ugs/meshing/plan.hpp"

namespace ugs::geo {

struct HorizonSampling {
  std::vector<double> values;              // one per point (NaN where not covered)
  std::vector<std::uint32_t> outside;      // points outside the grid's nodes or the surface's triangles
  std::vector<std::uint32_t> undefined;    // points whose grid cell has an undefined node
  std::string format;                      // "IRAP classic ASCII", ...
  std::vector<std::string> cleaned;        // what was mended in the surface (said to the user)
  std::vector<std::string> notes;          // how the file was read (-v)
  std::array<double, 4> extent{};          // xmin, ymin, xmax, ymax of the surface, in its CRS
};

// A ZMAP+ grid read by GDAL's ZMap driver (nodes where the header puts them: ZMAP_PIXEL_IS_POINT),
// its lines checked first against the header (values per line and column, nothing after the last
// column), so that a grid whose header disagrees with its values is refused naming the line.
HorizonGrid read_zmap_grid(const std::string& path);

// Bilinear in the cell holding each point (points in the grid's CRS); points up to 1e-9 of a cell
// beyond the outer nodes count as on them.
HorizonSampling sample_grid(const HorizonGrid& g, std::span<const XY> points);

// A TSurf as a horizon: no edge shared by more than two triangles, no vertex where two sheets touch,
// neighbours oriented alike, no self-intersection (CGAL Polygon Mesh Processing), no triangle
// overturned against the others (the surface must be single-valued in z). InputError naming the
// TRGL line otherwise.
void check_horizon_surface(const TriangulatedSurface& s);

// Linear on the triangle holding each point (points in the surface's CRS).
HorizonSampling sample_tsurf(const TriangulatedSurface& s, std::span<const XY> points);

// Reads `path` (format told by its content), transforms the points from points_wkt to surface_wkt
// and evaluates. InputError "file:line: ..." for a file that cannot be read or a surface refused.
HorizonSampling sample_horizon(const std::string& path, const std::string& surface_wkt, std::span<const XY> points,
                               const std::string& points_wkt);

}  // namespace ugs::geo
