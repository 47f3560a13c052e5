// The forecast per fault and window (forecast.hpp) and the [seismicity] section of the case file.
#include <cmath>

#include <gtest/gtest.h>

#include "run_tool.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/seismicity/forecast.hpp"
#include "ugs/seismicity/rate_state.hpp"

using namespace ugs;
using namespace ugs::seismicity;

namespace {

constexpr double kYear = kSecondsPerYear;

std::int64_t date(const char* iso) { return *parse_iso_date(iso); }

Parameters params() {
  Parameters p;
  p.A_sigma = 0.05e6;
  p.stressing_rate = 1e-3 * 1e6 / kYear;
  p.background_rate = 0.2 / kYear / 1e6;  // 0.2 per year per km2
  p.M_c = 1.5;
  p.b_value = 1.0;
  return p;
}

// One fault, monthly dates over two years; pair 0 of area 2 km2 with a ramp, pair 1 of area 0 and a
// wild history, pair 2 of area 1 km2 interpolated with a steady history.
StressHistory history() {
  StressHistory h;
  for (int m = 0; m <= 24; ++m) h.dates.push_back(days_from_civil(2020 + m / 12, 1 + m % 12, 1) * 86400);
  FaultHistory f;
  f.name = "F1";
  f.source = "test";
  f.pairs.resize(3);
  f.pairs[0].area = 2e6;
  f.pairs[1].area = 0;
  f.pairs[2].area = 1e6;
  f.pairs[2].interpolated = true;
  for (std::size_t k = 0; k < h.dates.size(); ++k) {
    f.pairs[0].dcfs.push_back(0.01e6 * static_cast<double>(k));
    f.pairs[1].dcfs.push_back(k % 2 ? 3e6 : -3e6);
    f.pairs[2].dcfs.push_back(0.0);
  }
  h.faults.push_back(f);
  return h;
}

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

}  // namespace

TEST(SeismicityForecast, FaultValuesAreTheAreaWeightedPairsAndZeroAreaAddsNothing) {
  const StressHistory h = history();
  const std::vector<Window> windows{{date("2020-06-15"), date("2021-03-01")}};
  const Forecast fc = forecast(h, {params()}, date("2020-04-01"), windows);
  const FaultForecast& f = fc.faults.at(0);
  EXPECT_DOUBLE_EQ(f.area, 3e6);
  // The same forecast without the zero-area pair.
  StressHistory h2 = h;
  h2.faults[0].pairs.erase(h2.faults[0].pairs.begin() + 1);
  const Forecast fc2 = forecast(h2, {params()}, date("2020-04-01"), windows);
  const FaultForecast& g = fc2.faults.at(0);
  std::vector<double> t;
  for (auto d : h.dates) t.push_back(static_cast<double>(d - h.dates[0]));
  const PatchHistory p0(t, h.faults[0].pairs[0].dcfs, params().A_sigma, params().stressing_rate);
  const double ts = static_cast<double>(date("2020-04-01") - h.dates[0]);
  for (std::size_t k = 0; k < h.dates.size(); ++k) {
    EXPECT_EQ(f.rate_ratio[k], g.rate_ratio[k]);
    EXPECT_EQ(f.events[k], g.events[k]);
    EXPECT_EQ(f.rate_ratio_max[k], g.rate_ratio_max[k]);
    // (2 R0 + 1 * 1) / 3; max over the non-interpolated pair only (pair 2 is interpolated).
    EXPECT_LT(rel(f.rate_ratio[k], (2 * p0.rate_ratio(k) + 1) / 3), 1e-14);
    EXPECT_EQ(f.rate_ratio_max[k], f.pairs[0].rate_ratio[k]);
    EXPECT_LT(rel(f.rate[k], params().background_rate * 3e6 * f.rate_ratio[k]), 1e-14);
    const double tk = t[k];
    const double expect = tk <= ts ? 0.0
                                   : params().background_rate * (2e6 * p0.integral_rate_ratio(ts, tk) + 1e6 * (tk - ts));
    if (expect == 0) EXPECT_EQ(f.events[k], 0.0);
    else EXPECT_LT(rel(f.events[k], expect), 1e-12) << k;
  }
  const double w0 = static_cast<double>(windows[0].start - h.dates[0]), w1 = static_cast<double>(windows[0].end - h.dates[0]);
  const double n = params().background_rate * (2e6 * p0.integral_rate_ratio(w0, w1) + 1e6 * (w1 - w0));
  EXPECT_LT(rel(f.window_events[0], n), 1e-12);
  EXPECT_EQ(f.window_events[0], g.window_events[0]);
  // Gutenberg-Richter and Poisson.
  EXPECT_LT(rel(events_above(n, params(), 2.5), n / 10), 1e-15);
  EXPECT_LT(rel(probability_at_least_one(1e-12), 1e-12), 1e-11);
  EXPECT_LT(rel(probability_at_least_one(2.0), 1 - std::exp(-2.0)), 1e-15);
}

TEST(SeismicityForecast, StartAndWindowsOutsideTheHistoryAreRefused) {
  const StressHistory h = history();
  EXPECT_THROW(forecast(h, {params()}, date("2019-12-31"), {}), InputError);
  EXPECT_THROW(forecast(h, {params()}, date("2020-01-01"), {{date("2021-01-01"), date("2022-01-02")}}), InputError);
  StressHistory none = h;
  none.faults[0].pairs[0].area = none.faults[0].pairs[2].area = 0;
  EXPECT_THROW(forecast(none, {params()}, date("2020-01-01"), {}), InputError);
  // A first step of 40 MPa over A sigma 0.05 MPa (800 A sigma): R/r would not fit a double.
  StressHistory step = h;
  for (auto& v : step.faults[0].pairs[0].dcfs) v = 40e6;
  EXPECT_THROW(forecast(step, {params()}, date("2020-01-01"), {}), InputError);
}

TEST(SeismicityCase, SectionAndOverridesAreReadInSI) {
  test::TempDir dir("seis-case");
  test::spit(dir / "c.toml", "[seismicity]\nA_sigma_MPa = 0.05\nstressing_rate_MPa_per_yr = 1e-3\nbackground_rate_per_yr_km2 = 0.2\n"
                             "M_c = 1.5\nmagnitudes = [2.0, 3.0]\n[seismicity.fault.F1]\nA_sigma_MPa = 0.1\nb_value = 0.8\n");
  const CaseFile c = read_case_file(dir / "c.toml");
  ASSERT_TRUE(c.seismicity);
  const Parameters base = parameters_for(*c.seismicity, "F2", c.path), f1 = parameters_for(*c.seismicity, "F1", c.path);
  EXPECT_DOUBLE_EQ(base.A_sigma, 0.05e6);
  EXPECT_DOUBLE_EQ(base.stressing_rate, 1e3 / kYear);
  EXPECT_DOUBLE_EQ(base.background_rate, 0.2 / kYear / 1e6);
  EXPECT_EQ(base.b_value, 1.0);
  EXPECT_DOUBLE_EQ(f1.A_sigma, 0.1e6);
  EXPECT_EQ(f1.b_value, 0.8);
  EXPECT_EQ(f1.M_c, 1.5);
  EXPECT_EQ(c.seismicity->magnitudes, (std::vector<double>{2.0, 3.0}));
}

TEST(SeismicityCase, BadValuesNameTheirLines) {
  test::TempDir dir("seis-case-bad");
  test::spit(dir / "c.toml", "[seismicity]\nA_sigma_MPa = 0\nstressing_rate_MPa_per_yr = -1\nbackground_rate_per_yr_km2 = 0.2\n"
                             "b_value = 0\n[seismicity.fault.F1]\nA_sigmaMPa = 1\n");
  try {
    read_case_file(dir / "c.toml");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("c.toml:2: 'seismicity.A_sigma_MPa': must be positive, got 0"), std::string::npos) << m;
    EXPECT_NE(m.find("c.toml:3: 'seismicity.stressing_rate_MPa_per_yr': must be positive"), std::string::npos) << m;
    EXPECT_NE(m.find("b_value"), std::string::npos) << m;
    EXPECT_NE(m.find("'seismicity.M_c' is required"), std::string::npos) << m;
    EXPECT_NE(m.find("A_sigmaMPa"), std::string::npos) << m;
  }
}
