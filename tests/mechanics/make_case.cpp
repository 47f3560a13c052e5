// mech_make_case — writes ugs-solve test and benchmark cases: a box mesh (MSH), a case file and
// the pressure-change field series that ugs-flow would write for each pool (node field dp on the
// pool's sub-mesh, parent node and element tags). Used by tests/mechanics and bench/solve.
//
//   mech_make_case column DIR [--rule sigma-max]   V1 oedometer column, path 20-26-23-28-25 MPa
//   mech_make_case geertsma DIR [--refine F]       V2 disk reservoir (quarter domain, symmetry rollers)
//   mech_make_case small DIR [--refine F]           layered model, two pools, monthly across an inversion
//   mech_make_case thesis DIR [--history] [--linear] [--scale F]
//                                                   thesis-scale layered box (~500k nodes): one linear
//                                                   step (--linear) or the monthly 1950-2033 history
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/box_mesh.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

// Sub-mesh of the tetrahedra of `materials`, keeping parent node and element tags (as ugs-submesh).
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

struct Series {
  std::vector<std::string> dates;
  // dp [Pa] at a node of the sub-mesh for step k.
  std::function<double(const Point3&, std::size_t k)> dp;
};

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

// ---- V1 column --------------------------------------------------------------------------------
void make_column(const fs::path& dir, const std::string& rule) {
  const double d20 = 20.0 / 0.0126, H = 1.0;
  BoxMeshSpec spec;
  spec.x = {0, 1};
  spec.y = {0, 1};
  spec.z = linspace(-d20 - H / 2, -d20 + H / 2, 4);
  const Mesh m = make_box_mesh(spec);
  write_msh(m, (dir / "mesh.msh").string());
  write_text(dir / "case.toml", fmt::format(R"(# V1: oedometer column, sigma'_v0 = 20 MPa at its centre (VERIFICATION.md)
[initial_stress]
lithostatic_gradient_MPa_per_m = 0.0226
hydrostatic_gradient_MPa_per_m = 0.0100

[[material]]
name = "rock"
law = "hypoplastic"
nu_z = 0.3
Eh_over_Ez = 3.0
nuh_over_nuz = 0.2
c_R = 3.0

[boundary]
fixed = ["bottom"]
rollers = ["west", "east", "south", "north"]
free = ["top"]

[solver]
inversion_rule = "{}"
)", rule));
  Series s;
  s.dates = {"2000-01-01", "2001-01-01", "2002-01-01", "2003-01-01", "2004-01-01"};
  const double dp[] = {0, -6e6, -3e6, -8e6, -5e6};
  s.dp = [&](const Point3&, std::size_t k) { return dp[k]; };
  write_pressure(dir / "flow.h5", m, s);
}

// ---- V2 Geertsma ------------------------------------------------------------------------------
void make_geertsma(const fs::path& dir, double refine) {
  // eta = D / R = 1: the reference values of VERIFICATION.md V2 are tabulated for it.
  const double D = 1500, R = 1500, h = 50, L = 10 * R, depth = 10 * D;
  // Plan: uniform inside 1.6 R, graded to 10 R. Vertical: the reservoir in 4 layers, graded away.
  const double hx = 100 / refine;
  std::vector<double> x = linspace(0, 1.6 * R, static_cast<int>(std::lround(1.6 * R / hx)));
  for (double v : graded(1.6 * R, L, hx * 1.3, 1.3)) if (v > x.back()) x.push_back(v);
  std::vector<double> z;
  const double top = -D + h / 2, bot = -D - h / 2, hz = h / std::max(2.0, std::round(4 * refine));
  for (double v : graded(0, depth - (-bot), hz * 1.25, 1.25)) z.push_back(bot - v);  // below, downwards
  std::reverse(z.begin(), z.end());
  z.pop_back();
  for (double v : linspace(bot, top, static_cast<int>(std::lround(h / hz)))) z.push_back(v);
  for (double v : graded(0, -top, hz * 1.25, 1.25)) if (v > 0) z.push_back(top + v);
  z.back() = 0.0;
  BoxMeshSpec spec;
  spec.x = x;
  spec.y = x;
  spec.z = z;
  spec.material = [&](const Point3& c) {
    return (std::hypot(c[0], c[1]) < R && c[2] < top && c[2] > bot) ? std::string("reservoir") : std::string("rock");
  };
  const Mesh m = make_box_mesh(spec);
  write_msh(m, (dir / "mesh.msh").string());
  write_text(dir / "case.toml", R"(# V2: Geertsma disk (D = R = 1500 m, h = 50 m, dp = -10 MPa, E = 10 GPa, nu = 0.25).
# Quarter domain: rollers on the symmetry planes x = 0 (west) and y = 0 (south).
[[material]]
name = "rock"
law = "linear"
E_MPa = 10000
nu = 0.25

[[material]]
name = "reservoir"
law = "linear"
E_MPa = 10000
nu = 0.25

[boundary]
fixed = ["bottom", "east", "north"]
rollers = ["west", "south"]
free = ["top"]
)");
  Series s;
  s.dates = {"2000-01-01", "2001-01-01"};
  s.dp = [](const Point3&, std::size_t k) { return k == 0 ? 0.0 : -10e6; };
  write_pressure(dir / "flow.h5", submesh(m, {"reservoir"}), s);
  std::fprintf(stderr, "geertsma: %zu nodes, %zu tetrahedra\n", m.num_nodes(), m.count(ElementType::Tetrahedron));
}

// ---- a small layered model with two pools -----------------------------------------------------
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

struct Layered {
  double lx, ly, ztop_a, zbot_a, ztop_c, zbot_c, ra, rc, raq;  // pools: ellipse semi-axes ra/rc (x), 0.7 in y
};

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

void make_small(const fs::path& dir, double refine) {
  Layered L{3000, 2000, -1400, -1440, -1460, -1490, 700, 600, 1100};
  BoxMeshSpec spec;
  spec.x = linspace(0, L.lx, static_cast<int>(std::lround(12 * refine)));
  spec.y = linspace(0, L.ly, static_cast<int>(std::lround(8 * refine)));
  spec.z = {-2500, -2000, -1700, -1550, -1490, -1475, -1460, -1450, -1440, -1420, -1400, -1300, -1000, -500, 0};
  spec.material = [&](const Point3& c) { return material_of(L, c); };
  const Mesh m = make_box_mesh(spec);
  write_msh(m, (dir / "mesh.msh").string());
  write_text(dir / "case.toml", layered_case(R"(
[[pool]]
name = "Pool A"
materials = ["pool_a"]
aquifer_materials = ["aquifer_a"]
schedule = "unused.csv"
column = "p_MPa"

[output]
dates = ["1960-03-01", "1960-09-01"]
)"));
  // Monthly through the end of production and into the first cycle: load inversions.
  write_pools(dir, m, L, monthly(1959, 10, 1960, 9), 1950, 15e6);
  std::fprintf(stderr, "small: %zu nodes, %zu tetrahedra\n", m.num_nodes(), m.count(ElementType::Tetrahedron));
}

// ---- thesis scale -----------------------------------------------------------------------------
// Coordinates from lo to hi: spacing h inside [c - w, c + w], growing geometrically outside so
// that the total count is n intervals.
std::vector<double> focused(double lo, double hi, double c, double w, int n) {
  // Find the growth ratio giving n intervals.
  auto build = [&](double ratio) {
    const int ni = static_cast<int>(std::lround(2 * w / 50.0));
    std::vector<double> v = linspace(c - w, c + w, ni);
    double hgrow = 2 * w / ni;
    std::vector<double> left, right;
    double xl = c - w, xr = c + w, h = hgrow;
    while (xl > lo) {
      h *= ratio;
      xl -= h;
      left.push_back(std::max(xl, lo));
    }
    h = hgrow;
    while (xr < hi) {
      h *= ratio;
      xr += h;
      right.push_back(std::min(xr, hi));
    }
    std::vector<double> out(left.rbegin(), left.rend());
    out.insert(out.end(), v.begin(), v.end());
    out.insert(out.end(), right.begin(), right.end());
    // Merge a sliver at the ends.
    if (out.size() > 2 && out[1] - out[0] < 0.3 * (out[2] - out[1])) out.erase(out.begin() + 1);
    const std::size_t k = out.size();
    if (k > 2 && out[k - 1] - out[k - 2] < 0.3 * (out[k - 2] - out[k - 3])) out.erase(out.end() - 2);
    return out;
  };
  double lo_r = 1.0001, hi_r = 3.0;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo_r + hi_r);
    if (static_cast<int>(build(mid).size()) - 1 > n) lo_r = mid;
    else hi_r = mid;
  }
  return build(hi_r);
}

void make_thesis(const fs::path& dir, bool history, bool linear, double scale) {
  // Domain 42 x 30 km, bottom -10 km; the surfaces of Table 4.1 (flat) with their sub-layers.
  const double LX = 42000, LY = 30000;
  Layered L{LX, LY, -1410, -1476, -1498, -1515, 2200, 1800, 4000};
  const int nx = static_cast<int>(std::lround(130 * std::sqrt(scale))), ny = static_cast<int>(std::lround(94 * std::sqrt(scale)));
  BoxMeshSpec spec;
  spec.x = focused(0, LX, LX / 2, 1500 * std::sqrt(scale), nx);
  spec.y = focused(0, LY, LY / 2, 1100 * std::sqrt(scale), ny);
  const std::vector<std::pair<double, int>> surfaces{{50, 2},    {-346, 2},  {-1024, 2}, {-1152, 3}, {-1410, 5}, {-1476, 3},
                                                     {-1498, 8}, {-1515, 2}, {-1543, 10}, {-8655, 2}, {-10000, 0}};
  std::vector<double> z;
  for (std::size_t i = surfaces.size() - 1; i > 0; --i) {
    const auto seg = linspace(surfaces[i].first, surfaces[i - 1].first, surfaces[i - 1].second);
    for (double v : seg)
      if (z.empty() || v > z.back()) z.push_back(v);
  }
  spec.z = z;
  spec.material = [&](const Point3& c) {
    if (linear) return std::hypot(c[0] - LX / 2, (c[1] - LY / 2) / 0.7) < L.rc && c[2] < L.ztop_c && c[2] > L.zbot_c
                           ? std::string("pool_c")
                           : std::string("rock");
    return material_of(L, c);
  };
  const Mesh m = make_box_mesh(spec);
  write_msh(m, (dir / "mesh.msh").string());
  std::fprintf(stderr, "thesis: %zu x %zu x %zu nodes = %zu nodes, %zu tetrahedra\n", spec.x.size(), spec.y.size(),
               spec.z.size(), m.num_nodes(), m.count(ElementType::Tetrahedron));
  if (linear) {
    // One linear-elastic solve: depth-dependent elastic units everywhere, Pool C depleted by 10 MPa.
    write_text(dir / "case.toml", R"(# Thesis-scale linear elastic benchmark (bench/solve): elastic units with c_M from eq. 4.1
# at the initial effective stress, isotropic nu = 0.3; Pool C depleted by 10 MPa.
[initial_stress]
surface_elevation_m = 50
lithostatic_gradient_MPa_per_m = 0.0226
hydrostatic_gradient_MPa_per_m = 0.0100
k0 = 0.9

[[material]]
name = "rock"
law = "elastic"
nu = 0.3

[[material]]
name = "pool_c"
law = "elastic"
nu = 0.3

[output]
fields = ["displacement"]
)");
    Series s{{"2000-01-01"}, [](const Point3&, std::size_t) { return -10e6; }};
    write_pressure(dir / "flow.h5", submesh(m, {"pool_c"}), s);
    // The same mesh for the FEniCSx peer: a field series holding coordinates, cells and the
    // pressure change of each cell (the Pool C cells of the case).
    FieldSeriesWriter w((dir / "mesh_arrays.h5").string(), m);
    Field dp{"dp", 1, {}};
    for_each_output_cell(m, default_output_cell_types(m), [&](const ElementBlock& b, std::size_t) {
      dp.values.push_back(m.physical_name_of(b.entity_dim, b.entity_tag) == "mat:pool_c" ? -10e6 : 0.0);
    });
    const Field cells[] = {dp};
    w.add_step("2000-01-01", static_cast<double>(*parse_iso_date("2000-01-01")), {}, cells);
    w.commit();
    return;
  }
  write_text(dir / "case.toml", layered_case(history ? R"(
[output]
dates = ["2015-05-01", "2015-11-01", "2016-05-01", "2025-05-01", "2025-11-01"]
)"
                                                    : ""));
  const auto dates = history ? monthly(1950, 1, 2033, 12) : monthly(1950, 1, 1951, 12);
  write_pools(dir, m, L, dates, 1950, 15.2e6);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: mech_make_case column|geertsma|small|thesis DIR [options]\n");
    return 2;
  }
  const std::string kind = argv[1];
  const fs::path dir = argv[2];
  fs::create_directories(dir);
  std::map<std::string, std::string> opt;
  for (int i = 3; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--history" || a == "--linear") opt[a] = "1";
    else if (i + 1 < argc) opt[a] = argv[++i];
  }
  try {
    if (kind == "column") make_column(dir, opt.count("--rule") ? opt["--rule"] : "sigma-max");
    else if (kind == "geertsma") make_geertsma(dir, opt.count("--refine") ? std::stod(opt["--refine"]) : 1.0);
    else if (kind == "small") make_small(dir, opt.count("--refine") ? std::stod(opt["--refine"]) : 1.0);
    else if (kind == "thesis")
      make_thesis(dir, opt.count("--history") > 0, opt.count("--linear") > 0, opt.count("--scale") ? std::stod(opt["--scale"]) : 1.0);
    else {
      std::fprintf(stderr, "mech_make_case: unknown kind '%s'\n", kind.c_str());
      return 2;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mech_make_case: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
