#include "ugs/driver/step_plan.hpp"

#include "ugs/formats/csv.hpp"
#include "ugs/mechanics/collective.hpp"
#include "ugs/mechanics/step_dates.hpp"

namespace ugs::driver {

StepPlan plan_steps(mech::PressureHistory& history, const CaseFile& cs, const StepRule& rule) {
  const std::set<std::string> outs(cs.output_dates.begin(), cs.output_dates.end());
  std::set<double> out_times;
  for (const auto& d : outs) out_times.insert(static_cast<double>(*parse_iso_date(d)));
  const auto& steps = history.steps();
  std::vector<char> take(steps.size(), 1);
  if (rule.turning_points) {
    // The dates stepped on whatever the turns (output dates, must_take, the windows, the last one,
    // the restart's) go in first: a turn whose window holds one of them needs no date of its own.
    std::vector<char> forced(steps.size(), 0);
    std::size_t last = steps.size();
    for (std::size_t k = 0; k < steps.size(); ++k) {
      if (steps[k].time <= rule.until) last = k;
      if (out_times.count(steps[k].time) || rule.must_take.count(steps[k].time) || steps[k].time == rule.after)
        forced[k] = 1;
      for (const auto& [from, to] : rule.every_date_in)
        if (steps[k].time >= from && steps[k].time <= to) forced[k] = 1;
    }
    if (last < steps.size()) forced[last] = 1;
    take = mech::turning_points(history, rule.turning_tolerance, rule.turning_rule, std::move(forced), rule.fewest);
  }
  StepPlan plan;
  int since_checkpoint = 0;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const auto& s = steps[k];
    if (s.time <= rule.after || s.time > rule.until) continue;
    ++plan.dates_in_run;
    if (!take[k]) continue;
    plan.dates.push_back(s.date);
    plan.times.push_back(s.time);
    const bool out = outs.empty() || out_times.count(s.time);
    plan.output.push_back(out);
    ++since_checkpoint;
    const bool cp = out || (rule.checkpoint_every > 0 && since_checkpoint >= rule.checkpoint_every);
    if (cp) since_checkpoint = 0;
    plan.checkpoint.push_back(cp);
  }
  return plan;
}

void broadcast(MPI_Comm comm, StepPlan& plan) {
  std::string all;
  for (const auto& s : plan.dates) all += s + '\n';
  mech::broadcast(comm, all);
  plan.dates.clear();
  for (std::size_t p = 0; p < all.size();) {
    const auto q = all.find('\n', p);
    plan.dates.push_back(all.substr(p, q - p));
    p = q + 1;
  }
  const std::size_t n = plan.dates.size();
  plan.times.resize(n);
  plan.output.resize(n);
  plan.checkpoint.resize(n);
  if (n) {
    MPI_Bcast(plan.times.data(), static_cast<int>(n), MPI_DOUBLE, 0, comm);
    MPI_Bcast(plan.output.data(), static_cast<int>(n), MPI_CHAR, 0, comm);
    MPI_Bcast(plan.checkpoint.data(), static_cast<int>(n), MPI_CHAR, 0, comm);
  }
}

}  // namespace ugs::driver
