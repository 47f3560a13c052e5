// Which dates of the pressure history the continuous model must step on (docs/mechanics.md,
// "Turning-point steps").
#pragma once
#include <cstdint>
#include <vector>

#include "ugs/mechanics/pressure.hpp"

namespace ugs::mech {

// With the sigma-max rule an element's stiffness depends on its vertical stress and on its
// preconsolidation stress only, so the state at a date does not depend on the path to it as long
// as no element raises its preconsolidation stress in between. The element's pressure change stands
// for its stress: a date is a turning point when some element's pressure change has its lowest
// value there — lower than at any earlier turning point, and than 0 (the undisturbed, normally
// consolidated start), by more than `tolerance` [Pa] — and later rises by more than `tolerance`
// before it falls lower. A step across that date would miss the element's preconsolidation stress.
//
// A faulted model needs more (TurningRule::Extremes): the fault tractions answer every rise as
// well as every fall, and chi is reported on the dates stepped on. There a date is a turning point
// when some element's pressure change has a local extremum there, low or high: it moved away from
// the previous extremum (0 at the start) by more than `tolerance`, and then moves back from its
// value by more than `tolerance`. Between two steps every element's pressure is then monotonic.
// Every turning point of NewLows is one of Extremes.
enum class TurningRule { NewLows, Extremes };

class TurningPoints {
public:
  explicit TurningPoints(double tolerance, TurningRule rule = TurningRule::NewLows) : tolerance_(tolerance), rule_(rule) {}
  // The pressure change [Pa] per element at the next date (the same elements every time).
  void add(const std::vector<double>& dp);
  // One flag per date added: a turning point.
  const std::vector<char>& turns() const { return turns_; }

private:
  void add_new_lows(const std::vector<double>& dp, std::int32_t k);
  void add_extremes(const std::vector<double>& dp, std::int32_t k);

  double tolerance_;
  TurningRule rule_;
  std::vector<char> turns_;
  // Per element: the low secured by a turning point already found (0 at the start), and the lowest
  // value since, more than `tolerance` below it, with its date (-1: none).
  std::vector<double> secured_, low_;
  std::vector<std::int32_t> low_date_;
  // Extremes, per element: the direction since the last extremum (-1 falling, +1 rising, 0 not yet
  // left the start by `tolerance`) and the extreme value since, with its date (in low_, low_date_).
  std::vector<std::int8_t> direction_;
};

// The turning points of a whole pressure history: one flag per step of `history`.
std::vector<char> turning_points(PressureHistory& history, double tolerance, TurningRule rule = TurningRule::NewLows);

}  // namespace ugs::mech
