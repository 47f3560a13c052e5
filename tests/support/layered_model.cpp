#include "layered_model.hpp"

#include <cmath>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "pressure_files.hpp"

namespace ugs::testcase {
namespace fs = std::filesystem;
namespace {

// Pool pressure (normalized drop): primary production to `drop` by year 10, then seasonal cycles
// (minimum 1 April, maximum 1 November) between drop_min and drop_max.
double pool_drop(double years, double drop, double cyc_lo, double cyc_hi) {
  if (years <= 0) return 0;
  if (years < 10) return drop * std::pow(years / 10, 1.3);
  const double y = years - 10, ph = y - std::floor(y);  // phase within the year from 1 January
  // from 1 Apr (0.25) to 1 Nov (0.83) rising (pressure up = drop down), falling otherwise
  auto mix = [&](double t) { return 0.5 * (1 - std::cos(M_PI * t)); };
  double v;
  if (ph >= 0.25 && ph < 0.833) v = cyc_lo + (cyc_hi - cyc_lo) * mix((ph - 0.25) / 0.583);
  else {
    const double t = ph >= 0.833 ? (ph - 0.833) / 0.417 : (ph + 0.167) / 0.417;
    v = cyc_hi + (cyc_lo - cyc_hi) * mix(t);
  }
  const double ramp = std::min(1.0, y);  // from the end of production into the cycles
  return (1 - ramp) * drop + ramp * v;
}

double years_since(const std::string& d, int y0) {
  return (static_cast<double>(*parse_iso_date(d)) - static_cast<double>(*parse_iso_date(fmt::format("{:04d}-01-01", y0)))) /
         (365.2425 * 86400.0);
}

}  // namespace

CaseToml layered_case() {
  CaseToml c("# Layered test model: elastic rock, two hypo-plastic pools with aquifers.\n");
  c.initial_stress({.surface_elevation_m = 0, .k0 = 0.9}).material(elastic("rock", 0.3));
  c.material(hypoplastic("pool_a", 5)).material(hypoplastic("aquifer_a", 5));
  c.material(hypoplastic("pool_c", 3)).material(hypoplastic("aquifer_c", 3));
  return c;
}

std::string material_of(const Layered& L, const Point3& c) {
  const double rx = c[0] - L.lx / 2, ry = (c[1] - L.ly / 2) / 0.7;
  const double r = std::hypot(rx, ry);
  if (c[2] < L.ztop_a && c[2] > L.zbot_a) return r < L.ra ? "pool_a" : r < L.raq ? "aquifer_a" : "rock";
  if (c[2] < L.ztop_c && c[2] > L.zbot_c) return r < L.rc ? "pool_c" : r < L.raq ? "aquifer_c" : "rock";
  return "rock";
}

void write_pools(const fs::path& dir, const Mesh& m, const Layered& L, const std::vector<std::string>& dates, int y0,
                 double p0) {
  auto dp_at = [&](double drop_scale, double r_pool, double lo, double hi) {
    return [=, &L, &dates](const Point3& x, std::size_t k) {
      const double r = std::hypot(x[0] - L.lx / 2, (x[1] - L.ly / 2) / 0.7);
      const double d = std::max(0.0, r - r_pool);
      // The aquifer follows the pool with a delay and decays with distance from its edge.
      const double lag = d / 1500.0;  // years
      return -p0 * drop_scale * pool_drop(years_since(dates[k], y0) - lag, 0.5, lo, hi) * std::exp(-d / 2000.0);
    };
  };
  Series a{dates, dp_at(0.9, L.ra, 0.30, 0.05)};
  write_pressure(dir / "flow_pool_a.h5", submesh(m, {"pool_a", "aquifer_a"}), a);
  Series c{dates, dp_at(1.0, L.rc, 0.55, 0.12)};
  write_pressure(dir / "flow_pool_c.h5", submesh(m, {"pool_c", "aquifer_c"}), c);
}

}  // namespace ugs::testcase
