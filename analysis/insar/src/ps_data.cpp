#include "ugs/insar/ps_data.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <unordered_map>

#include <cpl_json.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include <fmt/format.h>

#include "gdal_quiet.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/insar/crs.hpp"

namespace ugs::insar {

std::optional<std::size_t> PsData::find(const std::string& id) const {
  for (std::size_t i = 0; i < points.size(); ++i)
    if (points[i].id == id) return i;
  return std::nullopt;
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && lower(s.substr(s.size() - suffix.size())) == suffix;
}

// A header that looks like a date: starts with a digit and has only digits and '-' (YYYYMMDD,
// YYYY-MM-DD). It must then parse, or the file is refused (a misprinted date is not a value column).
bool looks_like_date(std::string_view h) {
  if (h.empty() || !std::isdigit(static_cast<unsigned char>(h.front()))) return false;
  return std::all_of(h.begin(), h.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)) || c == '-'; });
}

std::optional<std::size_t> find_any(const CsvTable& t, std::initializer_list<const char*> names) {
  for (const char* n : names)
    for (std::size_t c = 0; c < t.columns().size(); ++c)
      if (lower(t.columns()[c]) == n) return c;
  return std::nullopt;
}

bool is_missing(std::string_view s) {
  return s.empty() || s == "nan" || s == "NaN" || s == "NAN" || s == "NA" || s == "null";
}

std::string list_columns(const CsvTable& t) {
  std::string s;
  for (std::size_t i = 0; i < t.columns().size() && i < 12; ++i) s += (i ? ", " : "") + t.columns()[i];
  if (t.columns().size() > 12) s += fmt::format(", ... ({} columns)", t.columns().size());
  return s;
}

void check_ids_unique(const PsData& d) {
  std::unordered_map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < d.points.size(); ++i) {
    auto [it, fresh] = seen.emplace(d.points[i].id, i);
    if (!fresh)
      throw InputError(d.points[i].where, fmt::format("point id '{}' also used at {}", d.points[i].id, d.points[it->second].where));
  }
}

void reproject(PsData& d, const PsReadOptions& o) {
  if (d.points.empty()) throw InputError(d.path, "no points");
  if (o.model_crs.empty()) {
    if (is_geographic(d.source_crs))
      throw InputError(d.path, fmt::format("points are in {} (longitude/latitude): the model CRS is needed to place them "
                                           "(give it, or a case file with crs)", crs_name(d.source_crs)));
    return;
  }
  if (d.source_crs.empty()) return;  // taken as being in the model CRS
  CoordinateTransform ct(d.source_crs, o.model_crs, d.path);
  if (ct.identity()) return;
  std::vector<double> x, y;
  std::vector<std::string> where;
  for (const auto& p : d.points) {
    x.push_back(p.x);
    y.push_back(p.y);
    where.push_back(p.where);
  }
  ct.apply(x, y, where);
  for (std::size_t i = 0; i < d.points.size(); ++i) {
    d.points[i].x = x[i];
    d.points[i].y = y[i];
  }
  d.reprojected = true;
}

PsData read_csv_points(const std::string& path, const PsReadOptions& o) {
  const CsvTable t = CsvTable::read(path);
  PsData d;
  d.path = t.name();
  // Date columns first: they decide the layout.
  std::vector<std::size_t> date_cols;
  for (std::size_t c = 0; c < t.columns().size(); ++c) {
    const std::string& h = t.columns()[c];
    if (!looks_like_date(h)) continue;
    const auto s = parse_iso_date(h);
    if (!s) throw InputError(d.path + ":1", fmt::format("column '{}' is not a date (YYYYMMDD or YYYY-MM-DD)", h));
    if (!d.dates.empty() && *s <= d.dates.back())
      throw InputError(d.path + ":1", fmt::format("date column '{}' is not after the one before it", h));
    d.dates.push_back(*s);
    date_cols.push_back(c);
  }
  auto xcol = find_any(t, {"easting"}), ycol = find_any(t, {"northing"});
  const bool egms = xcol && ycol && !date_cols.empty();
  std::string default_crs;
  if (egms) {
    d.layout = "EGMS";
    default_crs = "EPSG:3035";
  } else {
    d.layout = "CSV";
    if (!xcol || !ycol) {
      xcol = find_any(t, {"x", "x_m"});
      ycol = find_any(t, {"y", "y_m"});
    }
    if (!xcol || !ycol) {
      xcol = find_any(t, {"lon", "longitude", "long"});
      ycol = find_any(t, {"lat", "latitude"});
      if (xcol && ycol) default_crs = "EPSG:4326";
    }
    if (!xcol || !ycol) {
      // Name what is missing precisely: the EGMS pair, or any pair.
      if (find_any(t, {"easting"}) || find_any(t, {"northing"}))
        throw InputError(d.path + ":1", fmt::format("no column '{}' (columns: {})", find_any(t, {"easting"}) ? "northing" : "easting",
                                                     list_columns(t)));
      throw InputError(d.path + ":1", fmt::format("no coordinate columns: need easting,northing (EGMS), x,y or lon,lat "
                                                   "(columns: {})", list_columns(t)));
    }
  }
  if (!o.points_crs.empty())
    d.source_crs = any_crs_wkt(o.points_crs, "points CRS");
  else if (!default_crs.empty())
    d.source_crs = any_crs_wkt(default_crs, d.path);
  if (o.require_series && d.dates.empty())
    throw InputError(d.path + ":1", fmt::format("no date columns (YYYYMMDD, as in EGMS files; columns: {})", list_columns(t)));

  std::optional<std::size_t> idcol;
  if (!o.id_column.empty()) {
    idcol = t.find_column(o.id_column);
    if (!idcol) throw InputError(d.path + ":1", fmt::format("no column '{}' (columns: {})", o.id_column, list_columns(t)));
  } else {
    idcol = find_any(t, {"pid", "id", "name", "point_id", "ps_id"});
    if (egms && !idcol) throw InputError(d.path + ":1", fmt::format("no column 'pid' (columns: {})", list_columns(t)));
  }
  const auto hcol = find_any(t, {"height", "height_m", "z"});

  const std::size_t nd = d.dates.size();
  d.values_mm.assign(t.rows() * nd, kNaN);
  d.points.reserve(t.rows());
  for (std::size_t r = 0; r < t.rows(); ++r) {
    PsPoint p;
    p.where = t.where(r);
    p.id = idcol ? std::string(t.text(r, *idcol)) : std::to_string(r + 1);
    if (p.id.empty()) throw InputError(p.where, "empty point id");
    p.x = t.number(r, *xcol);
    p.y = t.number(r, *ycol);
    if (hcol && !is_missing(t.text(r, *hcol))) p.height = t.number(r, *hcol);
    std::size_t have = 0;
    for (std::size_t k = 0; k < nd; ++k) {
      if (is_missing(t.text(r, date_cols[k]))) continue;
      const double v = t.number(r, date_cols[k]);
      // Finite is not enough: a misfit of 1e308 mm squares to inf.
      if (std::abs(v) > kMaxDisplacementMm)
        throw InputError(p.where, fmt::format("column '{}': displacement {} mm (expected at most {:g} mm: a kilometre is not a measured "
                                              "displacement)", t.columns()[date_cols[k]], v, kMaxDisplacementMm));
      d.values_mm[r * nd + k] = v;
      ++have;
    }
    if (nd > 0 && have == 0) throw InputError(p.where, fmt::format("point '{}' has no data (every date is empty)", p.id));
    d.points.push_back(std::move(p));
  }
  check_ids_unique(d);
  return d;
}

PsData read_ogr_points(const std::string& path, const PsReadOptions& o) {
  GdalQuiet quiet;
  std::unique_ptr<GDALDataset, void (*)(GDALDataset*)> ds(
      GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY), [](GDALDataset* p) { GDALClose(p); });
  if (!ds) throw InputError(path, "cannot open as a CSV or vector file: " + gdal_last_error());
  PsData d;
  d.path = path;
  d.layout = "OGR";
  if (o.require_series)
    throw InputError(path, "vector files carry no displacement series here: use the EGMS CSV layout (YYYYMMDD columns)");
  // GDAL gives a GeoJSON without a "crs" member WGS 84 (RFC 7946): right for longitude/latitude,
  // a wrong answer for projected coordinates. Whether the member is there is read from the file.
  const std::string driver = ds->GetDriver() ? ds->GetDriver()->GetDescription() : "";
  bool declared_crs = true;
  if (driver == "GeoJSON") {
    CPLJSONDocument doc;
    declared_crs = doc.Load(path) && doc.GetRoot().GetObj("crs").IsValid();
  } else if (driver == "GeoJSONSeq") {
    declared_crs = false;
  }
  for (int li = 0; li < ds->GetLayerCount(); ++li) {
    OGRLayer* layer = ds->GetLayer(li);
    std::string layer_crs;
    if (const OGRSpatialReference* s = layer->GetSpatialRef()) layer_crs = wkt_of_srs(*s);
    if (!declared_crs || layer_crs.empty()) d.undeclared_crs = true;
    if (li == 0 || d.source_crs.empty()) d.source_crs = layer_crs;
    OGRFeatureDefn* defn = layer->GetLayerDefn();
    int idfield = -1;
    if (!o.id_column.empty()) {
      idfield = defn->GetFieldIndex(o.id_column.c_str());
      if (idfield < 0) throw InputError(path, fmt::format("layer '{}' has no field '{}'", layer->GetName(), o.id_column));
    } else {
      for (const char* n : {"pid", "id", "name", "point_id", "ps_id"})
        if ((idfield = defn->GetFieldIndex(n)) >= 0) break;
    }
    int hfield = defn->GetFieldIndex("height");
    layer->ResetReading();
    for (OGRFeature* f; (f = layer->GetNextFeature()) != nullptr;) {
      std::unique_ptr<OGRFeature> owner(f);
      PsPoint p;
      p.where = fmt::format("{}: feature {}", path, f->GetFID());
      const OGRGeometry* g = f->GetGeometryRef();
      if (!g || g->IsEmpty()) throw InputError(p.where, "has no geometry");
      if (wkbFlatten(g->getGeometryType()) != wkbPoint)
        throw InputError(p.where, fmt::format("is a {}, not a point", g->getGeometryName()));
      p.x = g->toPoint()->getX();
      p.y = g->toPoint()->getY();
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
        throw InputError(p.where, fmt::format("coordinates ({}, {}) are not finite", p.x, p.y));
      p.id = idfield >= 0 && f->IsFieldSetAndNotNull(idfield) ? f->GetFieldAsString(idfield) : std::to_string(f->GetFID());
      if (hfield >= 0 && f->IsFieldSetAndNotNull(hfield)) {
        p.height = f->GetFieldAsDouble(hfield);
        if (!std::isfinite(*p.height)) throw InputError(p.where, fmt::format("height {} is not finite", *p.height));
      }
      d.points.push_back(std::move(p));
    }
  }
  if (!o.points_crs.empty()) {
    d.source_crs = any_crs_wkt(o.points_crs, "points CRS");
    d.undeclared_crs = false;
  } else if (d.undeclared_crs && !d.points.empty()) {
    const bool geojson = driver.rfind("GeoJSON", 0) == 0;
    const auto not_lonlat = std::find_if(d.points.begin(), d.points.end(),
                                         [](const PsPoint& p) { return !(std::abs(p.x) <= 180 && std::abs(p.y) <= 90); });
    if (geojson && not_lonlat == d.points.end()) {
      d.undeclared_crs = false;  // RFC 7946: longitude/latitude in WGS 84, as GDAL says
    } else if (geojson || !o.model_crs.empty()) {
      // GDAL's WGS 84 would send projected coordinates off the globe; any other layer without a
      // CRS cannot be placed in the model's.
      throw InputError(path, fmt::format("the layer has no coordinate reference system (expected {}, e.g. EPSG:32632, or "
                                         "the points CRS){}",
                                         geojson ? "a \"crs\" member" : driver == "ESRI Shapefile" ? "a .prj file beside it"
                                                                                                  : "a CRS in the layer",
                                         not_lonlat == d.points.end() || !geojson
                                             ? std::string()
                                             : fmt::format("; ({:.6g}, {:.6g}) is no longitude/latitude", not_lonlat->x,
                                                           not_lonlat->y)));
    }
  }
  check_ids_unique(d);
  return d;
}

}  // namespace

PsData read_ps(const std::string& path, const PsReadOptions& o) {
  const bool csv = path == "-" || path.empty() || ends_with(path, ".csv") || ends_with(path, ".txt");
  PsData d = csv ? read_csv_points(path, o) : read_ogr_points(path, o);
  reproject(d, o);
  return d;
}

PsData select_points(const PsData& data, const std::vector<std::string>& ids) {
  PsData s = data;
  s.points.clear();
  s.values_mm.clear();
  const std::size_t nd = data.dates.size();
  for (const auto& id : ids) {
    const auto i = data.find(id);
    if (!i) throw InputError(data.path, fmt::format("no point '{}'", id));
    s.points.push_back(data.points[*i]);
    s.values_mm.insert(s.values_mm.end(), data.values_mm.begin() + static_cast<std::ptrdiff_t>(*i * nd),
                       data.values_mm.begin() + static_cast<std::ptrdiff_t>((*i + 1) * nd));
  }
  return s;
}

}  // namespace ugs::insar
