#include "ugs/mechanics/step_dates.hpp"

#include <stdexcept>

namespace ugs::mech {

void TurningPoints::add(const std::vector<double>& dp) {
  const auto k = static_cast<std::int32_t>(turns_.size());
  turns_.push_back(0);
  if (k == 0) {
    secured_.assign(dp.size(), 0.0);
    low_.assign(dp.size(), 0.0);
    low_date_.assign(dp.size(), -1);
    direction_.assign(dp.size(), 0);
  } else if (dp.size() != secured_.size()) {
    throw std::logic_error("TurningPoints::add: a date with another number of elements");
  }
  if (rule_ == TurningRule::Extremes)
    add_extremes(dp, k);
  else
    add_new_lows(dp, k);
}

void TurningPoints::add_new_lows(const std::vector<double>& dp, std::int32_t k) {
  for (std::size_t e = 0; e < dp.size(); ++e) {
    const double p = dp[e];
    if (low_date_[e] < 0) {
      if (p < secured_[e] - tolerance_) {
        low_[e] = p;
        low_date_[e] = k;
      }
    } else if (p < low_[e]) {
      low_[e] = p;
      low_date_[e] = k;
    } else if (p > low_[e] + tolerance_) {
      turns_[low_date_[e]] = 1;
      secured_[e] = low_[e];
      low_date_[e] = -1;
    }
  }
}

void TurningPoints::add_extremes(const std::vector<double>& dp, std::int32_t k) {
  for (std::size_t e = 0; e < dp.size(); ++e) {
    const double p = dp[e];
    double& ext = low_[e];  // the extreme value since the last turn (0 at the start)
    std::int8_t& dir = direction_[e];
    if (dir == 0) {
      if (p < ext - tolerance_ || p > ext + tolerance_) {
        dir = p < ext ? -1 : +1;
        ext = p;
        low_date_[e] = k;
      }
    } else if (dir * (p - ext) > 0) {  // further the same way
      ext = p;
      low_date_[e] = k;
    } else if (dir * (ext - p) > tolerance_) {  // back by more than the tolerance: ext was an extremum
      turns_[low_date_[e]] = 1;
      dir = static_cast<std::int8_t>(-dir);
      ext = p;
      low_date_[e] = k;
    }
  }
}

std::vector<char> turning_points(PressureHistory& history, double tolerance, TurningRule rule) {
  TurningPoints tp(tolerance, rule);
  // Elements under no pressure field stay at 0 and never turn: they are left out.
  for (const auto& s : history.steps()) tp.add(history.forced_cell_dp(s.time));
  return tp.turns();
}

}  // namespace ugs::mech
