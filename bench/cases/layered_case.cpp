#include "layered_case.hpp"

#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"

namespace ugs::cases {
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

Mesh submesh(const Mesh& m, const std::vector<std::string>& materials) {
  Mesh s;
  std::vector<std::int64_t> local(m.num_nodes(), -1);
  for (const auto& b : m.blocks) {
    if (b.type != ElementType::Tetrahedron) continue;
    const std::string name = m.physical_name_of(b.entity_dim, b.entity_tag);
    bool keep = false;
    for (const auto& mat : materials) keep = keep || name == "mat:" + mat;
    if (!keep) continue;
    const int e = s.entity_for_physical(3, name);
    for (std::size_t i = 0; i < b.size(); ++i) {
      std::uint32_t n[4];
      const auto el = b.element(i);
      for (int k = 0; k < 4; ++k) {
        if (local[el[k]] < 0) local[el[k]] = s.add_node(m.nodes[el[k]], m.node_tags[el[k]]);
        n[k] = static_cast<std::uint32_t>(local[el[k]]);
      }
      s.add_element(s.block(3, e, ElementType::Tetrahedron), n, b.tags[i]);
    }
  }
  s.update_entity_bboxes();
  return s;
}

void write_pressure(const fs::path& path, const Mesh& sub, const Series& s) {
  FieldSeriesWriter w(path.string(), sub);
  for (std::size_t k = 0; k < s.dates.size(); ++k) {
    Field f{"dp", 1, std::vector<double>(sub.num_nodes())};
    for (std::size_t v = 0; v < sub.num_nodes(); ++v) f.values[v] = s.dp(sub.nodes[v], k);
    const Field nodes[] = {f};
    w.add_step(s.dates[k], static_cast<double>(*parse_iso_date(s.dates[k])), nodes);
  }
  w.commit();
}

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream f(p);
  f << text;
}

std::vector<std::string> monthly(int y0, int m0, int y1, int m1) {
  std::vector<std::string> d;
  for (int y = y0, m = m0; y < y1 || (y == y1 && m <= m1);) {
    d.push_back(fmt::format("{:04d}-{:02d}-01", y, m));
    if (++m == 13) m = 1, ++y;
  }
  return d;
}

std::string layered_case(const std::string& extra) {
  return R"(# Layered test model: elastic rock, two hypo-plastic pools with aquifers.
[initial_stress]
surface_elevation_m = 0
lithostatic_gradient_MPa_per_m = 0.0226
hydrostatic_gradient_MPa_per_m = 0.0100
k0 = 0.9

[[material]]
name = "rock"
law = "elastic"
nu = 0.3

[[material]]
name = "pool_a"
law = "hypoplastic"
nu_z = 0.3
Eh_over_Ez = 3.0
nuh_over_nuz = 0.2
c_R = 5

[[material]]
name = "aquifer_a"
law = "hypoplastic"
nu_z = 0.3
Eh_over_Ez = 3.0
nuh_over_nuz = 0.2
c_R = 5

[[material]]
name = "pool_c"
law = "hypoplastic"
nu_z = 0.3
Eh_over_Ez = 3.0
nuh_over_nuz = 0.2
c_R = 3

[[material]]
name = "aquifer_c"
law = "hypoplastic"
nu_z = 0.3
Eh_over_Ez = 3.0
nuh_over_nuz = 0.2
c_R = 3
)" + extra;
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

}  // namespace ugs::cases
