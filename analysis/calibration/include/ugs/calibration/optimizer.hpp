// Derivative-free minimisation of the calibration misfit over bounded parameters.
//
// 1. Scan: a regular grid of `scan` values per parameter (bounds included), evaluated
//    concurrently; it gives the misfit profile and a start that is not a far local minimum.
// 2. Refinement from the best grid point:
//    - one parameter: Brent's method (golden section with parabolic steps, Brent 1973) inside the
//      grid cells next to the best point;
//    - several: NLopt's BOBYQA (Powell 2009: bounded quadratic models), initial step half a grid cell.
// Parameters are searched on [0, 1] (linear, or log10 for ":log" parameters); xtol is relative to
// that range. One parameter whose series respond affinely to 1/x: reciprocal.hpp (four runs).
#pragma once
#include <string>
#include <vector>

#include "ugs/calibration/evaluator.hpp"

namespace ugs::calibration {

struct OptimizerOptions {
  int scan = -1;          // grid values per parameter; -1: 5 for one parameter, 3 for more; 0 or 1: no scan
  double xtol = 0.005;    // stop when the step is below this fraction of each range
  int max_evals = 60;     // total evaluations (scan included)
};

struct OptimizerResult {
  std::vector<double> best_x;
  double best_rms_mm = 0;
  std::size_t best_index = 0;   // into the evaluator's history
  std::string method;           // "scan + Brent", "scan + BOBYQA", ...
  bool converged = false;
  std::string stop_reason;
};

// Maps [0, 1] to the parameter's natural units (linear or log10).
double to_natural(const runner::ParameterSpec& p, double s);
double to_unit(const runner::ParameterSpec& p, double x);

OptimizerResult optimize(Evaluator& evaluator, const std::vector<runner::ParameterSpec>& params, const OptimizerOptions& options);

// The answer of a search: the evaluation of lowest RMS among the evaluator's history from `first`
// on (best_index, best_x, best_rms_mm of `res`).
void take_best_evaluated(const Evaluator& evaluator, std::size_t first, OptimizerResult& res);

// Brent's localmin on [a, b] starting from x0 (f(x0) = f0 known), to tolerance tol; stops after
// max_evals calls of f. Returns the best x seen. Exposed for tests.
struct BrentResult {
  double x = 0, f = 0;
  int evaluations = 0;
  bool converged = false;
};
BrentResult brent_minimize(const std::function<double(double)>& f, double a, double b, double x0, double f0, double tol,
                           int max_evals);

}  // namespace ugs::calibration
