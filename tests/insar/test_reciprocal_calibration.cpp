// The reciprocal response model of the calibration (reciprocal.hpp) on synthetic evaluators: the
// "solver" copies the case to {out}, and the sampler builds the series of three PS points from the
// c_R in that copy with a chosen response g(c_R), each series u(t) = A_p(t) g(c_R) + B_p(t); the
// "measured" series are the same with the truth, an offset per point and (optionally) noise. The
// misfit is the tool's (offset-free RMS of the vertical series).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <numbers>

#include "input_error.hpp"
#include "run_tool.hpp"
#include "ugs/calibration/reciprocal.hpp"
#include "ugs/insar/misfit.hpp"
#include "ugs/runner/case_params.hpp"
#include "ugs/runner/solver_runs.hpp"

using namespace ugs;
using namespace ugs::insar;
using namespace ugs::runner;
using namespace ugs::calibration;

namespace {

constexpr int kPoints = 3, kTimes = 48;
constexpr double kMonth = 30.0 * 86400;

// The synthetic series: u_up(p, t) = A_p(t) g(x) + B_p(t) (m); east a tenth of it.
double amplitude(int p, int t) { return 0.004 * (1 + p) * std::sin(2 * std::numbers::pi * t / 12.0) + 0.001 * p * t / kTimes; }
double background(int p, int t) { return -0.002 * t / kTimes * (p + 1) + 0.0005 * std::cos(0.7 * t + p); }

SimulatedSeries series_for(const std::function<double(double)>& g, double x) {
  SimulatedSeries s;
  for (int p = 0; p < kPoints; ++p) s.ids.push_back("P" + std::to_string(p + 1));
  for (int t = 0; t < kTimes; ++t) s.times.push_back(static_cast<std::int64_t>(t * kMonth));
  for (int p = 0; p < kPoints; ++p)
    for (int t = 0; t < kTimes; ++t) {
      const double up = amplitude(p, t) * g(x) + background(p, t);
      s.enu.insert(s.enu.end(), {0.1 * up, 0.0, up});
    }
  return s;
}

// Measured: the series at the truth, in mm, with an offset per point and a deterministic noise.
PsData measured_for(const std::function<double(double)>& g, double truth, double noise_mm) {
  PsData m;
  const SimulatedSeries s = series_for(g, truth);
  for (int p = 0; p < kPoints; ++p) m.points.push_back({s.ids[p], 0, 0, {}, ""});
  m.dates = s.times;
  for (int p = 0; p < kPoints; ++p)
    for (int t = 0; t < kTimes; ++t)
      m.values_mm.push_back(1e3 * s.enu[(p * kTimes + t) * 3 + 2] + 5.0 * (p + 1) + noise_mm * std::sin(12.9898 * t + 78.233 * p));
  return m;
}

Misfit misfit_of(const PsData& meas, const SimulatedSeries& s) {
  std::vector<LocatedPoint> pts;
  for (const auto& p : meas.points) pts.push_back({p, {}});
  return combine_misfits(series_misfits(meas, s.at_dates(pts, meas.dates), 2, {}), {}, 0.0);
}

const char* kCaseText = "crs = \"EPSG:32632\"\n[[material]]\nname = \"pool_c\"\nlaw = \"hypoplastic\"\nc_R = 3.0\n";

// An evaluator whose solver is `cp {case} {out}` and whose sampler reads c_R from that copy.
struct Synthetic {
  std::filesystem::path dir;
  std::unique_ptr<CaseTemplate> tmpl;
  PsData meas;
  std::function<double(double)> g;
  std::unique_ptr<Evaluator> ev;

  Synthetic(const std::string& tag, std::function<double(double)> response, double truth, double noise_mm)
      : dir(test::temp_dir(tag)), g(std::move(response)) {
    test::spit(dir / "case.toml", kCaseText);
    tmpl = std::make_unique<CaseTemplate>((dir / "case.toml").string());
    meas = measured_for(g, truth, noise_mm);
    EvaluatorSetup s;
    s.case_template = tmpl.get();
    s.params = {parse_parameter("material.pool_c.c_R=1.5:6")};
    s.solver_command = "cp {case} {out}";
    s.cache_dir = (dir / "cache").string();
    s.jobs = 2;
    s.sample = [this](const std::string& copy) {
      const std::string text = read_text_file(copy);
      const auto at = text.find("c_R = ");
      if (at == std::string::npos) throw InputError(copy, "no c_R");
      return series_for(g, std::stod(text.substr(at + 6)));
    };
    s.misfit = [this](const SimulatedSeries& series) { return misfit_of(meas, series); };
    ev = std::make_unique<Evaluator>(std::move(s));
  }
  ~Synthetic() { std::filesystem::remove_all(dir); }
  double rms(double x) const { return misfit_of(meas, series_for(g, x)).rms_mm; }
  std::vector<ParameterSpec> params() const { return {parse_parameter("material.pool_c.c_R=1.5:6")}; }
};

std::size_t solver_runs(const Evaluator& ev) {
  return static_cast<std::size_t>(std::count_if(ev.history().begin(), ev.history().end(), [](const Evaluation& e) { return !e.cached; }));
}

}  // namespace

// Series exactly affine in 1/c_R, no noise: the model is exact, its minimum is the truth, and the
// check run confirms it: four solver runs, the truth to round-off, the misfit there zero.
TEST(ReciprocalResponse, ExactReciprocalRecoversTheTruthInFourRuns) {
  Synthetic s("recip-exact", [](double x) { return 1.0 / x; }, 3.0, 0.0);
  const ReciprocalResult r = calibrate_reciprocal(*s.ev, s.params(), OptimizerOptions{});
  ASSERT_EQ(s.ev->history().size(), 4u);
  EXPECT_EQ(solver_runs(*s.ev), 4u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(s.ev->history()[k].phase, "reciprocal");
  EXPECT_EQ(s.ev->history()[3].phase, "check");
  // The three runs: the bounds and the middle of the 1/x range (1 / ((1/1.5 + 1/6) / 2) = 2.4).
  EXPECT_EQ(r.report.x[0], 1.5);
  EXPECT_NEAR(r.report.x[1], 2.4, 1e-15);
  EXPECT_EQ(r.report.x[2], 6.0);
  EXPECT_TRUE(r.report.fallback.empty()) << r.report.fallback;
  EXPECT_EQ(r.result.method, "reciprocal response");
  EXPECT_TRUE(r.result.converged);
  EXPECT_NEAR(r.result.best_x[0], 3.0, 3.0 * 1e-12);
  EXPECT_NEAR(r.report.x_model, 3.0, 3.0 * 1e-12);
  EXPECT_TRUE(r.report.check_is_new_point);
  EXPECT_LT(r.result.best_rms_mm, 1e-9);
  EXPECT_LT(r.report.predicted_rms_mm, 1e-6);  // sqrt of a round-off-sized mean square
  // Affine in 1/x: the middle run on the chord of the outer two (mm, round-off), the series changing
  // by up to 12 mm A g over the range (A up to 12 mm, 1/1.5 - 1/6 = 0.5).
  EXPECT_LT(r.report.curvature_mm, 1e-12);
  EXPECT_GT(r.report.response_mm, 5.0);
  // The modelled profile is the misfit itself (exact model): compare at every profile point.
  ASSERT_EQ(r.report.profile.size(), 41u);
  EXPECT_EQ(r.report.profile.front()[0], 1.5);
  EXPECT_EQ(r.report.profile.back()[0], 6.0);
  for (const auto& [x, rms] : r.report.profile) EXPECT_NEAR(rms, s.rms(x), 1e-9 * (1 + s.rms(x))) << x;
}

// With noise the minimum is the least-squares value of 1/x, in closed form: with the offset-free
// residual r(y) = r0 + y r1, y* = -<r0, r1> / <r1, r1>. The model finds it to round-off.
TEST(ReciprocalResponse, ExactReciprocalWithNoiseFindsTheLeastSquaresValue) {
  auto g = [](double x) { return 1.0 / x; };
  Synthetic s("recip-noise", g, 3.0, 1.5);
  // r0 = residual at y = 0 (series B), r1 = A (per point, offset removed), vertical mm.
  double r0r1 = 0, r1r1 = 0;
  for (int p = 0; p < kPoints; ++p) {
    std::vector<double> r0, r1;
    for (int t = 0; t < kTimes; ++t) {
      r0.push_back(1e3 * background(p, t) - s.meas.value_mm(p, t));
      r1.push_back(1e3 * amplitude(p, t));
    }
    double m0 = 0, m1 = 0;
    for (int t = 0; t < kTimes; ++t) m0 += r0[t] / kTimes, m1 += r1[t] / kTimes;
    for (int t = 0; t < kTimes; ++t) r0r1 += (r0[t] - m0) * (r1[t] - m1), r1r1 += (r1[t] - m1) * (r1[t] - m1);
  }
  const double x_ls = 1.0 / (-r0r1 / r1r1);
  EXPECT_GT(std::abs(x_ls - 3.0), 1e-3);  // the noise moves it off the truth
  const ReciprocalResult r = calibrate_reciprocal(*s.ev, s.params(), OptimizerOptions{});
  EXPECT_EQ(s.ev->history().size(), 4u);
  EXPECT_EQ(solver_runs(*s.ev), 4u);
  EXPECT_TRUE(r.report.fallback.empty()) << r.report.fallback;
  EXPECT_NEAR(r.result.best_x[0], x_ls, 1e-10 * x_ls);
  EXPECT_NEAR(r.report.checked_rms_mm, r.report.predicted_rms_mm, 1e-9);
  EXPECT_NEAR(r.result.best_rms_mm, s.rms(x_ls), 1e-9);
  // The same evaluator again: every evaluation from the history, no solver run.
  const ReciprocalResult again = calibrate_reciprocal(*s.ev, s.params(), OptimizerOptions{});
  EXPECT_EQ(s.ev->history().size(), 8u);
  EXPECT_EQ(solver_runs(*s.ev), 4u);
  EXPECT_EQ(again.result.best_x, r.result.best_x);
}

// A response not quite reciprocal — g = x^-1.25, curved in 1/x (the middle run 0.27 mm off the
// chord of a 6.8 mm change) — still gives a unimodal model whose minimum lies within 0.5 % of the
// misfit's true minimum (found here by Brent on the synthetic misfit itself; measured 0.35 %) and
// whose RMS is within 0.001 mm of the true minimum's, in four runs. Printed beside it: the vertex
// of the parabola through the three runs' mean squares in 1/x (the model without the series'
// curvature), for docs/insar-and-reports.md.
TEST(ReciprocalResponse, MildlyNonlinearResponseLandsWithinHalfAPercent) {
  auto g = [](double x) { return std::pow(x, -1.25); };
  Synthetic s("recip-mild", g, 3.0, 0.5);
  const auto truth = brent_minimize([&](double x) { return s.rms(x); }, 1.5, 6.0, 3.0, s.rms(3.0), 1e-9, 200);
  ASSERT_TRUE(truth.converged);
  const ReciprocalResult r = calibrate_reciprocal(*s.ev, s.params(), OptimizerOptions{});
  EXPECT_TRUE(r.report.fallback.empty()) << r.report.fallback;
  EXPECT_EQ(s.ev->history().size(), 4u);
  EXPECT_NEAR(r.result.best_x[0], truth.x, 0.005 * truth.x) << "model " << r.report.x_model << ", true minimum " << truth.x;
  EXPECT_LT(r.report.checked_rms_mm, truth.f + 1e-3);
  EXPECT_GT(r.report.curvature_mm, 0.01);  // the departure from reciprocal is seen
  EXPECT_LT(r.report.curvature_mm, 0.1 * r.report.response_mm);
  EXPECT_NEAR(r.report.checked_rms_mm, s.rms(r.report.x_model), 1e-12);
  double y[3], f[3];
  for (int k = 0; k < 3; ++k) y[k] = 1.0 / r.report.x[k], f[k] = r.report.rms_mm[k] * r.report.rms_mm[k];
  const double d01 = (f[1] - f[0]) / (y[1] - y[0]), d12 = (f[2] - f[1]) / (y[2] - y[1]), c2 = (d12 - d01) / (y[2] - y[0]);
  const double x_parabola = 1.0 / (0.5 * (y[0] + y[1]) - d01 / (2 * c2));
  std::printf("true minimum %.6f (RMS %.4f mm); series model %.6f (RMS %.4f mm predicted, %.4f mm checked); parabola of the "
              "mean squares %.6f (RMS %.4f mm); curvature %.4f mm of %.4f mm\n",
              truth.x, truth.f, r.report.x_model, r.report.predicted_rms_mm, r.report.checked_rms_mm, x_parabola, s.rms(x_parabola),
              r.report.curvature_mm, r.report.response_mm);
}

// g = -cos(pi u) + 0.05 u in u, the position in the 1/x range (-1 .. 1): the three runs see 0.95,
// -1, 1.05; the measured series are 0.5 A, so the middle run is the worst and the modelled misfit
// has two local minima (where 1.95 u^2 + 0.05 u - 1 = 0.5): the model is not used, Brent refines
// inside the evaluated points next to the best (the run at the upper bound, u = -1).
TEST(ReciprocalResponse, TwoMinimaFallBackToBrent) {
  const double y_lo = 1.0 / 6.0, y_hi = 1.0 / 1.5;
  auto u = [=](double x) { return (2.0 / x - y_lo - y_hi) / (y_hi - y_lo); };
  auto g_u = [](double v) { return -std::cos(std::numbers::pi * v) + 0.05 * v; };
  auto g = [=](double x) { return g_u(u(x)); };
  // The truth: g = 0.5 on u in (-1, 0), where g falls from 0.95 to -1.
  double lo = -1, hi = 0;
  for (int i = 0; i < 200; ++i) (g_u(0.5 * (lo + hi)) > 0.5 ? lo : hi) = 0.5 * (lo + hi);
  const double u_true = 0.5 * (lo + hi);
  const double x_true = 2.0 / (u_true * (y_hi - y_lo) + y_lo + y_hi);
  Synthetic s("recip-two", g, x_true, 0.0);
  OptimizerOptions o;
  o.xtol = 1e-4;
  const ReciprocalResult r = calibrate_reciprocal(*s.ev, s.params(), o);
  EXPECT_NE(r.report.fallback.find("the modelled misfit has 2 local minima over the range"), std::string::npos) << r.report.fallback;
  EXPECT_EQ(r.result.method, "reciprocal response + Brent");
  EXPECT_TRUE(r.result.converged) << r.result.stop_reason;
  EXPECT_TRUE(std::isnan(r.report.checked_rms_mm));  // no check run
  EXPECT_EQ(s.ev->history()[3].phase, "brent");
  EXPECT_LE(static_cast<int>(s.ev->history().size()), o.max_evals);
  EXPECT_NEAR(r.result.best_x[0], x_true, 1e-3 * x_true);
}

// g = u^3: the three runs see -1, 0, 1, the model takes the series as affine in u, measured 0.9 A
// puts its minimum at u = 0.9, where the truth is 0.729: the check is worse than the run at the
// bound (u = 1, g = 1): the model is not used, Brent finds u = 0.9^(1/3) between 0.9 and 1.
TEST(ReciprocalResponse, CheckWorseThanTheRunsFallsBackToBrent) {
  const double y_lo = 1.0 / 6.0, y_hi = 1.0 / 1.5;
  auto u = [=](double x) { return (2.0 / x - y_lo - y_hi) / (y_hi - y_lo); };
  auto g = [=](double x) { return std::pow(u(x), 3); };
  const double u_true = std::cbrt(0.9);
  const double x_true = 2.0 / (u_true * (y_hi - y_lo) + y_lo + y_hi);
  Synthetic s("recip-check", g, x_true, 0.0);
  OptimizerOptions o;
  o.xtol = 1e-4;
  const ReciprocalResult r = calibrate_reciprocal(*s.ev, s.params(), o);
  EXPECT_NE(r.report.fallback.find("is worse than the best of the three runs"), std::string::npos) << r.report.fallback;
  EXPECT_NEAR(r.report.x_model, 2.0 / (0.9 * (y_hi - y_lo) + y_lo + y_hi), 1e-9);
  EXPECT_EQ(s.ev->history()[3].phase, "check");
  EXPECT_EQ(s.ev->history()[4].phase, "brent");
  EXPECT_EQ(r.result.method, "reciprocal response + Brent");
  EXPECT_NEAR(r.result.best_x[0], x_true, 1e-3 * x_true);
}

// What the model cannot do: several parameters, a range reaching 0 or below, :log, a scan, a budget
// below four. Named in words (the tool maps them to its flags, CalibrateCli.BadInputs).
TEST(ReciprocalResponse, RefusedSettings) {
  OptimizerOptions o;
  const auto one = [](const char* spec) { return std::vector<ParameterSpec>{parse_parameter(spec)}; };
  EXPECT_EQ(test::input_error_of([&] {
              check_reciprocal({parse_parameter("material.pool_c.c_R=2:6"), parse_parameter("material.pool_a.c_R=3:8")}, o, false);
            }),
            "response model: reciprocal calibrates one parameter, 2 were given (expected one parameter to calibrate; several paths "
            "sharing one value are one)");
  EXPECT_EQ(test::input_error_of([&] { check_reciprocal(one("material.pool_c.c_R=0:6"), o, false); }),
            "response model: reciprocal needs positive bounds, parameter to calibrate material.pool_c.c_R has lower bound 0 (expected "
            "0 < LOWER < UPPER: the model is in 1/x)");
  EXPECT_NE(test::input_error_of([&] { check_reciprocal(one("material.pool_c.c_R=-2:6"), o, false); }).find("lower bound -2"),
            std::string::npos);
  EXPECT_NE(test::input_error_of([&] { check_reciprocal(one("x=1e-8:1e-6:log"), o, false); }).find("asks for :log"), std::string::npos);
  EXPECT_EQ(test::input_error_of([&] { check_reciprocal(one("material.pool_c.c_R=2:6"), o, true); }),
            "response model: reciprocal makes its own three runs (expected no scan values per parameter)");
  o.max_evals = 3;
  EXPECT_EQ(test::input_error_of([&] { check_reciprocal(one("material.pool_c.c_R=2:6"), o, false); }),
            "response model: reciprocal needs 4 evaluations, the evaluation budget is 3 (expected at least 4)");
  o.max_evals = 4;
  EXPECT_EQ(test::input_error_of([&] { check_reciprocal(one("material.pool_c.c_R=2:6"), o, false); }), "(no InputError)");
}
