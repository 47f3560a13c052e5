#include "ugs/flow/schedule.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"

namespace ugs::flow {
namespace {

std::string days(std::int64_t seconds) {
  const double d = seconds / 86400.0;
  return d == std::floor(d) ? fmt::format("{} days", static_cast<std::int64_t>(d)) : fmt::format("{:.3f} days", d);
}

std::int64_t parse_case_date(const CaseFile& c, const std::string& text, const char* key) {
  const auto t = parse_iso_date(text);
  if (!t) throw InputError(c.path, fmt::format("[model] {} = '{}' is not an ISO 8601 date", key, text));
  return *t;
}

}  // namespace

double PoolSchedule::at(std::int64_t t) const {
  if (t <= times.front()) return dp.front();
  if (t >= times.back()) return dp.back();
  const auto k = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
  const double w = static_cast<double>(t - times[k - 1]) / static_cast<double>(times[k] - times[k - 1]);
  return dp[k - 1] + w * (dp[k] - dp[k - 1]);
}

PoolSchedule read_pool_schedule(const PoolSpec& pool, const ScheduleLimits& limits) {
  const CsvTable table = CsvTable::read(pool.schedule);
  PoolSchedule s;
  s.pool = pool.name;
  s.file = pool.schedule;
  s.reference_Pa = pool.reference_pressure_Pa;
  const std::size_t cd = table.column("date"), cv = table.column(pool.column);
  if (table.rows() == 0) throw InputError(pool.schedule, "schedule has no rows");
  const double scale = pool.column == "p_MPa" ? 1e6 : *pool.reference_pressure_Pa;
  double first = 0;
  for (std::size_t r = 0; r < table.rows(); ++r) {
    const std::int64_t t = table.date(r, cd);
    const double v = table.number(r, cv);
    if (r == 0) first = v;
    if (r > 0) {
      const std::int64_t prev = s.times.back();
      if (t == prev) throw InputError(table.where(r), fmt::format("duplicate date {}", format_iso_date(t)));
      if (t < prev)
        throw InputError(table.where(r), fmt::format("date {} is earlier than the row before ({}): dates must increase",
                                                     format_iso_date(t), format_iso_date(prev)));
      if (t - prev > limits.max_step_seconds)
        throw InputError(table.where(r), fmt::format("gap of {} after {} is longer than the step ({}; the longest step sets it)",
                                                     days(t - prev), format_iso_date(prev), days(limits.max_step_seconds)));
    }
    s.times.push_back(t);
    s.dp.push_back((v - first) * scale);
    s.where.push_back(table.where(r));
  }
  return s;
}

RunWindow run_window(const CaseFile& c, const std::vector<PoolSchedule>& schedules, std::optional<std::int64_t> end) {
  RunWindow w;
  const bool case_start = !c.start_date.empty(), case_end = !c.end_date.empty();
  if (case_start) {
    w.start = parse_case_date(c, c.start_date, "start");
  } else {
    w.start = schedules.front().times.front();
    for (const auto& s : schedules) w.start = std::min(w.start, s.times.front());
  }
  if (case_end) {
    w.end = parse_case_date(c, c.end_date, "end");
  } else {
    w.end = schedules.front().times.back();
    for (const auto& s : schedules) w.end = std::max(w.end, s.times.back());
  }
  if (w.end <= w.start)
    throw InputError(c.path, fmt::format("the run ends ({}) before it starts ({})", format_iso_date(w.end), format_iso_date(w.start)));
  if (end) {
    if (*end <= w.start || *end > w.end)
      throw InputError("end date", fmt::format("{} lies outside the run {} .. {}", format_iso_date(*end), format_iso_date(w.start),
                                            format_iso_date(w.end)));
    w.truncated = *end < w.end;
    w.end = *end;
  }
  for (const auto& s : schedules) {
    for (std::size_t r = 0; r < s.times.size(); ++r) {
      if (s.times[r] < w.start)
        throw InputError(s.where[r], fmt::format("date {} lies before the run start {}", format_iso_date(s.times[r]),
                                                 format_iso_date(w.start)));
      if (s.times[r] > w.end && !w.truncated)
        throw InputError(s.where[r], fmt::format("date {} lies after the run end {}", format_iso_date(s.times[r]),
                                                 format_iso_date(w.end)));
    }
    if (s.times.front() != w.start)
      throw InputError(s.where.front(), fmt::format("pool '{}': the schedule starts {}, after the run start {} (its first row "
                                                    "is the reference of the pressure change)",
                                                    s.pool, format_iso_date(s.times.front()), format_iso_date(w.start)));
    if (s.times.back() < w.end)
      throw InputError(s.where.back(), fmt::format("pool '{}': the schedule ends {}, before the run end {}", s.pool,
                                                   format_iso_date(s.times.back()), format_iso_date(w.end)));
  }
  return w;
}

TimeGrid make_time_grid(const std::vector<PoolSchedule>& schedules, const RunWindow& w, const std::vector<std::int64_t>& extra) {
  TimeGrid g;
  for (const auto& s : schedules)
    for (auto t : s.times)
      if (t >= w.start && t <= w.end) g.dates.push_back(t);
  std::sort(g.dates.begin(), g.dates.end());
  g.dates.erase(std::unique(g.dates.begin(), g.dates.end()), g.dates.end());
  const std::vector<std::int64_t> schedule_dates = g.dates;
  if (g.dates.back() != w.end) g.dates.push_back(w.end);  // truncated between two rows
  for (auto t : extra) {
    if (t < w.start || t > w.end)
      throw InputError("", fmt::format("date {} lies outside the run {} .. {}", format_iso_date(t), format_iso_date(w.start),
                                       format_iso_date(w.end)));
    g.dates.push_back(t);
  }
  std::sort(g.dates.begin(), g.dates.end());
  g.dates.erase(std::unique(g.dates.begin(), g.dates.end()), g.dates.end());
  g.is_schedule_date.resize(g.dates.size());
  for (std::size_t k = 0; k < g.dates.size(); ++k)
    g.is_schedule_date[k] = std::binary_search(schedule_dates.begin(), schedule_dates.end(), g.dates[k]);
  for (const auto& s : schedules) {
    std::vector<double> v(g.dates.size());
    for (std::size_t k = 0; k < g.dates.size(); ++k) v[k] = s.at(g.dates[k]);
    g.pool_dp.push_back(std::move(v));
  }
  return g;
}

}  // namespace ugs::flow
