// The safe-scale search of a faulted run (docs/fault-mechanics.md, "Maximum safe storage
// pressure"): after the scenario's reference date the pressure change is scaled about its value
// there, dp_s(t) = dp(t_ref) + s (dp(t) - dp(t_ref)); the search looks for the smallest s at which,
// at any later step, a fault patch (a node pair acting on free degrees of freedom) reaches chi = 1
// or a seal element fails (caprock.hpp: tensile or shear failure): doubling from 1 up to max_scale,
// then bisection to scale_tolerance. Each trial is a rerun from
// the state saved at the reference date, given to the search as a function.
#pragma once
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "ugs/contact/fault_model.hpp"
#include "ugs/contact/fault_output.hpp"
#include "ugs/driver/caprock.hpp"

namespace ugs::driver {

// What fails first: a fault patch at chi = 1, or a seal element by tension or by shear.
enum class Limiter { None, FaultChi, CaprockTensile, CaprockShear };
// "fault chi = 1", "caprock tensile failure", "caprock shear failure" ("" for None).
std::string limiter_text(Limiter l);

// The first failure after the reference date (at one step: a fault before a seal), the largest chi
// and the smallest seal margins seen.
struct Watch {
  double max_chi = 0;
  double min_tensile_margin = std::numeric_limits<double>::infinity();  // Pa, over the seals
  double min_shear_margin = std::numeric_limits<double>::infinity();
  bool critical = false;
  Limiter limiter = Limiter::None;
  std::string fault, seal, date;  // the fault or the seal material that failed first
  Point3 at{};
  double dp_max = 0, dp_min = 0;  // pressure change extremes seen [Pa]

  void see(const contact::FaultModel& fm, const contact::FaultFields& f, const std::string& date);
  void see(const CaprockStep& caprock, const std::string& date);
  // "fault F first reaches chi = 1", "seal S fails first (caprock tensile failure)"
  std::string what() const;
};

struct SafeScale {
  bool found = false;                  // a critical scale below max_scale
  double safe = 0, critical = 0;       // largest safe and smallest critical scale tried
  Watch first;                         // the trial at `critical`: what fails first, where and when
  double peak_dp_max = 0, peak_dp_min = 0;  // pressure change extremes after the reference at `safe` [Pa]
};

SafeScale search_safe_scale(double max_scale, double tolerance, const std::function<Watch(double)>& trial);

// dp about the reference: ref + s (dp - ref).
void scale_about(std::vector<double>& dp, const std::vector<double>& ref, double s);

}  // namespace ugs::driver
