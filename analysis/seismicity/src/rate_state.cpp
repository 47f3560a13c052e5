#include "ugs/seismicity/rate_state.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ugs::seismicity {

double log_mean_exp_linear(double d) {
  // log((e^d - 1) / d) = d / 2 + log(sinh(d / 2) / (d / 2)); near 0 the series of the second term
  // (y^2 / 6 - y^4 / 180 + y^6 / 2835, next term below 1e-27 for |d| < 1e-3), else expm1 on the side
  // where it cannot overflow.
  if (std::abs(d) < 1e-3) {
    const double y2 = 0.25 * d * d;
    return 0.5 * d + y2 * (1.0 / 6 - y2 * (1.0 / 180 - y2 / 2835));
  }
  if (d > 0) return d + std::log(-std::expm1(-d) / d);
  return std::log(std::expm1(d) / d);
}

double softplus(double z) { return z > 0 ? z + std::log1p(std::exp(-z)) : std::log1p(std::exp(z)); }

double log_add_exp(double a, double b) {
  const double hi = std::max(a, b), lo = std::min(a, b);
  if (hi == -std::numeric_limits<double>::infinity()) return hi;
  return hi + std::log1p(std::exp(lo - hi));
}

PatchHistory::PatchHistory(std::span<const double> t, std::span<const double> dcfs, double A_sigma, double stressing_rate) {
  if (t.size() < 2 || t.size() != dcfs.size())
    throw std::invalid_argument("PatchHistory: needs two dates or more, and one stress per date");
  if (!(A_sigma > 0) || !(stressing_rate > 0) || !std::isfinite(A_sigma) || !std::isfinite(stressing_rate))
    throw std::invalid_argument("PatchHistory: A sigma and the stressing rate must be positive");
  t_.assign(t.begin(), t.end());
  t_a_ = A_sigma / stressing_rate;
  log_t_a_ = std::log(t_a_);
  x_.resize(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (!std::isfinite(t[k]) || !std::isfinite(dcfs[k]) || (k > 0 && !(t[k] > t[k - 1])))
      throw std::invalid_argument("PatchHistory: dates must increase and stresses be finite");
    x_[k] = (t[k] - t[0]) / t_a_ + dcfs[k] / A_sigma;
  }
  log_I_.assign(t.size(), -std::numeric_limits<double>::infinity());
  for (std::size_t k = 1; k < t.size(); ++k)
    log_I_[k] = log_add_exp(log_I_[k - 1], log_integral_between(k - 1, t_[k - 1], t_[k]));
}

std::size_t PatchHistory::piece_of(double t) const {
  const auto it = std::upper_bound(t_.begin(), t_.end(), t);
  const std::size_t i = it == t_.begin() ? 0 : static_cast<std::size_t>(it - t_.begin()) - 1;
  return std::min(i, t_.size() - 2);
}

double PatchHistory::x_at(std::size_t i, double t) const {
  if (t == t_[i]) return x_[i];
  if (t == t_[i + 1]) return x_[i + 1];
  return x_[i] + (x_[i + 1] - x_[i]) * ((t - t_[i]) / (t_[i + 1] - t_[i]));
}

double PatchHistory::log_integral_between(std::size_t i, double a, double b) const {
  if (!(b > a)) return -std::numeric_limits<double>::infinity();
  const double xa = x_at(i, a), xb = x_at(i, b);
  return std::log(b - a) + xa + log_mean_exp_linear(xb - xa);
}

double PatchHistory::log_rate_ratio(std::size_t k) const { return x_[k] - softplus(log_I_[k] - log_t_a_); }

double PatchHistory::log_integral_at(double t) const {
  const std::size_t i = piece_of(t);
  return log_add_exp(log_I_[i], log_integral_between(i, t_[i], t));
}

double PatchHistory::log_rate_ratio_at(double t) const {
  const std::size_t i = piece_of(t);
  return x_at(i, t) - softplus(log_integral_at(t) - log_t_a_);
}

double PatchHistory::rate_ratio(std::size_t k) const { return std::exp(log_rate_ratio(k)); }

double PatchHistory::integral_rate_ratio(double t1, double t2) const {
  if (!(t2 > t1)) return 0.0;
  // Over [a, b]: t_a log(1 + (I(b) - I(a)) / (t_a + I(a))) = t_a softplus(log(I(b) - I(a)) - log(t_a + I(a))).
  double sum = 0;
  for (std::size_t i = piece_of(t1); i + 1 < t_.size(); ++i) {
    const double a = std::max(t1, t_[i]), b = std::min(t2, t_[i + 1]);
    if (b > a) {
      const double log_denominator = log_add_exp(log_t_a_, log_integral_at(a));
      sum += t_a_ * softplus(log_integral_between(i, a, b) - log_denominator);
    }
    if (t_[i + 1] >= t2) break;
  }
  return sum;
}

}  // namespace ugs::seismicity
