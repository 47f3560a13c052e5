// One load step: sub-stepping, each sub-step solved by Newton (newton.cpp), and the commit of its
// state (solver_impl.hpp, docs/mechanics.md).
#include "solver_impl.hpp"

namespace ugs::mech {

void MechanicsSolver::Impl::commit(const std::vector<double>& dp_target) {
  for (std::size_t h = 0; h < hyp.cells.size(); ++h) {
    const double d = dp_target[hyp.cells[h]] - dp_cell[hyp.cells[h]];
    if (d != 0) hyp.last_ddp[h] = d < 0 ? -1 : +1;
    hyp.committed[h].eps = hyp.trial_eps[h];
    hyp.committed[h].dsig = hyp.trial[h].dsig;
    hyp.committed[h].hypo = hyp.trial[h].hypo;
    hyp.committed_phase[h] = hyp.trial[h].phase;
    hyp.committed_c[h] = hyp.trial[h].c_tangent;
  }
  dp_cell = dp_target;
}

void MechanicsSolver::Impl::remember_increment_from(Vec base) {
  if (!assembler.mat_created) return;  // (no matrix yet: the step had no load)
  // With a coupling the saddle point predicts its own first iterate (the contact library's
  // SaddleGuess) and this basis is never used: three products with K and 48 vectors of the size
  // of u (0.63 GB over both processes at the thesis scale) spared.
  if (coupling) return;
  Vec v;
  UGS_PETSC(VecDuplicate(u, &v));
  UGS_PETSC(VecWAXPY(v, -1.0, base, u));
  zero_fixed(v);  // prescribed components do not move: keep the basis in the free space
  newton.predictor.remember(A, v);
}

void MechanicsSolver::Impl::restore_u() {
  UGS_PETSC(VecCopy(u_save, u));
  UGS_PETSC(VecGhostUpdateBegin(u, INSERT_VALUES, SCATTER_FORWARD));
  UGS_PETSC(VecGhostUpdateEnd(u, INSERT_VALUES, SCATTER_FORWARD));
}

StepReport MechanicsSolver::Impl::advance(const std::vector<double>& dp_rank0, const std::string& label) {
  const auto t0 = std::chrono::steady_clock::now();
  StepReport rep;
  rep.substeps = 0;
  // Every rank needs the pressure change of its elements.
  std::vector<double> dp_all;
  std::uint64_t n = lm.rank == 0 ? dp_rank0.size() : 0;
  MPI_Bcast(&n, 1, MPI_UINT64_T, 0, lm.comm);
  if (n != static_cast<std::uint64_t>(lm.n_global_cells))
    throw std::logic_error("MechanicsSolver::advance: pressure vector of wrong size");
  dp_all.resize(n);
  if (lm.rank == 0) std::copy(dp_rank0.begin(), dp_rank0.end(), dp_all.begin());
  MPI_Bcast(dp_all.data(), static_cast<int>(n), MPI_DOUBLE, 0, lm.comm);
  std::vector<double> target(lm.n_cells());
  for (std::size_t c = 0; c < lm.n_cells(); ++c) target[c] = dp_all[lm.cell_index[c]];
  dp_all = {};

  // A failed step leaves the state of the previous one (committed sub-steps are undone). The start
  // of the step is copied only when the step is split: until a sub-step short of the end (b < 1)
  // commits, the committed state is the start (a commit at b = 1 ends the step). Most steps are
  // not split, and the copies (pressure changes of the cells, the hypo-plastic elements' committed
  // states: ~130 bytes an element) would live through all their solves, the peak of the process.
  std::vector<double> start, dp_b;
  std::vector<fem::PointState> committed_start;
  std::vector<fem::LoadingPhase> phase_start;
  std::vector<double> c_start;
  std::vector<std::int8_t> last_ddp_start;  // the direction of the next step's first tangent
  bool saved = false;
  UGS_PETSC(VecCopy(u, u_step));
  if (coupling) coupling->begin_step();
  double done = 0, h = 1;
  const double h_min = 1.0 / opt.max_substeps;
  while (done < 1) {
    const double b = std::min(1.0, done + h);
    if (b < 1) {
      if (start.empty()) start = dp_cell;  // (no commit yet: dp_cell is the start)
      dp_b.resize(lm.n_cells());
      for (std::size_t k = 0; k < dp_b.size(); ++k) dp_b[k] = start[k] + b * (target[k] - start[k]);
    }
    const std::vector<double>& dp = b < 1 ? dp_b : target;
    std::string why;
    if (coupling) coupling->begin_substep(b);
    if (newton.iterate(dp, rep, why)) {
      if (coupling) coupling->commit();
      if (b < 1 && !saved) {
        committed_start = hyp.committed;
        phase_start = hyp.committed_phase;
        c_start = hyp.committed_c;
        last_ddp_start = hyp.last_ddp;
        saved = true;
      }
      commit(dp);
      remember_increment_from(u_save);
      done = b;
      ++rep.substeps;
      continue;
    }
    restore_u();
    if (coupling) coupling->revert_substep();
    if (rep.substep_reason.empty())
      rep.substep_reason = fmt::format("{} (relative residuals {})", why, history_text(rep.residuals));
    if (h / 2 < h_min * (1 - 1e-12) || (!has_hyp && !coupling)) {
      if (coupling) coupling->revert_step();
      if (saved) {
        hyp.committed = std::move(committed_start);
        hyp.committed_phase = std::move(phase_start);
        hyp.committed_c = std::move(c_start);
        hyp.last_ddp = std::move(last_ddp_start);
        dp_cell = std::move(start);
      }
      UGS_PETSC(VecCopy(u_step, u));
      UGS_PETSC(VecGhostUpdateBegin(u, INSERT_VALUES, SCATTER_FORWARD));
      UGS_PETSC(VecGhostUpdateEnd(u, INSERT_VALUES, SCATTER_FORWARD));
      rep.converged = false;
      rep.failure = fmt::format("{}: {} (relative residuals {}){}", label, why, history_text(rep.residuals),
                                h < 1 ? fmt::format("; sub-step of 1/{:.0f} of the step", 1 / h) : "");
      rep.seconds = seconds_since(t0);
      return rep;
    }
    h /= 2;
  }
  rep.converged = true;
  rep.seconds = seconds_since(t0);
  return rep;
}

}  // namespace ugs::mech
