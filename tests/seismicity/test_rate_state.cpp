// V11 (shared/docs/VERIFICATION.md): Dieterich's seismicity rate under a Coulomb stress history,
// evaluated in the closed form of Heimisson & Segall (2018) on a piecewise linear history.
// Units here are the verification case's (years, MPa): the closed form does not care.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "ugs/seismicity/rate_state.hpp"

using ugs::seismicity::PatchHistory;

namespace {

constexpr double kAs = 0.05, kSr = 1e-3, kTa = kAs / kSr;  // MPa, MPa/yr, yr

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

// The history sampled at `t` with dcfs(t).
template <class F>
PatchHistory sampled(const std::vector<double>& t, F dcfs, double As = kAs, double sr = kSr) {
  std::vector<double> s;
  for (double x : t) s.push_back(dcfs(x));
  return PatchHistory(t, s, As, sr);
}

// Composite Simpson of R / r on [a, b] with n (even) intervals, R evaluated independently of the
// library's integral: exp(log R / r) at each point.
double simpson(const PatchHistory& h, double a, double b, int n) {
  const double step = (b - a) / n;
  double s = std::exp(h.log_rate_ratio_at(a)) + std::exp(h.log_rate_ratio_at(b));
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4 : 2) * std::exp(h.log_rate_ratio_at(a + i * step));
  return s * step / 3;
}

}  // namespace

// A stress step dS at t0 = 0 (the history's first value; steady state under dCFS = 0):
// R/r = 1 / (1 + (exp(-dS / A sigma) - 1) exp(-t / t_a)).
TEST(V11RateState, StepMatchesTheClosedFormAndTheReferenceNumbers) {
  const std::vector<double> t{0, 1, kTa, 5 * kTa};
  for (double dS : {0.2, -0.2}) {
    const PatchHistory h = sampled(t, [&](double) { return dS; });
    for (std::size_t k = 0; k < t.size(); ++k) {
      const double exact = 1 / (1 + std::expm1(-dS / kAs) * std::exp(-t[k] / kTa));
      EXPECT_LT(rel(h.rate_ratio(k), exact), 1e-13) << "dS " << dS << " t " << t[k];
    }
  }
  // VERIFICATION.md's numbers, to the half unit of their last printed digit.
  const PatchHistory up = sampled(t, [](double) { return 0.2; }), down = sampled(t, [](double) { return -0.2; });
  EXPECT_NEAR(up.rate_ratio(0), 54.598, 0.5e-3);
  EXPECT_NEAR(up.rate_ratio(1), 26.487, 0.5e-3);
  EXPECT_NEAR(up.rate_ratio(2), 1.56529, 0.5e-5);
  EXPECT_NEAR(up.rate_ratio(3), 1.00666, 0.5e-5);
  EXPECT_NEAR(down.rate_ratio(0), 0.0183156, 0.5e-7);
  EXPECT_NEAR(down.rate_ratio(2), 0.0482680, 0.5e-7);
}

// The stressing rate multiplied by k = 10 at t0: dCFS = (k - 1) s_r t, linear, one piece per date:
// R/r = k / (1 + (k - 1) exp(-t k s_r / A sigma)).
TEST(V11RateState, RateChangeMatchesTheClosedFormAndTheReferenceNumbers) {
  const double k = 10;
  const std::vector<double> t{0, 1, 5, 50};
  const PatchHistory h = sampled(t, [&](double x) { return (k - 1) * kSr * x; });
  for (std::size_t i = 0; i < t.size(); ++i)
    EXPECT_LT(rel(h.rate_ratio(i), k / (1 + (k - 1) * std::exp(-t[i] * k * kSr / kAs))), 1e-13) << t[i];
  EXPECT_NEAR(h.rate_ratio(1), 1.19495, 0.5e-5);
  EXPECT_NEAR(h.rate_ratio(2), 2.31969, 0.5e-5);
  EXPECT_NEAR(h.rate_ratio(3), 9.99592, 0.5e-5);
  // Between dates (the same linear history): the closed form at t = 20 yr.
  EXPECT_LT(rel(std::exp(h.log_rate_ratio_at(20)), k / (1 + (k - 1) * std::exp(-20 * k * kSr / kAs))), 1e-13);
}

// dCFS = 0.1 sin(2 pi t) MPa: the reference values come from the state equation integrated to 1e-9.
// Sampled every 1e-4 yr the piecewise linear history is within 1e-7 of the sine (the sampling error
// falls as the square of the step: 3e-6 at 1e-3 yr, VERIFICATION.md), so the values agree to 1e-6
// relative; sampled every 1e-3 yr, to 3.5e-6.
TEST(V11RateState, SeasonalCycleMatchesTheReferenceNumbers) {
  const double ref[4][2] = {{0.25, 7.272261}, {0.75, 0.1315765}, {10.25, 5.934483}, {19.75, 0.0950353}};
  for (const double dt : {1e-4, 1e-3}) {
    std::vector<double> t;
    const int n = static_cast<int>(std::lround(19.75 / dt));
    for (int i = 0; i <= n; ++i) t.push_back(i * dt);
    const PatchHistory h = sampled(t, [](double x) { return 0.1 * std::sin(2 * M_PI * x); });
    for (const auto& [at, value] : ref) {
      const std::size_t i = static_cast<std::size_t>(std::lround(at / dt));
      EXPECT_LT(rel(h.rate_ratio(i), value), dt == 1e-4 ? 1e-6 : 3.5e-6) << "dt " << dt << " t " << at;
    }
  }
}

// The expected events: the closed form t_a log((t_a + I2) / (t_a + I1)) against a composite Simpson
// rule of R / r on each piece (R is smooth inside a piece), on a history with a first step, monthly
// seasonal pieces and a ramp; also over intervals that start and end inside pieces.
TEST(V11RateState, EventCountMatchesQuadrature) {
  std::vector<double> t;
  for (int m = 0; m <= 36; ++m) t.push_back(m / 12.0);
  t.push_back(3.5);
  t.push_back(6.0);
  const PatchHistory h = sampled(t, [](double x) { return x <= 3 ? 0.05 + 0.1 * std::sin(2 * M_PI * x) : 0.05 + 0.2 * (x - 3); });
  auto quadrature = [&](double a, double b) {
    double s = 0;
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
      const double lo = std::max(a, t[i]), hi = std::min(b, t[i + 1]);
      if (hi > lo) s += simpson(h, lo, hi, 2000);
    }
    return s;
  };
  for (const auto& [a, b] : std::vector<std::pair<double, double>>{{0, 6}, {0.3, 0.31}, {1.01, 2.99}, {2.5, 5.2}, {0, 1.0 / 12}})
    EXPECT_LT(rel(h.integral_rate_ratio(a, b), quadrature(a, b)), 1e-10) << a << " .. " << b;
  // Additive: the sum over the pieces is the whole.
  double sum = 0;
  for (std::size_t i = 0; i + 1 < t.size(); ++i) sum += h.integral_rate_ratio(t[i], t[i + 1]);
  EXPECT_LT(rel(sum, h.integral_rate_ratio(0, 6)), 1e-13);
}

// dCFS = 0: R = r at every date and between, and the expected events are r times the duration.
TEST(V11RateState, SteadyStateGivesTheBackgroundRate) {
  std::vector<double> t{0, 0.5, 1, 7, 30, 83};
  const PatchHistory h = sampled(t, [](double) { return 0.0; });
  for (std::size_t k = 0; k < t.size(); ++k) EXPECT_NEAR(h.rate_ratio(k), 1.0, 1e-14) << t[k];
  EXPECT_NEAR(std::exp(h.log_rate_ratio_at(12.3)), 1.0, 1e-14);
  EXPECT_LT(rel(h.integral_rate_ratio(0, 83), 83.0), 1e-14);
  EXPECT_LT(rel(h.integral_rate_ratio(0.2, 29.9), 29.7), 1e-14);
}

// 5 MPa over A sigma = 0.01 MPa (S / A sigma = 500): a one-month ramp is a stressing rate k s_r
// (k = 1 + 60 / 1e-3), then s_r again from R/r = R1 (R/r = 1 / (1 + (1 / R1 - 1) exp(-t / t_a)));
// a first step of 5 MPa gives R/r = e^500. Everything finite and on the closed forms.
TEST(V11RateState, StressChangesOfHundredsOfASigmaDoNotOverflow) {
  const double As = 0.01, sr = 1e-3, ta = As / sr, t1 = 1.0 / 12, k = 1 + (5 / t1) / sr;
  const std::vector<double> t{0, t1, t1 + 1, t1 + ta, t1 + 10 * ta};
  const PatchHistory h = sampled(t, [&](double x) { return std::min(x, t1) / t1 * 5; }, As, sr);
  const double R1 = k / (1 + (k - 1) * std::exp(-t1 * k * sr / As));
  EXPECT_LT(rel(h.rate_ratio(1), R1), 1e-12);
  for (std::size_t i = 2; i < t.size(); ++i)
    EXPECT_LT(rel(h.rate_ratio(i), 1 / (1 + (1 / R1 - 1) * std::exp(-(t[i] - t1) / ta))), 1e-12) << t[i];
  // Events during the ramp: integral of k / (1 + (k - 1) e^{-k t / t_a}) = t_a log((e^{k t1 / t_a} + k - 1) / k).
  const double ramp_events = k * t1 + ta * std::log((1 + (k - 1) * std::exp(-k * t1 / ta)) / k);
  EXPECT_LT(rel(h.integral_rate_ratio(0, t1), ramp_events), 1e-12);
  for (double x = 0; x <= t.back(); x += 0.37) {
    EXPECT_TRUE(std::isfinite(h.log_rate_ratio_at(x))) << x;
    EXPECT_TRUE(std::isfinite(h.integral_rate_ratio(0, x))) << x;
  }
  // A first step of 5 MPa: R/r = e^500 just after it, exactly in logarithms.
  const PatchHistory step = sampled({0, 1, 2}, [](double) { return 5.0; }, As, sr);
  EXPECT_DOUBLE_EQ(step.log_rate_ratio(0), 500.0);
  EXPECT_LT(rel(step.rate_ratio(0), std::exp(500.0)), 1e-13);
  EXPECT_TRUE(std::isfinite(step.integral_rate_ratio(0, 2)));
  // Same after the step: 1 / (1 + (e^-500 - 1) e^{-t / t_a}).
  EXPECT_LT(rel(step.rate_ratio(1), 1 / (1 + std::expm1(-500.0) * std::exp(-1 / ta))), 1e-12);
}

TEST(V11RateState, LogMeanExpIsAccurateAcrossItsBranches) {
  using ugs::seismicity::log_mean_exp_linear;
  EXPECT_EQ(log_mean_exp_linear(0.0), 0.0);
  for (double d : {1e-12, -1e-9, 1e-4, -9.99e-4, 1.001e-3, -0.5, 2.0, 40.0, -40.0, 800.0, -800.0, 1e6}) {
    // Reference: log((e^d - 1) / d) in long double where it fits, else d - log d or -log(-d).
    long double ref;
    if (std::abs(d) < 700) ref = std::log(std::expm1l(static_cast<long double>(d)) / d);
    else ref = d > 0 ? d - std::log(d) : -std::log(-d);
    EXPECT_NEAR(log_mean_exp_linear(d), static_cast<double>(ref), 4e-16 * std::max(1.0, std::abs(d))) << d;
  }
}
