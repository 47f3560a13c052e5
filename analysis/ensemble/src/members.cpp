#include "ugs/ensemble/members.hpp"

#include <atomic>
#include <filesystem>
#include <map>
#include <mutex>
#include <thread>

#include <fmt/format.h>

#include "ugs/ensemble/friction_variants.hpp"
#include "ugs/formats/error.hpp"

namespace ugs::ensemble {

namespace fs = std::filesystem;

bool forecast_only(const std::string& path) { return path.rfind("seismicity.", 0) == 0; }

EnsembleMembers::EnsembleMembers(const EnsembleSpec& spec, Design design, const runner::CaseTemplate& tmpl,
                                 const std::string& command, const std::string& mesh, const std::string& cache_dir)
    : spec_(spec), design_(std::move(design)), tmpl_(tmpl) {
  for (const auto& p : spec_.parameters)
    for (const auto& path : p.paths) {
      any_forecast_only_ = any_forecast_only_ || forecast_only(path);
      any_friction_ = any_friction_ || friction_only(path);
    }
  runner::SolverRunSetup s;
  s.case_template = &tmpl;
  s.command = command;
  s.mesh_path = mesh;
  s.cache_dir = cache_dir;
  s.key_label = "ugs-ensemble member key 1";
  s.entry_prefix = "member-";
  s.keep_results = true;
  runs_ = std::make_unique<runner::SolverRuns>(std::move(s));
}

runner::ParameterValues EnsembleMembers::values(std::size_t k) const {
  runner::ParameterValues v;
  for (std::size_t i = 0; i < spec_.parameters.size(); ++i)
    for (const auto& p : spec_.parameters[i].paths) v.emplace_back(p, design_.x[k][i]);
  return v;
}

runner::ParameterValues EnsembleMembers::solver_values(std::size_t k) const {
  runner::ParameterValues v = values(k);
  std::erase_if(v, [](const auto& pv) { return forecast_only(pv.first); });
  return v;
}

std::optional<CaseFile> EnsembleMembers::forecast_case(std::size_t k) const {
  if (!any_forecast_only_) return std::nullopt;
  return runner::read_rendered_case(tmpl_, values(k));
}

std::string EnsembleMembers::entry(std::size_t k) const { return runs_->entry_name(solver_values(k)); }
std::string EnsembleMembers::folder(std::size_t k) const { return runs_->entry_path(entry(k)); }

MemberStatus EnsembleMembers::status(std::size_t k) const {
  MemberStatus s;
  const auto v = solver_values(k);
  s.entry = runs_->entry_name(v);
  if (runs_->complete(v)) {
    s.state = MemberState::done;
    return s;
  }
  const fs::path err = fs::path(runs_->failed_path(s.entry)) / "error.txt";
  if (fs::exists(err)) {
    s.state = MemberState::failed;
    std::string line = runner::read_text_file(err.string());
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
    s.error = line.substr(0, line.find('\n'));
    return s;
  }
  s.error = "not run";
  return s;
}

std::string EnsembleMembers::stick_key(std::size_t k) const {
  std::string key;
  for (const auto& [path, v] : solver_values(k))
    if (!friction_only(path)) key += fmt::format("{}={}\n", path, v);
  return key;
}

MemberStatus EnsembleMembers::derive_from(std::size_t k, std::size_t source) {
  MemberStatus s;
  s.entry = entry(k);
  const std::string from = entry(source);
  const CaseFile run_case = runner::read_rendered_case(tmpl_, solver_values(source));
  const CaseFile member_case = runner::read_rendered_case(tmpl_, solver_values(k));
  FrictionVariant v;
  bool stored = false;
  try {
    stored = runs_->store_derived(solver_values(k), from, [&](const std::string& folder) {
      v = derive_friction_variant(runs_->entry_path(from), run_case, member_case, folder);
      if (v.derived)
        runner::write_text_file((fs::path(folder) / "derived.txt").string(), fmt::format("derived from {}: {}\n", from, v.reason));
      return v.derived;
    });
  } catch (const InputError& e) {  // the source's outputs do not read: the member runs itself
    v.reason = fmt::format("cannot read {}: {}", from, e.what());
  }
  s.note = v.reason;
  if (stored) {
    s.state = MemberState::done;
    s.derived_from = from;
  } else {
    s.error = "not run";
  }
  return s;
}

std::vector<MemberStatus> EnsembleMembers::run(const std::vector<std::size_t>& which, int jobs,
                                               const std::function<void(std::size_t, const MemberStatus&)>& on_done) {
  if (!any_friction_) return run_entries(which, jobs, on_done);
  // Friction variants: per group of members that differ only in the faults' friction (and in
  // forecast-only values), one solver run first — a member of the group already in the cache, else
  // the group's first — then the others derived from it where every fault sticks, and run where not.
  std::vector<MemberStatus> out(which.size());
  std::map<std::string, std::size_t> source;  // stick key -> member whose entry is done
  for (std::size_t k = 0; k < size(); ++k)
    if (status(k).state == MemberState::done) source.try_emplace(stick_key(k), k);
  std::vector<std::size_t> first, rest;  // positions in `which`
  std::map<std::string, std::size_t> first_of;
  for (std::size_t j = 0; j < which.size(); ++j) {
    const std::string g = stick_key(which[j]);
    if (!source.count(g) && first_of.emplace(g, which[j]).second) first.push_back(j);
    else rest.push_back(j);
  }
  auto subset = [&](const std::vector<std::size_t>& pos) {
    std::vector<std::size_t> v;
    for (auto j : pos) v.push_back(which[j]);
    return v;
  };
  const auto r1 = run_entries(subset(first), jobs, on_done);
  for (std::size_t i = 0; i < first.size(); ++i) {
    out[first[i]] = r1[i];
    if (r1[i].state == MemberState::done) source.try_emplace(stick_key(which[first[i]]), which[first[i]]);
  }
  std::vector<std::size_t> again;          // positions of members that run after all
  std::map<std::size_t, std::string> why;  // member -> why it was not derived
  for (std::size_t j : rest) {
    const std::size_t k = which[j];
    MemberStatus s = status(k);
    const auto src = source.find(stick_key(k));
    if (s.state != MemberState::done && src != source.end()) s = derive_from(k, src->second);
    if (s.state == MemberState::done) {
      out[j] = s;
      if (on_done) on_done(k, s);
    } else {
      again.push_back(j);
      why[k] = s.note;
    }
  }
  const auto r3 = run_entries(subset(again), jobs, [&](std::size_t k, const MemberStatus& st) {
    MemberStatus s = st;
    s.note = why.at(k);
    if (on_done) on_done(k, s);
  });
  for (std::size_t i = 0; i < again.size(); ++i) {
    out[again[i]] = r3[i];
    out[again[i]].note = why.at(which[again[i]]);
  }
  return out;
}

std::vector<MemberStatus> EnsembleMembers::run_entries(const std::vector<std::size_t>& which, int jobs,
                                                       const std::function<void(std::size_t, const MemberStatus&)>& on_done) {
  std::vector<MemberStatus> out(which.size());
  // One run per entry: members with the same solver values (forecast-only parameters aside) share
  // it, the first of them runs it and the others take its outcome afterwards.
  std::vector<std::size_t> runs, later;  // positions in `which`
  std::vector<std::size_t> first(which.size());  // per position: that of the member running its entry
  std::map<std::string, std::size_t> runner_of;
  for (std::size_t j = 0; j < which.size(); ++j) {
    const auto [it, fresh] = runner_of.emplace(entry(which[j]), j);
    first[j] = it->second;
    (fresh ? runs : later).push_back(j);
  }
  std::atomic<std::size_t> next{0};
  std::mutex lock;
  auto worker = [&] {
    for (;;) {
      const std::size_t i = next++;
      if (i >= runs.size()) return;
      const std::size_t j = runs[i], k = which[j];
      MemberStatus s = status(k);
      if (s.state != MemberState::done) {
        // Another process sharing the cache may run the same entry: the runner's atomic rename settles it.
        try {
          s.seconds = runs_->run(solver_values(k), fmt::format("member {}", k + 1), [](const std::string&, const std::string&) {});
          s.state = MemberState::done;
          s.error.clear();
        } catch (const ComputeError& e) {
          s.state = MemberState::failed;
          s.error = e.what();
        }
        s.ran_now = true;
      }
      std::lock_guard g(lock);
      out[j] = s;
      if (on_done) on_done(k, s);
    }
  };
  const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(std::max(jobs, 1)), runs.size());
  std::vector<std::thread> threads;
  for (std::size_t t = 1; t < n; ++t) threads.emplace_back(worker);
  if (n > 0) worker();
  for (auto& t : threads) t.join();
  for (std::size_t j : later) {
    const std::size_t k = which[j];
    MemberStatus s = out[first[j]];
    s.ran_now = false;
    s.seconds = 0;
    out[j] = s;
    if (on_done) on_done(k, s);
  }
  return out;
}

namespace {

// A make variable's value: '$' doubled, '#' escaped.
std::string make_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '$') o += "$$";
    else if (c == '#') o += "\\#";
    else o += c;
  }
  return o;
}

}  // namespace

std::string makefile(const EnsembleMembers& m, const std::string& member_command, const std::string& collect_command) {
  std::string f = fmt::format(
      "# {} members of an ugs-ensemble (written by ugs-ensemble --emit make): run them with\n"
      "#   make -f THIS -k -j N\n"
      "# (-k: a failed member is recorded and the others go on), then collect with `make -f THIS collect`.\n"
      "# Each target is a member's key.txt in the cache, written last by the run: done members are skipped.\n"
      "MEMBER = {}\n"
      "COLLECT = {}\n\n",
      m.size(), make_escape(member_command), make_escape(collect_command));
  std::string all = "all:";
  std::string rules;
  std::vector<std::string> seen;
  std::map<std::string, std::string> group_first;  // friction group -> its first member's target
  for (std::size_t k = 0; k < m.size(); ++k) {
    const std::string target = make_escape(m.folder(k) + "/key.txt");
    if (std::find(seen.begin(), seen.end(), target) != seen.end()) continue;  // same values as an earlier member
    seen.push_back(target);
    all += " \\\n  " + target;
    std::string after;  // a friction variant waits for its group's run, to be derived from it
    if (m.has_friction_variants()) {
      const auto [it, fresh] = group_first.emplace(m.friction_group(k), target);
      if (!fresh) after = " " + it->second;
    }
    rules += fmt::format("{}:{}\n\t$(MEMBER) --member {}\n", target, after, k + 1);
  }
  f += all + "\n\ncollect: all\n\t$(COLLECT)\n\n.PHONY: all collect\n\n" + rules;
  return f;
}

std::string slurm_script(const EnsembleMembers& m, const std::string& member_command, const std::string& collect_command) {
  return fmt::format(
      "#!/bin/bash\n"
      "# {} members of an ugs-ensemble (written by ugs-ensemble --emit slurm), one array task each:\n"
      "#   sbatch THIS\n"
      "# then, when the array is done: {}\n"
      "# A task whose member is already in the cache returns at once.\n"
      "#SBATCH --job-name=ugs-ensemble\n"
      "#SBATCH --array=1-{}\n"
      "#SBATCH --ntasks=1\n"
      "set -euo pipefail\n"
      "{} --member \"$SLURM_ARRAY_TASK_ID\"\n",
      m.size(), collect_command, m.size(), member_command);
}

}  // namespace ugs::ensemble
