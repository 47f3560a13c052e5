#include "ugs/fem/hypoplastic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ugs::fem {
namespace {

// One branch c(s) = k * max(s, smin)^-b  (b = 0 gives a constant compressibility k).
struct Branch {
  double k, b, smin;

  double c(double s) const { return k * std::pow(std::max(s, smin), -b); }

  // Integral of c from s0 to s1 (any order).
  double integral(double s0, double s1) const {
    if (s1 < s0) return -integral(s1, s0);
    double J = 0;
    if (s0 < smin) {
      const double top = std::min(s1, smin);
      J += c(smin) * (top - s0);
      s0 = top;
    }
    if (s1 > s0) J += power_integral(s0, s1);
    return J;
  }

  double power_integral(double s0, double s1) const {  // both >= smin
    if (b == 0) return k * (s1 - s0);
    if (std::abs(1 - b) < 1e-12) return k * std::log(s1 / s0);
    return k * (std::pow(s1, 1 - b) - std::pow(s0, 1 - b)) / (1 - b);
  }

  // s1 with integral(s0, s1) = J; +inf when a law with b > 1 cannot absorb J.
  double solve(double s0, double J) const {
    if (J == 0) return s0;
    if (J > 0) {
      if (s0 < smin) {
        const double J0 = c(smin) * (smin - s0);
        if (J <= J0) return s0 + J / c(smin);
        J -= J0;
        s0 = smin;
      }
      return power_solve(s0, J);
    }
    if (s0 > smin) {
      const double Jp = power_integral(s0, smin);  // negative
      if (J >= Jp) return power_solve(s0, J);
      J -= Jp;
      s0 = smin;
    }
    return s0 + J / c(smin);
  }

  double power_solve(double s0, double J) const {
    if (b == 0) return s0 + J / k;
    if (std::abs(1 - b) < 1e-12) return s0 * std::exp(J / k);
    const double base = std::pow(s0, 1 - b) + J * (1 - b) / k;
    if (!(base > 0)) return std::numeric_limits<double>::infinity();
    return std::pow(base, 1 / (1 - b));
  }
};

Branch virgin_branch(const HypoParams& p) { return {p.a, p.b, p.sigma_min}; }

// The unloading/reloading branch below sigma_max, given the inversion stress in effect.
Branch ur_branch(const HypoParams& p, const HypoState& st, double sigma_inv_eff) {
  switch (p.rule) {
    case InversionRule::SigmaMax: return {p.cm(st.sigma_max) / p.c_R, 0.0, p.sigma_min};
    case InversionRule::SigmaInversion: return {p.cm(sigma_inv_eff) / p.c_R, 0.0, p.sigma_min};
    case InversionRule::StressDependent: return {p.a / p.c_R, p.b, p.sigma_min};
  }
  return {};
}

}  // namespace

InversionRule parse_inversion_rule(const std::string& s) {
  if (s == "sigma-max") return InversionRule::SigmaMax;
  if (s == "sigma-inversion") return InversionRule::SigmaInversion;
  if (s == "stress-dependent") return InversionRule::StressDependent;
  throw std::invalid_argument("unknown inversion rule '" + s + "'");
}

const char* inversion_rule_name(InversionRule r) {
  switch (r) {
    case InversionRule::SigmaMax: return "sigma-max";
    case InversionRule::SigmaInversion: return "sigma-inversion";
    case InversionRule::StressDependent: return "stress-dependent";
  }
  return "?";
}

double HypoParams::cm(double sigma) const { return a * std::pow(std::max(sigma, sigma_min), -b); }

HypoResult hypo_integrate(const HypoParams& p, const HypoState& st, double s0, double J, int guess, Hold hold) {
  HypoResult r;
  r.state = st;
  const int dir = J > 0 ? +1 : J < 0 ? -1 : (guess >= 0 ? +1 : -1);
  // The direction that selects the inversion stress: a held branch keeps the one it was held with.
  const int dir_inv = hold == Hold::UnloadReload ? (guess >= 0 ? +1 : -1) : dir;
  // A change of direction is a load inversion at s0.
  const double s_inv = dir_inv != st.direction ? s0 : st.sigma_inv;
  const Branch virgin = virgin_branch(p), ur = ur_branch(p, st, s_inv);
  // Below sigma_max, with a margin for the round-off of sigma carried through the stress.
  const bool below = s0 < st.sigma_max - 1e-9 * std::max(1.0, st.sigma_max);
  // The knee: reloading reaches sigma_max at J_knee (at sigma_max already: J = 0).
  const double s_knee = below ? st.sigma_max : s0;
  r.J_knee = below ? ur.integral(s0, st.sigma_max) : 0.0;
  const bool on_virgin = hold == Hold::None && dir > 0 && (J > r.J_knee || (!below && J == 0));
  if (on_virgin) {
    r.sigma1 = virgin.solve(s_knee, J - r.J_knee);
    r.c_tangent = virgin.c(r.sigma1);
    r.phase = LoadingPhase::Virgin;
  } else {
    r.sigma1 = ur.solve(s0, J);
    r.c_tangent = ur.c(r.sigma1);
    r.phase = dir > 0 ? LoadingPhase::Reloading : LoadingPhase::Unloading;
  }
  if (!std::isfinite(r.sigma1)) {
    // The virgin law (b > 1) has a finite strain capacity; report it and keep numbers finite.
    r.saturated = true;
    r.sigma1 = std::max(s0, st.sigma_max) * 1e3;
    r.c_tangent = virgin.c(r.sigma1);
  }
  const double ds = r.sigma1 - s0;
  if (J == 0 || std::abs(ds) <= 1e-9 * std::max(std::abs(s0), 1.0)) {
    // Vanishing step: the secant is the tangent of the branch at the midpoint (exact to O(ds^2)).
    const double mid = 0.5 * (s0 + r.sigma1);
    r.c_secant = on_virgin && !below ? virgin.c(mid) : ur.c(mid);
    if (J == 0) r.c_tangent = r.c_secant;
  } else {
    r.c_secant = J / ds;
  }
  if (J != 0) {
    r.state.direction = dir;
    r.state.sigma_inv = dir != st.direction ? s0 : st.sigma_inv;
    r.state.sigma_max = std::max(st.sigma_max, r.sigma1);
  }
  return r;
}

}  // namespace ugs::fem
