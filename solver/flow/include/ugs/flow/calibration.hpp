// Calibration of the aquifer conductivity against a target influx (thesis 4.2.1: the water
// entered into Pool C by the end of primary production, 3.78e6 m3, matched by the flow model).
// The unknown is a multiplier x > 0 on the conductivity of the chosen materials; the influx is
// monotone in it, so a bracketing root finder on log x is safe: the bracket is expanded from
// x0 by a constant factor until the misfit changes sign, then Brent's method (inverse quadratic
// interpolation with bisection safeguards) closes it.
#pragma once
#include <functional>
#include <string>

namespace ugs::flow {

struct RootEvaluation {
  int evaluation = 0;    // 1, 2, ...
  std::string phase;     // "bracket" or "brent"
  double x = 0;          // multiplier tried
  double g = 0;          // misfit g(x)
};

struct RootOptions {
  double x0 = 1.0;              // first guess
  double expand = 4.0;          // bracket expansion factor
  double g_tolerance = 0;       // stop when |g| <= this
  double x_rel_tolerance = 1e-6;// or when the bracket is this narrow (relative)
  int max_evaluations = 40;
  double x_min = 1e-8, x_max = 1e8;  // give up beyond these (ComputeError)
};

struct RootResult {
  double x = 0, g = 0;
  int evaluations = 0;
};

// Finds x with g(x) = 0. ComputeError when no sign change is found within [x_min, x_max] or the
// evaluations run out (the message names the range searched and the misfits seen).
RootResult find_multiplier(const std::function<double(double)>& g, const RootOptions& options,
                           const std::function<void(const RootEvaluation&)>& report = {});

}  // namespace ugs::flow
