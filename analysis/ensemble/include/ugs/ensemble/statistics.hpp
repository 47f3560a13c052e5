// What an ensemble says about a metric: quantiles, exceedance probabilities and the indices of the
// design (Sobol' first and total order with confidence intervals, or Morris mu*, sigma). Failed
// members are excluded: `ok` false. For Sobol' a base point whose block is incomplete (any of its
// d + 2 members failed) is excluded whole, as the estimator needs every block aligned.
#pragma once
#include <cstddef>
#include <vector>

#include "ugs/ensemble/design.hpp"

namespace ugs::ensemble {

// P10, P50, P90: the 10 %, 50 % and 90 % quantiles (probability of a value at or below them;
// OpenTURNS' empirical quantile: linear between the order statistics placed at probabilities
// (k - 1/2) / n, Hyndman & Fan 1996 type 5). n = values used.
struct Quantiles {
  std::size_t n = 0;
  double mean = 0, p10 = 0, p50 = 0, p90 = 0, min = 0, max = 0;
};
Quantiles quantiles(const std::vector<double>& values);

// Fraction of the values >= threshold.
double exceedance(const std::vector<double>& values, double threshold);

struct SobolIndices {
  std::vector<double> first, first_low, first_high;   // per parameter, and the interval bounds
  std::vector<double> total, total_low, total_high;
  std::size_t base = 0;                               // complete base points used
  double confidence = 0.95;
};
// Martinez' estimator (Martinez 2011; Baudin et al. 2016) from OpenTURNS, with its asymptotic
// (delta-method) confidence intervals at 95 %. Throws ComputeError when fewer than 2 complete base
// points remain or the output has no variance.
SobolIndices sobol_indices(const Design& design, const std::vector<double>& y, const std::vector<bool>& ok);

}  // namespace ugs::ensemble
