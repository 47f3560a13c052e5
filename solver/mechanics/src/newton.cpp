// Newton: the iteration of one (sub-)step with the knee holds (solver_impl.hpp, docs/mechanics.md).
#include "solver_impl.hpp"
#include "ugs/mechanics/petsc_session.hpp"

namespace ugs::mech {
namespace {

// -ugs_newton_monitor: every Newton iteration (linear tolerance and iterations, residual, the
// elements on each branch and held at the knee).
bool newton_monitor() {
  static const bool on = petsc_option_given("-ugs_newton_monitor");
  return on;
}

// The accuracy of the corrections: PETSc's -ugs_inexact_newton or -ugs_exact_newton (after "--" on
// ugs-solve's command line) override the solver options' choice.
Corrections corrections_in_use(Corrections chosen) {
  static const bool inexact = petsc_option_given("-ugs_inexact_newton"), exact = petsc_option_given("-ugs_exact_newton");
  return inexact ? Corrections::EisenstatWalker : exact ? Corrections::Exact : chosen;
}

}  // namespace

bool Newton::iterate(const std::vector<double>& dp_target, StepReport& rep, std::string& why) {
  const SolverOptions& opt = in_.opt;
  const LocalMesh& lm = in_.lm;
  Coupling* const coupling = in_.coupling;
  const bool has_hyp = in_.has_hyp;
  HypoStateStore& hyp = out_.hyp;
  const Vec u = out_.u, du = out_.du;
  op_.external_force(dp_target);
  first_tangents(dp_target);
  UGS_PETSC(VecCopy(u, out_.u_save));
  rep.residuals.clear();
  const double r0 = op_.residual();
  rep.residuals.push_back(1.0);
  if (r0 == 0) return true;
  // What the tolerance is relative to: the step's own unbalanced force (its load increment), or
  // the whole load at the step's date when that is larger (a monthly storage step then needs no
  // more digits than the total displacement can show).
  const double total = opt.tolerance_of_total_load ? op_.load_norm() : 0.0;
  const double ref = std::max(r0, total);
  double rk = r0, rprev = r0;
  double eta = step_is_nonlinear() || coupling ? 1e-4 : 0.0;
  // With a coupling (faults) the default stays exact: there eta is set by the contact even on a
  // linear storage month, bounded corrections took a second Newton iteration on it, and the field
  // split keeps its hierarchy only after one-solve steps (bench/faulted, thesis scale: storage
  // months 2.7 s exact, 11-12 s bounded).
  const Corrections chosen = coupling && opt.corrections == Corrections::Bounded ? Corrections::Exact : opt.corrections;
  const Corrections corrections = has_hyp ? corrections_in_use(chosen) : Corrections::EisenstatWalker;
  for (int k = 1; k <= opt.max_newton; ++k) {
    op_.assemble();
    const double rtol = correction_rtol(corrections, eta, ref, rk);
    const int setups_before = in_.reuse.setups;
    const bool guess = !coupling && k == 1 && predictor.predict(in_.A, in_.r, du);
    LinearSolveResult s;
    if (coupling) {
      const CouplingSolve cs = coupling->solve(in_.A, in_.r, du, rtol);
      s.iterations = cs.iterations;
      if (!cs.ok) {
        why = cs.failure + coupling->diagnosis();
        return false;
      }
    } else {
      s = op_.solve(rtol, guess);
    }
    rep.linear_iterations += s.iterations;
    rep.preconditioner_setups += in_.reuse.setups - setups_before;
    ++rep.newton_iterations;
    if (s.reason < 0 && !(s.reason == KSP_DIVERGED_ITS && s.reduction < 0.5)) {
      why = fmt::format("linear solver failed ({}) after {} iterations", KSPConvergedReasons[s.reason], s.iterations);
      return false;
    }
    UGS_PETSC(VecAXPY(u, 1.0, du));
    rprev = rk;
    std::vector<int> before(hyp.cells.size());
    for (std::size_t h = 0; h < hyp.cells.size(); ++h) before[h] = static_cast<int>(hyp.trial[h].phase);
    rk = op_.residual();
    track_branches(k);
    long long moved = 0, moved_all = 0;
    for (std::size_t h = 0; h < hyp.cells.size(); ++h) moved += tangent_moved(h, before[h]);
    MPI_Allreduce(&moved, &moved_all, 1, MPI_LONG_LONG, MPI_SUM, lm.comm);
    if (newton_monitor()) {
      long long c[4] = {0, 0, 0, 0};  // owned elements: virgin, unloading, reloading, held
      for (std::size_t h = 0; h < hyp.cells.size(); ++h) {
        if (!lm.cell_owned[hyp.cells[h]]) continue;
        c[0] += hyp.trial[h].phase == fem::LoadingPhase::Virgin;
        c[1] += hyp.trial[h].phase == fem::LoadingPhase::Unloading;
        c[2] += hyp.trial[h].phase == fem::LoadingPhase::Reloading;
        c[3] += hyp.hold[h] != fem::Hold::None;
      }
      MPI_Allreduce(MPI_IN_PLACE, c, 4, MPI_LONG_LONG, MPI_SUM, lm.comm);
      // The predictor (first iteration): the residual its prediction left, relative to r_0.
      const double predicted = predictor.predicted();
      const std::string pred = k != 1 || coupling || predicted < 0 ? ""
                               : std::isfinite(predicted)          ? fmt::format(", predictor {:.3e}", predicted)
                                                                   : std::string(", predictor dropped");
      UGS_PETSC(PetscPrintf(lm.comm,
                            "  Newton %d: linear rtol %.1e%s, %d iterations%s%s; residual %.3e; branch changes %lld (virgin "
                            "%lld, unloading %lld, reloading %lld), held %lld\n",
                            k, rtol, pred.c_str(), static_cast<int>(s.iterations), *s.setup ? ", preconditioner set up: " : "",
                            s.setup, rk / r0, moved_all, c[0], c[1], c[2], c[3]));
    }
    rep.residuals.push_back(rk / r0);
    if (!std::isfinite(rk)) {
      why = "the residual is not finite";
      if (coupling) why += coupling->diagnosis();  // which faults and node pairs
      return false;
    }
    if (converged(rk, ref)) {
      rep.off_branch = std::max(rep.off_branch, held_off_branch() / r0);
      return true;
    }
    if (rk > 1e4 * r0) {
      why = "Newton diverged";
      if (coupling) why += coupling->diagnosis();
      return false;
    }
    if (coupling) {
      why = coupling->stalled();
      if (!why.empty()) return false;
    }
    eta = next_forcing(eta, rk, rprev, moved_all);
  }
  int sat = hyp.saturated ? 1 : 0, any_sat = 0;
  MPI_Allreduce(&sat, &any_sat, 1, MPI_INT, MPI_MAX, lm.comm);
  why = fmt::format("Newton did not converge in {} iterations{}", opt.max_newton,
                    any_sat ? " (the virgin compressibility law cannot absorb the strain of some elements)" : "");
  if (coupling) why += coupling->diagnosis();
  return false;
}

void Newton::first_tangents(const std::vector<double>& dp_target) {
  HypoStateStore& hyp = out_.hyp;
  for (std::size_t h = 0; h < hyp.cells.size(); ++h) {
    // First tangent: the element keeps its direction unless its pressure change reverses.
    const double d = dp_target[hyp.cells[h]] - in_.dp_cell[hyp.cells[h]];
    const int sd = d < 0 ? -1 : d > 0 ? +1 : 0, dir = hyp.committed[h].hypo.direction;
    hyp.guess[h] = static_cast<std::int8_t>(sd != 0 && sd != hyp.last_ddp[h] ? -dir : dir);
    hyp.piece[h] = 0;
    hyp.flips[h] = 0;
    hyp.hold[h] = fem::Hold::None;
  }
}

bool Newton::step_is_nonlinear() const {
  const HypoStateStore& hyp = out_.hyp;
  const LocalMesh& lm = in_.lm;
  // A step is nonlinear if an element is on the virgin branch or is expected to change direction
  // (under sigma-max only a change from virgin loading: unloading and reloading share one stiffness).
  int nonlinear = 0;
  for (std::size_t h = 0; h < hyp.cells.size() && !nonlinear; ++h) {
    const fem::InversionRule rule = lm.materials[lm.cell_material[hyp.cells[h]]].hypo.rule;
    nonlinear = (hyp.guess[h] != hyp.committed[h].hypo.direction &&
                 (rule != fem::InversionRule::SigmaMax || hyp.committed_phase[h] == fem::LoadingPhase::Virgin)) ||
                (hyp.guess[h] > 0 && hyp.start_sigma(static_cast<int>(h), in_.s0) >= hyp.committed[h].hypo.sigma_max * (1 - 1e-9)) ||
                rule == fem::InversionRule::StressDependent;
  }
  int any_nonlinear = 0;
  MPI_Allreduce(&nonlinear, &any_nonlinear, 1, MPI_INT, MPI_MAX, lm.comm);
  return any_nonlinear != 0;
}

double Newton::correction_rtol(Corrections corrections, double eta, double r0, double rk) const {
  const SolverOptions& opt = in_.opt;
  // Inexact Newton (Eisenstat-Walker): no sharper than the nonlinearity warrants, but never
  // looser than what reaches the target in one more iteration of a linear problem. With
  // hypo-plastic elements, which elements are held at their knee, and on which side, is decided
  // on the iterates, and the converged state depends on it (the response there is set-valued):
  // with Eisenstat-Walker alone MUMPS and BoomerAMG corrections gave answers 2.6e-2 of max |u|
  // apart on tests/fault_mechanics/test_locked_history. So no correction may leave more than
  // kCorrectionBound x tolerance x r_0: the iterates, the held set and the answer are then those
  // of an exact Newton within the tolerance, whatever the linear solver, its preconditioner
  // reuse or the predictor (docs/mechanics.md "Newton corrections"); a coupling (faults) asks for
  // exact corrections by default (iterate), -ugs_inexact_newton aside.
  const double target_rtol = 0.5 * opt.tolerance * r0 / rk;
  double rtol = std::max(target_rtol, eta);
  if (corrections == Corrections::Exact) rtol = target_rtol;
  if (corrections == Corrections::Bounded) rtol = std::max(target_rtol, std::min(eta, kCorrectionBound * opt.tolerance * r0 / rk));
  return std::min(0.5, rtol);
}

bool Newton::converged(double rk, double r0) const {
  return rk <= in_.opt.tolerance * r0 && (!in_.coupling || in_.coupling->settled());
}

double Newton::next_forcing(double eta, double rk, double rprev, long long moved_all) const {
  if (in_.has_hyp || in_.coupling) eta = std::min(0.1, 0.9 * (rk / rprev) * (rk / rprev));
  // While elements still change branch the next residual is set by them, not by the accuracy
  // of the linear solve: a sharper solve would be wasted.
  if (moved_all > 0) eta = std::max(eta, 1e-2);
  return eta;
}

bool Newton::tangent_moved(std::size_t h, int phase_before) const {
  const HypoStateStore& hyp = out_.hyp;
  return tangent_differs(in_.lm.materials[in_.lm.cell_material[hyp.cells[h]]].hypo.rule, phase_before,
                         static_cast<int>(hyp.trial[h].phase));
}

void Newton::track_branches(int k) {
  HypoStateStore& hyp = out_.hyp;
  const int enough = k >= kHoldOnFirstChangeFrom ? 1 : 2;
  for (std::size_t h = 0; h < hyp.cells.size(); ++h) {
    const auto p = static_cast<std::int8_t>(hyp.trial[h].phase);
    if (hyp.piece[h] != 0 && p != hyp.piece[h] && ++hyp.flips[h] >= enough && hyp.hold[h] == fem::Hold::None) {
      hyp.hold[h] = fem::Hold::UnloadReload;
      hyp.hold_dir[h] = static_cast<std::int8_t>(hyp.trial[h].J > 0 ? +1 : hyp.trial[h].J < 0 ? -1 : hyp.guess[h]);
    }
    hyp.piece[h] = p;
  }
}

double Newton::held_off_branch() const {
  const HypoStateStore& hyp = out_.hyp;
  const LocalMesh& lm = in_.lm;
  double mine = 0;
  for (std::size_t h = 0; h < hyp.cells.size(); ++h) {
    if (hyp.hold[h] == fem::Hold::None) continue;
    const double delta = hyp.trial[h].J - hyp.trial[h].J_knee;
    const bool wrong = delta > 0;  // held on unloading/reloading, ended beyond the knee
    if (!wrong) continue;
    const int c = hyp.cells[h];
    if (lm.cell_owned[c]) {
      const fem::Material& m = lm.materials[lm.cell_material[c]];
      Vec6 ds;
      for (int i = 0; i < 6; ++i) ds[i] = delta * m.Dhat[6 * i + ZZ] * 1e6 / hyp.trial[h].c_tangent;
      double fe[12] = {};
      fem::tet4_add_internal_force(in_.geo[c], ds, fe);
      double n2 = 0;
      for (double f : fe) n2 += f * f;
      mine += std::sqrt(n2);
    }
  }
  double all = 0;
  MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_SUM, lm.comm);
  return all;
}

}  // namespace ugs::mech
