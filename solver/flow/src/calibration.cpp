#include "ugs/flow/calibration.hpp"

#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs::flow {

RootResult find_multiplier(const std::function<double(double)>& g, const RootOptions& o,
                           const std::function<void(const RootEvaluation&)>& report) {
  int evals = 0;
  auto eval = [&](double u, const char* phase) {
    if (evals >= o.max_evaluations)
      throw ComputeError(fmt::format("calibration: no convergence after {} evaluations", o.max_evaluations));
    const double x = std::exp(u);
    const double v = g(x);
    ++evals;
    if (report) report({evals, phase, x, v});
    return v;
  };
  // 1. Bracket in u = ln x: step away from x0 in the direction that reduces |g|, growing the step.
  const double step0 = std::log(o.expand);
  double ua = std::log(o.x0), ga = eval(ua, "bracket");
  if (ga == 0) return {o.x0, 0, evals};
  if (std::abs(ga) <= o.g_tolerance) return {o.x0, ga, evals};
  double ub = ua + step0, gb = eval(ub, "bracket");
  double dir = 1;
  if (ga * gb > 0 && std::abs(gb) > std::abs(ga)) {
    // Going up made it worse: go down from x0 instead.
    dir = -1;
    ub = ua - step0;
    gb = eval(ub, "bracket");
  }
  double step = step0;
  while (ga * gb > 0) {
    ua = ub, ga = gb;
    step *= 2;
    ub = ua + dir * step;
    if (ub < std::log(o.x_min) || ub > std::log(o.x_max))
      throw ComputeError(fmt::format("calibration: the target is not reached for multipliers {:g} .. {:g} (misfit {:.6g} at {:g})",
                                     o.x_min, o.x_max, ga, std::exp(ua)));
    gb = eval(ub, "bracket");
  }
  if (gb == 0) return {std::exp(ub), 0, evals};
  // 2. Brent's method on [ua, ub] (Brent 1973, "zero").
  double a = ua, fa = ga, b = ub, fb = gb, c = a, fc = fa, d = b - a, e = d;
  for (;;) {
    if (fb * fc > 0) c = a, fc = fa, d = e = b - a;
    if (std::abs(fc) < std::abs(fb)) {
      a = b, b = c, c = a;
      fa = fb, fb = fc, fc = fa;
    }
    const double tol = 2 * 2.2e-16 * std::abs(b) + 0.5 * o.x_rel_tolerance;
    const double m = 0.5 * (c - b);
    if (std::abs(m) <= tol || std::abs(fb) <= o.g_tolerance || fb == 0) return {std::exp(b), fb, evals};
    if (std::abs(e) < tol || std::abs(fa) <= std::abs(fb)) {
      d = e = m;  // bisection
    } else {
      double s = fb / fa, p, q;
      if (a == c) {
        p = 2 * m * s;  // secant
        q = 1 - s;
      } else {
        const double qq = fa / fc, r = fb / fc;  // inverse quadratic interpolation
        p = s * (2 * m * qq * (qq - r) - (b - a) * (r - 1));
        q = (qq - 1) * (r - 1) * (s - 1);
      }
      if (p > 0) q = -q; else p = -p;
      if (2 * p < std::min(3 * m * q - std::abs(tol * q), std::abs(e * q))) {
        e = d;
        d = p / q;
      } else {
        d = e = m;
      }
    }
    a = b, fa = fb;
    b += std::abs(d) > tol ? d : (m > 0 ? tol : -tol);
    fb = eval(b, "brent");
  }
}

}  // namespace ugs::flow
