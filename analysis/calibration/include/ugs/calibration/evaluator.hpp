// One calibration evaluation = the solver run for a set of parameter values, kept in a cache.
//
// For values x the evaluator has the shared runner (solver_runs.hpp) run the solver command on a
// copy of the case with x, samples the displacement of its result at the PS points in-process, and
// keeps the sampled series (not the results file, unless asked) in
//   CACHE/eval-<hash>/{case.toml, series.csv, entry.json, key.txt, inputs.txt, solver.log, timing.txt}
// The key covers what solver_runs.hpp lists, with `setup_extra` (the caller puts the PS points'
// ids and exact positions, the field and the top group there), and the values. Same key, same series; any change of an input
// gives another entry. A repeated run, or an optimizer coming back to a point, costs nothing;
// CACHE/index.csv lists every entry (no timings: they are in each entry's timing.txt and on
// stderr). Up to `jobs` evaluations run at once; entries appear by atomic rename, so several
// processes can share a cache. A failed solver run leaves its folder as CACHE/failed-<entry>/ (the
// error names it), never a temporary folder.
#pragma once
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "ugs/insar/misfit.hpp"
#include "ugs/runner/case_params.hpp"
#include "ugs/runner/solver_runs.hpp"

namespace ugs::calibration {

// The displacement at the PS points at every result step (what an evaluation keeps).
struct SimulatedSeries {
  std::vector<std::string> ids;
  std::vector<std::int64_t> times;
  std::vector<double> enu;  // ids x times x 3 (m), absolute (not relative to a reference)

  void write_csv(const std::string& path) const;
  static SimulatedSeries read_csv(const std::string& path);
  bool has(const std::string& id) const;
  // Interpolated linearly in time at `dates` for `points` (by id), as Samples (no reference).
  insar::Samples at_dates(const std::vector<insar::LocatedPoint>& points, const std::vector<std::int64_t>& dates) const;
};

struct EvaluatorSetup {
  const runner::CaseTemplate* case_template = nullptr;
  std::vector<runner::ParameterSpec> params;
  std::string solver_command;                 // must contain {case} and {out}
  std::string mesh_path;                      // for {mesh}
  std::string cache_dir;
  int jobs = 1;
  bool keep_results = false;
  std::string setup_extra;                    // anything else that changes a result (points, field, ...)
  std::vector<std::string> needed_ids;        // the series of these points must be in a cached entry
  // Result file -> series at the PS points (in-process sampling).
  std::function<SimulatedSeries(const std::string& result_h5)> sample;
  // Series -> misfit.
  std::function<insar::Misfit(const SimulatedSeries&)> misfit;
};

struct Evaluation {
  std::size_t index = 0;         // 1-based, in request order over the run
  std::vector<double> x;         // parameter values (natural units)
  insar::Misfit misfit;
  bool cached = false;
  double seconds = 0;            // solver wall time (0 when cached); for stderr and timing.txt only
  std::string phase;             // "scan", "brent", "bobyqa", ...
  std::string entry;             // cache entry folder
};

class Evaluator {
public:
  // InputError for a command template without {case} or {out} or with a {name} other than case,
  // out, mesh and dir, or for an input file that cannot be read. Hashes the inputs, then creates the cache folder.
  explicit Evaluator(EvaluatorSetup setup);

  // Evaluates each x (up to `jobs` at once), results in the order given; ComputeError naming the
  // evaluation, the exit code and the last log line when a solver run fails.
  std::vector<Evaluation> evaluate(const std::vector<std::vector<double>>& xs, const std::string& phase);
  const std::vector<Evaluation>& history() const { return history_; }
  // Called after each evaluation (under a lock), e.g. to log progress.
  std::function<void(const Evaluation&)> on_evaluation;

  std::string entry_name(const std::vector<double>& x) const;
  std::string key(const std::vector<double>& x) const;
  const SimulatedSeries& series_of(const Evaluation& e);  // from the cache entry
  // The misfit of any series with the points and dates of an evaluation's (e.g. a model's
  // prediction between runs), as an evaluation's is taken.
  insar::Misfit misfit_of(const SimulatedSeries& s) const { return setup_.misfit(s); }
  // What the key covers, one input a line (written to each entry's inputs.txt).
  const std::string& inputs_description() const { return runs_.inputs_description(); }

private:
  Evaluation run_one(const std::vector<double>& x);
  runner::ParameterValues values_of(const std::vector<double>& x) const;
  void write_index();

  EvaluatorSetup setup_;
  runner::SolverRuns runs_;  // the shared runner of solver subprocesses (solver_runs.hpp)
  std::vector<Evaluation> history_;
  std::map<std::string, SimulatedSeries> series_;   // entry -> series (for the best one and reports)
  std::map<std::string, std::string> index_rows_;   // entry -> CSV row
  std::mutex mutex_;
};

}  // namespace ugs::calibration
