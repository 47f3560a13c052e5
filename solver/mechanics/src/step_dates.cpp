#include "ugs/mechanics/step_dates.hpp"

#include <algorithm>
#include <set>
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
      list_.push_back({static_cast<std::int32_t>(e), low_date_[e], k - 1, low_[e], -1});
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
      list_.push_back({static_cast<std::int32_t>(e), low_date_[e], k - 1, ext, dir});
      dir = static_cast<std::int8_t>(-dir);
      ext = p;
      low_date_[e] = k;
    }
  }
}

TurnWindows::TurnWindows(std::vector<Turn> turns, std::size_t elements, double tolerance)
    : turns_(std::move(turns)), next_(elements), end_(elements), run_start_(elements, -1), tolerance_(tolerance) {
  std::sort(turns_.begin(), turns_.end(),
            [](const Turn& a, const Turn& b) { return a.element != b.element ? a.element < b.element : a.date < b.date; });
  std::size_t t = 0;
  for (std::size_t e = 0; e < elements; ++e) {
    next_[e] = static_cast<std::int64_t>(t);
    while (t < turns_.size() && turns_[t].element == static_cast<std::int32_t>(e)) ++t;
    end_[e] = static_cast<std::int64_t>(t);
  }
  if (t != turns_.size()) throw std::logic_error("TurnWindows: a turn of an element beyond the count");
  windows_.reserve(turns_.size());
}

void TurnWindows::add(const std::vector<double>& dp) {
  if (dp.size() != next_.size()) throw std::logic_error("TurnWindows::add: a date with another number of elements");
  const std::int32_t k = date_++;
  for (std::size_t e = 0; e < dp.size(); ++e) {
    if (next_[e] == end_[e]) continue;
    const Turn& t = turns_[static_cast<std::size_t>(next_[e])];
    const bool within = t.sign < 0 ? dp[e] <= t.value + tolerance_ : dp[e] >= t.value - tolerance_;
    if (!within) {
      run_start_[e] = -1;
      continue;
    }
    if (run_start_[e] < 0) run_start_[e] = k;
    if (k == t.date) {
      windows_.push_back({run_start_[e], t.last_within});
      run_start_[e] = -1;
      ++next_[e];
    }
  }
}

std::vector<char> fewest_dates(std::vector<TurnWindow> windows, std::vector<char> forced) {
  std::sort(windows.begin(), windows.end(),
            [](const TurnWindow& a, const TurnWindow& b) { return a.last != b.last ? a.last < b.last : a.first < b.first; });
  std::set<std::int32_t> chosen;
  for (std::size_t k = 0; k < forced.size(); ++k)
    if (forced[k]) chosen.insert(static_cast<std::int32_t>(k));
  for (const TurnWindow& w : windows) {
    const auto it = chosen.lower_bound(w.first);
    if (it == chosen.end() || *it > w.last) chosen.insert(w.last);
  }
  for (const std::int32_t k : chosen) {
    if (static_cast<std::size_t>(k) >= forced.size()) forced.resize(static_cast<std::size_t>(k) + 1, 0);
    forced[static_cast<std::size_t>(k)] = 1;
  }
  return forced;
}

std::vector<char> turning_points(PressureHistory& history, double tolerance, TurningRule rule, std::vector<char> forced,
                                 bool fewest) {
  const auto& steps = history.steps();
  forced.resize(steps.size(), 0);
  TurningPoints tp(tolerance, rule);
  // Elements under no pressure field stay at 0 and never turn: they are left out.
  std::size_t elements = 0;
  for (const auto& s : steps) {
    const std::vector<double> dp = history.forced_cell_dp(s.time);
    elements = dp.size();
    tp.add(dp);
  }
  if (!fewest) {
    for (std::size_t k = 0; k < steps.size(); ++k) forced[k] = forced[k] || tp.turns()[k];
    return forced;
  }
  TurnWindows tw(tp.turn_list(), elements, tolerance);
  if (!tp.turn_list().empty())
    for (const auto& s : steps) tw.add(history.forced_cell_dp(s.time));
  return fewest_dates(tw.windows(), std::move(forced));
}

}  // namespace ugs::mech
