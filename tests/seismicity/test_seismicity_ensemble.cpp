// ugs-ensemble's seismicity metrics (docs/ensemble.md): a member folder as ugs-solve and the ensemble
// leave it (result.h5, the member's case.toml with [seismicity], a per-pair fault CSV) gives
// seismic_events.<fault>.<window> on the closed forms of V11 (a pair under a rate change k = 10, a
// pair in steady state), p_event = 1 - exp(-N), p_event_M<m> through Gutenberg-Richter, and "all".
#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "run_tool.hpp"
#include "ugs/ensemble/metrics.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"

using namespace ugs;

namespace {

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

}  // namespace

TEST(SeismicityEnsembleMetrics, MembersReportEventsAndProbabilitiesPerFaultAndWindow) {
  test::TempDir d("seis-ens");
  // result.h5: two triangles, u = 0 (the surface metrics are not the subject).
  Mesh m;
  for (const Point3 p : {Point3{0, 0, 0}, Point3{1000, 0, 0}, Point3{0, 1000, 0}, Point3{1000, 1000, 0}}) m.add_node(p);
  auto& b = m.block(2, m.entity_for_physical(2, "bnd:top"), ElementType::Triangle);
  const std::uint32_t t0[3] = {0, 1, 2}, t1[3] = {1, 3, 2};
  m.add_element(b, t0);
  m.add_element(b, t1);
  {
    FieldSeriesWriter w(d / "result.h5", m, {{ElementType::Triangle}});
    for (const std::string date : {"2020-01-01", "2021-01-01"}) {
      const Field nf[] = {{"u", 3, std::vector<double>(12, 0.0)}};
      w.add_step(date, double(*parse_iso_date(date)), nf);
    }
    w.commit();
  }
  test::spit(d / "case.toml", "[[fault]]\nname = \"F\"\n\n[seismicity]\nA_sigma_MPa = 0.05\nstressing_rate_MPa_per_yr = 1e-3\n"
                              "background_rate_per_yr_km2 = 0.3\nM_c = 1.5\nb_value = 0.9\nmagnitudes = [2.5]\n");
  const double k = 10, sr = 1e-3, ta = 50, r = 0.3, A1 = 2.0, A2 = 1.0;  // yr, /yr/km2, km2
  const std::int64_t first = *parse_iso_date("2020-01-01");
  auto years = [&](std::int64_t t) { return static_cast<double>(t - first) / kSecondsPerYear; };
  std::string csv = "# ugs-solve fault F: one row per node pair and output date\n"
                    "date,node,x_m,y_m,z_m,along_strike_m,down_dip_m,area_m2,cfs_change_MPa,interpolated\n";
  for (int mo = 0; mo <= 12; ++mo) {
    const std::int64_t t = days_from_civil(2020 + mo / 12, 1 + mo % 12, 1) * 86400;
    csv += fmt::format("{},1,0,0,-1000,0,0,{},{},0\n", format_iso_date(t), A1 * 1e6, (k - 1) * sr * years(t));
    csv += fmt::format("{},2,0,0,-1100,0,100,{},0,0\n", format_iso_date(t), A2 * 1e6);
  }
  test::spit(d / "result_fault_F.csv", csv);
  ensemble::MetricOptions o;
  o.seismic_windows.push_back(ensemble::parse_phase("w=2020-03-01/2020-12-01"));
  const auto metrics = ensemble::member_metrics(d.path.string(), o);
  std::map<std::string, double> by_name(metrics.begin(), metrics.end());
  // N = r [A1 t_a (g(t2) - g(t1)) + A2 (t2 - t1)], g(t) = log((e^{k t / t_a} + k - 1) / k).
  auto g = [&](double t) { return std::log((std::exp(k * t / ta) + k - 1) / k); };
  const double a = years(*parse_iso_date("2020-03-01")), e = years(*parse_iso_date("2020-12-01"));
  const double n = r * (A1 * ta * (g(e) - g(a)) + A2 * (e - a));
  for (const std::string who : {"F", "all"}) {
    ASSERT_TRUE(by_name.count("seismic_events." + who + ".w")) << who;
    EXPECT_LT(rel(by_name["seismic_events." + who + ".w"], n), 1e-10) << who;
    EXPECT_LT(rel(by_name["p_event." + who + ".w"], -std::expm1(-n)), 1e-10) << who;
    EXPECT_LT(rel(by_name["p_event_M2.5." + who + ".w"], -std::expm1(-n * std::pow(10.0, -0.9))), 1e-10) << who;
  }
  // Without a per-pair CSV the seismicity metrics cannot be computed: the member fails, named.
  std::filesystem::remove(d / "result_fault_F.csv");
  EXPECT_THROW(ensemble::member_metrics(d.path.string(), o), InputError);
}
