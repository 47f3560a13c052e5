#include "saddle_reuse.hpp"

#include <algorithm>

#include "ugs/mechanics/reuse_rule.hpp"

namespace ugs::contact::detail {

double SaddleReuse::per_decade(int iterations, double decades) {
  // A solve that reduced less than a decade (a good first iterate) counts as one decade.
  return static_cast<double>(iterations) / std::max(decades, 1.0);
}

bool SaddleReuse::keep(bool allowed, const std::vector<double>& signature) const {
  return allowed && built_ && signature == signature_ && mech::keep_multigrid(baseline_ipd_, last_ipd_);
}

void SaddleReuse::record(int iterations, double decades, bool fresh, const std::vector<double>& signature) {
  last_ipd_ = per_decade(iterations, decades);
  if (fresh) {
    baseline_ipd_ = last_ipd_;
    signature_ = signature;
    built_ = true;
    ++setups_;
  }
}

bool FactorReuse::keep(bool allowed, const std::vector<double>& signature) const {
  return allowed && built_ && signature == signature_ && extra_ < mech::kRefactorIterations &&
         mech::keep_factorization(baseline_ipd_, last_ipd_, last_decades_, mech::kRefactorIterations, mech::kFactorHorizon);
}

void FactorReuse::record(int iterations, double reduction, bool fresh, const std::vector<double>& signature) {
  last_decades_ = mech::counted_decades(reduction);  // as the continuous solver counts
  last_ipd_ = iterations / last_decades_;
  if (fresh) {
    baseline_ipd_ = last_ipd_;
    extra_ = 0;
    signature_ = signature;
    built_ = true;
    ++setups_;
  } else {
    extra_ += std::max(0.0, (last_ipd_ - baseline_ipd_) * last_decades_);
  }
}

int FactorReuse::budget(double rtol) { return mech::factor_budget(rtol); }

}  // namespace ugs::contact::detail
