// Dieterich's (1994) rate-and-state seismicity for any Coulomb stress history, in the closed form of
// Heimisson & Segall (2018): with S(t) = s_r (t - t_0) + dCFS(t) and t_a = A sigma / s_r,
//
//   R(t) / r = exp(S / A sigma) / (1 + I(t) / t_a),   I(t) = integral_{t_0}^t exp(S(t') / A sigma) dt',
//
// and the expected number of events, integral of R, in closed form too:
//
//   integral_{t1}^{t2} R / r dt = t_a log((t_a + I(t2)) / (t_a + I(t1))).
//
// dCFS is piecewise linear between the history's dates, so I is exact on each piece
// (h e^{x_i} (e^d - 1) / d, d the change of S / A sigma over the piece): no quadrature. Everything is
// carried as logarithms (log I, log R / r), so S / A sigma of thousands neither overflows nor loses
// the small values; nothing returned is inf or NaN. The population is in steady state (R = r) under
// dCFS = 0: a history whose first value is not 0 starts with a step there (VERIFICATION.md V11).
// Units are the caller's, consistent: the library works in SI (s, Pa).
#pragma once
#include <cstddef>
#include <span>
#include <vector>

namespace ugs::seismicity {

// log((e^d - 1) / d), the log of the mean of e^x over a piece where x rises linearly by d: exact
// to round-off for any finite d (0 at d = 0).
double log_mean_exp_linear(double d);
// log(1 + e^z) without overflow; 0 at z = -inf.
double softplus(double z);
// log(e^a + e^b); -inf when both are -inf.
double log_add_exp(double a, double b);

class PatchHistory {
public:
  // `t` strictly increasing (s; two dates or more), `dcfs` the Coulomb stress change from the steady state at each
  // (Pa, finite), A sigma and s_r positive (Pa, Pa/s). std::invalid_argument otherwise (callers
  // check their input first and report it).
  PatchHistory(std::span<const double> t, std::span<const double> dcfs, double A_sigma, double stressing_rate);

  std::size_t size() const { return t_.size(); }
  double start() const { return t_.front(); }
  double end() const { return t_.back(); }
  double t_a() const { return t_a_; }

  // log(R / r) at the k-th date, and at any t in [start, end] (linear dCFS between dates).
  double log_rate_ratio(std::size_t k) const;
  double log_rate_ratio_at(double t) const;
  // R / r (exp of the above); finite as long as R / r fits a double (a first step of more than
  // ~709 A sigma does not: check log_rate_ratio first).
  double rate_ratio(std::size_t k) const;
  // log I(t): -inf at start.
  double log_integral_at(double t) const;
  // integral_{t1}^{t2} R / r dt (the unit of t), start <= t1 <= t2 <= end: exact, a sum of
  // positive terms (one per piece the interval spans), no cancellation.
  double integral_rate_ratio(double t1, double t2) const;

private:
  std::size_t piece_of(double t) const;          // i with t_i <= t <= t_{i+1}
  double x_at(std::size_t i, double t) const;    // S / A sigma at t in piece i
  double log_integral_between(std::size_t i, double a, double b) const;  // log of the integral over [a, b] in piece i
  std::vector<double> t_, x_, log_I_;            // dates, S / A sigma, log I at the dates
  double t_a_ = 0, log_t_a_ = 0;
};

}  // namespace ugs::seismicity
