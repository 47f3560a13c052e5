#include "saddle_reuse.hpp"

#include <algorithm>

#include "ugs/mechanics/reuse_rule.hpp"

namespace ugs::contact::detail {

double SaddleReuse::per_decade(int iterations, double decades) {
  // A solve that reduced less than a decade (a good first iterate) counts as one decade.
  return static_cast<double>(iterations) / std::max(decades, 1.0);
}

bool SaddleReuse::keep(bool allowed, const std::vector<double>& signature) const {
  return allowed && built_ && solves_in_step_ == 0 && last_step_linear_ && signature == signature_ &&
         mech::keep_multigrid(baseline_ipd_, last_ipd_);
}

void SaddleReuse::record(int iterations, double decades, bool fresh, const std::vector<double>& signature) {
  ++solves_in_step_;
  last_ipd_ = per_decade(iterations, decades);
  if (fresh) {
    baseline_ipd_ = last_ipd_;
    signature_ = signature;
    built_ = true;
    ++setups_;
  }
}

}  // namespace ugs::contact::detail
