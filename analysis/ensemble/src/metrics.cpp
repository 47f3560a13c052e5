#include "ugs/ensemble/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <functional>
#include <mutex>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/insar/displacement.hpp"
#include "ugs/insar/inputs.hpp"
#include "ugs/insar/sampling.hpp"
#include "ugs/insar/surface.hpp"
#include "ugs/seismicity/run.hpp"

namespace ugs::ensemble {

namespace fs = std::filesystem;

struct PairHistoryCache::Impl {
  std::map<std::string, seismicity::StressHistory> by_folder;  // folder -> its histories (the files read)
  const seismicity::StressHistory& get(const std::string& folder, const std::vector<std::string>& files) {
    auto it = by_folder.find(folder);
    if (it == by_folder.end()) it = by_folder.emplace(folder, seismicity::read_pair_csvs(files)).first;
    return it->second;
  }
};

PairHistoryCache::PairHistoryCache() : impl_(std::make_unique<Impl>()) {}
PairHistoryCache::~PairHistoryCache() = default;

Phase parse_phase(const std::string& text) {
  const auto eq = text.find('='), slash = text.find('/');
  if (eq == std::string::npos || eq == 0 || slash == std::string::npos || slash < eq)
    throw InputError("metric phase " + text, "expected NAME=START/END, e.g. storage=2015-05-01/2015-11-01");
  const auto a = parse_iso_date(text.substr(eq + 1, slash - eq - 1)), b = parse_iso_date(text.substr(slash + 1));
  if (!a || !b) throw InputError("metric phase " + text, "dates must be ISO 8601 (YYYY-MM-DD)");
  if (*a >= *b) throw InputError("metric phase " + text, "the start must come before the end");
  return {text.substr(0, eq), *a, *b};
}

namespace {

// The one file of the folder whose name ends with `suffix` ("" if none).
std::string one_file_ending(const std::string& folder, const std::string& suffix) {
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(folder)) {
    const std::string n = e.path().filename().string();
    if (n.size() >= suffix.size() && n.compare(n.size() - suffix.size(), suffix.size(), suffix) == 0) found.push_back(e.path().string());
  }
  if (found.size() > 1) {
    std::sort(found.begin(), found.end());
    throw InputError(folder, fmt::format("{} files ending in {} ({} and {}): expected one", found.size(), suffix, found[0], found[1]));
  }
  return found.empty() ? "" : found.front();
}

double in_mm(double m) { return m * 1e3; }

void surface_metrics(const std::string& h5, const MetricOptions& o, MemberOutputs& mo) {
  Metrics& out = mo.metrics;
  const insar::TopSurface top = insar::load_top_surface("", "", h5);
  insar::SurfaceDisplacement res(h5, top, o.field);
  const auto& times = res.times();
  if (times.empty()) throw InputError(h5, "has no result step");
  std::vector<Phase> phases = o.phases;
  if (phases.empty()) phases.push_back({"all", times.front(), times.back()});
  std::vector<bool> use(top.points.size(), true);
  if (o.trace)
    for (std::size_t i = 0; i < top.points.size(); ++i) use[i] = o.trace->contains({top.points[i][0], top.points[i][1]});
  if (std::find(use.begin(), use.end(), true) == use.end()) throw InputError(h5, "no top-surface node lies inside the trace polygons");
  std::vector<insar::LocatedPoint> ps;
  if (o.ps) {
    const insar::SurfaceLocator loc(top);
    ps = insar::locate_points(loc, o.ps->points, false).sampled;
    if (ps.empty()) throw InputError(h5, "no PS point lies on the results' top surface (wrong CRS?)");
  }
  for (const auto& ph : phases) {
    const auto a = res.at_time(ph.start), b = res.at_time(ph.end);
    if (!a || !b)
      throw InputError(h5, fmt::format("phase {} ({} / {}) lies outside the results' dates {} .. {}", ph.name,
                                       format_iso_date(ph.start), format_iso_date(ph.end), format_iso_date(times.front()),
                                       format_iso_date(times.back())));
    double up = 0, down = 0;
    for (std::size_t i = 0; i < use.size(); ++i)
      if (use[i]) {
        const double dz = (*b)[3 * i + 2] - (*a)[3 * i + 2];
        up = std::max(up, dz);
        down = std::max(down, -dz);
      }
    out.emplace_back("uplift_max_mm." + ph.name, in_mm(up));
    out.emplace_back("settlement_max_mm." + ph.name, in_mm(down));
    if (!ps.empty()) {
      double pu = 0, pd = 0;
      for (const auto& p : ps) {
        double dz = 0;
        for (int k = 0; k < 3; ++k) {
          const std::size_t n = top.triangles[p.hit.triangle][static_cast<std::size_t>(k)];
          dz += p.hit.weights[static_cast<std::size_t>(k)] * ((*b)[3 * n + 2] - (*a)[3 * n + 2]);
        }
        pu = std::max(pu, dz);
        pd = std::max(pd, -dz);
      }
      out.emplace_back("ps_uplift_max_mm." + ph.name, in_mm(pu));
      out.emplace_back("ps_settlement_max_mm." + ph.name, in_mm(pd));
    }
  }
  if (o.ps && o.ps->has_series()) {
    const insar::Samples s = insar::sample_displacement(res, ps, o.ps->dates, std::nullopt);
    // Vertical, plus the east-west series when given: the misfit ugs-calibrate minimises.
    std::vector<insar::SeriesMisfit> east;
    if (o.ps_east && o.ps_east->has_series()) {
      const insar::SurfaceLocator loc(top);
      const auto pe = insar::locate_points(loc, o.ps_east->points, false).sampled;
      east = insar::series_misfits(*o.ps_east, insar::sample_displacement(res, pe, o.ps_east->dates, std::nullopt), 0, o.window);
    }
    const insar::Misfit m =
        insar::combine_misfits(insar::series_misfits(*o.ps, s, 2, o.window), std::move(east), o.ps_east ? o.east_weight : 0.0);
    out.emplace_back("insar_rms_mm", m.rms_mm);
    // The series relative to the first PS date the results reach.
    std::size_t first = s.dates.size();
    for (std::size_t d = 0; d < s.dates.size() && first == s.dates.size(); ++d)
      if (!ps.empty() && std::isfinite(s.at(0, d)[2])) first = d;
    mo.ps_dates = s.dates;
    for (std::size_t p = 0; p < ps.size(); ++p) {
      mo.ps_ids.push_back(ps[p].point.id);
      for (std::size_t d = 0; d < s.dates.size(); ++d)
        mo.ps_up_mm.push_back(first < s.dates.size() ? in_mm(s.at(p, d)[2] - s.at(p, first)[2]) : NAN);
    }
  }
}

void fault_metrics(const std::string& folder, Metrics& out) {
  const std::string path = one_file_ending(folder, "_faults.csv");
  if (path.empty()) return;
  const CsvTable t = CsvTable::read(path);
  const auto cd = t.column("date"), cf = t.column("fault"), cc = t.column("max_chi");
  std::map<std::string, std::map<std::int64_t, double>> chi;  // fault -> date -> max chi
  for (std::size_t r = 0; r < t.rows(); ++r) {
    double& v = chi[std::string(t.text(r, cf))].try_emplace(t.date(r, cd), 0.0).first->second;
    v = std::max(v, t.number(r, cc));
  }
  for (const auto& [fault, by_date] : chi) {
    double m = 0;
    for (const auto& [d, v] : by_date) m = std::max(m, v);
    out.emplace_back("chi_max." + fault, m);
  }
  for (const auto& [fault, by_date] : chi)
    for (const auto& [d, v] : by_date) out.emplace_back("chi_max." + fault + "." + format_iso_date(d), v);
}

void scenario_metrics(const std::string& folder, Metrics& out) {
  const std::string path = one_file_ending(folder, "_scenario.csv");
  if (path.empty()) return;
  const CsvTable t = CsvTable::read(path);
  const auto cs = t.column("scale"), cc = t.column("critical");
  // The largest non-critical scale below the smallest critical one (the search's bracket).
  double critical = INFINITY, safe = 0;
  for (std::size_t r = 0; r < t.rows(); ++r)
    if (t.integer(r, cc) != 0) critical = std::min(critical, t.number(r, cs));
  bool any = false;
  for (std::size_t r = 0; r < t.rows(); ++r)
    if (t.integer(r, cc) == 0 && t.number(r, cs) < critical) {
      safe = std::max(safe, t.number(r, cs));
      any = true;
    }
  if (t.rows() == 0) throw InputError(path, "has no trial");
  out.emplace_back("safe_scale", any ? safe : 0.0);
}

// The seals' smallest margins over the run (ugs-solve's caprock table, docs/caprock.md), MPa, per seal
// in name order: seal_tensile_margin_min.<seal> and seal_shear_margin_min.<seal>.
void caprock_metrics(const std::string& folder, Metrics& out) {
  const std::string path = one_file_ending(folder, "_caprock.csv");
  if (path.empty()) return;
  const CsvTable t = CsvTable::read(path);
  const auto cs = t.column("seal"), ct = t.column("min_tensile_margin_MPa"), ch = t.column("min_shear_margin_MPa");
  std::map<std::string, std::pair<double, double>> low;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    auto [it, fresh] = low.try_emplace(std::string(t.text(r, cs)), t.number(r, ct), t.number(r, ch));
    if (!fresh) it->second = {std::min(it->second.first, t.number(r, ct)), std::min(it->second.second, t.number(r, ch))};
  }
  if (low.empty()) throw InputError(path, "has no rows (expected ugs-solve's caprock table)");
  for (const auto& [seal, m] : low) {
    out.emplace_back("seal_tensile_margin_min." + seal, m.first);
    out.emplace_back("seal_shear_margin_min." + seal, m.second);
  }
}

// The seismicity forecast of the member (docs/seismicity.md) over each window: its per-pair fault CSVs
// (<stem>_fault_<F>.csv, in name order) with the [seismicity] parameters of the member's case: its
// own case copy, or `forecast_case` when given.
void seismicity_metrics(const std::string& folder, const std::vector<Phase>& windows, const CaseFile* forecast_case,
                        PairHistoryCache* cache, Metrics& out) {
  if (windows.empty()) return;
  std::vector<std::string> pairs;
  for (const auto& e : fs::directory_iterator(folder)) {
    const std::string n = e.path().filename().string();
    if (n.find("_fault_") != std::string::npos && n.size() > 4 && n.compare(n.size() - 4, 4, ".csv") == 0) pairs.push_back(e.path().string());
  }
  if (pairs.empty())
    throw InputError(folder, "has no per-pair fault CSV (*_fault_<F>.csv) for the seismicity metrics (expected a faulted ugs-solve run)");
  std::sort(pairs.begin(), pairs.end());
  seismicity::RunSettings s;
  s.inputs = pairs;
  s.case_file = (fs::path(folder) / "case.toml").string();
  for (const auto& w : windows) s.windows.push_back(format_iso_date(w.start) + "/" + format_iso_date(w.end));
  std::optional<CaseFile> own;
  const CaseFile& c = forecast_case ? *forecast_case : own.emplace(read_case_file(s.case_file));
  std::optional<seismicity::StressHistory> own_history;
  const seismicity::StressHistory& h =
      cache ? cache->impl().get(folder, pairs) : own_history.emplace(seismicity::read_pair_csvs(pairs));
  const seismicity::Forecast fc = seismicity::compute(s, c, h);
  const std::vector<double>& magnitudes = c.seismicity->magnitudes;
  for (std::size_t i = 0; i < windows.size(); ++i) {
    auto add = [&](const std::string& who, const std::function<double(double)>& events_above_m, double mc) {
      const double n = events_above_m(mc);
      out.emplace_back(fmt::format("seismic_events.{}.{}", who, windows[i].name), n);
      out.emplace_back(fmt::format("p_event.{}.{}", who, windows[i].name), seismicity::probability_at_least_one(n));
      for (double m : magnitudes)
        out.emplace_back(fmt::format("p_event_M{}.{}.{}", m, who, windows[i].name), seismicity::probability_at_least_one(events_above_m(m)));
    };
    for (const auto& f : fc.faults)
      add(f.name, [&](double m) { return seismicity::events_above(f.window_events[i], f.params, m); }, f.params.M_c);
    // "all": the sum over the faults, above the first fault's M_c (each fault through its own b).
    add("all", [&](double m) {
      double n = 0;
      for (const auto& f : fc.faults) n += seismicity::events_above(f.window_events[i], f.params, m);
      return n;
    }, fc.faults.front().params.M_c);
  }
}

}  // namespace

Metrics member_metrics(const std::string& folder, const MetricOptions& options) { return member_outputs(folder, options).metrics; }

MemberOutputs member_outputs(const std::string& folder, const MetricOptions& options, const CaseFile* forecast_case,
                             PairHistoryCache* cache) {
  MemberOutputs mo;
  Metrics& out = mo.metrics;
  const std::string h5 = (fs::path(folder) / "result.h5").string();
  if (!fs::exists(h5)) throw InputError(folder, "has no result.h5");
  {
    static std::mutex hdf5_mutex;  // HDF5 may be built without thread safety: one reader at a time
    std::lock_guard lock(hdf5_mutex);
    surface_metrics(h5, options, mo);
  }
  fault_metrics(folder, out);
  scenario_metrics(folder, out);
  caprock_metrics(folder, out);
  seismicity_metrics(folder, options.seismic_windows, forecast_case, cache, out);
  for (const auto& [name, v] : out)
    if (!std::isfinite(v)) throw InputError(folder, fmt::format("metric {} is not finite", name));
  return mo;
}

}  // namespace ugs::ensemble
