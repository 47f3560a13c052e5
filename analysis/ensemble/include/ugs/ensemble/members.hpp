// The members of an ensemble as solver runs: member k (1-based) of the design is the case with
// the parameters' paths set to row k, run through the shared runner (runner::SolverRuns, as
// ugs-calibrate's evaluations) into CACHE/member-<hash>/, content-addressed, so a rerun (or a
// Makefile / Slurm job running one member) skips the members already done. The entry keeps the
// solver's outputs (result.h5, *_faults.csv, *_scenario.csv): metrics are computed when collecting.
// Parameters the solver never reads (the seismicity forecast's, `seismicity.*`) do not enter the
// run: members that differ only in them share one entry, and collect applies each member's own
// values to its forecast (forecast_case). Members that differ from a run only in the faults'
// friction angles (fault.<name>.friction_deg) take that run's results when every fault sticks in it
// (friction_variants.hpp): their entries are derived, not run (entry.json names the source).
#pragma once
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ugs/ensemble/design.hpp"
#include "ugs/runner/solver_runs.hpp"

namespace ugs::ensemble {

// A case path read only by the metrics (the rate-and-state forecast, [seismicity] and its per-fault
// overrides), never by the solver.
bool forecast_only(const std::string& path);

enum class MemberState { done, failed, missing };

struct MemberStatus {
  MemberState state = MemberState::missing;
  std::string entry;        // the entry folder's name
  std::string error;        // failed: the runner's error line; missing: "not run"
  bool ran_now = false;
  double seconds = 0;
  std::string derived_from;  // set when the entry was derived now from another (friction variants)
  std::string note;          // what the derivation checked, or why it did not hold (then the member ran)
};

class EnsembleMembers {
public:
  EnsembleMembers(const EnsembleSpec& spec, Design design, const runner::CaseTemplate& tmpl, const std::string& command,
                  const std::string& mesh, const std::string& cache_dir);

  std::size_t size() const { return design_.x.size(); }
  const Design& design() const { return design_; }
  runner::ParameterValues values(std::size_t k) const;          // k 0-based; every parameter
  runner::ParameterValues solver_values(std::size_t k) const;   // those the solver reads: the run's key
  // The member's whole case (every parameter set) when some parameter is forecast-only, for its
  // forecast metrics; nullopt otherwise (the entry's own case copy is the member's).
  std::optional<CaseFile> forecast_case(std::size_t k) const;
  std::string entry(std::size_t k) const;
  std::string folder(std::size_t k) const;                // CACHE/entry
  MemberStatus status(std::size_t k) const;              // from the cache, runs nothing

  // Runs the members `which` (0-based) not yet done, up to `jobs` at once. A failed member is
  // recorded (failed-<entry>/error.txt) and reported in its status, never thrown;
  // `on_done(k, status)` is called under a lock after each.
  std::vector<MemberStatus> run(const std::vector<std::size_t>& which, int jobs,
                                const std::function<void(std::size_t, const MemberStatus&)>& on_done);
  const runner::SolverRuns& runs() const { return *runs_; }
  // Whether members may be derived from a run of another (friction angles among the parameters),
  // and the group of member k: the members that differ only in friction and forecast-only values.
  bool has_friction_variants() const { return any_friction_; }
  std::string friction_group(std::size_t k) const { return stick_key(k); }

private:
  // run() without friction variants: one solver run per entry, `jobs` at once.
  std::vector<MemberStatus> run_entries(const std::vector<std::size_t>& which, int jobs,
                                        const std::function<void(std::size_t, const MemberStatus&)>& on_done);
  // The values the solution depends on while every fault sticks: the solver's, friction aside.
  std::string stick_key(std::size_t k) const;
  // Derives member k's entry from member `source`'s (done); the status says whether it held.
  MemberStatus derive_from(std::size_t k, std::size_t source);

  const EnsembleSpec& spec_;
  Design design_;
  const runner::CaseTemplate& tmpl_;
  bool any_forecast_only_ = false;
  bool any_friction_ = false;
  std::unique_ptr<runner::SolverRuns> runs_;
};

// A Makefile (GNU make) and a Slurm job-array script whose jobs each run one member with
// `member_command` + " --member K" (K 1-based) — the same code path as a local run, into the same
// cache, so `ugs-ensemble collect` afterwards reads their results as its own. In the Makefile a
// member that may be derived (friction variants) waits for its group's first member, so that
// `make -j` derives it instead of running it; the array jobs all start at once and each derives
// only from a member already in the cache.
std::string makefile(const EnsembleMembers& members, const std::string& member_command, const std::string& collect_command);
std::string slurm_script(const EnsembleMembers& members, const std::string& member_command, const std::string& collect_command);

}  // namespace ugs::ensemble
