// Geodata through GDAL/OGR for the meshing tools: coordinate reference systems, vector features
// (any OGR format) reprojected to the model CRS, point-in-polygon sets, and bilinear sampling of
// any GDAL raster. Errors are InputError naming the file (GDAL's own messages are kept quiet).
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "ugs/meshing/xy.hpp"

namespace ugs::geo {

// The CRS a user wrote ("EPSG:32632", WKT, PROJ string, ...) as WKT; InputError(where) if unknown.
std::string crs_wkt(const std::string& user_crs, const std::string& where);
// Short name for messages: "EPSG:32632" when it has an EPSG code, else its name.
std::string crs_label(const std::string& wkt);
bool same_crs(const std::string& wkt_a, const std::string& wkt_b);

struct Polygon {
  std::vector<XY> outer;                   // closed ring without the repeated last point
  std::vector<std::vector<XY>> holes;
};

struct Feature {
  std::int64_t fid = 0;
  std::string layer;
  std::map<std::string, std::string> text;     // every set field, as text
  std::map<std::string, double> number;        // numeric fields (integer or real)
  std::vector<Polygon> polygons;               // parts of (multi)polygons
  std::vector<std::vector<XY>> lines;          // parts of (multi)line strings
  std::optional<double> number_of(const std::string& field) const;
  std::optional<std::string> text_of(const std::string& field) const;
};

struct VectorData {
  std::string path;
  std::string source_crs;                      // WKT of the file's CRS ("" if it has none)
  std::vector<Feature> features;
};

// The CRS of the first layer of a vector file that has one, "" if none.
std::string vector_crs(const std::string& path);
// Every feature of every layer, filtered by an OGR attribute filter `where` (SQL WHERE syntax) and
// transformed to `model_wkt` (a file without a CRS is taken as being in it). Curves are linearised,
// z dropped, points ignored.
VectorData read_vector(const std::string& path, const std::string& model_wkt, const std::string& where = "");

// Even-odd point-in-polygon over a set of polygons (holes excluded), with bounding-box culling.
// Each ring's edges are sorted into horizontal slabs, so that a point visits only the edges whose
// y-range holds it (the others cannot cross its ray): the same answer as testing every edge.
class PolygonSet {
public:
  PolygonSet() = default;
  explicit PolygonSet(std::vector<Polygon> polygons);
  bool contains(const XY& p) const;
  bool empty() const { return polygons_.empty(); }

private:
  struct RingSlabs {
    double y0 = 0, y1 = 0, per_y = 0;  // the ring's y-range, slabs per unit of y
    std::vector<std::uint32_t> start;   // per slab: its first entry in edges
    std::vector<std::uint32_t> edges;   // edge i joins vertex i and the one before it
    std::size_t slab(double y) const;
  };
  static RingSlabs slabs_of(const std::vector<XY>& ring);
  static bool crossings_odd(const std::vector<XY>& ring, const RingSlabs& s, const XY& p);
  std::vector<Polygon> polygons_;
  std::vector<std::array<double, 4>> boxes_;
  std::vector<std::vector<RingSlabs>> slabs_;  // per polygon: its outer ring, then its holes
};

struct RasterSampling {
  std::vector<double> values;                  // one per point (NaN where not covered)
  std::vector<std::uint32_t> outside;          // points outside the raster
  std::vector<std::uint32_t> nodata;           // points whose bilinear stencil touches no-data or NaN
  std::string crs;                             // label of the raster's CRS
};

// The CRS of a raster as WKT ("" if it has none); InputError if it cannot be opened.
std::string raster_crs(const std::string& path);

// Bilinear interpolation between pixel centres of band `band` (scale and offset applied). Points
// in the outer half pixel are clamped to the edge pixels; points beyond the raster are `outside`.
// Points are in `points_wkt` and transformed to the raster's CRS when it differs.
RasterSampling sample_raster(const std::string& path, int band, std::span<const XY> points, const std::string& points_wkt);

}  // namespace ugs::geo
