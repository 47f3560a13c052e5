// The driver: run() calls its named steps in order (read the inputs, plan the steps, make the
// solver, open the outputs, march, search the safe scale, commit), the same for the continuous and
// the faulted model; what only a faulted mesh does is in fault_part.hpp.
#include "ugs/driver/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include <fmt/format.h>

#include "fault_part.hpp"
#include "ugs/driver/caprock.hpp"
#include "ugs/contact/contact.hpp"
#include "ugs/driver/fault_state_file.hpp"
#include "ugs/driver/names.hpp"
#include "ugs/driver/output_set.hpp"
#include "ugs/driver/step_plan.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/mechanics/case_section.hpp"
#include "ugs/mechanics/collective.hpp"
#include "ugs/mechanics/model.hpp"
#include "ugs/mechanics/pressure.hpp"
#include "ugs/mechanics/solver.hpp"
#include "ugs/mechanics/state_file.hpp"

namespace ugs::driver {

std::string output_stem(const std::string& h5) {
  if (h5.size() > 3 && h5.compare(h5.size() - 3, 3, ".h5") == 0) return h5.substr(0, h5.size() - 3);
  return h5;
}

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Everything only rank 0 holds.
struct Root {
  CaseFile cs;
  Mesh mesh;
  mech::Model model;
  contact::FaultModel fm;
  std::unique_ptr<mech::PressureHistory> history;
  std::unique_ptr<OutputSet> out;
  std::unique_ptr<CaprockCheck> caprock;      // the [[seal]] elements (empty without seals)
  std::unique_ptr<CaprockOutput> caprock_out;
  mech::SavedState restart;
  contact::FaultContact::Snapshot restart_faults;
  std::string restart_date;
  double restart_time = -INFINITY;
  std::vector<double> ref_cell, ref_node;  // pressure change at the scenario's reference date
  mech::SavedState snapshot;               // the state there (safe-scale search)
};

// Settings every rank agrees on (the case file is read on rank 0).
struct Shared {
  int faulted = 0, linear = 0, partition = 0, max_newton = 25, max_substeps = 64, reuse = 1, fault_solver = 0, search = 0,
      total_load = 0, caprock = 0;
  double tolerance = 1e-8, scale = 1, max_scale = 10, scale_tolerance = 0.01, ref_time = -INFINITY;
};

template <class T>
void release(std::vector<T>& v) {
  std::vector<T>().swap(v);
}

// Once the solver holds each rank's part and the output files hold the mesh, rank 0 keeps of the
// global model only what the per-step outputs read: the nodes and tags of the mesh (the top
// surface) and bnd:top; the restart state copies its mesh from the results file. On the 1.49M-dof
// box this is ~180 MB of rank 0's peak.
void release_distributed(Root& R) {
  mech::Model& m = R.model;
  release(m.x), release(m.tets), release(m.tet_material), release(m.tet_tags);
  release(m.fixed), release(m.prescribed), release(m.traction_force);
  for (ElementBlock& b : R.mesh.blocks) release(b.tags), release(b.nodes);
}

class Run {
public:
  Run(MPI_Comm comm, const RunSettings& o) : comm_(comm), o_(o) { MPI_Comm_rank(comm, &rank_); }

  RunSummary operator()() {
    read_inputs();
    plan();
    make_solver();
    open_outputs();
    march();
    find_safe_scale();
    commit();
    return sum_;
  }

private:
  MPI_Comm comm_;
  const RunSettings& o_;
  int rank_ = 0;
  std::unique_ptr<Root> root_;
  Shared set_;
  StepPlan steps_;
  std::unique_ptr<mech::MechanicsSolver> solver_;
  std::unique_ptr<contact::FaultContact> contact_;
  contact::FaultContact::Snapshot contact_snapshot_;
  bool have_snapshot_ = false, critical_before_ = false;
  std::size_t first_after_ = 0;  // first step after the reference date
  std::vector<mech::CellField> cell_fields_;  // the cell fields of an output date, in writing order
  Watch base_;
  Watch before_;  // the steps up to the reference date (rank 0): what failed there, if anything
  RunSummary sum_;
  // Warnings and notes about the inputs wait until every input has been checked and the outputs
  // are open: a run that stops on bad input prints its error lines and nothing else.
  std::vector<std::pair<int, std::string>> deferred_;

  void log(int level, const std::string& s) const {
    if (rank_ == 0 && o_.log) o_.log(level, s);
  }
  void log_later(int level, const std::string& s) { deferred_.emplace_back(level, s); }
  bool faulted() const { return set_.faulted != 0; }
  bool caprock() const { return set_.caprock != 0; }
  // The scenario (scale and safe-scale search) applies to runs with something to keep safe.
  bool guarded() const { return faulted() || caprock(); }

  // 1. Inputs (rank 0): case, mesh, model (and faults), pressure history, restart state.
  void read_inputs() {
    const auto t0 = Clock::now();
    mech::collective(comm_, [&] {
      if (rank_ != 0) return;
      root_ = std::make_unique<Root>();
      Root& R = *root_;
      // Every problem of the case file at once: the reader's and the solver libraries' own checks.
      ErrorList errors;
      R.cs = read_case_file(o_.case_file, errors);
      mech::check_solver_section(R.cs, errors);
      contact::check_fault_section(R.cs, errors);
      errors.throw_if_any();
      R.mesh = read_msh(o_.mesh);
      set_.faulted = R.mesh.count(ElementType::Prism) > 0 ? 1 : 0;
      if (faulted()) {
        log(1, fmt::format("mesh: {} nodes, {} tetrahedra, {} interface elements", R.mesh.num_nodes(),
                           R.mesh.count(ElementType::Tetrahedron), R.mesh.count(ElementType::Prism)));
        R.model = mech::build_model(R.mesh, R.cs, true);
        R.fm = build_faults(R.mesh, R.cs, R.model, [&](int level, const std::string& s) {
          if (level > 0) log(level, s);
          else log_later(level, s);
        });
      } else {
        log(1, fmt::format("mesh: {} nodes, {} tetrahedra", R.mesh.num_nodes(), R.mesh.count(ElementType::Tetrahedron)));
        R.model = mech::build_model(R.mesh, R.cs);
        if (!R.cs.faults.empty())
          log_later(-1, fmt::format("{}: [[fault]] entries are ignored by the continuous model", R.cs.path));
      }
      R.caprock = std::make_unique<CaprockCheck>(R.model, R.mesh, R.cs);
      set_.caprock = R.caprock->empty() ? 0 : 1;
      if (caprock())
        log(1, fmt::format("caprock: {} element(s) of {} seal material(s) checked at every step", R.caprock->size(),
                           R.cs.seals.size()));
      R.history = std::make_unique<mech::PressureHistory>(o_.pressure, R.mesh, R.model);
      log(1, fmt::format("pressure: {} file(s), {} dates, {} of {} elements under a pressure change", o_.pressure.size(),
                         R.history->steps().size(), R.history->forced_cells(), R.model.tets.size()));
      for (const auto& d : R.cs.output_dates) R.history->add_step(d, R.cs.path + ": [output] dates");
      if (guarded()) {
        if (!R.cs.scenario_reference_date.empty()) {
          R.history->add_step(R.cs.scenario_reference_date, R.cs.path + ": [scenario] reference_date");
          set_.ref_time = static_cast<double>(*parse_iso_date(R.cs.scenario_reference_date));
        } else {
          set_.ref_time = R.history->steps().front().time;
        }
        if (faulted())
          set_.fault_solver = static_cast<int>(o_.faults.solver.value_or(*lookup(fault_solver_names(), R.cs.fault_solver)));
        set_.scale = o_.faults.scale.value_or(R.cs.scenario_scale);
        set_.search = o_.faults.find_safe_scale ? 1 : 0;
        set_.max_scale = R.cs.scenario_max_scale;
        set_.scale_tolerance = R.cs.scenario_tolerance;
      } else if (o_.faults.find_safe_scale) {
        throw InputError(o_.case_file, "--find-safe-scale: nothing to keep safe (the mesh has no fault and the case no [[seal]])");
      }
      set_.linear = static_cast<int>(o_.linear.value_or(*lookup(linear_solver_names(), R.cs.linear_solver)));
      set_.partition = static_cast<int>(o_.partition);
      set_.tolerance = o_.tolerance.value_or(R.cs.newton_tolerance);
      set_.total_load = o_.tolerance_of.value_or(R.cs.tolerance_of) == "total-load" ? 1 : 0;
      set_.max_newton = R.cs.max_newton_iterations;
      set_.max_substeps = R.cs.max_substeps;
      set_.reuse = R.cs.reuse_preconditioner ? 1 : 0;
      if (o_.steps && *o_.steps != "every-date" && R.cs.inversion_rule != "sigma-max")
        throw InputError("--steps", fmt::format("{} needs inversion_rule = \"sigma-max\" ({} has \"{}\": the other "
                                                "rules depend on the whole path)", *o_.steps, R.cs.path, R.cs.inversion_rule));
      if (R.model.top_nodes.empty()) log_later(-1, "the mesh has no bnd:top group: no top-surface table is written");
      if (o_.restart) {
        R.restart = mech::read_state(*o_.restart, R.mesh, R.restart_date, R.restart_time);
        if (faulted()) {
          if (set_.search && R.restart_time >= set_.ref_time)
            throw InputError(*o_.restart, fmt::format("the state is of {}, not before the [scenario] reference date: the "
                                                      "safe-scale search reruns from the reference date, so the run must "
                                                      "pass it", R.restart_date));
          R.restart_faults = read_fault_state(fault_state_path(*o_.restart), R.fm, R.restart_date);
        }
        log_later(0, fmt::format("restarting from {} ({})", *o_.restart, R.restart_date));
      }
    });
    MPI_Bcast(&set_, sizeof(Shared), MPI_BYTE, 0, comm_);
    sum_.seconds_read = since(t0);
  }

  // 2. The step plan: dates, output dates and checkpoints.
  void plan() {
    // Collective: the plan reads and checks the pressure history, and whatever rank 0 throws here
    // must not leave the other ranks waiting in the broadcast below.
    mech::collective(comm_, [&] {
      if (rank_ != 0) return;
      const Root& R = *root_;
      StepRule rule;
      rule.after = R.restart_time;
      if (o_.until) rule.until = *o_.until;
      rule.checkpoint_every = o_.checkpoint_every.value_or(R.cs.checkpoint_every);
      const std::string steps = o_.steps.value_or(R.cs.steps);
      rule.turning_points = steps == "turning-points" || steps == "turning-windows";
      rule.fewest = steps == "turning-windows";
      rule.every_date_in = o_.every_date_in;
      rule.turning_tolerance = R.cs.turning_point_tolerance;
      if (faulted()) rule.turning_rule = mech::TurningRule::Extremes;
      if (set_.search) rule.must_take.insert(set_.ref_time);  // the search reruns from the state there
      steps_ = plan_steps(*root_->history, R.cs, rule);
      // Every pressure step the run will read, checked before any note is printed (those the plan
      // read for its turning points are not read again).
      root_->history->check_steps(steps_.times.empty() ? -std::numeric_limits<double>::infinity() : steps_.times.back());
      if (rule.turning_points) {
        log(1, fmt::format("turning-point steps: {} of {} dates ({}, output dates, {}the last date)", steps_.size(),
                           steps_.dates_in_run,
                           rule.fewest ? "the fewest dates within the tolerance of every turn of the pressure"
                           : faulted() ? "every low and high of the pressure: the faults answer both"
                                       : "turning points of the pressure",
                           rule.every_date_in.empty() ? "" : "every date in the --every-date-in windows, "));
        // Every output date is a step; the other dates skipped are missing from the per-step outputs
        // (an InSAR comparison would interpolate across them): say so once.
        if (steps_.size() < steps_.dates_in_run)
          log_later(-1, fmt::format("{}: steps = \"{}\": {} of the {} pressure dates are not stepped on and are "
                                    "missing from the top-surface series{}; list the dates you need in [output] dates, or "
                                    "set [solver] steps = \"every-date\"",
                                    R.cs.path, steps, steps_.dates_in_run - steps_.size(), steps_.dates_in_run,
                                    R.cs.output_dates.empty() ? " and the results" : ""));
      }
    });
    broadcast(comm_, steps_);
    first_after_ = steps_.size();
    for (std::size_t i = 0; i < steps_.size(); ++i)
      if (steps_.times[i] > set_.ref_time) {
        first_after_ = i;
        break;
      }
  }

  // 3. The distributed solver (with the fault contact on a faulted mesh), restored on a restart.
  void make_solver() {
    const auto t0 = Clock::now();
    mech::SolverOptions sopt;
    sopt.linear = static_cast<mech::LinearSolver>(set_.linear);
    sopt.partition = static_cast<mech::PartitionMethod>(set_.partition);
    sopt.tolerance = set_.tolerance;
    sopt.tolerance_of_total_load = set_.total_load != 0;
    sopt.max_newton = set_.max_newton;
    sopt.max_substeps = set_.max_substeps;
    sopt.reuse_preconditioner = set_.reuse != 0;
    solver_ = std::make_unique<mech::MechanicsSolver>(comm_, rank_ == 0 ? &root_->model : nullptr, sopt);
    if (faulted()) {
      contact::ContactOptions copt;
      copt.solver = static_cast<contact::SaddleSolver>(set_.fault_solver);
      copt.reuse_preconditioner = sopt.reuse_preconditioner;
      contact_ = std::make_unique<contact::FaultContact>(comm_, rank_ == 0 ? &root_->fm : nullptr, copt);
      solver_->set_coupling(*contact_);
      log(1, fmt::format("{} nodes ({} on rank 0), {} cells; faults: {}", solver_->global_nodes(), solver_->local_nodes(),
                         solver_->global_cells(), contact_->description()));
    } else {
      log(1, fmt::format("{} nodes ({} on rank 0), {} cells; {}", solver_->global_nodes(), solver_->local_nodes(),
                         solver_->global_cells(), solver_->solver_description()));
    }
    if (o_.restart) {
      solver_->restore_state(rank_ == 0 ? root_->restart : mech::SavedState{});
      if (contact_) contact_->restore_gathered(rank_ == 0 ? root_->restart_faults : contact::FaultContact::Snapshot{});
    }
    sum_.seconds_setup = since(t0);
  }

  // 4. The output set (rank 0), then the notes held back until now.
  void open_outputs() {
    const auto t0 = Clock::now();
    mech::collective(comm_, [&] {
      if (rank_ != 0) return;
      Root& R = *root_;
      R.out = std::make_unique<OutputSet>(o_, R.mesh, R.model, R.cs, faulted() ? &R.fm : nullptr);
      cell_fields_ = R.out->cell_fields();
      if (caprock()) {
        const std::vector<std::string> c{"ugs-solve caprock integrity per seal material and step: the smallest tensile margin "
                                         "(fracture pressure S3 + T0 minus the pore pressure) and Mohr-Coulomb shear margin "
                                         "of its elements (docs/caprock.md)",
                                         o_.command_line};
        R.caprock_out = std::make_unique<CaprockOutput>(o_.caprock_fields.value_or(""), o_.caprock_table.value_or(""),
                                                        *R.caprock, c);
      }
      release_distributed(R);
      if (guarded()) {
        R.ref_cell = R.history->cell_dp(set_.ref_time);
        R.ref_node = R.history->node_dp(set_.ref_time);
      }
    });
    // Every rank gathers the cell fields of an output date with rank 0, one at a time.
    int nf = static_cast<int>(cell_fields_.size());
    MPI_Bcast(&nf, 1, MPI_INT, 0, comm_);
    std::vector<int> fields(nf);
    for (int k = 0; k < nf && rank_ == 0; ++k) fields[k] = static_cast<int>(cell_fields_[k]);
    MPI_Bcast(fields.data(), nf, MPI_INT, 0, comm_);
    cell_fields_.clear();
    for (int f : fields) cell_fields_.push_back(static_cast<mech::CellField>(f));
    sum_.seconds_setup += since(t0);
    for (const auto& [level, text] : deferred_) log(level, text);
    if (steps_.size() == 0) log(-1, "no steps after the restart date: nothing to solve");
  }

  // The pressure change of step i at scale s (rank 0): per element, and per node where the faults
  // (per node pair, handed to the contact) or the seals need it. Collective.
  struct Load {
    std::vector<double> cell, node;
  };
  Load load(std::size_t i, double s) {
    Load l;
    std::vector<double> pair;
    mech::collective(comm_, [&] {
      if (rank_ != 0) return;
      Root& R = *root_;
      l.cell = R.history->cell_dp(steps_.times[i]);
      if (!guarded()) return;
      l.node = R.history->node_dp(steps_.times[i]);
      if (steps_.times[i] > set_.ref_time && s != 1.0) {
        scale_about(l.cell, R.ref_cell, s);
        scale_about(l.node, R.ref_node, s);
      }
      if (faulted()) pair = pair_dp(R.fm, l.node);
    });
    if (contact_) contact_->set_pressure_change(pair);
    return l;
  }

  // The seals' check of the step just solved (rank 0 returns it; empty without seals). Collective.
  CaprockStep check_caprock(const Load& l) {
    CaprockStep st;
    if (!caprock()) return st;
    std::vector<double> stress = solver_->gather_cell_field(mech::CellField::Stress);
    mech::collective(comm_, [&] {
      if (rank_ == 0) st = root_->caprock->evaluate(stress, l.cell, l.node);
    });
    return st;
  }

  // The state at the reference date, for the safe-scale search's reruns.
  void keep_reference_state() {
    mech::SavedState st = solver_->gather_state();
    if (rank_ == 0) root_->snapshot = std::move(st);
    if (contact_) contact_snapshot_ = contact_->save();
    have_snapshot_ = true;
  }

  // Writes the restart state of the solver (and the faults) as of `date`. Collective.
  // One field at a time, each gathered only when written: rank 0 never holds the whole state (its
  // peak on the 1.49M-dof box was this gather).
  void save_state(const std::string& date, double time) {
    std::vector<double> u = solver_->gather_displacement();
    contact::FaultContact::Snapshot fs;
    if (contact_) fs = contact_->gather_snapshot();
    std::unique_ptr<mech::StateFileWriter> w;
    mech::collective(comm_, [&] {
      // The results (open_outputs) hold the same mesh and cell types: their stored arrays are copied.
      if (rank_ == 0) w = std::make_unique<mech::StateFileWriter>(*o_.state, root_->out->results(), date, time, std::move(u));
    });
    for (const mech::StateField f : mech::kStateFields) {
      std::vector<double> v = solver_->gather_state_field(f);
      mech::collective(comm_, [&] {
        if (rank_ == 0) w->add(f, std::move(v));
      });
    }
    mech::collective(comm_, [&] {
      if (rank_ != 0) return;
      w->commit();
      if (faulted()) write_fault_state(fault_state_path(*o_.state), root_->fm, date, time, fs);
    });
  }

  // 5. March over the steps at the case's scale, writing everything.
  void march() {
    const std::size_t n = steps_.size();
    std::string last_good_date = rank_ == 0 ? root_->restart_date : "";
    mech::broadcast(comm_, last_good_date);  // every rank must agree on whether to gather a state below
    double last_good_time = rank_ == 0 ? root_->restart_time : 0;
    if (set_.search && first_after_ == 0) keep_reference_state();  // the reference is the state before the first step
    for (std::size_t i = 0; i < n; ++i) {
      const std::string& date = steps_.dates[i];
      const double time = steps_.times[i];
      const std::string label = fmt::format("step {}/{} ({})", i + 1, n, date);
      const Load dp = load(i, set_.scale);
      contact::ContactStats before;
      if (contact_) before = contact_->stats();
      const mech::StepReport rep = solver_->advance(dp.cell, label);
      sum_.seconds_solve += rep.seconds;
      sum_.newton_iterations += rep.newton_iterations;
      sum_.linear_iterations += rep.linear_iterations;
      sum_.preconditioner_setups += rep.preconditioner_setups;
      sum_.substeps += rep.substeps;
      if (!rep.converged) {
        // The solver kept the state of the previous step: that is the last good one.
        std::string saved;
        if (last_good_date.empty() || !o_.state) {
          saved = !o_.state ? "; no state saved (none asked for)" : "; no state saved (the first step failed)";
        } else {
          save_state(last_good_date, last_good_time);
          saved = fmt::format("; last good state ({}) saved to {}: a restart resumes from it", last_good_date, *o_.state);
        }
        throw ComputeError(rep.failure + saved);
      }
      // Nothing is solved after the last step (the safe-scale search would rerun steps): its
      // output is gathered and written without the matrix and the preconditioner.
      if (i + 1 == n && !set_.search && !faulted()) solver_->release_linear_system();
      const auto to = Clock::now();
      const std::vector<double> u = solver_->gather_displacement();
      contact::PairResults pr;
      if (contact_) pr = contact_->gather();
      const CaprockStep cap = check_caprock(dp);
      std::string note;
      mech::collective(comm_, [&] {
        if (rank_ != 0) return;
        Root& R = *root_;
        Watch& watch = time > set_.ref_time ? base_ : before_;
        if (faulted()) {
          const contact::FaultFields ff = contact::derive_fault_fields(R.fm, pr);
          watch.see(R.fm, ff, date);
          note = "; " + fault_step_note(R.fm, ff);
          R.out->faults()->add(date, time, ff, steps_.output[i], steps_.output[i] || o_.faults.pairs_every_step);
        }
        if (caprock()) {
          watch.see(cap, date);
          note += fmt::format("; seals: tensile margin {:.3f} MPa, shear margin {:.3f} MPa", cap.tensile.margin_Pa * 1e-6,
                              cap.shear.margin_Pa * 1e-6);
          if (R.caprock_out) R.caprock_out->add(date, time, cap, steps_.output[i]);
        }
        R.out->write_step(date, time, u, steps_.output[i], *R.history);
      });
      if (steps_.output[i])
        for (const mech::CellField f : cell_fields_) {
          std::vector<double> v = solver_->gather_cell_field(f);
          mech::collective(comm_, [&] {
            if (rank_ == 0) root_->out->add_cell_field(f, std::move(v));
          });
        }
      if (o_.state && (steps_.checkpoint[i] || i + 1 == n)) save_state(date, time);
      log(1, fmt::format("{}: {} Newton iteration{}, {} linear iterations, {} sub-step{}{}, {:.2f} s{}{}", label,
                         rep.newton_iterations, rep.newton_iterations == 1 ? "" : "s", rep.linear_iterations, rep.substeps,
                         rep.substeps == 1 ? "" : "s",
                         contact_ ? fmt::format(", {} contact state changes", contact_->stats().state_changes - before.state_changes)
                                  : "",
                         rep.seconds,
                         rep.off_branch > 0 ? fmt::format(" (held elements off their branch: {:.1e})", rep.off_branch) : "",
                         note));
      if (!rep.substep_reason.empty())
        log(1, fmt::format("{}: split into {} sub-steps: {}", label, rep.substeps, rep.substep_reason));
      if (set_.search && !have_snapshot_ && i + 1 == first_after_) keep_reference_state();
      last_good_date = date;
      last_good_time = time;
      sum_.seconds_output += since(to);
      ++sum_.steps;
      if (rank_ == 0 && o_.progress) o_.progress(i + 1, n);
    }
    int cb = before_.critical ? 1 : 0;  // (before_ is rank 0's)
    MPI_Bcast(&cb, 1, MPI_INT, 0, comm_);
    critical_before_ = cb != 0;
  }

  // One trial of the search: the steps after the reference date rerun at scale s.
  Watch trial(double s, CsvWriter* table) {
    solver_->restore_state(rank_ == 0 ? root_->snapshot : mech::SavedState{});
    if (contact_) contact_->restore(contact_snapshot_);
    Watch w;
    std::string note;
    for (std::size_t i = first_after_; i < steps_.size(); ++i) {
      const Load dp = load(i, s);
      if (rank_ == 0)
        for (double v : dp.cell) w.dp_max = std::max(w.dp_max, v), w.dp_min = std::min(w.dp_min, v);
      const mech::StepReport rep = solver_->advance(dp.cell, fmt::format("scale {:.4g}, {}", s, steps_.dates[i]));
      sum_.newton_iterations += rep.newton_iterations;
      sum_.linear_iterations += rep.linear_iterations;
      if (!rep.converged) {
        // Newton fails only where faults slip widely: count it as critical.
        note = "Newton failed: " + rep.failure;
        if (rank_ == 0 && !w.critical) {
          w.critical = true, w.date = steps_.dates[i];
          if (faulted()) w.limiter = Limiter::FaultChi, w.max_chi = std::max(w.max_chi, 1.0);
        }
        break;
      }
      contact::PairResults pr;
      if (contact_) pr = contact_->gather();
      const CaprockStep cap = check_caprock(dp);
      if (rank_ == 0) {
        if (faulted()) w.see(root_->fm, contact::derive_fault_fields(root_->fm, pr), steps_.dates[i]);
        if (caprock()) w.see(cap, steps_.dates[i]);
      }
    }
    int c = w.critical ? 1 : 0;
    MPI_Bcast(&c, 1, MPI_INT, 0, comm_);
    w.critical = c != 0;
    mech::collective(comm_, [&] {
      if (rank_ == 0) scenario_row(*table, s, w, note);
    });
    std::string seen = faulted() ? fmt::format("max chi {:.4f}", w.max_chi) : "";
    if (caprock())
      seen += fmt::format("{}smallest seal margins {:.3f} MPa (tensile), {:.3f} MPa (shear)", seen.empty() ? "" : ", ",
                          w.min_tensile_margin * 1e-6, w.min_shear_margin * 1e-6);
    log(0, fmt::format("scale {:.4g}: {}{}", s, seen, w.critical ? fmt::format(" — critical: {} on {}", failure_text(w), w.date) : ""));
    return w;
  }

  // What failed in a critical trial, for the log ("Newton failed" when nothing did before Newton).
  static std::string failure_text(const Watch& w) { return w.what().empty() ? "Newton failed" : w.what(); }

  // One row of the search's table (rank 0): the trial at scale s and what it saw.
  void scenario_row(CsvWriter& table, double s, const Watch& w, const std::string& note) const {
    table.number(s, 6).number(w.max_chi, 6).integer(w.critical ? 1 : 0).text(w.fault).text(w.date);
    table.number(w.at[0], 2).number(w.at[1], 2).number(w.at[2], 2);
    table.number(w.dp_max * 1e-6, 4).number(w.dp_min * 1e-6, 4);
    table.text(limiter_text(w.limiter)).text(w.seal);
    if (caprock()) table.number(w.min_tensile_margin * 1e-6, 4).number(w.min_shear_margin * 1e-6, 4);
    else table.text("").text("");
    table.text(note).end_row();
  }

  // 6. The safe-scale search (faulted runs that ask for it): reruns from the reference state.
  void find_safe_scale() {
    if (!set_.search) return;
    sum_.searched = true;
    if (!have_snapshot_ || first_after_ >= steps_.size())
      throw InputError(rank_ == 0 ? root_->cs.path : "case", "[scenario] reference_date: no step after it to scale");
    std::unique_ptr<CsvWriter> table;
    mech::collective(comm_, [&] {
      if (rank_ != 0) return;
      const std::vector<std::string> c{"ugs-solve safe-scale search: dp_s(t) = dp(t_ref) + scale (dp(t) - dp(t_ref)) after the "
                                       "reference date; critical = some fault patch reaches chi = 1 or a seal element fails "
                                       "(limiter: what failed first; margins: the smallest of the seals over the trial)",
                                       o_.command_line};
      table = std::make_unique<CsvWriter>(
          o_.faults.scenario_table,
          std::vector<std::string>{"scale", "max_chi", "critical", "fault", "date", "x_m", "y_m", "z_m", "dp_max_MPa",
                                   "dp_min_MPa", "limiter", "seal", "min_tensile_margin_MPa", "min_shear_margin_MPa", "note"},
          c);
    });
    if (critical_before_) {
      sum_.critical_before = true;
      std::string what;
      mech::collective(comm_, [&] {
        if (rank_ != 0) return;
        what = fmt::format("{} on {}", before_.what(), before_.date);
        // One row, the base run's: critical before any scaling (its pressure extremes are not tracked: 0).
        scenario_row(*table, set_.scale, before_, "before or at the reference date: no scale of the later swing is safe");
      });
      log(-1, fmt::format("{} (before or at the reference date): no scale of the later swing is safe", what));
    } else {
      const SafeScale safe = search_safe_scale(set_.max_scale, set_.scale_tolerance, [&](double s) { return trial(s, table.get()); });
      if (safe.found)
        log(0, fmt::format("maximum safe scale {:.4g} (critical at {:.4g}: {} on {} at ({:.0f}, "
                           "{:.0f}, {:.0f})); the pressure change then peaks at {:+.3f} MPa / {:+.3f} MPa",
                           safe.safe, safe.critical, failure_text(safe.first), safe.first.date, safe.first.at[0],
                           safe.first.at[1], safe.first.at[2], safe.peak_dp_max * 1e-6, safe.peak_dp_min * 1e-6));
      else
        log(0, fmt::format("no {} up to scale {:.4g} (max_scale)",
                           faulted() && caprock() ? "fault patch reaches chi = 1 and no seal fails"
                           : faulted()            ? "fault patch reaches chi = 1"
                                                  : "seal fails",
                           safe.safe));
      sum_.safe = safe;
    }
    mech::collective(comm_, [&] {
      if (rank_ == 0) table->commit();
    });
  }

  // 7. Commit (rename into place) only now: a failed run leaves no results behind.
  void commit() {
    mech::collective(comm_, [&] {
      if (rank_ != 0) return;
      for (const auto& n : root_->history->notes()) log(-1, n);
      root_->out->commit();
      if (root_->caprock_out) root_->caprock_out->commit();
    });
    if (contact_) {
      const contact::ContactStats& cst = contact_->stats();
      log(1, fmt::format("faults: {} saddle-point solves, {} linear iterations, {} preconditioner setups, {:.2f} s in the contact "
                         "solver", cst.solves, cst.linear_iterations, cst.preconditioner_setups, cst.seconds));
    }
  }
};

}  // namespace

RunSummary run(MPI_Comm comm, const RunSettings& settings) { return Run(comm, settings)(); }

}  // namespace ugs::driver
