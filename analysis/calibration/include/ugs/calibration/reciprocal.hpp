// Calibration of one parameter whose simulated series respond (close to) affinely to its
// reciprocal, in three concurrent solver runs and one check: c_R, whose reloading uplift goes as
// 1 / c_R (the reloading compressibility is c_M / c_R, docs/theory.md).
//
// With y = 1 / x, the runs at the range's ends and at the middle of its y range give each value of
// the simulated series (every PS point, component and output date) as a quadratic in y through
// the three (Lagrange interpolation): exact when the series are affine in y, and it carries the
// curvature when they are not quite. The misfit is a quadratic form of the series (offset removal,
// interpolation in time and the window are linear), so the modelled mean square is a quartic in y,
// built exactly from the misfits of the three runs and of their pairwise averages (polarisation).
// Its minimum on the range is the model's answer x* = 1 / y*; one solver run checks it.
//
// The model is not trusted — and Brent's method (in y, inside the evaluated points next to the best
// one, with the rest of the evaluation budget) takes over, saying why — when the modelled misfit
// has more than one local minimum over the range, when the runs' series do not share points and
// dates, when the misfit is not the quadratic form the model assumes, or when the check is worse
// than the best of the three runs. The answer is the best point evaluated.
#pragma once
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "ugs/calibration/evaluator.hpp"
#include "ugs/calibration/optimizer.hpp"

namespace ugs::calibration {

struct ReciprocalReport {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::array<double, 3> x{kNaN, kNaN, kNaN};        // the three runs: lower bound, 1 / middle of 1/x, upper bound
  std::array<double, 3> rms_mm{kNaN, kNaN, kNaN};   // their misfits
  // Largest departure of the middle run's series from the affine interpolation in 1/x of the outer
  // two (any point, component, output date) and the largest change of a series value over the
  // range: how far from reciprocal the response is, in mm.
  double curvature_mm = kNaN, response_mm = kNaN;
  double x_model = kNaN;             // the model's minimum (NaN: no model)
  double predicted_rms_mm = kNaN;    // the model's RMS there
  double checked_rms_mm = kNaN;      // the check run's RMS there (NaN: not run)
  bool check_is_new_point = false;    // false when x_model is one of the three runs (no solver run)
  std::string fallback;              // why the model was not trusted ("" when it was)
  std::vector<std::array<double, 2>> profile;  // the modelled misfit: (x, RMS mm) over the range
};

struct ReciprocalResult {
  OptimizerResult result;
  ReciprocalReport report;
};

// InputError (settings named in words: "response model", "parameter to calibrate", "evaluation
// budget", "scan values per parameter") unless there is one parameter, with positive linear bounds,
// a budget of at least 4 evaluations and no scan (`scan_given`).
void check_reciprocal(const std::vector<runner::ParameterSpec>& params, const OptimizerOptions& options, bool scan_given);

// Three runs (concurrent, phase "reciprocal"), the model, one check run (phase "check"), and Brent
// (phase "brent") only when the model is not trusted. `xtol` is a fraction of the 1/x range there.
ReciprocalResult calibrate_reciprocal(Evaluator& evaluator, const std::vector<runner::ParameterSpec>& params,
                                      const OptimizerOptions& options);

}  // namespace ugs::calibration
