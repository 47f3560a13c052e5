// Maps of a field on the top surface as rasters: linear interpolation on the surface triangles
// at the centres of a regular north-up grid (NaN where the surface does not reach), written as
// GeoTIFF (Float32, DEFLATE, NaN no-data, the model CRS) through GDAL, atomically.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "ugs/insar/surface.hpp"

namespace ugs::insar {

struct GridSpec {
  double x0 = 0, y0 = 0;   // upper-left corner (west, north)
  double cell = 1;         // square cells (m)
  int nx = 0, ny = 0;
  double x(int i) const { return x0 + (i + 0.5) * cell; }
  double y(int j) const { return y0 - (j + 0.5) * cell; }
};

// A grid covering `extent` (xmin, xmax, ymin, ymax) with corners on multiples of the cell size;
// cell <= 0 picks 1, 2 or 5 x 10^k giving about 400 cells along the longer side.
GridSpec grid_for_extent(const std::array<double, 4>& extent, double cell);

// The surface location of every grid cell centre (reused for several fields).
std::vector<SurfaceHit> locate_grid(const SurfaceLocator& locator, const GridSpec& grid);
// Component `c` of a node field at the located cell centres (NaN where not inside), times `scale`.
std::vector<double> grid_values(const std::vector<SurfaceHit>& hits, const TopSurface& surface,
                                const std::vector<double>& node_values, int components, int c, double scale);

// Component `c` of a node field (`components` values per surface node) times `scale`, on the grid
// (row-major from the north-west corner).
std::vector<double> grid_surface_field(const SurfaceLocator& locator, const std::vector<double>& node_values,
                                       int components, int c, const GridSpec& grid, double scale);

struct RasterBand {
  std::vector<double> values;   // ny x nx
  std::string description;      // e.g. "u_z change 2015-05-01 to 2015-11-01"
};

// `crs_wkt` "" writes no CRS. `unit` goes into each band's unit type ("mm").
void write_geotiff(const std::string& path, const GridSpec& grid, const std::vector<RasterBand>& bands,
                   const std::string& crs_wkt, const std::string& unit);

}  // namespace ugs::insar
