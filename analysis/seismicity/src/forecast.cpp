#include "ugs/seismicity/forecast.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/seismicity/rate_state.hpp"

namespace ugs::seismicity {

namespace {

std::string fault_list(const StressHistory& h) {
  std::string s;
  bool unnamed = false;
  for (const auto& f : h.faults) {
    s += (s.empty() ? "" : ", ") + f.name;
    unnamed = unnamed || (f.name.rfind("fault ", 0) == 0 && !f.pairs.empty() && f.source.size() > 3 &&
                          f.source.compare(f.source.size() - 3, 3, ".h5") == 0);
  }
  // A faults HDF5 holds tags, not names: the mesh of the run names them.
  return unnamed ? s + "; a faults HDF5 names its faults only with the mesh of the run" : s;
}

// Largest log(R / r) a table may hold: R / r and the rate times the area stay well inside doubles.
constexpr double kLogRateRatioMax = 700.0;

}  // namespace

Parameters parameters_for(const SeismicitySpec& spec, const std::string& fault, const std::string& case_path) {
  const SeismicityValues* own = nullptr;
  if (const auto it = spec.faults.find(fault); it != spec.faults.end()) own = &it->second;
  auto pick = [&](std::optional<double> SeismicityValues::*member, const char* key) {
    if (own && (own->*member)) return *(own->*member);
    if (spec.values.*member) return *(spec.values.*member);
    throw InputError(spec.values.where.empty() ? case_path : spec.values.where,
                     fmt::format("[seismicity] gives no {} (needed for fault '{}')", key, fault));
  };
  Parameters p;
  p.A_sigma = pick(&SeismicityValues::A_sigma_Pa, "A_sigma_MPa");
  p.stressing_rate = pick(&SeismicityValues::stressing_rate_Pa_per_s, "stressing_rate_MPa_per_yr");
  p.background_rate = pick(&SeismicityValues::background_rate_per_s_m2, "background_rate_per_yr_km2");
  p.M_c = pick(&SeismicityValues::M_c, "M_c");
  p.b_value = pick(&SeismicityValues::b_value, "b_value");
  return p;
}

void check_case_faults(const CaseFile& c, const StressHistory& h, bool case_faults) {
  std::set<std::string> have;
  for (const auto& f : h.faults) have.insert(f.name);
  if (c.seismicity)
    for (const auto& [name, v] : c.seismicity->faults)
      if (!have.count(name))
        throw InputError(v.where, fmt::format("[seismicity.fault.{}]: the results have no fault '{}' (faults: {})", name, name,
                                              fault_list(h)));
  if (case_faults)
    for (const auto& f : c.faults)
      if (!have.count(f.name))
        throw InputError(f.where, fmt::format("fault '{}' of the case is missing from the results (faults: {}; expected the "
                                              "results of every fault)", f.name, fault_list(h)));
}

Window parse_window(const std::string& text, const std::string& where) {
  const auto slash = text.find('/');
  const auto a = slash == std::string::npos ? std::nullopt : parse_iso_date(text.substr(0, slash));
  const auto b = slash == std::string::npos ? std::nullopt : parse_iso_date(text.substr(slash + 1));
  if (!a || !b) throw InputError(where, fmt::format("'{}' is not START/END (ISO 8601 dates, e.g. 2025-01-01/2033-01-01)", text));
  if (!(*b > *a)) throw InputError(where, fmt::format("'{}': the end is not after the start", text));
  return {*a, *b};
}

double events_above(double events_mc, const Parameters& p, double m) {
  return events_mc * std::pow(10.0, -p.b_value * (m - p.M_c));
}

double probability_at_least_one(double n) { return -std::expm1(-n); }

Forecast forecast(const StressHistory& h, const std::vector<Parameters>& params, std::int64_t start,
                  const std::vector<Window>& windows) {
  if (params.size() != h.faults.size()) throw std::invalid_argument("forecast: one parameter set per fault");
  const std::size_t nd = h.dates.size();
  const std::int64_t t0 = h.dates.front(), t1 = h.dates.back();
  const std::string span = fmt::format("the stress history ({} .. {})", format_iso_date(t0), format_iso_date(t1));
  if (start < t0 || start > t1)
    throw InputError("start date", fmt::format("{} lies outside {}", format_iso_date(start), span));
  for (const auto& w : windows)
    if (w.start < t0 || w.end > t1)
      throw InputError("window", fmt::format("{}/{} lies outside {}", format_iso_date(w.start), format_iso_date(w.end), span));
  // Times from the first date, s (relative, so that the differences keep their digits).
  std::vector<double> t(nd);
  for (std::size_t k = 0; k < nd; ++k) t[k] = static_cast<double>(h.dates[k] - t0);
  const double ts = static_cast<double>(start - t0);
  Forecast fc;
  fc.dates = h.dates;
  fc.start = start;
  fc.windows = windows;
  for (std::size_t f = 0; f < h.faults.size(); ++f) {
    const FaultHistory& fh = h.faults[f];
    const Parameters& p = params[f];
    FaultForecast ff;
    ff.name = fh.name;
    ff.params = p;
    for (auto* v : {&ff.cfs_mean, &ff.rate_ratio, &ff.rate_ratio_max, &ff.rate, &ff.events}) v->assign(nd, 0.0);
    ff.window_events.assign(windows.size(), 0.0);
    bool any_direct = false;
    for (const auto& q : fh.pairs) {
      ff.area += q.area;
      any_direct = any_direct || (q.area > 0 && !q.interpolated);
    }
    if (!(ff.area > 0))
      throw InputError(fh.source, fmt::format("fault '{}' has no area (its {} node pairs have area 0)", fh.name, fh.pairs.size()));
    ff.pairs.resize(fh.pairs.size());
    for (std::size_t q = 0; q < fh.pairs.size(); ++q) {
      const PairHistory& ph = fh.pairs[q];
      PairForecast& pf = ff.pairs[q];
      const PatchHistory patch(t, ph.dcfs, p.A_sigma, p.stressing_rate);
      pf.rate_ratio.resize(nd);
      pf.events_per_m2.assign(nd, 0.0);
      double from_start = 0;
      for (std::size_t k = 0; k < nd; ++k) {
        const double log_r = patch.log_rate_ratio(k);
        if (log_r > kLogRateRatioMax)
          throw InputError(fh.source, fmt::format("fault '{}', node {}: R/r = 10^{:.0f} at {}: dCFS = {} MPa at the first date is a "
                                                  "step of {:.0f} A sigma from the steady state (expected a history starting "
                                                  "near dCFS = 0, or a larger A sigma)", fh.name, ph.node, log_r / std::log(10.0),
                                                  format_iso_date(h.dates[k]), ph.dcfs.front() / 1e6,
                                                  ph.dcfs.front() / p.A_sigma));
        pf.rate_ratio[k] = std::exp(log_r);
        if (k > 0 && t[k] > ts) from_start += patch.integral_rate_ratio(std::max(t[k - 1], ts), t[k]);
        pf.events_per_m2[k] = p.background_rate * from_start;
      }
      if (!(ph.area > 0)) continue;  // a pair without area adds nothing to its fault
      for (std::size_t k = 0; k < nd; ++k) {
        ff.cfs_mean[k] += ph.area * ph.dcfs[k];
        ff.rate_ratio[k] += ph.area * pf.rate_ratio[k];
        ff.events[k] += ph.area * pf.events_per_m2[k];
        if (!ph.interpolated || !any_direct) ff.rate_ratio_max[k] = std::max(ff.rate_ratio_max[k], pf.rate_ratio[k]);
      }
      for (std::size_t w = 0; w < windows.size(); ++w)
        ff.window_events[w] += ph.area * p.background_rate *
                               patch.integral_rate_ratio(static_cast<double>(windows[w].start - t0),
                                                         static_cast<double>(windows[w].end - t0));
    }
    for (std::size_t k = 0; k < nd; ++k) {
      ff.rate[k] = p.background_rate * ff.rate_ratio[k];
      ff.cfs_mean[k] /= ff.area;
      ff.rate_ratio[k] /= ff.area;
    }
    // The inputs are bounded so that every value is finite; a table never holds inf or NaN.
    auto finite = [](const std::vector<double>& v) { return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }); };
    bool ok = finite(ff.rate) && finite(ff.events) && finite(ff.rate_ratio_max) && finite(ff.window_events) && finite(ff.cfs_mean);
    for (const auto& q : ff.pairs) ok = ok && finite(q.rate_ratio) && finite(q.events_per_m2);
    if (!ok)
      throw ComputeError(fmt::format("fault '{}': the forecast is not finite (A sigma {} MPa, s_r {} MPa/yr): a rate or count "
                                     "beyond doubles", fh.name, p.A_sigma / 1e6, p.stressing_rate * kSecondsPerYear / 1e6));
    fc.faults.push_back(std::move(ff));
  }
  return fc;
}

}  // namespace ugs::seismicity
