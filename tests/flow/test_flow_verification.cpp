// V3 (shared/docs/VERIFICATION.md): aquifer flow against closed forms, through the library code
// ugs-flow runs (build_flow_model + run_transient). Each case is a box mesh (meshing/box_mesh.hpp)
// with a one-cell "pool" slab whose nodes follow the boundary pressure; the influx is the
// reaction there. Tolerance 2 % on dp where dp >= 0.05 dp0, and on the cumulative volume W.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <fmt/format.h>

#include "flow_cases.hpp"
#include "ugs/flow/transient.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/meshing/box_mesh.hpp"

using namespace ugs;
using namespace ugs::flow;

namespace {

constexpr double kDp0 = -1e6;  // depletion: water flows from the aquifer into the pool

// Pressure change at the nodes of the line y = y0, z = z0 (first match per x), sorted by x.
std::vector<std::pair<double, double>> profile(const Mesh& mesh, const FlowModel& fm, const std::vector<double>& dp, double y0,
                                               double z0, double x_from) {
  std::vector<std::pair<double, double>> v;
  for (std::size_t n = 0; n < mesh.num_nodes(); ++n) {
    const auto& x = mesh.nodes[n];
    if (std::abs(x[1] - y0) < 1e-9 && std::abs(x[2] - z0) < 1e-9 && x[0] >= x_from) v.push_back({x[0], dp[fm.dof_of_node[n]]});
  }
  std::sort(v.begin(), v.end());
  return v;
}

// A long thin bar along x: pool slab [-1, 0], aquifer [0, L], cross-section 1 m2.
Mesh bar(std::vector<double> x_aquifer) {
  BoxMeshSpec s;
  s.x = {-1.0};
  s.x.insert(s.x.end(), x_aquifer.begin(), x_aquifer.end());
  s.y = {0, 1};
  s.z = {-1001, -1000};
  s.material = [](const Point3& c) { return c[0] < 0 ? std::string("pool") : std::string("aquifer"); };
  return make_box_mesh(s);
}

// With UGS_V3_OUT=DIR set, the cases also write their numbers as CSV for plot_v3.py.
struct PlotTable {
  std::FILE* f = nullptr;
  PlotTable(const char* name, const char* header) {
    if (const char* dir = std::getenv("UGS_V3_OUT")) {
      f = std::fopen((std::string(dir) + "/" + name).c_str(), "w");
      if (f) std::fprintf(f, "%s\n", header);
    }
  }
  ~PlotTable() {
    if (f) std::fclose(f);
  }
  void row(std::initializer_list<double> v) {
    if (!f) return;
    const char* sep = "";
    for (double x : v) std::fprintf(f, "%s%.10g", sep, x), sep = ",";
    std::fprintf(f, "\n");
  }
};

}  // namespace

TEST(FlowV3, SemiInfiniteAquiferErfcAndInflow) {
  test::AquiferParams a;
  const Mesh mesh = bar(graded(0, 3000, 1.0, 1.05));
  const CaseFile c = test::aquifer_case(a);
  const FlowModel fm = build_flow_model(mesh, c);
  // T: diffusion length sqrt(eta T) = 200 m, far from the closed end at 3,000 m.
  const std::int64_t T = 400000, dt = 1000;
  const TimeGrid g = test::step_grid(test::uniform_dates(dt, T), kDp0);
  std::vector<std::pair<double, std::vector<double>>> snapshots;
  const TransientResult r = run_transient(fm, g, {}, [&](const DateState& s) {
    if (s.index > 0 && (s.date == T / 4 || s.date == T / 2 || s.date == T)) snapshots.push_back({double(s.date), *s.dp});
  });
  ASSERT_EQ(snapshots.size(), 3u);
  PlotTable plot("semi_infinite.csv", "t_s,x_m,dp_Pa,exact_Pa");
  for (const auto& [t, dp] : snapshots) {
    for (const auto& [x, v] : profile(mesh, fm, dp, 0, -1000, 0))
      if (x < 1000) plot.row({t, x, v, kDp0 * test::erfc_profile(x, t, a.eta)});
    int checked = 0;
    double worst = 0;
    for (const auto& [x, v] : profile(mesh, fm, dp, 0, -1000, 0)) {
      const double exact = kDp0 * test::erfc_profile(x, t, a.eta);
      if (std::abs(exact) < 0.05 * std::abs(kDp0)) continue;
      EXPECT_NEAR(v, exact, 0.02 * std::abs(exact)) << "x = " << x << " t = " << t;
      worst = std::max(worst, std::abs(v / exact - 1));
      ++checked;
    }
    EXPECT_GT(checked, 20);
    RecordProperty("profile_max_rel_error_t" + std::to_string(static_cast<long>(t)), std::to_string(worst));
    // Cumulative inflow per unit area (area 1 m2): W = 2 s |dp0| sqrt(eta t / pi).
    const std::size_t k = static_cast<std::size_t>(t / dt);
    const double W = 2 * a.s() * std::abs(kDp0) * std::sqrt(a.eta * t / M_PI);
    EXPECT_NEAR(r.influx[0][k], W, 0.02 * W) << "t = " << t;
    RecordProperty("W_rel_error_t" + std::to_string(static_cast<long>(t)), std::to_string(r.influx[0][k] / W - 1));
  }
}

TEST(FlowV3, FiniteClosedAquiferSeries) {
  test::AquiferParams a;
  const double L = 100;
  const Mesh mesh = bar(linspace(0, L, 100));
  const FlowModel fm = build_flow_model(mesh, test::aquifer_case(a));
  const std::int64_t Tref = static_cast<std::int64_t>(L * L / a.eta);  // 1e5 s
  const std::int64_t dt = 50;
  const TimeGrid g = test::step_grid(test::uniform_dates(dt, Tref), kDp0);
  int checked = 0;
  double worst = 0;
  PlotTable plot("finite.csv", "tD,x_m,dp_Pa,exact_Pa");
  run_transient(fm, g, {}, [&](const DateState& s) {
    const double tD = double(s.date) / Tref;
    if (s.index == 0 || !(s.date == Tref / 20 || s.date == Tref / 5 || s.date == Tref / 2 || s.date == Tref)) return;
    for (const auto& [x, v] : profile(mesh, fm, *s.dp, 0, -1000, 0)) {
      const double exact = kDp0 * test::closed_profile(x, double(s.date), a.eta, L);
      plot.row({tD, x, v, exact});
      if (std::abs(exact) < 0.05 * std::abs(kDp0)) continue;
      EXPECT_NEAR(v, exact, 0.02 * std::abs(exact)) << "x = " << x << " tD = " << tD;
      worst = std::max(worst, std::abs(v / exact - 1));
      ++checked;
    }
  });
  EXPECT_GT(checked, 200);
  RecordProperty("max_rel_error", std::to_string(worst));
}

// Radial aquifer around a cylindrical reservoir of radius r_o (van Everdingen-Hurst): a sector
// of an annulus, the box (r, theta, z) mapped to (r cos theta, r sin theta, z).
TEST(FlowV3, RadialVanEverdingenHurst) {
  test::AquiferParams a;
  const double ro = 100, h = 10, sector = 10.0 * M_PI / 180.0;
  BoxMeshSpec s;
  s.x = {ro - 1.0};
  for (double r : graded(ro, 40 * ro, 0.25, 1.07)) s.x.push_back(r);
  s.y = linspace(0, sector, 4);
  s.z = {-1000 - h, -1000};
  s.material = [&](const Point3& c) { return c[0] < ro ? std::string("pool") : std::string("aquifer"); };
  Mesh mesh = make_box_mesh(s);
  for (auto& x : mesh.nodes) x = {x[0] * std::cos(x[1]), x[0] * std::sin(x[1]), x[2]};
  const FlowModel fm = build_flow_model(mesh, test::aquifer_case(a));
  const std::int64_t Tref = static_cast<std::int64_t>(ro * ro / a.eta);  // t_D = 1 at 1e5 s
  // Steps refined where W_D changes fastest: t_D 0..0.1 by 0.0005, ..1 by 0.005, ..10 by 0.05.
  std::vector<std::int64_t> dates = test::uniform_dates(Tref / 2000, Tref / 10);
  dates = test::uniform_dates(Tref / 200, Tref, dates);
  dates = test::uniform_dates(Tref / 20, 10 * Tref, dates);
  const TimeGrid g = test::step_grid(dates, kDp0);
  const TransientResult r = run_transient(fm, g);
  const double fraction = sector / (2 * M_PI);
  {
    PlotTable plot("radial.csv", "tD,WD");
    const double unit = 2 * M_PI * a.s() * h * ro * ro * std::abs(kDp0) * fraction;
    for (std::size_t k = 1; k < r.dates.size(); ++k) plot.row({double(r.dates[k]) / Tref, r.influx[0][k] / unit});
  }
  const std::pair<double, double> WD[] = {{0.1, 0.404339}, {1, 1.568292}, {10, 7.401522}};
  for (const auto& [tD, wd] : WD) {
    const auto t = static_cast<std::int64_t>(std::llround(tD * Tref));
    const std::size_t k = static_cast<std::size_t>(std::find(r.dates.begin(), r.dates.end(), t) - r.dates.begin());
    ASSERT_LT(k, r.dates.size());
    const double W = 2 * M_PI * a.s() * h * ro * ro * std::abs(kDp0) * wd * fraction;
    EXPECT_NEAR(r.influx[0][k], W, 0.02 * W) << "t_D = " << tD;
    RecordProperty("WD_rel_error_tD" + std::to_string(tD), std::to_string(r.influx[0][k] / W - 1));
  }
}

// Mass balance: stored water change = time integral of the boundary inflow, to 1e-10, on an
// anisotropic two-material aquifer with depth-dependent c_M, a cycling schedule, uneven steps.
TEST(FlowV3, MassBalance) {
  BoxMeshSpec s;
  s.x = graded(0, 3000, 100, 1.2);
  s.y = linspace(0, 2000, 6);
  s.z = linspace(-1600, -1500, 4);
  s.material = [](const Point3& c) {
    if (c[0] < 600 && c[1] < 800) return std::string("pool");
    return std::string(c[2] > -1550 ? "aquifer" : "aquifer_deep");
  };
  const Mesh mesh = make_box_mesh(s);
  CaseFile c = test::aquifer_case({});
  c.initial_stress.surface_elevation = 50;
  for (auto& m : c.materials) m.law = MaterialLaw::ElasticDepth;  // c_M = a sigma_z^-b at each centroid
  c.materials[0].K = std::array<double, 3>{2.04e-7, 2.04e-7, 2.04e-8};
  MaterialSpec deep = c.materials[0];
  deep.name = "aquifer_deep";
  deep.K = std::array<double, 3>{5e-7, 1e-7, 1e-9};
  c.materials.push_back(deep);
  const FlowModel fm = build_flow_model(mesh, c);
  // Monthly dates 1950-01 .. 1960-01 with a depletion and storage cycles.
  TimeGrid g;
  for (int m = 0; m <= 120; ++m) g.dates.push_back(days_from_civil(1950 + m / 12, m % 12 + 1, 1) * 86400);
  g.is_schedule_date.assign(g.dates.size(), 1);
  std::vector<double> v;
  for (int m = 0; m <= 120; ++m) v.push_back(-3e6 * (1 - std::exp(-m / 30.0)) + 1e6 * std::sin(2 * M_PI * m / 12.0) * (m > 48));
  g.pool_dp = {v};
  TransientOptions o;
  o.substeps = 2;
  const TransientResult r = run_transient(fm, g, o);
  EXPECT_EQ(r.solver.factorizations, 4u);  // 28, 29, 30 and 31 days (halved)
  EXPECT_GT(r.influx[0].back(), 1e3);      // water entered the depleted pool
  EXPECT_LT(r.balance_error(), 1e-10);
  RecordProperty("balance_error", fmt::format("{:.3g}", r.balance_error()));
  // The same by hand: stored change + influx at the end.
  EXPECT_NEAR(r.stored.back() + r.influx[0].back(), 0.0, 1e-10 * std::abs(r.stored.back()));
}

TEST(FlowModel, StorageFromCompressibilityLawAtDepth) {
  CaseFile c;
  c.initial_stress.surface_elevation = 50;
  c.initial_stress.lithostatic_gradient = 0.0226e6;
  c.initial_stress.hydrostatic_gradient = 0.0100e6;
  MaterialSpec m;
  m.name = "aquifer";
  m.porosity = 0.2;
  // At z = -1,500 m: sigma_z = 0.0126 MPa/m * 1,550 m = 19.53 MPa; c_M = 1.0044e-2 * 19.53^-1.1347 1/MPa.
  const double sigma = 0.0126 * 1550;
  const double cm = 1.0044e-2 * std::pow(sigma, -1.1347) * 1e-6;
  const InitialState init = initial_state_of(c, 2000);
  EXPECT_NEAR(initial_effective_vertical_stress(c, init, m, -1500), sigma * 1e6, 1e-3);
  EXPECT_NEAR(storage_coefficient(c, init, m, -1500), 0.2 * 4.4e-10 + cm, 1e-20);
  // Near or above the surface the stress is floored at sigma_z_min_MPa (0.1 MPa by default), as in the mechanics.
  EXPECT_NEAR(storage_coefficient(c, init, m, 60), 0.2 * 4.4e-10 + 1.0044e-2 * std::pow(0.1, -1.1347) * 1e-6, 1e-20);
  // The material's Biot coefficient enters as in the mechanics: sigma'_v = S_v - alpha p0.
  m.biot = 0.8;
  EXPECT_NEAR(initial_effective_vertical_stress(c, init, m, -1500), (0.0226 - 0.8 * 0.0100) * 1550 * 1e6, 1e-3);
  // The mechanical earth model's pore pressure enters too: a constant overpressure of 2 MPa.
  c.initial_stress.overpressure = {{0, 2e6}};
  const InitialState over = initial_state_of(c, 2000);
  EXPECT_NEAR(initial_effective_vertical_stress(c, over, m, -1500), (0.0226 - 0.8 * 0.0100) * 1550 * 1e6 - 0.8 * 2e6, 1e-3);
  const double cm_over = 1.0044e-2 * std::pow((0.0226 - 0.8 * 0.0100) * 1550 - 1.6, -1.1347) * 1e-6;
  EXPECT_NEAR(storage_coefficient(c, over, m, -1500), 0.2 * 4.4e-10 + cm_over, 1e-20);
}
