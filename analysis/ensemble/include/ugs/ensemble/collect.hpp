// Gathering an ensemble: every member's metrics (metrics.hpp) from its cache entry, the failed
// and missing members with their error line, and the statistics, as CSV files in `out_dir`
// (formats in docs/ensemble.md): parameters.csv, members.csv, failures.csv, quantiles.csv,
// exceedance.csv, chi_exceedance_pairs.csv (with per-pair fault CSVs), ps_series.csv (with PS
// series), and sobol.csv or morris.csv for those designs. A failed member (also one whose fault
// node pairs differ from the others') is excluded from every statistic and listed in failures.csv
// (and returned for stderr), never dropped silently.
#pragma once
#include <string>
#include <vector>

#include "ugs/ensemble/members.hpp"
#include "ugs/ensemble/metrics.hpp"

namespace ugs::ensemble {

struct CollectSummary {
  std::size_t members = 0, done = 0;
  std::vector<std::pair<std::size_t, std::string>> failures;  // member (1-based), error line
  std::vector<std::string> notes;                             // e.g. metrics without variance
};

// Writes the files into `out_dir` (an existing folder). ComputeError when no member succeeded.
CollectSummary collect(const EnsembleSpec& spec, const EnsembleMembers& members, const MetricOptions& options,
                       const std::string& out_dir, const std::vector<std::string>& comments);

}  // namespace ugs::ensemble
