// Morris' elementary-effects screening (Morris 1991, Technometrics 33(2) 161-174), with mu*, the
// mean of the absolute effects (Campolongo, Cariboni & Saltelli 2007, Environ. Model. Softw. 22,
// 1509-1518). OpenTURNS 1.20's core has no Morris design (it lives in the separate otmorris
// module, not packaged by Debian), so the trajectories are built here, from OpenTURNS' random
// generator.
//
// In the unit cube with p levels {0, 1/(p-1), ..., 1} and the step Delta = p / (2 (p - 1)), a
// trajectory starts at a random grid point whose coordinates allow a step of Delta, then moves one
// parameter at a time, in a random order, by +Delta or -Delta (random direction): d + 1 points. A
// level u becomes a value through the parameter's quantile at (0.5 + u (p - 1)) / p, the midpoint of
// the p equally likely bins, so unbounded distributions work too. The elementary effect of
// parameter i on a step is (y_after - y_before) / step_i, step_i the change of the quantile's
// probability (+-Delta (p - 1) / p): effects are in the metric's units per unit of probability, so
// parameters with different units compare (a uniform parameter on [a, b] with y = k x has mu* = k (b - a)).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ugs::ensemble {

struct MorrisDesign {
  std::vector<std::vector<double>> unit;   // r (d + 1) rows in [0, 1]^d
  std::vector<std::size_t> factor;         // per row: the parameter changed to reach it (0 on a first row)
  std::vector<double> step;                // per row: its signed step (0 on a first row)
};

// `r` trajectories of `d` parameters on `levels` levels (even, >= 2); uses OpenTURNS'
// RandomGenerator, which the caller seeds.
MorrisDesign morris_trajectories(std::size_t d, std::size_t r, int levels);

// Unit level -> probability of the quantile taken.
double morris_probability(double unit, int levels);

struct MorrisEffects {
  std::vector<double> mu, mu_star, sigma;  // per parameter
  std::size_t trajectories = 0;            // complete trajectories used
};

// y per row; `ok` false for a failed member: its trajectory is left out whole.
MorrisEffects morris_effects(std::size_t d, const std::vector<std::size_t>& factor, const std::vector<double>& step,
                             const std::vector<double>& y, const std::vector<bool>& ok);

}  // namespace ugs::ensemble
