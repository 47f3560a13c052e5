// Persistent-scatterer (PS) points and their displacement series, from
//   - the European Ground Motion Service (EGMS) CSV layout: one row per point, columns pid,
//     easting, northing (EPSG:3035, ETRS89-LAEA, unless told otherwise), height, ..., then one
//     column per acquisition date named YYYYMMDD, displacement in mm;
//   - a generic CSV: x,y (model CRS unless told) or lon,lat (EPSG:4326 unless told), an optional
//     id column (pid, id, name), optional date columns (YYYYMMDD or YYYY-MM-DD) in mm;
//   - any OGR point file (GeoJSON, GeoPackage, Shapefile, ...), in the layer's CRS. A layer without
//     one (a GeoJSON without "crs" member, a Shapefile without .prj) is refused when the points
//     must be placed in a model CRS, unless the points CRS is given; a GeoJSON without "crs" whose
//     coordinates are all longitude/latitude is WGS 84 (RFC 7946).
// Points are reprojected to the model CRS through PROJ. Empty cells and "NaN" are missing values.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ugs::insar {

struct PsPoint {
  std::string id;
  double x = 0, y = 0;            // model CRS (m)
  std::optional<double> height;   // scatterer height as given (m)
  std::string where;              // "file:line" (CSV) or "file: feature N" (OGR)
};

// The largest measured displacement read (mm): a kilometre is no InSAR measurement, and a value
// near the largest double squares to inf in a misfit.
inline constexpr double kMaxDisplacementMm = 1.0e6;

struct PsData {
  std::string path;
  std::string layout;             // "EGMS", "CSV" or "OGR"
  std::string source_crs;         // WKT of the file's coordinates ("" if unknown)
  bool reprojected = false;       // coordinates were transformed to the model CRS
  bool undeclared_crs = false;    // an OGR layer without a CRS, taken as the model's (no model CRS known)
  std::vector<PsPoint> points;
  std::vector<std::int64_t> dates;   // acquisition dates (s since 1970), increasing; may be empty
  std::vector<double> values_mm;     // points x dates, NaN where missing

  bool has_series() const { return !dates.empty(); }
  double value_mm(std::size_t point, std::size_t date) const { return values_mm[point * dates.size() + date]; }
  std::optional<std::size_t> find(const std::string& id) const;
};

struct PsReadOptions {
  std::string model_crs;          // WKT of the model CRS; "" = keep the file's coordinates
  std::string points_crs;         // user override of the file's CRS (any PROJ/GDAL text); "" = from the file
  std::string id_column;          // "" = the first of pid, id, name, point_id
  bool require_series = false;    // InputError if the file has no date columns
};

// Reads `path` ("-" = stdin, CSV). InputError naming file and line for: no coordinate columns,
// a date column that does not parse, dates out of order, a non-numeric value or one beyond
// kMaxDisplacementMm, a point without any value (when the file has series), duplicate ids, no
// points at all, or a non-point OGR geometry.
PsData read_ps(const std::string& path, const PsReadOptions& options);

// Only the points whose ids are listed (order of `ids`); InputError naming the first unknown id.
PsData select_points(const PsData& data, const std::vector<std::string>& ids);

}  // namespace ugs::insar
