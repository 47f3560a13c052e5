// Horizon grids and triangulated surfaces sampled at the plan's columns. The bilinear stencil is
// geo::sample_raster's (cell corners weighted (1-fx)(1-fy), fx(1-fy), (1-fx)fy, fx fy, zero weights
// skipped, summed in that order), with the grid's nodes where sample_raster has pixel centres.
#include "ugs/meshing/horizon_grids.hpp"

#include <algorithm>
#include <charconv>
#include <string_view>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/formats/io.hpp"
#include "ugs/meshing/gdal_util.hpp"
#include "ugs/meshing/surface_checks.hpp"

namespace ugs::geo {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// ---- ZMAP+ ----------------------------------------------------------------------------------------

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (c == ',') {
      out.push_back(cur);
      cur.clear();
    } else if (c != ' ' && c != '\t' && c != '\r') {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

long long whole(const std::string& t, const std::string& where, const std::string& what, long long lo, long long hi) {
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(t.c_str(), &end, 10);
  if (t.empty() || *end || errno || v < lo || v > hi)
    throw InputError(where, fmt::format("{} '{}' is not a whole number from {} to {}", what, t.substr(0, 40), lo, hi));
  return v;
}

// The lines GDAL's ZMap driver (3.6) reads: each column starts a line, each line holds the column's
// next min(per_line, left) values in fields of `width` characters. GDAL fails on a line that does
// not, without saying where, and ignores values after the last column: both are said here.
void check_zmap_layout(const std::string& path) {
  auto in = InputStream::open(path, "a ZMAP+ grid");
  std::string line;
  std::size_t n = 0;
  auto next = [&] {
    if (!in->getline(line)) return false;
    ++n;
    return true;
  };
  auto at = [&] { return fmt::format("{}:{}", in->name(), n); };
  do {
    if (!next()) throw InputError(at(), "the file ends before the ZMAP+ header");
  } while (line.starts_with("!"));
  auto h1 = split_commas(line.substr(line.starts_with("@") ? 1 : 0));
  if (h1.size() != 3) throw InputError(at(), "expected the ZMAP+ header line @name, GRID, values per line");
  const long long per_line = whole(h1[2], at(), "values per line", 1, 1000);
  if (!next()) throw InputError(at(), "the file ends inside the ZMAP+ header");
  const auto h2 = split_commas(line);
  if (h2.size() != 5) throw InputError(at(), "expected the ZMAP+ header line field width, null value, null text, decimals, 1");
  const long long width = whole(h2[0], at(), "field width", 1, 39);
  if (!next()) throw InputError(at(), "the file ends inside the ZMAP+ header");
  const auto h3 = split_commas(line);
  if (h3.size() != 6) throw InputError(at(), "expected the ZMAP+ header line rows, columns, xmin, xmax, ymin, ymax");
  const long long rows = whole(h3[0], at(), "rows", 2, 10'000'000), cols = whole(h3[1], at(), "columns", 2, 10'000'000);
  if (!next() || !next()) throw InputError(at(), "the file ends inside the ZMAP+ header");
  if (!line.starts_with("@")) throw InputError(at(), "expected the '@' line that ends the ZMAP+ header");
  for (long long c = 0; c < cols; ++c)
    for (long long left = rows; left > 0;) {
      const long long want = std::min(left, per_line);
      if (!next())
        throw InputError(at(), fmt::format("the file ends in column {} of {} with {} of its {} values missing (the "
                                           "header's {} rows x {} columns disagree with the values)",
                                           c + 1, cols, left, rows, rows, cols));
      std::size_t tokens = 0;
      for (std::size_t i = 0; i < line.size();) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        if (i < line.size()) ++tokens;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
      }
      if (tokens != static_cast<std::size_t>(want))
        throw InputError(at(), fmt::format("{} value(s) where column {} of {} expects {} (the header's {} values per line, "
                                           "{} rows x {} columns disagree with the values)",
                                           tokens, c + 1, cols, want, per_line, rows, cols));
      if (line.size() != static_cast<std::size_t>(want * width))
        throw InputError(at(), fmt::format("the line is {} characters long, {} fields of {} make {} (ZMAP+ values are "
                                           "fixed-width fields; no spaces at the end of a line)",
                                           line.size(), want, width, want * width));
      // GDAL reads a field's leading number and ignores the rest ("-21\xff\xff00" is -21), and takes
      // a field without a decimal point as implied decimals: both would be elevations nobody wrote.
      for (long long k = 0; k < want; ++k) {
        std::string_view fld = std::string_view(line).substr(static_cast<std::size_t>(k * width),
                                                             static_cast<std::size_t>(width));
        while (!fld.empty() && (fld.front() == ' ' || fld.front() == '\t')) fld.remove_prefix(1);
        while (!fld.empty() && (fld.back() == ' ' || fld.back() == '\t')) fld.remove_suffix(1);
        std::string_view num = fld.starts_with("+") ? fld.substr(1) : fld;
        double v = 0;
        const auto r = std::from_chars(num.data(), num.data() + num.size(), v);
        if (num.empty() || r.ec != std::errc() || r.ptr != num.data() + num.size() || !std::isfinite(v) ||
            fld.find('.') == std::string_view::npos) {
          std::string shown;
          for (char ch : fld.substr(0, 40)) {
            const auto u = static_cast<unsigned char>(ch);
            shown += u >= 0x20 && u < 0x7f ? std::string(1, ch) : fmt::format("\\x{:02x}", u);
          }
          throw InputError(at(), fmt::format("field {} '{}' is not a finite number with a decimal point (ZMAP+ fields "
                                             "of {} characters; GDAL would read a part of it, or implied decimals)",
                                             k + 1, shown, width));
        }
      }
      left -= want;
    }
  while (next())
    if (line.find_first_not_of(" \t") != std::string::npos)
      throw InputError(at(), fmt::format("values after the last of the header's {} columns of {} rows (the header "
                                         "disagrees with the values)",
                                         cols, rows));
}

// ---- triangulated surfaces --------------------------------------------------------------------

double cross2(const std::array<double, 3>& a, const std::array<double, 3>& b, const std::array<double, 3>& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

}  // namespace

HorizonGrid read_zmap_grid(const std::string& path) {
  check_zmap_layout(path);
  QuietGdal quiet;
  GdalDatasetPtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds || !ds->GetDriver() || std::string(ds->GetDriver()->GetDescription()) != "ZMap")
    throw InputError(path, fmt::format("GDAL's ZMap driver cannot read it: {}", gdal_error()));
  double gt[6];
  if (ds->GetGeoTransform(gt) != CE_None || gt[2] != 0 || gt[4] != 0 || !(gt[1] > 0) || !(gt[5] < 0))
    throw InputError(path, "GDAL gives the ZMAP+ grid no usable georeferencing (xmin < xmax, ymin < ymax expected)");
  HorizonGrid g;
  g.path = path;
  g.format = "ZMAP+";
  g.nx = static_cast<std::size_t>(ds->GetRasterXSize());
  g.ny = static_cast<std::size_t>(ds->GetRasterYSize());
  // ZMAP_PIXEL_IS_POINT (gdal_init): the first pixel's centre is the node (xmin, ymax).
  g.dx = gt[1];
  g.dy = -gt[5];
  g.x0 = gt[0] + 0.5 * gt[1];
  g.y0 = gt[3] + (static_cast<double>(g.ny) - 0.5) * gt[5];
  std::vector<double> buf(g.nx * g.ny);
  GDALRasterBand* band = ds->GetRasterBand(1);
  if (band->RasterIO(GF_Read, 0, 0, static_cast<int>(g.nx), static_cast<int>(g.ny), buf.data(), static_cast<int>(g.nx),
                     static_cast<int>(g.ny), GDT_Float64, 0, 0) != CE_None)
    throw InputError(path, "GDAL's ZMap driver cannot read the values: " + gdal_error());
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  g.z.resize(buf.size());
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      double v = buf[(g.ny - 1 - j) * g.nx + i];
      if (!std::isfinite(v) || (has_nodata && std::fabs(v - nodata) <= 1e-9 * std::max(1.0, std::fabs(nodata)))) {
        v = nan;
        ++g.undefined;
      }
      g.z[j * g.nx + i] = v;
    }
  return g;
}

HorizonSampling sample_grid(const HorizonGrid& g, std::span<const XY> points) {
  HorizonSampling out;
  out.format = g.format;
  const std::size_t n = points.size();
  out.values.assign(n, nan);
  {
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    for (std::size_t i : {std::size_t{0}, g.nx - 1})
      for (std::size_t j : {std::size_t{0}, g.ny - 1}) {
        const auto p = g.node(i, j);
        x0 = std::min(x0, p[0]), y0 = std::min(y0, p[1]), x1 = std::max(x1, p[0]), y1 = std::max(y1, p[1]);
      }
    out.extent = {x0, y0, x1, y1};
  }
  for (std::size_t k = 0; k < n; ++k) {
    switch (horizon_grid_value(g, points[k][0], points[k][1], out.values[k])) {
      case GridPoint::Value: break;
      case GridPoint::Outside: out.outside.push_back(static_cast<std::uint32_t>(k)); break;
      case GridPoint::Undefined: out.undefined.push_back(static_cast<std::uint32_t>(k)); break;
    }
  }
  return out;
}

void check_horizon_surface(const TriangulatedSurface& s) {
  check_surface_topology(s);
  const std::size_t nt = s.triangles.size();
  // Overturned triangles: with one orientation throughout, a single-valued surface faces all up or
  // all down in plan; triangles vertical in plan (no area) are allowed and never sampled.
  double scale = 0;
  for (const auto& p : s.vertices) scale = std::max({scale, std::fabs(p[0]), std::fabs(p[1])});
  std::size_t up = 0, down = 0, first_up = 0, first_down = 0;
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& a = s.vertices[s.triangles[t][0]];
    const auto& b = s.vertices[s.triangles[t][1]];
    const auto& c = s.vertices[s.triangles[t][2]];
    const double d = cross2(a, b, c);
    const double l2 = std::max({(b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]),
                                (c[0] - a[0]) * (c[0] - a[0]) + (c[1] - a[1]) * (c[1] - a[1])});
    if (std::fabs(d) <= 1e-9 * l2) continue;
    if (d > 0 && up++ == 0) first_up = t;
    if (d < 0 && down++ == 0) first_down = t;
  }
  if (up && down) {
    const bool few_down = down <= up;
    const std::size_t t = few_down ? first_down : first_up;
    throw at_triangle(s, t,
                      fmt::format("the surface folds over itself: {} triangle(s) face {} in plan while {} face {} (first "
                                  "the other way: line {}); a horizon must have one elevation at each x, y",
                                  few_down ? down : up, few_down ? "down" : "up", few_down ? up : down,
                                  few_down ? "up" : "down", s.triangle_line[few_down ? first_up : first_down]));
  }
  check_surface_self_intersections(s);
}

HorizonSampling sample_tsurf(const TriangulatedSurface& s, std::span<const XY> points) {
  HorizonSampling out;
  out.format = "GOCAD TSurf";
  const std::size_t n = points.size(), nt = s.triangles.size();
  out.values.assign(n, nan);
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for (const auto& p : s.vertices)
    x0 = std::min(x0, p[0]), y0 = std::min(y0, p[1]), x1 = std::max(x1, p[0]), y1 = std::max(y1, p[1]);
  out.extent = {x0, y0, x1, y1};
  // A uniform bin grid over the surface's extent, about one triangle per bin.
  const std::size_t nb = std::clamp<std::size_t>(static_cast<std::size_t>(std::sqrt(static_cast<double>(nt))), 1, 2048);
  const double bw = std::max((x1 - x0) / static_cast<double>(nb), 1e-300),
               bh = std::max((y1 - y0) / static_cast<double>(nb), 1e-300);
  auto bin = [&](double v, double lo, double w) {
    return std::min(nb - 1, static_cast<std::size_t>(std::max(0.0, std::floor((v - lo) / w))));
  };
  std::vector<std::vector<std::uint32_t>> bins(nb * nb);
  for (std::uint32_t t = 0; t < nt; ++t) {
    double tx0 = std::numeric_limits<double>::infinity(), ty0 = tx0, tx1 = -tx0, ty1 = -tx0;
    for (auto v : s.triangles[t]) {
      const auto& p = s.vertices[v];
      tx0 = std::min(tx0, p[0]), ty0 = std::min(ty0, p[1]), tx1 = std::max(tx1, p[0]), ty1 = std::max(ty1, p[1]);
    }
    for (std::size_t j = bin(ty0, y0, bh); j <= bin(ty1, y0, bh); ++j)
      for (std::size_t i = bin(tx0, x0, bw); i <= bin(tx1, x0, bw); ++i) bins[j * nb + i].push_back(t);
  }
  const double tol_z = 1e-6;
  for (std::size_t k = 0; k < n; ++k) {
    const double px = points[k][0], py = points[k][1];
    const double pad = 1e-9 * std::max(x1 - x0, y1 - y0);
    if (!(px >= x0 - pad && px <= x1 + pad && py >= y0 - pad && py <= y1 + pad)) {
      out.outside.push_back(static_cast<std::uint32_t>(k));
      continue;
    }
    bool found = false;
    std::uint32_t first = 0;
    double z = nan;
    for (auto t : bins[bin(py, y0, bh) * nb + bin(px, x0, bw)]) {
      const auto& a = s.vertices[s.triangles[t][0]];
      const auto& b = s.vertices[s.triangles[t][1]];
      const auto& c = s.vertices[s.triangles[t][2]];
      const double d = cross2(a, b, c);
      if (d == 0) continue;
      const std::array<double, 3> p{px, py, 0};
      const double l0 = cross2(p, b, c) / d, l1 = cross2(a, p, c) / d, l2 = cross2(a, b, p) / d;
      constexpr double eps = 1e-9;
      if (l0 < -eps || l1 < -eps || l2 < -eps) continue;
      const double zt = l0 * a[2] + l1 * b[2] + l2 * c[2];
      if (!found) {
        found = true, first = t, z = zt;
      } else if (std::fabs(zt - z) > tol_z) {
        throw at_triangle(s, t,
                          fmt::format("the surface has two elevations at x={:.2f}, y={:.2f}: {:.3f} m on this triangle, "
                                      "{:.3f} m on the one of line {} (a horizon must be single-valued)",
                                      px, py, zt, z, s.triangle_line[first]));
      }
    }
    if (found) out.values[k] = z;
    else out.outside.push_back(static_cast<std::uint32_t>(k));
  }
  return out;
}

HorizonSampling sample_horizon(const std::string& path, const std::string& surface_wkt, std::span<const XY> points,
                               const std::string& points_wkt) {
  const HorizonFormat f = detect_horizon_format(path);
  std::vector<XY> pts(points.begin(), points.end());
  std::vector<char> moved(pts.size(), 1);
  if (auto ct = transformation(points_wkt, surface_wkt, path)) {
    QuietGdal quiet;
    std::vector<double> x(pts.size()), y(pts.size());
    std::vector<int> ok(pts.size(), 0);
    for (std::size_t i = 0; i < pts.size(); ++i) x[i] = pts[i][0], y[i] = pts[i][1];
    ct->Transform(static_cast<int>(pts.size()), x.data(), y.data(), nullptr, ok.data());
    for (std::size_t i = 0; i < pts.size(); ++i) {
      pts[i] = {x[i], y[i]};
      moved[i] = ok[i] != 0;
    }
  }
  HorizonSampling out;
  switch (f) {
    case HorizonFormat::Irap: out = sample_grid(read_irap_grid(path), pts); break;
    case HorizonFormat::Cps3: out = sample_grid(read_cps3_grid(path), pts); break;
    case HorizonFormat::Zmap: out = sample_grid(read_zmap_grid(path), pts); break;
    case HorizonFormat::Tsurf: {
      const TriangulatedSurface s = read_gocad_tsurf(path);
      check_horizon_surface(s);
      out = sample_tsurf(s, pts);
      if (s.merged_vertices)
        out.cleaned.push_back(fmt::format("{}: {} vertices at the same x, y, z as an earlier one were merged into it",
                                          path, s.merged_vertices));
      if (s.depth_positive) out.notes.push_back(fmt::format("{}: ZPOSITIVE Depth: z read as depth (elevation = -z)", path));
      break;
    }
    case HorizonFormat::Unknown:
      throw InputError(path, "is none of the horizon formats read (expected IRAP classic ASCII starting -996, CPS-3 "
                             "ASCII starting FSASCI, ZMAP+ starting @name, GRID, or GOCAD TSurf)");
  }
  // Points that could not be transformed count as outside.
  std::vector<std::uint32_t> outside;
  for (std::size_t i = 0, o = 0; i < pts.size(); ++i) {
    const bool was = o < out.outside.size() && out.outside[o] == i;
    if (was) ++o;
    if (was || !moved[i]) {
      outside.push_back(static_cast<std::uint32_t>(i));
      out.values[i] = nan;
    }
  }
  out.outside = std::move(outside);
  std::erase_if(out.undefined, [&](std::uint32_t i) { return !moved[i]; });
  return out;
}

}  // namespace ugs::geo
