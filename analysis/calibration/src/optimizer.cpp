#include "ugs/calibration/optimizer.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

#include <fmt/format.h>
#include <nlopt.hpp>

#include "ugs/formats/error.hpp"

namespace ugs::calibration {

using runner::ParameterSpec;

double to_natural(const ParameterSpec& p, double s) {
  s = std::clamp(s, 0.0, 1.0);
  if (p.log_scale) return std::pow(10.0, std::log10(p.lower) + s * (std::log10(p.upper) - std::log10(p.lower)));
  return p.lower + s * (p.upper - p.lower);
}

double to_unit(const ParameterSpec& p, double x) {
  if (p.log_scale) return (std::log10(x) - std::log10(p.lower)) / (std::log10(p.upper) - std::log10(p.lower));
  return (x - p.lower) / (p.upper - p.lower);
}

BrentResult brent_minimize(const std::function<double(double)>& f, double a, double b, double x0, double f0, double tol,
                           int max_evals) {
  const double c = 0.5 * (3.0 - std::sqrt(5.0));
  const double eps = std::sqrt(std::numeric_limits<double>::epsilon());
  double x = std::clamp(x0, a, b), w = x, v = x, fx = f0, fw = f0, fv = f0;
  double d = 0, e = 0;
  BrentResult r;
  for (;;) {
    const double m = 0.5 * (a + b);
    const double tol1 = eps * std::abs(x) + tol / 3.0, t2 = 2.0 * tol1;
    if (std::abs(x - m) <= t2 - 0.5 * (b - a)) {
      r.converged = true;
      break;
    }
    if (r.evaluations >= max_evals) break;
    bool golden = true;
    if (std::abs(e) > tol1) {
      // Parabola through (v, fv), (w, fw), (x, fx).
      double rr = (x - w) * (fx - fv), q = (x - v) * (fx - fw), p = (x - v) * q - (x - w) * rr;
      q = 2.0 * (q - rr);
      if (q > 0)
        p = -p;
      else
        q = -q;
      const double e_old = e;
      e = d;
      if (std::abs(p) < std::abs(0.5 * q * e_old) && p > q * (a - x) && p < q * (b - x)) {
        d = p / q;
        const double u = x + d;
        if (u - a < t2 || b - u < t2) d = x < m ? tol1 : -tol1;
        golden = false;
      }
    }
    if (golden) {
      e = (x < m ? b : a) - x;
      d = c * e;
    }
    const double u = x + (std::abs(d) >= tol1 ? d : (d > 0 ? tol1 : -tol1));
    const double fu = f(u);
    ++r.evaluations;
    if (fu <= fx) {
      (u < x ? b : a) = x;
      v = w, fv = fw, w = x, fw = fx, x = u, fx = fu;
    } else {
      (u < x ? a : b) = u;
      if (fu <= fw || w == x) {
        v = w, fv = fw, w = u, fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u, fv = fu;
      }
    }
  }
  r.x = x;
  r.f = fx;
  return r;
}

namespace {

std::vector<double> natural(const std::vector<ParameterSpec>& params, const std::vector<double>& s) {
  std::vector<double> x(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) x[i] = to_natural(params[i], s[i]);
  return x;
}

}  // namespace

OptimizerResult optimize(Evaluator& ev, const std::vector<ParameterSpec>& params, const OptimizerOptions& o) {
  const std::size_t n = params.size();
  if (n == 0) throw InputError("", "no parameter to calibrate was given");
  OptimizerResult res;
  int scan = o.scan < 0 ? (n == 1 ? 5 : 3) : o.scan;
  if (scan == 1) scan = 0;
  std::vector<double> start(n, 0.5);
  double half_cell = 0.25;
  int used = 0;
  if (scan >= 2) {
    std::size_t total = 1;
    for (std::size_t i = 0; i < n; ++i) total *= static_cast<std::size_t>(scan);
    if (total > 100000) throw InputError("scan values per parameter", fmt::format("{}^{} grid points is too many", scan, n));
    std::vector<std::vector<double>> grid;
    for (std::size_t g = 0; g < total; ++g) {
      std::vector<double> s(n);
      std::size_t rem = g;
      for (std::size_t i = 0; i < n; ++i) {
        s[i] = double(rem % scan) / double(scan - 1);
        rem /= scan;
      }
      grid.push_back(natural(params, s));
    }
    const auto evs = ev.evaluate(grid, "scan");
    used += static_cast<int>(evs.size());
    std::size_t best = 0;
    for (std::size_t g = 1; g < evs.size(); ++g)
      if (evs[g].misfit.rms_mm < evs[best].misfit.rms_mm) best = g;
    for (std::size_t i = 0; i < n; ++i) start[i] = to_unit(params[i], grid[best][i]);
    half_cell = 0.5 / double(scan - 1);
  }
  const int budget = o.max_evals - used;
  auto f_unit = [&](const std::vector<double>& s, const char* phase) {
    return ev.evaluate({natural(params, s)}, phase).front().misfit.rms_mm;
  };
  if (budget > 0 && n == 1) {
    const double h = scan >= 2 ? 2 * half_cell : 0.5;
    const double a = std::max(0.0, start[0] - h), b = std::min(1.0, start[0] + h);
    const double f0 = f_unit(start, "brent");  // from the scan: costs nothing
    const auto br = brent_minimize([&](double s) { return f_unit({s}, "brent"); }, a, b, start[0], f0, o.xtol, budget);
    res.method = scan >= 2 ? "scan + Brent" : "Brent";
    res.converged = br.converged;
    res.stop_reason = br.converged ? fmt::format("bracket below xtol {}", o.xtol) : "evaluation budget used";
  } else if (budget > 0) {
    nlopt::opt opt(nlopt::LN_BOBYQA, static_cast<unsigned>(n));
    opt.set_lower_bounds(std::vector<double>(n, 0.0));
    opt.set_upper_bounds(std::vector<double>(n, 1.0));
    opt.set_xtol_abs(o.xtol);
    opt.set_maxeval(budget);
    std::vector<double> step(n);
    for (std::size_t i = 0; i < n; ++i) step[i] = std::min(half_cell, std::max(start[i], 1.0 - start[i]));
    opt.set_initial_step(step);
    struct Ctx {
      decltype(f_unit)* f;
      std::exception_ptr error;
      nlopt::opt* opt;
    } ctx{&f_unit, nullptr, &opt};
    opt.set_min_objective(
        [](unsigned nn, const double* s, double*, void* data) -> double {
          auto* c = static_cast<Ctx*>(data);
          try {
            return (*c->f)(std::vector<double>(s, s + nn), "bobyqa");
          } catch (...) {
            c->error = std::current_exception();
            c->opt->force_stop();
            return std::numeric_limits<double>::max();
          }
        },
        &ctx);
    std::vector<double> s = start;
    double fmin = 0;
    nlopt::result r = nlopt::FAILURE;
    try {
      r = opt.optimize(s, fmin);
    } catch (const nlopt::forced_stop&) {
    } catch (const std::runtime_error& e) {
      if (!ctx.error) throw ComputeError(std::string("BOBYQA failed: ") + e.what());
    }
    if (ctx.error) std::rethrow_exception(ctx.error);
    res.method = scan >= 2 ? "scan + BOBYQA" : "BOBYQA";
    res.converged = r == nlopt::XTOL_REACHED || r == nlopt::FTOL_REACHED || r == nlopt::SUCCESS;
    res.stop_reason = r == nlopt::XTOL_REACHED   ? fmt::format("step below xtol {}", o.xtol)
                      : r == nlopt::MAXEVAL_REACHED ? "evaluation budget used"
                      : r == nlopt::FTOL_REACHED    ? "misfit change below ftol"
                                                    : fmt::format("NLopt result {}", static_cast<int>(r));
  } else {
    res.method = "scan";
    res.stop_reason = "evaluation budget used by the scan";
  }
  // The answer is the best point evaluated.
  take_best_evaluated(ev, 0, res);
  return res;
}

void take_best_evaluated(const Evaluator& evaluator, std::size_t first, OptimizerResult& res) {
  const auto& h = evaluator.history();
  std::size_t best = first;
  for (std::size_t i = first + 1; i < h.size(); ++i)
    if (h[i].misfit.rms_mm < h[best].misfit.rms_mm) best = i;
  res.best_index = best;
  res.best_x = h[best].x;
  res.best_rms_mm = h[best].misfit.rms_mm;
}

}  // namespace ugs::calibration
