// Test support: small GeoTIFF rasters and GeoJSON files written with GDAL/OGR, so the meshing tests
// run without the sample data.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

namespace ugs::test {

struct Grid {
  double x0, y_top, cell;  // upper-left corner and square cell size
  int nx, ny;
  double cx(int i) const { return x0 + (i + 0.5) * cell; }   // pixel centres
  double cy(int j) const { return y_top - (j + 0.5) * cell; }
};

// A one-band Float64 GeoTIFF with value f(x, y) at each pixel centre; `nodata_at` marks pixels
// that get the no-data value.
inline void write_raster(const std::string& path, const Grid& g, const std::function<double(double, double)>& f,
                         int epsg = 32632, const std::function<bool(int, int)>& nodata_at = {}) {
  GDALAllRegister();
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
  GDALDataset* ds = drv->Create(path.c_str(), g.nx, g.ny, 1, GDT_Float64, nullptr);
  if (!ds) throw std::runtime_error("cannot create " + path);
  double gt[6] = {g.x0, g.cell, 0, g.y_top, 0, -g.cell};
  ds->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.importFromEPSG(epsg);
  ds->SetSpatialRef(&srs);
  std::vector<double> v(static_cast<std::size_t>(g.nx) * g.ny);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      v[static_cast<std::size_t>(j) * g.nx + i] = nodata_at && nodata_at(i, j) ? -9999.0 : f(g.cx(i), g.cy(j));
  GDALRasterBand* b = ds->GetRasterBand(1);
  if (nodata_at) b->SetNoDataValue(-9999.0);
  if (b->RasterIO(GF_Write, 0, 0, g.nx, g.ny, v.data(), g.nx, g.ny, GDT_Float64, 0, 0) != CE_None)
    throw std::runtime_error("cannot write " + path);
  GDALClose(ds);
}

struct VectorFeature {
  std::string name;
  std::string wkt;                       // geometry
  std::vector<std::pair<std::string, double>> numbers;
};

// A GeoJSON file with a `name` field, numeric fields and WKT geometries, in `epsg`.
inline void write_vector(const std::string& path, const std::vector<VectorFeature>& features, int epsg = 32632) {
  GDALAllRegister();
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GeoJSON");
  GDALDataset* ds = drv->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
  if (!ds) throw std::runtime_error("cannot create " + path);
  OGRSpatialReference srs;
  srs.importFromEPSG(epsg);
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRLayer* layer = ds->CreateLayer("features", &srs, wkbUnknown, nullptr);
  OGRFieldDefn name("name", OFTString);
  layer->CreateField(&name);
  std::vector<std::string> numeric;
  for (const auto& f : features)
    for (const auto& [k, v] : f.numbers)
      if (std::find(numeric.begin(), numeric.end(), k) == numeric.end()) {
        numeric.push_back(k);
        OGRFieldDefn d(k.c_str(), OFTReal);
        layer->CreateField(&d);
      }
  for (const auto& f : features) {
    OGRFeature* feat = OGRFeature::CreateFeature(layer->GetLayerDefn());
    feat->SetField("name", f.name.c_str());
    for (const auto& [k, v] : f.numbers) feat->SetField(k.c_str(), v);
    OGRGeometry* geom = nullptr;
    OGRGeometryFactory::createFromWkt(f.wkt.c_str(), nullptr, &geom);
    if (!geom) throw std::runtime_error("bad WKT " + f.wkt);
    feat->SetGeometryDirectly(geom);
    if (layer->CreateFeature(feat) != OGRERR_NONE) throw std::runtime_error("cannot write a feature to " + path);
    OGRFeature::DestroyFeature(feat);
  }
  GDALClose(ds);
}

// x, y of a point given in `from_epsg`, transformed to `to_epsg` (x = easting / longitude).
inline std::array<double, 2> transform_point(double x, double y, int from_epsg, int to_epsg) {
  OGRSpatialReference a, b;
  a.importFromEPSG(from_epsg);
  b.importFromEPSG(to_epsg);
  a.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  b.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRCoordinateTransformation* ct = OGRCreateCoordinateTransformation(&a, &b);
  ct->Transform(1, &x, &y);
  OGRCoordinateTransformation::DestroyCT(ct);
  return {x, y};
}

}  // namespace ugs::test
