// Synthetic "measured" InSAR series for the calibration twins: a results file sampled at PS
// points, relative to the first date, plus seeded Gaussian noise, written in the EGMS ortho
// layout (easting/northing in EPSG:3035, one column per YYYYMMDD date, mm).
#pragma once
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/io.hpp"
#include "ugs/insar/crs.hpp"
#include "ugs/insar/displacement.hpp"
#include "ugs/insar/sampling.hpp"
#include "ugs/insar/surface.hpp"

namespace ugs::test {

struct TwinPoint {
  std::string id;
  double x, y;  // EPSG:32632
};

// Monthly dates on the 11th, as the Radarsat part of the sample twin.
inline std::vector<std::int64_t> monthly_dates(int y0, int m0, int y1, int m1) {
  std::vector<std::int64_t> d;
  for (int y = y0, m = m0; y < y1 || (y == y1 && m <= m1);) {
    d.push_back(days_from_civil(y, m, 11) * 86400);
    if (++m > 12) m = 1, ++y;
  }
  return d;
}

// component: 0 east, 2 up. Writes `path`; returns nothing (throws on error).
inline void write_twin_egms(const std::string& results_h5, const std::vector<TwinPoint>& pts,
                            const std::vector<std::int64_t>& dates, int component, double noise_mm, unsigned seed,
                            const std::string& path) {
  using namespace ugs::insar;
  const FieldSeriesReader r(results_h5);
  const TopSurface top = surface_from_results(r);
  const SurfaceLocator loc(top);
  SurfaceDisplacement res(results_h5, top);
  std::vector<PsPoint> ps;
  for (const auto& p : pts) ps.push_back({p.id, p.x, p.y, {}, ""});
  const Located l = locate_points(loc, ps, false);
  if (l.sampled.size() != pts.size()) throw std::runtime_error("twin point outside the surface");
  const Samples s = sample_displacement(res, l.sampled, dates, dates.front());
  std::vector<double> x, y;
  for (const auto& p : pts) x.push_back(p.x), y.push_back(p.y);
  CoordinateTransform ct(any_crs_wkt("EPSG:32632", "twin"), any_crs_wkt("EPSG:3035", "twin"), "twin");
  ct.apply(x, y, {});
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_mm);
  std::string text = "pid,easting,northing,height,rmse,mean_velocity,mean_velocity_std";
  for (auto t : dates) {
    const auto c = civil_from_days(t / 86400);
    text += fmt::format(",{:04d}{:02d}{:02d}", c.year, c.month, c.day);
  }
  text += "\n";
  for (std::size_t p = 0; p < pts.size(); ++p) {
    text += fmt::format("{},{:.3f},{:.3f},30.0,1.5,0.0,0.1", pts[p].id, x[p], y[p]);
    for (std::size_t d = 0; d < dates.size(); ++d)
      text += fmt::format(",{:.2f}", s.at(p, d)[component] * 1e3 + (d == 0 ? 0.0 : noise(rng)));
    text += "\n";
  }
  OutputFile f(path);
  f.write(text);
  f.commit();
}

}  // namespace ugs::test
