// The safe-scale search of a faulted run (docs/fault-mechanics.md, "Maximum safe storage
// pressure"): after the scenario's reference date the pressure change is scaled about its value
// there, dp_s(t) = dp(t_ref) + s (dp(t) - dp(t_ref)); the search looks for the smallest s at which a
// fault patch (a node pair acting on free degrees of freedom) reaches chi = 1 at any later step:
// doubling from 1 up to max_scale, then bisection to scale_tolerance. Each trial is a rerun from
// the state saved at the reference date, given to the search as a function.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "ugs/contact/fault_model.hpp"
#include "ugs/contact/fault_output.hpp"

namespace ugs::driver {

// The first patch at chi = 1 after the reference date, and the largest chi seen.
struct Watch {
  double max_chi = 0;
  bool critical = false;
  std::string fault, date;
  Point3 at{};
  double dp_max = 0, dp_min = 0;  // pressure change extremes seen [Pa]

  void see(const contact::FaultModel& fm, const contact::FaultFields& f, const std::string& date);
};

struct SafeScale {
  bool found = false;                  // a critical scale below max_scale
  double safe = 0, critical = 0;       // largest safe and smallest critical scale tried
  std::string fault, date;             // first patch to reach chi = 1 at `critical`
  Point3 at{};
  double peak_dp_max = 0, peak_dp_min = 0;  // pressure change extremes after the reference at `safe` [Pa]
};

SafeScale search_safe_scale(double max_scale, double tolerance, const std::function<Watch(double)>& trial);

// dp about the reference: ref + s (dp - ref).
void scale_about(std::vector<double>& dp, const std::vector<double>& ref, double s);

}  // namespace ugs::driver
