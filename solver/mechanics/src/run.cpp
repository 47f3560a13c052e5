#include "ugs/mechanics/run.hpp"

#include <chrono>
#include <cmath>
#include <memory>
#include <set>

#include <fmt/format.h>

#include "state_file.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/mechanics/collective.hpp"
#include "ugs/mechanics/model.hpp"
#include "ugs/mechanics/pressure.hpp"
#include "ugs/mechanics/solver.hpp"
#include "ugs/mechanics/step_dates.hpp"
#include "ugs/mechanics/step_output.hpp"

namespace ugs::mech {
namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Everything only rank 0 holds.
struct Root {
  CaseFile cs;
  Mesh mesh;
  Model model;
  std::unique_ptr<PressureHistory> history;
  std::set<std::string> fields;
  Mesh top_mesh;
  std::unique_ptr<FieldSeriesWriter> results, top;
  std::unique_ptr<CsvWriter> top_csv;
  SavedState restart;
  std::string restart_date;
  double restart_time = -INFINITY;
};

Mesh make_top_mesh(const Mesh& mesh, const Model& model) {
  Mesh top;
  std::vector<std::uint32_t> local(mesh.num_nodes(), 0);
  for (auto v : model.top_nodes) local[v] = top.add_node(mesh.nodes[v], mesh.node_tags[v]);
  const int e = top.entity_for_physical(2, "bnd:top");
  auto& b = top.block(2, e, ElementType::Triangle);
  for (const auto& t : model.top_triangles) {
    const std::uint32_t n[3] = {local[t[0]], local[t[1]], local[t[2]]};
    top.add_element(b, n);
  }
  top.update_entity_bboxes();
  return top;
}

// Solver settings agreed by every rank (the case file is read on rank 0).
struct Settings {
  int linear = 0, partition = 0, max_newton = 25, max_substeps = 64, reuse = 1, checkpoint_every = 0;
  double tolerance = 1e-8;
};

std::vector<std::string> broadcast_strings(MPI_Comm comm, std::vector<std::string> v) {
  std::string all;
  for (const auto& s : v) all += s + '\n';
  broadcast(comm, all);
  v.clear();
  std::size_t p = 0;
  while (p < all.size()) {
    const auto q = all.find('\n', p);
    v.push_back(all.substr(p, q - p));
    p = q + 1;
  }
  return v;
}

// The [solver] numbers the reader takes as they come (positive, at least 1) must also be usable:
// a Newton tolerance of 1 or more accepts the first iterate of every step (no equilibrium, exit 0),
// one below 1e-14 is beyond double precision (every step would fail after all its sub-steps), and
// 10^9 Newton iterations per sub-step never end.
void check_solver_settings(const CaseFile& cs) {
  if (!(cs.newton_tolerance >= 1e-14 && cs.newton_tolerance < 1))
    throw InputError(cs.path, fmt::format("[solver] tolerance = {}: outside [1e-14, 1) (a relative residual ||r|| / ||r_0||)",
                                          cs.newton_tolerance));
  if (cs.max_newton_iterations > 1000)
    throw InputError(cs.path, fmt::format("[solver] max_newton_iterations = {}: more than 1000 (a step takes 2-25)",
                                          cs.max_newton_iterations));
}

}  // namespace

std::string output_stem(const std::string& h5) {
  if (h5.size() > 3 && h5.compare(h5.size() - 3, 3, ".h5") == 0) return h5.substr(0, h5.size() - 3);
  return h5;
}

RunSummary run_solve(MPI_Comm comm, const RunOptions& o) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  auto log = [&](int level, const std::string& s) {
    if (rank == 0 && o.log) o.log(level, s);
  };
  // Warnings and notes about the inputs wait until every input has been checked and the outputs
  // are open: a run that stops on bad input prints its one error line and nothing else.
  std::vector<std::pair<int, std::string>> deferred;
  auto log_later = [&](int level, const std::string& s) { deferred.emplace_back(level, s); };
  RunSummary sum;
  const std::string stem = output_stem(o.output);
  const std::string top_path = o.top.empty() ? stem + "_top.h5" : o.top;
  const std::string state_path = o.state.empty() ? stem + "_state.h5" : o.state;
  auto t0 = Clock::now();

  // 1. Inputs (rank 0).
  std::unique_ptr<Root> root;
  Settings set;
  double until = INFINITY;
  int faulted = 0;
  collective(comm, [&] {
    if (rank != 0) return;
    if (!o.until.empty()) {
      const auto t = parse_iso_date(o.until);
      if (!t) throw InputError("--until", fmt::format("'{}' is not an ISO 8601 date", o.until));
      until = static_cast<double>(*t);
    }
    root = std::make_unique<Root>();
    Root& R = *root;
    if (o.case_file.empty()) throw InputError("--case", "a case file is required");
    if (o.pressure.empty()) throw InputError("--pressure", "at least one pressure field series (ugs-flow output) is required");
    if (o.output == "-" || o.output.empty()) throw InputError("-o", "results are HDF5 files: give a file name");
    R.cs = read_case_file(o.case_file);
    check_solver_settings(R.cs);
    R.mesh = read_msh(o.mesh);
    if (o.faulted && R.mesh.count(ElementType::Prism) > 0) {
      if (R.cs.steps != "every-date")
        throw InputError(R.cs.path, "[solver] steps = \"turning-points\" is for the continuous model: fault slip depends on the whole path");
      faulted = 1;  // interface elements: the fault mechanics take the run
      return;
    }
    log(1, fmt::format("mesh: {} nodes, {} tetrahedra", R.mesh.num_nodes(), R.mesh.count(ElementType::Tetrahedron)));
    R.model = build_model(R.mesh, R.cs);
    if (!R.cs.faults.empty())
      log_later(-1, fmt::format("{}: [[fault]] entries are ignored by the continuous model", R.cs.path));
    R.history = std::make_unique<PressureHistory>(o.pressure, R.mesh, R.model);
    log(1, fmt::format("pressure: {} file(s), {} dates, {} of {} elements under a pressure change", o.pressure.size(),
                       R.history->steps().size(), R.history->forced_cells(), R.model.tets.size()));
    for (const auto& d : R.cs.output_dates) R.history->add_step(d, R.cs.path + ": [output] dates");
    R.fields.insert(R.cs.output_fields.begin(), R.cs.output_fields.end());
    if (R.fields.empty()) R.fields = {"displacement", "strain", "stress", "stress_change", "cm", "state"};
    set.linear = static_cast<int>(parse_linear_solver(o.solver.empty() ? R.cs.linear_solver : o.solver));
    set.partition = static_cast<int>(parse_partition_method(o.partition));
    set.tolerance = R.cs.newton_tolerance;
    set.max_newton = R.cs.max_newton_iterations;
    set.max_substeps = R.cs.max_substeps;
    set.reuse = R.cs.reuse_preconditioner ? 1 : 0;
    set.checkpoint_every = o.checkpoint_every >= 0 ? o.checkpoint_every : R.cs.checkpoint_every;
    if (R.model.top_nodes.empty()) log_later(-1, "the mesh has no bnd:top group: no top-surface table is written");
    if (!o.restart.empty()) {
      R.restart = read_state(o.restart, R.mesh, R.restart_date, R.restart_time);
      log_later(0, fmt::format("restarting from {} ({})", o.restart, R.restart_date));
    }
  });
  MPI_Bcast(&faulted, 1, MPI_INT, 0, comm);
  if (faulted) return o.faulted(comm, o, rank == 0 ? &root->mesh : nullptr, rank == 0 ? &root->cs : nullptr);
  MPI_Bcast(&set, sizeof(Settings), MPI_BYTE, 0, comm);
  sum.seconds_read = since(t0);

  // 2. Steps: dates, and which write fields or checkpoints (every rank takes part in gathers).
  std::vector<std::string> dates;
  std::vector<double> times;
  std::vector<char> is_output, is_checkpoint;
  if (rank == 0) {
    const std::set<std::string> outs(root->cs.output_dates.begin(), root->cs.output_dates.end());
    std::set<double> out_times;
    for (const auto& d : outs) out_times.insert(static_cast<double>(*parse_iso_date(d)));
    const auto& steps = root->history->steps();
    // The steps the run takes: every date, or the turning points, outputs and the last date.
    std::vector<char> take(steps.size(), 1);
    if (root->cs.steps == "turning-points") {
      take = turning_points(*root->history, root->cs.turning_point_tolerance);
      std::size_t last = steps.size();
      for (std::size_t k = 0; k < steps.size(); ++k) {
        if (steps[k].time <= until) last = k;
        if (out_times.count(steps[k].time)) take[k] = 1;
      }
      if (last < steps.size()) take[last] = 1;
    }
    int since_checkpoint = 0;
    std::size_t in_run = 0;  // dates between the restart and --until
    for (std::size_t k = 0; k < steps.size(); ++k) {
      const auto& s = steps[k];
      if (s.time <= root->restart_time || s.time > until) continue;
      ++in_run;
      if (!take[k]) continue;
      dates.push_back(s.date);
      times.push_back(s.time);
      const bool out = outs.empty() || out_times.count(s.time);
      is_output.push_back(out);
      ++since_checkpoint;
      const bool cp = out || (set.checkpoint_every > 0 && since_checkpoint >= set.checkpoint_every);
      if (cp) since_checkpoint = 0;
      is_checkpoint.push_back(cp);
    }
    if (root->cs.steps == "turning-points") {
      log(1, fmt::format("turning-point steps: {} of {} dates (turning points of the pressure, output dates, the last date)",
                         dates.size(), in_run));
      // Every output date is a step; the other dates skipped are missing from the per-step outputs
      // (an InSAR comparison would interpolate across them): say so once.
      if (dates.size() < in_run)
        log_later(-1, fmt::format("{}: steps = \"turning-points\": {} of the {} pressure dates are not stepped on and are "
                                  "missing from the top-surface series{}; list the dates you need in [output] dates, or "
                                  "set [solver] steps = \"every-date\"",
                                  root->cs.path, in_run - dates.size(), in_run, outs.empty() ? " and the results" : ""));
    }
  }
  dates = broadcast_strings(comm, dates);
  std::uint64_t nsteps = dates.size();
  MPI_Bcast(&nsteps, 1, MPI_UINT64_T, 0, comm);
  times.resize(nsteps);
  is_output.resize(nsteps);
  is_checkpoint.resize(nsteps);
  if (nsteps) {
    MPI_Bcast(times.data(), static_cast<int>(nsteps), MPI_DOUBLE, 0, comm);
    MPI_Bcast(is_output.data(), static_cast<int>(nsteps), MPI_CHAR, 0, comm);
    MPI_Bcast(is_checkpoint.data(), static_cast<int>(nsteps), MPI_CHAR, 0, comm);
  }

  // 3. The distributed solver.
  t0 = Clock::now();
  SolverOptions sopt;
  sopt.linear = static_cast<LinearSolver>(set.linear);
  sopt.partition = static_cast<PartitionMethod>(set.partition);
  sopt.tolerance = set.tolerance;
  sopt.max_newton = set.max_newton;
  sopt.max_substeps = set.max_substeps;
  sopt.reuse_preconditioner = set.reuse != 0;
  MechanicsSolver solver(comm, rank == 0 ? &root->model : nullptr, sopt);
  log(1, fmt::format("{} nodes ({} on rank 0), {} cells; {}", solver.global_nodes(), solver.local_nodes(), solver.global_cells(),
                     solver.solver_description()));
  if (!o.restart.empty()) solver.restore_state(rank == 0 ? root->restart : SavedState{});
  collective(comm, [&] {
    if (rank != 0) return;
    Root& R = *root;
    R.results = std::make_unique<FieldSeriesWriter>(o.output, R.mesh);
    if (top_path != "none" && !R.model.top_nodes.empty()) {
      R.top_mesh = make_top_mesh(R.mesh, R.model);
      R.top = std::make_unique<FieldSeriesWriter>(top_path, R.top_mesh);
    }
    if (!o.top_csv.empty() && !R.model.top_nodes.empty()) {
      const std::vector<std::string> comments{"ugs-solve top-surface displacement (bnd:top nodes), one row per node and date",
                                              o.command_line};
      R.top_csv = std::make_unique<CsvWriter>(o.top_csv, std::vector<std::string>{"date", "node", "x_m", "y_m", "ux_mm", "uy_mm", "uz_mm"},
                                              comments);
    }
  });
  sum.seconds_setup = since(t0);
  for (const auto& [level, text] : deferred) log(level, text);
  if (nsteps == 0) log(-1, "no steps after the restart date: nothing to solve");

  // 4. March over the steps.
  std::string last_good_date = rank == 0 ? root->restart_date : "";
  broadcast(comm, last_good_date);  // every rank must agree on whether to gather a state below
  double last_good_time = rank == 0 ? root->restart_time : 0;
  for (std::uint64_t i = 0; i < nsteps; ++i) {
    const std::string label = fmt::format("step {}/{} ({})", i + 1, nsteps, dates[i]);
    std::vector<double> dp;
    collective(comm, [&] {
      if (rank == 0) dp = root->history->cell_dp(times[i]);
    });
    const StepReport rep = solver.advance(dp, label);
    sum.seconds_solve += rep.seconds;
    sum.newton_iterations += rep.newton_iterations;
    sum.linear_iterations += rep.linear_iterations;
    sum.preconditioner_setups += rep.preconditioner_setups;
    sum.substeps += rep.substeps;
    if (!rep.converged) {
      // The solver kept the state of the previous step: that is the last good one.
      const bool any = !last_good_date.empty() && state_path != "none";
      SavedState st;
      if (any) st = solver.gather_state();
      std::string saved;
      collective(comm, [&] {
        if (rank != 0) return;
        if (any) {
          write_state(state_path, root->mesh, last_good_date, last_good_time, st);
          saved = fmt::format("; last good state ({}) saved to {}: resume with --restart {}", last_good_date, state_path, state_path);
        } else {
          saved = state_path == "none" ? "; no state saved (--state none)" : "; no state saved (the first step failed)";
        }
      });
      broadcast(comm, saved);
      throw ComputeError(rep.failure + saved);
    }
    log(1, fmt::format("{}: {} Newton iteration{}, {} linear iterations, {} sub-step{}, {:.2f} s{}", label, rep.newton_iterations,
                       rep.newton_iterations == 1 ? "" : "s", rep.linear_iterations, rep.substeps, rep.substeps == 1 ? "" : "s",
                       rep.seconds,
                       rep.off_branch > 0 ? fmt::format(" (held elements off their branch: {:.1e})", rep.off_branch) : ""));
    if (!rep.substep_reason.empty())
      log(1, fmt::format("{}: split into {} sub-steps: {}", label, rep.substeps, rep.substep_reason));
    // Outputs.
    const auto to = Clock::now();
    const std::vector<double> u = solver.gather_displacement();
    CellResults cells;
    const bool want_cells = is_output[i];
    if (want_cells) cells = solver.gather_cells();
    SavedState st;
    if (state_path != "none" && (is_checkpoint[i] || i + 1 == nsteps)) st = solver.gather_state();
    collective(comm, [&] {
      if (rank != 0) return;
      Root& R = *root;
      write_top_surface(R.top.get(), R.top_csv.get(), R.mesh, R.model, dates[i], times[i], u);
      if (want_cells) write_volume_fields(*R.results, R.fields, *R.history, dates[i], times[i], u, cells);
      if (!st.u.empty()) write_state(state_path, R.mesh, dates[i], times[i], st);
    });
    last_good_date = dates[i];
    last_good_time = times[i];
    sum.seconds_output += since(to);
    ++sum.steps;
    if (rank == 0 && o.progress) o.progress(i + 1, nsteps);
  }

  // 5. Commit (rename into place) only now: a failed run leaves no results behind.
  collective(comm, [&] {
    if (rank != 0) return;
    Root& R = *root;
    for (const auto& n : R.history->notes()) log(-1, n);
    R.results->commit();
    if (R.top) R.top->commit();
    if (R.top_csv) R.top_csv->commit();
  });
  return sum;
}

}  // namespace ugs::mech
