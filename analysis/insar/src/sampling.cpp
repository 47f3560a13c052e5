#include "ugs/insar/sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"

namespace ugs::insar {

Located locate_points(const SurfaceLocator& locator, const std::vector<PsPoint>& points, bool keep_outside) {
  Located r;
  for (const auto& p : points) {
    LocatedPoint lp{p, locator.locate(p.x, p.y)};
    if (lp.hit.inside || keep_outside)
      r.sampled.push_back(std::move(lp));
    else
      r.outside.push_back(std::move(lp));
  }
  return r;
}

void require_some_on_surface(const TopSurface& surface, const PsData& data) {
  const SurfaceLocator locator(surface);
  for (const auto& p : data.points)
    if (locator.locate(p.x, p.y).inside) return;
  const auto e = surface.extent();
  throw InputError(data.path, fmt::format("none of the {} PS points lies on the model's top surface (x {:.0f}..{:.0f}, y "
                                          "{:.0f}..{:.0f}); wrong CRS?", data.points.size(), e[0], e[1], e[2], e[3]));
}

namespace {
std::array<double, 3> interpolate(const std::vector<double>& u, const TopSurface& s, const SurfaceHit& h) {
  std::array<double, 3> v{0, 0, 0};
  const auto& tr = s.triangles[h.triangle];
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j) v[j] += h.weights[k] * u[3 * std::size_t(tr[k]) + j];
  return v;
}
}  // namespace

Samples sample_displacement(SurfaceDisplacement& results, const std::vector<LocatedPoint>& points,
                            std::vector<std::int64_t> dates, std::optional<std::int64_t> reference) {
  Samples s;
  s.points = points;
  s.dates = dates.empty() ? results.times() : std::move(dates);
  s.reference = reference;
  const TopSurface& surf = results.surface();
  std::vector<std::array<double, 3>> ref(points.size(), {0, 0, 0});
  if (reference) {
    const auto u0 = results.at_time(*reference);
    if (!u0)
      throw InputError(results.path(), fmt::format("reference date {} lies outside the results ({} .. {})",
                                                   format_iso_date(*reference), format_iso_date(results.times().front()),
                                                   format_iso_date(results.times().back())));
    for (std::size_t p = 0; p < points.size(); ++p) ref[p] = interpolate(*u0, surf, points[p].hit);
  }
  s.enu.assign(points.size() * s.dates.size() * 3, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t d = 0; d < s.dates.size(); ++d) {
    const auto u = results.at_time(s.dates[d]);
    if (!u) continue;
    for (std::size_t p = 0; p < points.size(); ++p) {
      const auto v = interpolate(*u, surf, points[p].hit);
      double* out = s.enu.data() + (p * s.dates.size() + d) * 3;
      for (int j = 0; j < 3; ++j) out[j] = v[j] - ref[p][j];
    }
  }
  return s;
}

void write_samples_csv(const std::string& path, const Samples& s, const std::vector<LosGeometry>& los,
                       const std::vector<std::string>& comments) {
  std::vector<std::string> cols{"pid",         "date",        "x_m",      "y_m",    "x_surface_m", "y_surface_m",
                                "z_surface_m", "offset_m",    "inside",   "east_mm", "north_mm",   "up_mm"};
  for (const auto& g : los) cols.push_back("los_" + g.name + "_mm");
  CsvWriter w(path, cols, comments);
  std::vector<char> any(s.dates.size(), 0);
  for (std::size_t d = 0; d < s.dates.size(); ++d)
    for (std::size_t p = 0; p < s.points.size() && !any[d]; ++p) any[d] = !std::isnan(s.at(p, d)[0]);
  for (std::size_t p = 0; p < s.points.size(); ++p) {
    const auto& lp = s.points[p];
    for (std::size_t d = 0; d < s.dates.size(); ++d) {
      if (!any[d]) continue;
      const double* u = s.at(p, d);
      w.text(lp.point.id).date(s.dates[d]);
      w.number(lp.point.x, 3).number(lp.point.y, 3);
      w.number(lp.hit.point[0], 3).number(lp.hit.point[1], 3).number(lp.hit.point[2], 3).number(lp.hit.distance, 3);
      w.integer(lp.hit.inside ? 1 : 0);
      for (int j = 0; j < 3; ++j) w.number(u[j] * 1e3, 6);
      for (const auto& g : los) w.number(los_displacement({u[0], u[1], u[2]}, g) * 1e3, 6);
      w.end_row();
    }
  }
  w.commit();
}

Samples read_samples_csv(const std::string& path) {
  const CsvTable t = CsvTable::read(path);
  const auto cp = t.column("pid"), cd = t.column("date"), cx = t.column("x_m"), cy = t.column("y_m"),
             csx = t.column("x_surface_m"), csy = t.column("y_surface_m"), csz = t.column("z_surface_m"),
             co = t.column("offset_m"), ci = t.column("inside"), ce = t.column("east_mm"), cn = t.column("north_mm"),
             cu = t.column("up_mm");
  Samples s;
  std::vector<std::int64_t> dates;
  for (std::size_t r = 0; r < t.rows(); ++r) dates.push_back(t.date(r, cd));
  std::vector<std::int64_t> all = dates;
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  s.dates = all;
  std::vector<std::string> ids;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const std::string id(t.text(r, cp));
    if (std::find(ids.begin(), ids.end(), id) != ids.end()) continue;
    ids.push_back(id);
    LocatedPoint lp;
    lp.point.id = id;
    lp.point.where = t.where(r);
    lp.point.x = t.number(r, cx);
    lp.point.y = t.number(r, cy);
    lp.hit.point = {t.number(r, csx), t.number(r, csy), t.number(r, csz)};
    lp.hit.distance = t.number(r, co);
    lp.hit.inside = t.integer(r, ci) != 0;
    s.points.push_back(lp);
  }
  if (s.points.empty()) throw InputError(t.name(), "no samples");
  s.enu.assign(s.points.size() * s.dates.size() * 3, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const std::size_t p = static_cast<std::size_t>(
        std::find(ids.begin(), ids.end(), std::string(t.text(r, cp))) - ids.begin());
    const std::size_t d = static_cast<std::size_t>(std::lower_bound(s.dates.begin(), s.dates.end(), dates[r]) - s.dates.begin());
    double* u = s.enu.data() + (p * s.dates.size() + d) * 3;
    u[0] = t.number(r, ce) * 1e-3;
    u[1] = t.number(r, cn) * 1e-3;
    u[2] = t.number(r, cu) * 1e-3;
  }
  return s;
}

}  // namespace ugs::insar
