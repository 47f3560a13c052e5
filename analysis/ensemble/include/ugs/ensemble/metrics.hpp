// What a member's outputs say, as named numbers (docs/ensemble.md, "Metrics"):
//   uplift_max_mm.<phase>, settlement_max_mm.<phase>     over the top surface (or the nodes inside
//                                                        the trace polygons): the largest rise and
//                                                        the largest fall of u_z from the phase's
//                                                        start to its end, mm (>= 0)
//   ps_uplift_max_mm.<phase>, ps_settlement_max_mm.<phase>   the same at the PS points
//   insar_rms_mm                                         the calibration misfit (misfit.hpp) at the PS points
//   chi_max.<fault>                                      the largest chi of the fault over all dates
//   chi_max.<fault>.<date>                               per date (the solver's *_faults.csv)
//   safe_scale                                           the safe-scale search's answer (*_scenario.csv)
//   seismic_events.<fault>.<window>, p_event.<fault>.<window>, p_event_M<m>.<fault>.<window>
//                                                        with seismic windows: the expected events >= M_c
//                                                        and P(at least one >= M_c, >= m) over the window,
//                                                        per fault and for "all" (ugs-seismicity's model,
//                                                        docs/seismicity.md), from the member's per-pair
//                                                        CSVs *_fault_<F>.csv and its case's [seismicity]
// The results file is the member's result.h5 (the {out} of the solver command: full results with
// `u` or the top-surface file with `u_mm`); the fault and scenario tables are the single
// *_faults.csv and *_scenario.csv in the member's folder, when there.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ugs/formats/case_file.hpp"
#include "ugs/insar/misfit.hpp"
#include "ugs/insar/ps_data.hpp"
#include "ugs/meshing/geodata.hpp"

namespace ugs::ensemble {

struct Phase {
  std::string name;
  std::int64_t start = 0, end = 0;   // seconds since 1970
};
// NAME=START/END (ISO dates, START before END); InputError at "metric phase TEXT".
Phase parse_phase(const std::string& text);

struct MetricOptions {
  std::vector<Phase> phases;                        // empty: one phase "all", first to last result step
  std::optional<geo::PolygonSet> trace;             // restricts the surface metrics
  std::optional<insar::PsData> ps;                  // PS points (model CRS) and measured series
  std::optional<insar::PsData> ps_east;             // east-west series of some of those points
  double east_weight = 1.0;                         // of the east residuals (ugs-calibrate's misfit)
  insar::MisfitWindow window;
  std::string field;                                // displacement field ("" = u, else u_mm)
  std::vector<Phase> seismic_windows;               // forecast windows of the seismicity metrics (none: no such metrics)
};

using Metrics = std::vector<std::pair<std::string, double>>;  // in a fixed order

// InputError when an output is missing or unreadable, or a phase lies outside the results' dates.
Metrics member_metrics(const std::string& folder, const MetricOptions& options);

// The metrics and, with PS points that have dates, the simulated vertical displacement at each
// point on each PS date, relative to the first PS date the results reach (mm; NaN outside the
// results' dates): points x dates, the data of the fan charts.
struct MemberOutputs {
  Metrics metrics;
  std::vector<std::string> ps_ids;
  std::vector<std::int64_t> ps_dates;
  std::vector<double> ps_up_mm;
};
// The fault stress histories read from the per-pair CSVs of each entry folder, kept across the
// members that share the folder (forecast-only parameters, friction variants aside: one read per
// entry instead of one per member; the demo's 8 members read 320 MB of CSV twice, not eight times).
class PairHistoryCache {
public:
  PairHistoryCache();
  ~PairHistoryCache();
  PairHistoryCache(const PairHistoryCache&) = delete;
  PairHistoryCache& operator=(const PairHistoryCache&) = delete;
  struct Impl;
  Impl& impl() { return *impl_; }

private:
  std::unique_ptr<Impl> impl_;
};

// `forecast_case`: the member's own case for the seismicity metrics when it is not the folder's
// case copy (forecast-only parameters, EnsembleMembers::forecast_case); nullptr = the copy.
// `cache`: histories already read (nullptr: read them).
MemberOutputs member_outputs(const std::string& folder, const MetricOptions& options, const CaseFile* forecast_case = nullptr,
                             PairHistoryCache* cache = nullptr);

}  // namespace ugs::ensemble
