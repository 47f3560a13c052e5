// Pool pressure schedules (CSV: a `date` column and a p_norm or p_MPa column) and the time grid of
// a flow run. A pool's Dirichlet value is the pressure CHANGE from the schedule's first value, in
// Pa (p_MPa x 1e6, or p_norm x the pool's reference pressure); between dates it is linear in time.
// The run's steps are the union of the schedule dates (plus any requested output date), each
// optionally split into equal sub-steps.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ugs/formats/case_file.hpp"

namespace ugs::flow {

struct PoolSchedule {
  std::string pool;
  std::string file;
  std::vector<std::int64_t> times;  // seconds since 1970, strictly increasing
  std::vector<double> dp;           // Pa, change from the first value
  std::vector<std::string> where;   // "file:line" of each row
  std::optional<double> reference_Pa;

  // Pressure change at time t, linear between dates (t within [times.front(), times.back()]).
  double at(std::int64_t t) const;
};

struct ScheduleLimits {
  // Longest allowed interval between consecutive dates: a longer gap is a missing row, not a step.
  std::int64_t max_step_seconds = 31 * 86400;
};

// Reads a pool's schedule; InputError "file:line: ..." for missing columns, non-numeric values,
// unsorted or duplicate dates and gaps longer than the step.
PoolSchedule read_pool_schedule(const PoolSpec& pool, const ScheduleLimits& limits = {});

struct RunWindow {
  std::int64_t start = 0, end = 0;
  // The end was cut short on request (--end): rows after it are ignored rather than rejected.
  bool truncated = false;
};

// The run: [model] start/end of the case when given, else the span of the schedules; `end` (if
// set) cuts it short. Every schedule must start exactly at the run start and reach the run end;
// rows outside the run are errors (file:line).
RunWindow run_window(const CaseFile& c, const std::vector<PoolSchedule>& schedules,
                     std::optional<std::int64_t> end = std::nullopt);

struct TimeGrid {
  std::vector<std::int64_t> dates;           // step boundaries [s], dates.front() = run start
  std::vector<char> is_schedule_date;        // 1 where some schedule has a row
  std::vector<std::vector<double>> pool_dp;  // [pool][date] Dirichlet value [Pa]
};

// Union of the schedule dates within the window and the `extra` dates (which must lie inside it).
TimeGrid make_time_grid(const std::vector<PoolSchedule>& schedules, const RunWindow& window,
                        const std::vector<std::int64_t>& extra = {});

}  // namespace ugs::flow
