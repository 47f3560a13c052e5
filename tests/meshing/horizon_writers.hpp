// Test support: one node grid written in every horizon format ugs-meshgen reads (GeoTIFF through
// GDAL with pixel centres on the nodes, ZMAP+, IRAP classic ASCII, CPS-3 ASCII, GOCAD TSurf with
// each cell split into two triangles), values printed so that every format reads back the same
// doubles (the tests give node values on multiples of 1/1024 m).
#pragma once
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <gdal_priv.h>
#include <ogr_spatialref.h>

namespace ugs::test {

struct NodeGrid {
  double x0, y0, dx, dy, rotation_deg = 0;
  int nx, ny;
  std::vector<double> z;  // [j * nx + i], NaN = undefined
  double at(int i, int j) const { return z[static_cast<std::size_t>(j) * nx + i]; }
  // Position of fractional node (u, v): the grid's own axes turned counter-clockwise.
  std::array<double, 2> point(double u, double v) const {
    const double a = rotation_deg * M_PI / 180.0;
    return {x0 + std::cos(a) * u * dx - std::sin(a) * v * dy, y0 + std::sin(a) * u * dx + std::cos(a) * v * dy};
  }
};

inline std::FILE* open_w(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path);
  return f;
}

inline void write_geotiff(const std::string& path, const NodeGrid& g, int epsg = 32632) {
  GDALAllRegister();
  GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GTiff")->Create(path.c_str(), g.nx, g.ny, 1, GDT_Float64, nullptr);
  if (!ds) throw std::runtime_error("cannot create " + path);
  // Pixel (column i, row j) centred on node (i, j).
  const double a = g.rotation_deg * M_PI / 180.0;
  double gt[6] = {0, g.dx * std::cos(a), -g.dy * std::sin(a), 0, g.dx * std::sin(a), g.dy * std::cos(a)};
  gt[0] = g.x0 - 0.5 * (gt[1] + gt[2]);
  gt[3] = g.y0 - 0.5 * (gt[4] + gt[5]);
  ds->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.importFromEPSG(epsg);
  ds->SetSpatialRef(&srs);
  std::vector<double> v(g.z);
  for (double& x : v)
    if (std::isnan(x)) x = -99999.0;
  GDALRasterBand* b = ds->GetRasterBand(1);
  b->SetNoDataValue(-99999.0);
  if (b->RasterIO(GF_Write, 0, 0, g.nx, g.ny, v.data(), g.nx, g.ny, GDT_Float64, 0, 0) != CE_None)
    throw std::runtime_error("cannot write " + path);
  GDALClose(ds);
}

// ZMAP+ (unrotated): columns from the west, each from the north; fixed fields of 24 characters.
inline void write_zmap(const std::string& path, const NodeGrid& g) {
  std::FILE* f = open_w(path);
  std::fprintf(f, "! test grid\n@top, GRID, 5\n     24, -99999.0, , 10, 1\n%d, %d, %.10f, %.10f, %.10f, %.10f\n0.0, 0.0, 0.0\n@\n",
               g.ny, g.nx, g.x0, g.x0 + (g.nx - 1) * g.dx, g.y0, g.y0 + (g.ny - 1) * g.dy);
  for (int i = 0; i < g.nx; ++i) {
    int k = 0;
    for (int j = g.ny - 1; j >= 0; --j) {
      const double v = std::isnan(g.at(i, j)) ? -99999.0 : g.at(i, j);
      std::fprintf(f, "%24.10f", v);
      if (++k % 5 == 0 || j == 0) std::fputc('\n', f);
    }
  }
  std::fclose(f);
}

inline void write_irap(const std::string& path, const NodeGrid& g) {
  std::FILE* f = open_w(path);
  std::fprintf(f, "-996 %d %.10f %.10f\n%.10f %.10f %.10f %.10f\n%d %.10f %.10f %.10f\n0  0  0  0  0  0  0\n", g.ny, g.dx,
               g.dy, g.x0, g.x0 + (g.nx - 1) * g.dx, g.y0, g.y0 + (g.ny - 1) * g.dy, g.nx, g.rotation_deg, g.x0, g.y0);
  for (std::size_t k = 0; k < g.z.size(); ++k) {
    if (std::isnan(g.z[k])) std::fprintf(f, " 9999900.000000");
    else std::fprintf(f, " %.10f", g.z[k]);
    if (k % 6 == 5 || k + 1 == g.z.size()) std::fputc('\n', f);
  }
  std::fclose(f);
}

// CPS-3 (unrotated): columns from the west, each from the north.
inline void write_cps3(const std::string& path, const NodeGrid& g) {
  std::FILE* f = open_w(path);
  double lo = 1e300, hi = -1e300;
  for (double v : g.z)
    if (!std::isnan(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  std::fprintf(f, "FSASCI 0 1 COMPUTED 0 1.0000000E+30\nFSATTR 0 0\nFSLIMI %.10f %.10f %.10f %.10f %.10f %.10f\n"
                  "FSNROW %d %d\nFSXINC %.10f %.10f\n->top\n",
               g.x0, g.x0 + (g.nx - 1) * g.dx, g.y0, g.y0 + (g.ny - 1) * g.dy, lo, hi, g.ny, g.nx, g.dx, g.dy);
  int k = 0;
  for (int i = 0; i < g.nx; ++i)
    for (int j = g.ny - 1; j >= 0; --j) {
      if (std::isnan(g.at(i, j))) std::fprintf(f, " 1.0000000E+30");
      else std::fprintf(f, " %.10f", g.at(i, j));
      if (++k % 5 == 0) std::fputc('\n', f);
    }
  std::fputc('\n', f);
  std::fclose(f);
}

// GOCAD TSurf: a vertex per defined node, each cell with four defined nodes split along its
// (i, j)-(i+1, j+1) diagonal into two counter-clockwise triangles.
inline void write_tsurf(const std::string& path, const NodeGrid& g) {
  std::FILE* f = open_w(path);
  std::fprintf(f, "GOCAD TSurf 1\nHEADER {\nname:top\n}\nGOCAD_ORIGINAL_COORDINATE_SYSTEM\nNAME Default\n"
                  "AXIS_NAME \"X\" \"Y\" \"Z\"\nAXIS_UNIT \"m\" \"m\" \"m\"\nZPOSITIVE Elevation\n"
                  "END_ORIGINAL_COORDINATE_SYSTEM\nTFACE\n");
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      if (std::isnan(g.at(i, j))) continue;
      const auto p = g.point(i, j);
      std::fprintf(f, "VRTX %d %.17g %.17g %.10f\n", j * g.nx + i + 1, p[0], p[1], g.at(i, j));
    }
  for (int j = 0; j + 1 < g.ny; ++j)
    for (int i = 0; i + 1 < g.nx; ++i) {
      if (std::isnan(g.at(i, j)) || std::isnan(g.at(i + 1, j)) || std::isnan(g.at(i, j + 1)) || std::isnan(g.at(i + 1, j + 1)))
        continue;
      const int a = j * g.nx + i + 1, b = a + 1, c = a + g.nx + 1, d = a + g.nx;
      std::fprintf(f, "TRGL %d %d %d\nTRGL %d %d %d\n", a, b, c, a, c, d);
    }
  std::fprintf(f, "END\n");
  std::fclose(f);
}

}  // namespace ugs::test
