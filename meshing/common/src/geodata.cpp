#include "ugs/meshing/geodata.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>

#include <cpl_conv.h>
#include <cpl_json.h>
#include <cpl_vsi.h>
#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>
#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/meshing/gdal_util.hpp"

namespace ugs::geo {

void gdal_init() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    // ZMAP+ headers give the outer nodes (xmin .. xmax over columns - 1 cells): without this GDAL's
    // ZMap driver takes them as the outer pixel edges and spreads the grid over one cell too few.
    CPLSetConfigOption("ZMAP_PIXEL_IS_POINT", "TRUE");
    // The block cache's size is read from the configuration on its first use, unguarded: read
    // here once, so that rasters sampled on two threads (prepare_model) do not both set it.
    GDALGetCacheMax64();
  });
}

QuietGdal::QuietGdal() {
  gdal_init();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  CPLErrorReset();
}
QuietGdal::~QuietGdal() { CPLPopErrorHandler(); }

std::string gdal_error() {
  const char* m = CPLGetLastErrorMsg();
  return m && *m ? std::string(m) : std::string("no reason given by GDAL");
}

OGRSpatialReference srs_from_wkt(const std::string& wkt) {
  OGRSpatialReference s;
  s.importFromWkt(wkt.c_str());
  s.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return s;
}

std::string wkt_of(const OGRSpatialReference& s) {
  char* w = nullptr;
  const char* options[] = {"FORMAT=WKT2_2018", nullptr};
  s.exportToWkt(&w, options);
  std::string r = w ? w : "";
  CPLFree(w);
  return r;
}

std::unique_ptr<OGRCoordinateTransformation> transformation(const std::string& from_wkt, const std::string& to_wkt,
                                                            const std::string& where) {
  if (from_wkt.empty() || to_wkt.empty() || same_crs(from_wkt, to_wkt)) return nullptr;
  OGRSpatialReference a = srs_from_wkt(from_wkt), b = srs_from_wkt(to_wkt);
  std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(&a, &b));
  if (!ct)
    throw InputError(where, fmt::format("no transformation from {} to {}: {}", crs_label(from_wkt), crs_label(to_wkt),
                                        gdal_error()));
  return ct;
}

std::string crs_wkt(const std::string& user_crs, const std::string& where) {
  QuietGdal quiet;
  OGRSpatialReference s;
  if (user_crs.empty() || s.SetFromUserInput(user_crs.c_str()) != OGRERR_NONE)
    throw InputError(where, fmt::format("unknown coordinate reference system '{}' (e.g. \"EPSG:32632\")", user_crs));
  if (!s.IsProjected())
    throw InputError(where, fmt::format("coordinate reference system '{}' is not projected: the model needs metres "
                                        "(e.g. \"EPSG:32632\")", user_crs));
  return wkt_of(s);
}

std::string crs_label(const std::string& wkt) {
  if (wkt.empty()) return "no CRS";
  QuietGdal quiet;
  OGRSpatialReference s = srs_from_wkt(wkt);
  const char* auth = s.GetAuthorityName(nullptr);
  const char* code = s.GetAuthorityCode(nullptr);
  if (auth && code) return fmt::format("{}:{}", auth, code);
  const char* name = s.GetName();
  return name ? name : "unnamed CRS";
}

bool same_crs(const std::string& a, const std::string& b) {
  if (a == b) return true;
  QuietGdal quiet;
  OGRSpatialReference sa = srs_from_wkt(a), sb = srs_from_wkt(b);
  return sa.IsSame(&sb);
}

std::optional<double> Feature::number_of(const std::string& field) const {
  auto it = number.find(field);
  if (it == number.end()) return std::nullopt;
  return it->second;
}

std::optional<std::string> Feature::text_of(const std::string& field) const {
  auto it = text.find(field);
  if (it == text.end()) return std::nullopt;
  return it->second;
}

namespace {
// Why GDAL could not open `path`: a missing file or a directory is said so, not as GDAL's "no reason".
[[noreturn]] void open_failed(const std::string& path, const std::string& as, const std::string& expected) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw InputError(path, fmt::format("cannot open: {}", std::strerror(errno)));
  if (S_ISDIR(st.st_mode)) throw InputError(path, fmt::format("is a directory (expected {})", expected));
  const char* m = CPLGetLastErrorMsg();
  throw InputError(path, fmt::format("cannot open as {}: {}", as, m && *m ? m : "GDAL does not recognise its format"));
}
}  // namespace

namespace {
bool is_geojson(GDALDataset& ds) {
  return ds.GetDriver() && std::string(ds.GetDriver()->GetDescription()) == "GeoJSON";
}

std::string json_text(const CPLJSONObject& v) {
  if (v.GetType() == CPLJSONObject::Type::Null) return "null";
  std::string t = v.Format(CPLJSONObject::PrettyFormat::Plain);
  if (t.size() > 40) t = t.substr(0, 37) + "...";
  return t;
}

bool json_number(const CPLJSONObject& v) {
  const auto t = v.GetType();
  return t == CPLJSONObject::Type::Integer || t == CPLJSONObject::Type::Long ||
         (t == CPLJSONObject::Type::Double && std::isfinite(v.ToDouble()));
}

// Every position of a GeoJSON "coordinates" member holds 2 or 3 finite numbers; `fail` names what is not.
void check_positions(const CPLJSONObject& c, const std::function<void(const std::string&)>& fail) {
  if (c.GetType() != CPLJSONObject::Type::Array) {
    fail(fmt::format("coordinates {} are not an array of positions", json_text(c)));
    return;
  }
  const CPLJSONArray a = c.ToArray();
  const bool nested = a.Size() > 0 && a[0].GetType() == CPLJSONObject::Type::Array;
  if (nested) {
    for (int i = 0; i < a.Size(); ++i) check_positions(a[i], fail);
    return;
  }
  for (int i = 0; i < a.Size(); ++i)
    if (a[i].GetType() == CPLJSONObject::Type::Array || !json_number(a[i]))
      fail(fmt::format("coordinate {} in position {} is not a number (expected [x, y] numbers)", json_text(a[i]),
                       json_text(c)));
  if (a.Size() < 2) fail(fmt::format("position {} has fewer than 2 numbers (expected [x, y])", json_text(c)));
}

void check_geometry(const CPLJSONObject& g, const std::function<void(const std::string&)>& fail) {
  if (!g.IsValid() || g.GetType() == CPLJSONObject::Type::Null) return;  // no geometry: the callers decide
  if (g.GetType() != CPLJSONObject::Type::Object) return fail(fmt::format("geometry {} is not an object", json_text(g)));
  if (g.GetString("type") == "GeometryCollection") {
    const CPLJSONArray parts = g.GetArray("geometries");
    for (int i = 0; i < parts.Size(); ++i) check_geometry(parts[i], fail);
    return;
  }
  const CPLJSONObject c = g.GetObj("coordinates");
  if (!c.IsValid()) return fail(fmt::format("{} geometry without coordinates", g.GetString("type")));
  check_positions(c, fail);
}

// GDAL drops a GeoJSON geometry holding a coordinate that is not a number ("abc", null) and keeps the
// feature without it: a fault line would vanish without a word. Checked here instead, naming the
// feature and the value (files up to 1 GB; larger ones are left to GDAL).
void check_geojson_coordinates(const std::string& path) {
  VSIStatBufL st;
  if (VSIStatL(path.c_str(), &st) != 0 || st.st_size > (decltype(st.st_size){1} << 30)) return;
  CPLJSONDocument doc;
  if (!doc.Load(path)) return;  // GDAL read it: its own parser is more lenient; nothing to add
  const CPLJSONObject root = doc.GetRoot();
  auto check_feature = [&](const CPLJSONObject& f, int index) {
    const std::string name = f.GetObj("properties").GetString("name");
    const std::string who = name.empty() ? fmt::format("feature {}", index) : fmt::format("feature {} ('{}')", index, name);
    check_geometry(f.GetObj("geometry"), [&](const std::string& what) { throw InputError(path, who + ": " + what); });
  };
  const std::string type = root.GetString("type");
  if (type == "FeatureCollection") {
    const CPLJSONArray features = root.GetArray("features");
    for (int i = 0; i < features.Size(); ++i) check_feature(features[i], i);
  } else if (type == "Feature") {
    check_feature(root, 0);
  } else {
    check_geometry(root, [&](const std::string& what) { throw InputError(path, what); });
  }
}
}  // namespace

GdalDatasetPtr open_vector(const std::string& path) {
  GdalDatasetPtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  if (!ds) open_failed(path, "a vector file", "a vector file: GeoJSON, GeoPackage, Shapefile, ...");
  if (is_geojson(*ds)) check_geojson_coordinates(path);
  if (ds->GetLayerCount() == 0) throw InputError(path, "has no vector layer");
  return ds;
}

std::string layer_wkt(const std::string& path, GDALDataset& ds, OGRLayer& layer, bool used) {
  const OGRSpatialReference* s = layer.GetSpatialRef();
  if (!s) return "";
  if (!used) return wkt_of(*s);
  // A GeoJSON file without a "crs" member is WGS 84 longitude/latitude (RFC 7946): GDAL says so and
  // PROJ then fails on projected coordinates with "Invalid coordinate". Say that the crs is missing.
  OGREnvelope env;
  if (is_geojson(ds) && s->IsGeographic() && layer.GetExtent(&env, TRUE) == OGRERR_NONE &&
      (env.MinX < -180.5 || env.MaxX > 360.5 || env.MinY < -90.5 || env.MaxY > 90.5)) {
    bool declared = false;
    CPLJSONDocument doc;
    if (doc.Load(path)) declared = doc.GetRoot().GetObj("crs").IsValid();
    if (!declared)
      throw InputError(path, fmt::format("has no \"crs\" member, so GeoJSON takes its coordinates as WGS 84 longitude/"
                                         "latitude (RFC 7946), but they reach x {:.0f} .. {:.0f}, y {:.0f} .. {:.0f}, which "
                                         "are not degrees: add the CRS of the coordinates, e.g. \"crs\": {{\"type\": "
                                         "\"name\", \"properties\": {{\"name\": \"urn:ogc:def:crs:EPSG::32632\"}}}}",
                                         env.MinX, env.MaxX, env.MinY, env.MaxY));
    throw InputError(path, fmt::format("its crs {} is geographic (degrees), but the coordinates reach x {:.0f} .. {:.0f}, "
                                       "y {:.0f} .. {:.0f}: give the CRS the coordinates are in",
                                       crs_label(wkt_of(*s)), env.MinX, env.MaxX, env.MinY, env.MaxY));
  }
  return wkt_of(*s);
}

std::string vector_crs(const std::string& path) {
  QuietGdal quiet;
  auto ds = open_vector(path);
  for (int i = 0; i < ds->GetLayerCount(); ++i)
    if (const std::string w = layer_wkt(path, *ds, *ds->GetLayer(i), true); !w.empty()) return w;
  return "";
}

namespace {

std::vector<XY> ring_points(const OGRSimpleCurve& c) {
  std::vector<XY> r;
  r.reserve(c.getNumPoints());
  for (int i = 0; i < c.getNumPoints(); ++i) r.push_back({c.getX(i), c.getY(i)});
  return r;
}

}  // namespace

void collect_geometry(const OGRGeometry& g, Feature& f) {
  switch (wkbFlatten(g.getGeometryType())) {
    case wkbPolygon: {
      const auto& p = *g.toPolygon();
      if (p.IsEmpty()) return;
      Polygon poly;
      poly.outer = ring_points(*p.getExteriorRing());
      if (poly.outer.size() > 1 && poly.outer.front() == poly.outer.back()) poly.outer.pop_back();
      for (int i = 0; i < p.getNumInteriorRings(); ++i) {
        auto h = ring_points(*p.getInteriorRing(i));
        if (h.size() > 1 && h.front() == h.back()) h.pop_back();
        poly.holes.push_back(std::move(h));
      }
      f.polygons.push_back(std::move(poly));
      return;
    }
    case wkbLineString:
    case wkbLinearRing: f.lines.push_back(ring_points(*g.toSimpleCurve())); return;
    case wkbMultiPolygon:
    case wkbMultiLineString:
    case wkbGeometryCollection:
      for (const auto* part : *g.toGeometryCollection()) collect_geometry(*part, f);
      return;
    default: return;  // points and anything else carry no polygon or line
  }
}

VectorData read_vector(const std::string& path, const std::string& model_wkt, const std::string& where) {
  QuietGdal quiet;
  auto ds = open_vector(path);
  VectorData out;
  out.path = path;
  for (int li = 0; li < ds->GetLayerCount(); ++li) {
    OGRLayer* layer = ds->GetLayer(li);
    const std::string lwkt = layer_wkt(path, *ds, *layer, !model_wkt.empty());
    if (out.source_crs.empty()) out.source_crs = lwkt;
    auto ct = transformation(lwkt, model_wkt, path);
    if (!where.empty() && layer->SetAttributeFilter(where.c_str()) != OGRERR_NONE)
      throw InputError(path, fmt::format("bad attribute filter \"{}\": {}", where, gdal_error()));
    layer->ResetReading();
    const OGRFeatureDefn* defn = layer->GetLayerDefn();
    while (std::unique_ptr<OGRFeature> feat{layer->GetNextFeature()}) {
      Feature f;
      f.fid = feat->GetFID();
      f.layer = layer->GetName();
      for (int i = 0; i < defn->GetFieldCount(); ++i) {
        if (!feat->IsFieldSetAndNotNull(i)) continue;
        const OGRFieldDefn* fd = defn->GetFieldDefn(i);
        f.text[fd->GetNameRef()] = feat->GetFieldAsString(i);
        const auto t = fd->GetType();
        if (t == OFTInteger || t == OFTInteger64 || t == OFTReal) f.number[fd->GetNameRef()] = feat->GetFieldAsDouble(i);
      }
      if (const OGRGeometry* g0 = feat->GetGeometryRef()) {
        std::unique_ptr<OGRGeometry> g(g0->hasCurveGeometry() ? g0->getLinearGeometry() : g0->clone());
        g->flattenTo2D();
        if (ct && g->transform(ct.get()) != OGRERR_NONE)
          throw InputError(path, fmt::format("feature {}: cannot transform to {}: {}", f.fid, crs_label(model_wkt),
                                             gdal_error()));
        collect_geometry(*g, f);
      }
      out.features.push_back(std::move(f));
    }
    if (!where.empty()) layer->SetAttributeFilter(nullptr);
  }
  return out;
}

PolygonSet::PolygonSet(std::vector<Polygon> polygons) : polygons_(std::move(polygons)) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (const auto& p : polygons_) {
    std::array<double, 4> b{inf, inf, -inf, -inf};
    for (const auto& q : p.outer) b = {std::min(b[0], q[0]), std::min(b[1], q[1]), std::max(b[2], q[0]), std::max(b[3], q[1])};
    boxes_.push_back(b);
    auto& s = slabs_.emplace_back();
    s.push_back(slabs_of(p.outer));
    for (const auto& h : p.holes) s.push_back(slabs_of(h));
  }
}

// Non-decreasing in y (a difference and a product by a positive constant, truncated), so an edge
// listed in the slabs of its lower and upper ends and those between is in the slab of every y
// between them.
std::size_t PolygonSet::RingSlabs::slab(double y) const {
  const double k = (y - y0) * per_y;
  return std::min(start.size() - 3, static_cast<std::size_t>(std::max(0.0, k)));  // slabs 0 .. start.size() - 3
}

PolygonSet::RingSlabs PolygonSet::slabs_of(const std::vector<XY>& r) {
  RingSlabs s;
  if (r.size() < 3) return s;
  s.y0 = s.y1 = r[0][1];
  for (const auto& q : r) {
    s.y0 = std::min(s.y0, q[1]);
    s.y1 = std::max(s.y1, q[1]);
  }
  const std::size_t n = std::max<std::size_t>(1, r.size() / 2);
  s.per_y = s.y1 > s.y0 ? static_cast<double>(n) / (s.y1 - s.y0) : 0.0;
  s.start.assign(n + 2, 0);
  // An edge crosses a point's ray only if exactly one end is above the point: lo <= y < hi.
  auto each = [&](auto&& f) {
    for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
      const double lo = std::min(r[i][1], r[j][1]), hi = std::max(r[i][1], r[j][1]);
      if (!(lo < hi)) continue;
      for (std::size_t k = s.slab(lo), last = s.slab(hi); k <= last; ++k) f(k, static_cast<std::uint32_t>(i));
    }
  };
  each([&](std::size_t k, std::uint32_t) { ++s.start[k + 2]; });
  for (std::size_t k = 2; k < s.start.size(); ++k) s.start[k] += s.start[k - 1];
  s.edges.resize(s.start.back());
  each([&](std::size_t k, std::uint32_t i) { s.edges[s.start[k + 1]++] = i; });
  return s;
}

bool PolygonSet::crossings_odd(const std::vector<XY>& r, const RingSlabs& s, const XY& p) {
  if (s.start.empty() || !(p[1] >= s.y0 && p[1] < s.y1)) return false;  // no edge has lo <= p.y < hi
  const std::size_t k = s.slab(p[1]);
  bool in = false;
  for (std::uint32_t e = s.start[k]; e < s.start[k + 1]; ++e) {
    const std::size_t i = s.edges[e], j = i == 0 ? r.size() - 1 : i - 1;
    const auto& a = r[i];
    const auto& b = r[j];
    if ((a[1] > p[1]) != (b[1] > p[1]) && p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0]) in = !in;
  }
  return in;
}

bool PolygonSet::contains(const XY& p) const {
  for (std::size_t k = 0; k < polygons_.size(); ++k) {
    const auto& b = boxes_[k];
    if (p[0] < b[0] || p[0] > b[2] || p[1] < b[1] || p[1] > b[3]) continue;
    const auto& poly = polygons_[k];
    if (poly.outer.size() < 3) continue;
    bool in = crossings_odd(poly.outer, slabs_[k][0], p);
    for (std::size_t h = 0; h < poly.holes.size(); ++h)
      if (poly.holes[h].size() >= 3 && crossings_odd(poly.holes[h], slabs_[k][h + 1], p)) in = !in;
    if (in) return true;
  }
  return false;
}

std::string raster_crs(const std::string& path) {
  QuietGdal quiet;
  GdalDatasetPtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds) open_failed(path, "a raster", "a raster file: GeoTIFF, ...");
  const OGRSpatialReference* rs = ds->GetSpatialRef();
  return rs ? wkt_of(*rs) : "";
}

RasterSampling sample_raster(const std::string& path, int band_no, std::span<const XY> points, const std::string& points_wkt) {
  QuietGdal quiet;
  GdalDatasetPtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds) open_failed(path, "a raster", "a raster file: GeoTIFF, ...");
  if (band_no < 1 || band_no > ds->GetRasterCount())
    throw InputError(path, fmt::format("has {} band(s); band {} does not exist", ds->GetRasterCount(), band_no));
  double gt[6], inv[6];
  if (ds->GetGeoTransform(gt) != CE_None || !GDALInvGeoTransform(gt, inv))
    throw InputError(path, "has no usable georeferencing (geotransform)");
  const OGRSpatialReference* rs = ds->GetSpatialRef();
  const std::string rwkt = rs ? wkt_of(*rs) : "";
  RasterSampling out;
  out.crs = rwkt.empty() ? crs_label(points_wkt) : crs_label(rwkt);
  auto ct = transformation(points_wkt, rwkt, path);

  const int nx = ds->GetRasterXSize(), ny = ds->GetRasterYSize();
  const std::size_t n = points.size();
  out.values.assign(n, std::numeric_limits<double>::quiet_NaN());
  std::vector<double> px(n), py(n);
  std::vector<char> ok(n, 1);
  {
    std::vector<double> x(n), y(n);
    for (std::size_t i = 0; i < n; ++i) x[i] = points[i][0], y[i] = points[i][1];
    if (ct) {
      std::vector<int> success(n, 0);
      ct->Transform(static_cast<int>(n), x.data(), y.data(), nullptr, success.data());
      for (std::size_t i = 0; i < n; ++i) ok[i] = success[i] != 0;
    }
    constexpr double eps = 1e-9;
    for (std::size_t i = 0; i < n; ++i) {
      px[i] = inv[0] + inv[1] * x[i] + inv[2] * y[i];
      py[i] = inv[3] + inv[4] * x[i] + inv[5] * y[i];
      if (!ok[i] || !(px[i] >= -eps && px[i] <= nx + eps && py[i] >= -eps && py[i] <= ny + eps)) {
        ok[i] = 0;
        out.outside.push_back(static_cast<std::uint32_t>(i));
      }
    }
  }
  // Bilinear stencil between pixel centres, clamped to the edge pixels in the outer half pixel.
  std::vector<int> i0(n), j0(n);
  std::vector<double> fx(n), fy(n);
  int wx0 = nx, wy0 = ny, wx1 = -1, wy1 = -1;
  for (std::size_t i = 0; i < n; ++i) {
    if (!ok[i]) continue;
    const double u = std::clamp(px[i] - 0.5, 0.0, nx - 1.0), v = std::clamp(py[i] - 0.5, 0.0, ny - 1.0);
    i0[i] = std::min(static_cast<int>(std::floor(u)), std::max(nx - 2, 0));
    j0[i] = std::min(static_cast<int>(std::floor(v)), std::max(ny - 2, 0));
    fx[i] = u - i0[i];
    fy[i] = v - j0[i];
    wx0 = std::min(wx0, i0[i]);
    wy0 = std::min(wy0, j0[i]);
    wx1 = std::max(wx1, std::min(i0[i] + 1, nx - 1));
    wy1 = std::max(wy1, std::min(j0[i] + 1, ny - 1));
  }
  if (wx1 < 0) return out;
  const int w = wx1 - wx0 + 1, h = wy1 - wy0 + 1;
  GDALRasterBand* band = ds->GetRasterBand(band_no);
  std::vector<double> buf(static_cast<std::size_t>(w) * h);
  if (band->RasterIO(GF_Read, wx0, wy0, w, h, buf.data(), w, h, GDT_Float64, 0, 0) != CE_None)
    throw InputError(path, "cannot read band " + std::to_string(band_no) + ": " + gdal_error());
  std::vector<unsigned char> mask;
  const int flags = band->GetMaskFlags();
  if (!(flags & GMF_ALL_VALID) && !(flags & GMF_NODATA)) {
    mask.resize(buf.size());
    if (band->GetMaskBand()->RasterIO(GF_Read, wx0, wy0, w, h, mask.data(), w, h, GDT_Byte, 0, 0) != CE_None)
      throw InputError(path, "cannot read the mask of band " + std::to_string(band_no) + ": " + gdal_error());
  }
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  int has_scale = 0, has_offset = 0;
  double scale = band->GetScale(&has_scale), offset = band->GetOffset(&has_offset);
  if (!has_scale) scale = 1.0;
  if (!has_offset) offset = 0.0;
  auto valid = [&](std::size_t k) {
    const double v = buf[k];
    if (!std::isfinite(v)) return false;
    if (has_nodata && (v == nodata || (std::isnan(nodata) && std::isnan(v)))) return false;
    if (!mask.empty() && mask[k] == 0) return false;
    return true;
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!ok[i]) continue;
    const int ia = i0[i] - wx0, ja = j0[i] - wy0;
    const int ib = std::min(i0[i] + 1, nx - 1) - wx0, jb = std::min(j0[i] + 1, ny - 1) - wy0;
    const double wts[4] = {(1 - fx[i]) * (1 - fy[i]), fx[i] * (1 - fy[i]), (1 - fx[i]) * fy[i], fx[i] * fy[i]};
    const std::size_t idx[4] = {static_cast<std::size_t>(ja) * w + ia, static_cast<std::size_t>(ja) * w + ib,
                                static_cast<std::size_t>(jb) * w + ia, static_cast<std::size_t>(jb) * w + ib};
    double sum = 0;
    bool good = true;
    for (int k = 0; k < 4; ++k) {
      if (wts[k] == 0) continue;
      if (!valid(idx[k])) {
        good = false;
        break;
      }
      sum += wts[k] * buf[idx[k]];
    }
    if (!good) {
      out.nodata.push_back(static_cast<std::uint32_t>(i));
      continue;
    }
    out.values[i] = sum * scale + offset;
  }
  return out;
}

}  // namespace ugs::geo
