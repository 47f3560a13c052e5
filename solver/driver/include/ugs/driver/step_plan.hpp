// The step plan of a run: which dates of the pressure history are stepped on, which write the
// volume fields (output dates) and which save the restart state (checkpoints). Made on rank 0 from
// the history and the case, then shared by every rank.
#pragma once
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <mpi.h>

#include "ugs/formats/case_file.hpp"
#include "ugs/mechanics/pressure.hpp"
#include "ugs/mechanics/step_dates.hpp"

namespace ugs::driver {

struct StepPlan {
  std::vector<std::string> dates;
  std::vector<double> times;
  std::vector<char> output, checkpoint;
  std::size_t dates_in_run = 0;  // history dates between the restart and the end (rank 0)
  std::size_t size() const { return dates.size(); }
};

struct StepRule {
  double after = -1e300;        // the restart time: later dates only
  double until = 1e300;         // the last date to step on
  int checkpoint_every = 0;     // also a checkpoint every N steps (0: output dates only)
  bool turning_points = false;  // [solver] steps = "turning-points" or "turning-windows"
  bool fewest = false;          // "turning-windows": the fewest dates within the tolerance of every turn
  double turning_tolerance = 0; // [Pa]
  // New lows for the continuous model; every extremum, low or high, for a faulted one (its chi is
  // reported on the dates stepped on: step_dates.hpp).
  mech::TurningRule turning_rule = mech::TurningRule::NewLows;
  std::set<double> must_take;   // times stepped on whatever the rule (the scenario's reference date)
  std::vector<std::pair<double, double>> every_date_in;  // windows [from, to] stepped on every date
};

// Rank 0. Every date, or with turning_points the turning points of the pressure, the output dates,
// `must_take`, the dates inside `every_date_in` and the last date.
StepPlan plan_steps(mech::PressureHistory& history, const CaseFile& cs, const StepRule& rule);

// Collective: rank 0's plan on every rank.
void broadcast(MPI_Comm comm, StepPlan& plan);

}  // namespace ugs::driver
