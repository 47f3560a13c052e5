// Maps of the land displacement over each phase (thesis figures 4.21-4.26, 4.37-4.39): u_x, u_y,
// u_z change between the phase's dates on the top surface, as PNG (with the reservoir trace and the
// PS points) and as GeoTIFF on a regular grid; the headline uplift, settlement and horizontal motion.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "report.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/insar/inputs.hpp"
#include "ugs/insar/npy.hpp"
#include "ugs/insar/raster.hpp"

namespace ugs::report {

namespace {

std::array<double, 4> map_extent(const Context& c) {
  const auto e = c.top->extent();
  if (!c.opt.map_extent.empty()) {
    const auto v = insar::parse_number_list("--map-extent", c.opt.map_extent, 4, "XMIN/XMAX/YMIN/YMAX");
    if (!(v[0] < v[1]) || !(v[2] < v[3]))
      throw InputError("--map-extent", fmt::format("'{}': XMIN/YMIN are not below XMAX/YMAX", c.opt.map_extent));
    return {v[0], v[1], v[2], v[3]};
  }
  if (c.trace_lines.empty()) return e;
  // The trace and as much again on every side (the thesis' maps show the field and its surroundings).
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& l : c.trace_lines)
    for (const auto& p : l) x0 = std::min(x0, p[0]), x1 = std::max(x1, p[0]), y0 = std::min(y0, p[1]), y1 = std::max(y1, p[1]);
  const double m = std::max(x1 - x0, y1 - y0);
  return {std::max(e[0], x0 - m), std::min(e[1], x1 + m), std::max(e[2], y0 - m), std::min(e[3], y1 + m)};
}

std::string phase_thesis(const std::string& name, const char* what) {
  const std::string n = slug(name);
  const std::string w = what;
  if (n.find("forecast") != std::string::npos) return w == "uplift" ? "up to 5 mm (storage May-Nov 2025)" : "";
  if (n.find("storage") != std::string::npos || n.find("injection") != std::string::npos) {
    if (w == "uplift") return "up to about 4 mm (May-Nov 2015)";
    if (w == "horizontal") return "a few mm, away from the centre";
  }
  if (n.find("production") != std::string::npos || n.find("supply") != std::string::npos ||
      n.find("withdrawal") != std::string::npos) {
    if (w == "settlement") return "under 2 mm (Nov 2015-May 2016)";
    if (w == "horizontal") return "a few mm, towards the centre";
  }
  return "";
}

}  // namespace

void build_maps(Context& c) {
  if (!c.top) {
    c.notes.push_back("no top surface: displacement maps skipped");
    return;
  }
  std::unique_ptr<insar::SurfaceDisplacement> disp;
  try {
    disp = std::make_unique<insar::SurfaceDisplacement>(c.surface_results, *c.top, "");
  } catch (const InputError& e) {
    c.notes.push_back(fmt::format("displacement maps skipped: {}", e.what()));
    return;
  }
  const auto& top = *c.top;
  std::vector<double> xy;
  for (const auto& p : top.points) xy.insert(xy.end(), {p[0], p[1]});
  std::vector<std::int32_t> tri;
  for (const auto& t : top.triangles)
    for (auto n : t) tri.push_back(static_cast<std::int32_t>(n));
  insar::write_npy(c.work_file("top_xy.npy"), xy, {top.points.size(), 2});
  insar::write_npy(c.work_file("top_tri.npy"), tri, {top.triangles.size(), 3});
  const auto ext = map_extent(c);
  const insar::SurfaceLocator locator(top);
  const auto grid = insar::grid_for_extent(top.extent(), c.opt.raster_cell);
  const auto hits = insar::locate_grid(locator, grid);
  static const char* kComp[3] = {"x", "y", "z"};
  static const char* kDir[3] = {"west-east", "south-north", "vertical"};
  for (const auto& ph : c.phases) {
    const auto a = disp->at_time(ph.start), b = disp->at_time(ph.end);
    if (!a || !b)
      throw InputError(c.surface_results, fmt::format("phase {} lies outside the results ({} .. {})", ph.label(),
                                                   format_iso_date(disp->times().front()), format_iso_date(disp->times().back())));
    std::vector<double> d(a->size());
    for (std::size_t i = 0; i < d.size(); ++i) d[i] = ((*b)[i] - (*a)[i]) * 1e3;  // mm
    double up = -1e300, down = 1e300, hz = 0;
    std::size_t iu = 0, id = 0;
    for (std::size_t n = 0; n < top.points.size(); ++n) {
      if (d[3 * n + 2] > up) up = d[3 * n + 2], iu = n;
      if (d[3 * n + 2] < down) down = d[3 * n + 2], id = n;
      hz = std::max(hz, std::hypot(d[3 * n], d[3 * n + 1]));
    }
    const std::string g = ph.label();
    auto keep = [&](const char* key, double v, std::size_t n) {
      auto& m = c.measures[key];
      if (m.where.empty() || v > m.value)
        m = {v, fmt::format("{} at x {:.0f}, y {:.0f}", ph.label(), top.points[n][0], top.points[n][1])};
    };
    keep("uplift_max_mm", std::max(up, 0.0), iu);
    keep("settlement_max_mm", std::max(-down, 0.0), id);
    auto where = [&](double v, std::size_t n) {
      return v > 0 ? fmt::format("{} mm at x {:.0f}, y {:.0f}", mm(v), top.points[n][0], top.points[n][1]) : std::string("none");
    };
    c.headlines.push_back({g, "maximum uplift", where(up, iu), phase_thesis(ph.name, "uplift")});
    c.headlines.push_back({g, "maximum settlement", where(-down, id), phase_thesis(ph.name, "settlement")});
    c.headlines.push_back({g, "maximum horizontal displacement", mm(hz) + " mm", phase_thesis(ph.name, "horizontal")});
    for (int k = 0; k < 3; ++k) {
      std::vector<double> v(top.points.size());
      for (std::size_t n = 0; n < v.size(); ++n) v[n] = d[3 * n + k];
      const std::string stem = fmt::format("u{}_{}", kComp[k], slug(ph.name));
      insar::write_npy(c.work_file(stem + ".npy"), v, {v.size()});
      Figure f;
      f.kind = "map";
      f.png = stem + ".png";
      f.title = fmt::format("u_{} ({}), {}", kComp[k], kDir[k], ph.label());
      f.caption = fmt::format("Displacement u_{} ({}) from the simulation over the {} phase, {} to {} (mm).", kComp[k],
                              kDir[k], ph.name, format_iso_date(ph.start), format_iso_date(ph.end));
      f.json = fmt::format("\"nodes\": {}, \"triangles\": {}, \"values\": {}, \"label\": {}, \"extent\": [{}, {}, {}, {}], "
                           "\"trace\": {}, \"points\": {}, \"symmetric\": true",
                           jwork("top_xy.npy"), jwork("top_tri.npy"), jwork(stem + ".npy"),
                           jstr(fmt::format("u_{} (mm)", kComp[k])), ext[0], ext[1], ext[2], ext[3],
                           c.trace_lines.empty() ? "null" : jwork("trace.csv"),
                           c.measured_up ? jwork("ps_points.csv") : std::string("null"));
      c.add(f);
      insar::RasterBand band{insar::grid_values(hits, top, d, 3, k, 1.0),
                             fmt::format("u_{} change {} to {} (mm)", kComp[k], format_iso_date(ph.start), format_iso_date(ph.end))};
      insar::write_geotiff(c.out + "/" + stem + ".tif", grid, {band}, c.crs_wkt, "mm");
      c.written.push_back(stem + ".tif");
    }
  }
}

}  // namespace ugs::report
