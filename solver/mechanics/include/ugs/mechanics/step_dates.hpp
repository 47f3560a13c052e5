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
//
// A turn need not be stepped on at its own date: every date around it where the element stays
// within `tolerance` of its extreme value (its window) secures the extreme to the same tolerance.
// Aquifer rings that reach their lows one month after another, slowly, have wide overlapping
// windows, and one date inside all of them serves them all: with `fewest`, `turning_points` steps
// on the fewest dates that meet every window (TurnWindows, fewest_dates; `steps = "turning-windows"`).
enum class TurningRule { NewLows, Extremes };

// One turn of one element: the date of its extreme `value` [Pa], low (sign -1) or high (+1), and
// the last date before the element moved back from it by more than the tolerance.
struct Turn {
  std::int32_t element = 0, date = 0, last_within = 0;
  double value = 0;
  std::int8_t sign = -1;
};

// The dates, first to last, around a turn where the element is within the tolerance of it.
struct TurnWindow {
  std::int32_t first = 0, last = 0;
};

class TurningPoints {
public:
  explicit TurningPoints(double tolerance, TurningRule rule = TurningRule::NewLows) : tolerance_(tolerance), rule_(rule) {}
  // The pressure change [Pa] per element at the next date (the same elements every time).
  void add(const std::vector<double>& dp);
  // One flag per date added: a turning point.
  const std::vector<char>& turns() const { return turns_; }
  // Every turn found, in the order found.
  const std::vector<Turn>& turn_list() const { return list_; }

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
  std::vector<Turn> list_;
};

// The windows of the turns: a second pass over the same dates finds where each window starts (it
// ends with the turn's last_within).
class TurnWindows {
public:
  TurnWindows(std::vector<Turn> turns, std::size_t elements, double tolerance);
  // The pressure change per element at the next date, as given to TurningPoints.
  void add(const std::vector<double>& dp);
  const std::vector<TurnWindow>& windows() const { return windows_; }

private:
  std::vector<Turn> turns_;              // by element, then date
  std::vector<std::int64_t> next_, end_;  // per element: its next turn in turns_, one past its last
  std::vector<std::int32_t> run_start_;  // per element: first date of the run within the tolerance (-1: none)
  std::vector<TurnWindow> windows_;
  double tolerance_;
  std::int32_t date_ = 0;
};

// The fewest dates that meet every window, the `forced` ones (a flag per date) counted first: the
// greedy choice of the earliest-ending unmet window's last date, optimal for intervals. One flag
// per date, the forced ones included.
std::vector<char> fewest_dates(std::vector<TurnWindow> windows, std::vector<char> forced);

// The dates of a whole pressure history a run steps on for its turns, one flag per step of
// `history`, `forced` (one flag per step, or empty) included: the turning points themselves, or
// with `fewest` the fewest dates that meet every turn's window.
std::vector<char> turning_points(PressureHistory& history, double tolerance, TurningRule rule = TurningRule::NewLows,
                                 std::vector<char> forced = {}, bool fewest = false);

}  // namespace ugs::mech
