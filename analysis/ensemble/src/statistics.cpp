#include "ugs/ensemble/statistics.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <openturns/OT.hxx>

#include "ugs/formats/error.hpp"

namespace ugs::ensemble {

Quantiles quantiles(const std::vector<double>& values) {
  Quantiles q;
  q.n = values.size();
  if (values.empty()) return q;
  OT::Sample s(values.size(), 1);
  for (std::size_t i = 0; i < values.size(); ++i) s(i, 0) = values[i];
  q.mean = s.computeMean()[0];
  q.p10 = s.computeQuantilePerComponent(0.1)[0];
  q.p50 = s.computeQuantilePerComponent(0.5)[0];
  q.p90 = s.computeQuantilePerComponent(0.9)[0];
  q.min = *std::min_element(values.begin(), values.end());
  q.max = *std::max_element(values.begin(), values.end());
  return q;
}

double exceedance(const std::vector<double>& values, double threshold) {
  if (values.empty()) return 0;
  const auto n = std::count_if(values.begin(), values.end(), [&](double v) { return v >= threshold; });
  return static_cast<double>(n) / static_cast<double>(values.size());
}

SobolIndices sobol_indices(const Design& design, const std::vector<double>& y, const std::vector<bool>& ok) {
  const std::size_t d = design.dimension, n = design.base;
  if (design.method != DesignMethod::sobol || design.x.size() != n * (d + 2) || y.size() != design.x.size())
    throw std::invalid_argument("sobol_indices: not a Sobol' design of this output");
  // Base points whose d + 2 members all succeeded.
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < n; ++i) {
    bool complete = true;
    for (std::size_t b = 0; b < d + 2; ++b) complete = complete && ok[b * n + i];
    if (complete) kept.push_back(i);
  }
  if (kept.size() < 2)
    throw ComputeError(fmt::format("Sobol' indices need 2 complete base points; {} of {} remain", kept.size(), n));
  const std::size_t m = kept.size();
  OT::Sample X(m * (d + 2), d), Y(m * (d + 2), 1);
  for (std::size_t b = 0; b < d + 2; ++b)
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t from = b * n + kept[k], to = b * m + k;
      for (std::size_t j = 0; j < d; ++j) X(to, j) = design.x[from][j];
      Y(to, 0) = y[from];
    }
  double lo = Y(0, 0), hi = Y(0, 0);
  for (std::size_t i = 0; i < Y.getSize(); ++i) {
    lo = std::min(lo, Y(i, 0));
    hi = std::max(hi, Y(i, 0));
  }
  if (!(hi > lo)) throw ComputeError("the output takes one value over all members: no variance to apportion");
  OT::MartinezSensitivityAlgorithm a(X, Y, m);
  a.setUseAsymptoticDistribution(true);
  a.setConfidenceLevel(0.95);
  SobolIndices s;
  s.base = m;
  const OT::Point s1 = a.getFirstOrderIndices(), st = a.getTotalOrderIndices();
  const OT::Interval i1 = a.getFirstOrderIndicesInterval(), it = a.getTotalOrderIndicesInterval();
  for (std::size_t j = 0; j < d; ++j) {
    s.first.push_back(s1[j]);
    s.first_low.push_back(i1.getLowerBound()[j]);
    s.first_high.push_back(i1.getUpperBound()[j]);
    s.total.push_back(st[j]);
    s.total_low.push_back(it.getLowerBound()[j]);
    s.total_high.push_back(it.getUpperBound()[j]);
  }
  return s;
}

}  // namespace ugs::ensemble
