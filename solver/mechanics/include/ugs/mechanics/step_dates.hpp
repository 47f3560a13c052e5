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
class TurningPoints {
public:
  explicit TurningPoints(double tolerance) : tolerance_(tolerance) {}
  // The pressure change [Pa] per element at the next date (the same elements every time).
  void add(const std::vector<double>& dp);
  // One flag per date added: a turning point.
  const std::vector<char>& turns() const { return turns_; }

private:
  double tolerance_;
  std::vector<char> turns_;
  // Per element: the low secured by a turning point already found (0 at the start), and the lowest
  // value since, more than `tolerance` below it, with its date (-1: none).
  std::vector<double> secured_, low_;
  std::vector<std::int32_t> low_date_;
};

// The turning points of a whole pressure history: one flag per step of `history`.
std::vector<char> turning_points(PressureHistory& history, double tolerance);

}  // namespace ugs::mech
