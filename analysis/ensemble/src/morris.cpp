#include "ugs/ensemble/morris.hpp"

#include <cmath>
#include <numeric>

#include <openturns/OT.hxx>

namespace ugs::ensemble {

double morris_probability(double unit, int levels) { return (0.5 + unit * (levels - 1)) / levels; }

MorrisDesign morris_trajectories(std::size_t d, std::size_t r, int levels) {
  MorrisDesign m;
  const double p = levels;
  const double delta = p / (2 * (p - 1));
  // Grid levels from which a step of +Delta stays inside: 0 .. p/2 - 1 (a step of -Delta starts
  // Delta higher, so it covers the upper half).
  const auto half = static_cast<OT::UnsignedInteger>(levels / 2);
  for (std::size_t t = 0; t < r; ++t) {
    std::vector<double> x(d);
    std::vector<double> sign(d);
    for (std::size_t j = 0; j < d; ++j) {
      const auto k = OT::RandomGenerator::IntegerGenerate(1, half)[0];
      sign[j] = OT::RandomGenerator::Generate() < 0.5 ? 1.0 : -1.0;
      x[j] = static_cast<double>(k) / (p - 1) + (sign[j] < 0 ? delta : 0.0);
    }
    // A random order of the parameters (Fisher-Yates from OpenTURNS' generator).
    std::vector<std::size_t> order(d);
    std::iota(order.begin(), order.end(), 0);
    for (std::size_t i = d; i > 1; --i) {
      const auto j = OT::RandomGenerator::IntegerGenerate(1, i)[0];
      std::swap(order[i - 1], order[j]);
    }
    m.unit.push_back(x);
    m.factor.push_back(0);
    m.step.push_back(0);
    for (std::size_t s = 0; s < d; ++s) {
      const std::size_t j = order[s];
      x[j] += sign[j] * delta;
      m.unit.push_back(x);
      m.factor.push_back(j);
      m.step.push_back(sign[j] * delta);
    }
  }
  return m;
}

MorrisEffects morris_effects(std::size_t d, const std::vector<std::size_t>& factor, const std::vector<double>& step,
                             const std::vector<double>& y, const std::vector<bool>& ok) {
  MorrisEffects e;
  std::vector<std::vector<double>> ee(d);
  const std::size_t len = d + 1;
  for (std::size_t t = 0; t + len <= y.size(); t += len) {
    bool complete = true;
    for (std::size_t i = t; i < t + len; ++i) complete = complete && ok[i];
    if (!complete) continue;
    ++e.trajectories;
    for (std::size_t i = t + 1; i < t + len; ++i) ee[factor[i]].push_back((y[i] - y[i - 1]) / step[i]);
  }
  e.mu.assign(d, 0);
  e.mu_star.assign(d, 0);
  e.sigma.assign(d, 0);
  for (std::size_t j = 0; j < d; ++j) {
    const auto n = static_cast<double>(ee[j].size());
    if (ee[j].empty()) continue;
    for (double v : ee[j]) {
      e.mu[j] += v / n;
      e.mu_star[j] += std::abs(v) / n;
    }
    if (ee[j].size() > 1) {
      double ss = 0;
      for (double v : ee[j]) ss += (v - e.mu[j]) * (v - e.mu[j]);
      e.sigma[j] = std::sqrt(ss / (n - 1));
    }
  }
  return e;
}

}  // namespace ugs::ensemble
