#include "ugs/insar/raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <cpl_string.h>
#include <gdal_priv.h>
#include <fmt/format.h>

#include "gdal_quiet.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/io.hpp"

namespace ugs::insar {

GridSpec grid_for_extent(const std::array<double, 4>& e, double cell) {
  const double w = e[1] - e[0], h = e[3] - e[2];
  if (!(w > 0 && h > 0)) throw InputError("", "the surface has no plan extent to grid");
  if (!(cell > 0)) {
    const double raw = std::max(w, h) / 400.0;
    const double p = std::pow(10.0, std::floor(std::log10(raw)));
    cell = raw <= p ? p : raw <= 2 * p ? 2 * p : raw <= 5 * p ? 5 * p : 10 * p;
  }
  if (!std::isfinite(cell)) throw InputError("raster cell size", fmt::format("{} (expected a finite cell size in m)", cell));
  GridSpec g;
  g.cell = cell;
  g.x0 = std::floor(e[0] / cell) * cell;
  g.y0 = std::ceil(e[3] / cell) * cell;
  // Counted in double first: a tiny cell must not overflow the int.
  const double nx = std::ceil((e[1] - g.x0) / cell - 1e-9), ny = std::ceil((g.y0 - e[2]) / cell - 1e-9);
  if (!(nx * ny <= 1e8))
    throw InputError("raster cell size", fmt::format("{} m gives {:.3g} x {:.3g} cells, too many (at most 1e8)", cell, nx, ny));
  g.nx = static_cast<int>(nx);
  g.ny = static_cast<int>(ny);
  return g;
}

std::vector<SurfaceHit> locate_grid(const SurfaceLocator& loc, const GridSpec& g) {
  std::vector<SurfaceHit> hits(static_cast<std::size_t>(g.nx) * g.ny);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) hits[std::size_t(j) * g.nx + i] = loc.locate(g.x(i), g.y(j));
  return hits;
}

std::vector<double> grid_values(const std::vector<SurfaceHit>& hits, const TopSurface& s, const std::vector<double>& v,
                                int components, int c, double scale) {
  std::vector<double> out(hits.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < hits.size(); ++k) {
    const auto& h = hits[k];
    if (!h.inside) continue;
    const auto& t = s.triangles[h.triangle];
    double sum = 0;
    for (int n = 0; n < 3; ++n) sum += h.weights[n] * v[std::size_t(t[n]) * components + c];
    out[k] = sum * scale;
  }
  return out;
}

std::vector<double> grid_surface_field(const SurfaceLocator& loc, const std::vector<double>& v, int components, int c,
                                       const GridSpec& g, double scale) {
  return grid_values(locate_grid(loc, g), loc.surface(), v, components, c, scale);
}

void write_geotiff(const std::string& path, const GridSpec& g, const std::vector<RasterBand>& bands,
                   const std::string& crs_wkt, const std::string& unit) {
  GdalQuiet quiet;
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (!drv) throw ComputeError("GDAL has no GTiff driver");
  OutputFile out(path);  // GDAL writes the temporary by name; commit renames it
  if (out.is_stdout()) throw InputError(path, "a GeoTIFF needs a file name");
  char** opts = nullptr;
  opts = CSLSetNameValue(opts, "COMPRESS", "DEFLATE");
  opts = CSLSetNameValue(opts, "PREDICTOR", "3");
  opts = CSLSetNameValue(opts, "TILED", "NO");
  GDALDataset* ds = drv->Create(out.temp_path().c_str(), g.nx, g.ny, static_cast<int>(bands.size()), GDT_Float32, opts);
  CSLDestroy(opts);
  if (!ds) throw ComputeError(fmt::format("{}: cannot create the GeoTIFF: {}", path, gdal_last_error()));
  double gt[6] = {g.x0, g.cell, 0, g.y0, 0, -g.cell};
  ds->SetGeoTransform(gt);
  if (!crs_wkt.empty()) {
    OGRSpatialReference srs = srs_of(crs_wkt);
    ds->SetSpatialRef(&srs);
  }
  bool ok = true;
  for (std::size_t b = 0; b < bands.size(); ++b) {
    GDALRasterBand* band = ds->GetRasterBand(static_cast<int>(b + 1));
    std::vector<float> f(bands[b].values.begin(), bands[b].values.end());
    band->SetNoDataValue(std::numeric_limits<double>::quiet_NaN());
    band->SetDescription(bands[b].description.c_str());
    band->SetUnitType(unit.c_str());
    ok = ok && band->RasterIO(GF_Write, 0, 0, g.nx, g.ny, f.data(), g.nx, g.ny, GDT_Float32, 0, 0) == CE_None;
  }
  GDALClose(ds);
  if (!ok) throw ComputeError(fmt::format("{}: writing the GeoTIFF failed: {}", path, gdal_last_error()));
  out.commit();
}

}  // namespace ugs::insar
