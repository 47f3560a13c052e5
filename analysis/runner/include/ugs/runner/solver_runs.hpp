// Solver runs as subprocesses, content-addressed: the one runner behind ugs-calibrate's evaluations
// and ugs-ensemble's members.
//
// For case-parameter values the runner renders a copy of the case (case_params.hpp), runs the
// solver command template in a fresh folder ({case}, {out}, {mesh}, {dir} are replaced by
// shell-quoted paths; the shell's ${VAR} is left alone), lets the caller keep what it needs from
// the outputs (`finish`), and turns the folder into CACHE/<prefix><hash>/ by atomic rename, with
//   case.toml, command.sh, inputs.txt, solver.log, entry.json, timing.txt, key.txt (written last).
// The key is a SHA-256 (content_hash.hpp) of everything that decides a run: the case text and the
// content of every file it names, the command template and the content of every file it names
// (pressure files, restart state, the solver program itself, also when found in PATH), the mesh's
// content, `extra` (anything else the caller's outputs depend on), and the values. Same key, same
// entry; any change of an input gives another. Several threads and processes may share a cache.
// A failed run leaves its folder as CACHE/failed-<entry>/ with error.txt (the ComputeError's
// text), never a temporary folder.
#pragma once
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "ugs/runner/case_params.hpp"

namespace ugs::runner {

using ParameterValues = std::vector<std::pair<std::string, double>>;  // case path -> value

struct SolverRunSetup {
  const CaseTemplate* case_template = nullptr;
  std::string command;          // must contain {case} and {out}
  std::string mesh_path;        // for {mesh}
  std::string cache_dir;
  std::string extra;            // anything else that changes what an entry holds
  std::string key_label;        // first line of the key text, e.g. "ugs-calibrate cache key 2"
  std::string entry_prefix;     // e.g. "eval-"
  bool keep_results = false;    // keep result.h5 (+ .xdmf) in the entry
};

class SolverRuns {
public:
  // InputError for a bad command template (check_command_template) or an input file that cannot be
  // read. Hashes the inputs, then creates the cache folder.
  explicit SolverRuns(SolverRunSetup setup);

  std::string key(const ParameterValues& values) const;
  std::string entry_name(const ParameterValues& values) const;
  std::string entry_path(const std::string& entry) const;   // CACHE/entry
  std::string failed_path(const std::string& entry) const;  // CACHE/failed-entry
  // True when the entry exists and its key.txt holds this key.
  bool complete(const ParameterValues& values) const;
  const std::string& cache_dir() const { return setup_.cache_dir; }
  const std::string& inputs_description() const { return inputs_; }
  // The command as run in `dir` (paths substituted and quoted).
  std::string command_in(const std::string& dir) const;

  // Runs the solver for `values` and returns its wall time (s). `finish(folder, result_h5)` writes
  // what the entry keeps from the outputs (InputError from it: the outputs are unusable). `label`
  // names the run in errors ("evaluation at c_R = 3"). ComputeError when the solver exits non-zero,
  // writes no {out}, or `finish` fails; the folder is then kept as failed-<entry>.
  double run(const ParameterValues& values, const std::string& label,
             const std::function<void(const std::string& folder, const std::string& result_h5)>& finish);

  // Stores the entry for `values` without running the solver, from results known to be the same as
  // a run's (ugs-ensemble's friction variants of a run in which every fault sticks): `fill(folder)`
  // writes the outputs, the runner adds case.toml, inputs.txt, entry.json (with `derived_from`) and
  // key.txt, and renames the folder into place as run() does. Returns false, leaving nothing, when
  // `fill` returns false (the results cannot be derived: the caller runs the solver instead);
  // exceptions from `fill` propagate, also leaving nothing.
  bool store_derived(const ParameterValues& values, const std::string& derived_from,
                     const std::function<bool(const std::string& folder)>& fill);

private:
  SolverRunSetup setup_;
  std::string setup_hash_;
  std::string inputs_;
};

// InputError for a solver command template without {case} or {out}, with a {name} other than
// case, out, mesh and dir, or using {mesh} without a mesh.
void check_command_template(const std::string& command, bool have_mesh);

// Files a shell command names: every word (or the value of --opt=VALUE) that is an existing regular
// file, and the program of each simple command looked up in PATH; absolute, sorted, unique.
// Words holding {case}, {out}, {mesh} or {dir} are skipped (each run substitutes its own files).
std::vector<std::string> files_named_in_command(const std::string& command);

// Text file helpers shared by the runners' callers.
std::string read_text_file(const std::string& path);
void write_text_file(const std::string& path, const std::string& text);
std::string json_string(const std::string& s);

}  // namespace ugs::runner
