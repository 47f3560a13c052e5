// The linear solves of the Newton iterations: Krylov method, preconditioner, its reuse (solver_impl.hpp,
// docs/mechanics.md).
#include "solver_impl.hpp"
#include "ugs/mechanics/petsc_session.hpp"
#include "ugs/mechanics/reuse_rule.hpp"

namespace ugs::mech {

bool keep_factorization(double baseline_ipd, double last_ipd, double last_decades, double refactor_iterations,
                        double horizon) {
  return (last_ipd - baseline_ipd) * last_decades * horizon <= refactor_iterations;
}

double counted_decades(double reduction) { return std::max(std::log10(1.0 / std::max(reduction, 1e-300)), 0.3); }

int factor_budget(double rtol) {
  const double decades = std::log10(1.0 / std::max(rtol, 1e-16));
  return static_cast<int>(std::ceil(2 * kFactorIterationsPerDecade * decades));
}

bool keep_multigrid(double baseline_ipd, double last_ipd) {
  return last_ipd <= std::max(1.5 * baseline_ipd, baseline_ipd + 3.0);
}

void MechanicsSolver::Impl::set_default_options(std::initializer_list<std::pair<const char*, const char*>> defaults) {
  for (const auto& [k, v] : defaults) {
    PetscBool has = PETSC_FALSE;
    UGS_PETSC(PetscOptionsHasName(nullptr, nullptr, k, &has));
    if (!has) UGS_PETSC(PetscOptionsSetValue(nullptr, k, v));
  }
}

void MechanicsSolver::Impl::set_krylov() {
  if (has_hyp) {
    UGS_PETSC(KSPSetType(ksp, KSPGMRES));
    UGS_PETSC(KSPGMRESSetRestart(ksp, 100));
    UGS_PETSC(KSPGMRESSetOrthogonalization(ksp, KSPGMRESModifiedGramSchmidtOrthogonalization));
    UGS_PETSC(KSPSetPCSide(ksp, PC_RIGHT));
  } else {
    UGS_PETSC(KSPSetType(ksp, KSPCG));
  }
  UGS_PETSC(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED));
}

void MechanicsSolver::Impl::setup_ksp() {
  UGS_PETSC(KSPCreate(lm.comm, &ksp));
  PC pc;
  UGS_PETSC(KSPGetPC(ksp, &pc));
  switch (opt.linear) {
    case LinearSolver::CgGamg:
      set_krylov();
      UGS_PETSC(PCSetType(pc, PCGAMG));
      UGS_PETSC(PCGAMGSetReuseInterpolation(pc, PETSC_TRUE));
      // Smoothed aggregation with the rigid-body near-null space (set on the matrix); CG
      // eigenvalue estimates for the Chebyshev smoothers when the operator is SPD.
      set_default_options({{"-mg_levels_esteig_ksp_type", has_hyp ? "gmres" : "cg"}});
      break;
    case LinearSolver::CgHypre: {
      set_krylov();
      UGS_PETSC(PCSetType(pc, PCHYPRE));
      UGS_PETSC(PCHYPRESetType(pc, "boomeramg"));
      // BoomerAMG for 3D elasticity on layered meshes (docs/mechanics.md, measured on the
      // thesis-like box): nodal coarsening of the 3 x 3 blocks, HMIS with extended+i
      // interpolation capped at 4 entries, aggressive coarsening on the first two levels. (Vector
      // interpolation with the rigid-body modes tripled the operator complexity there.)
      set_default_options({{"-pc_hypre_boomeramg_nodal_coarsen", "6"},
                           {"-pc_hypre_boomeramg_coarsen_type", "HMIS"},
                           {"-pc_hypre_boomeramg_interp_type", "ext+i"},
                           {"-pc_hypre_boomeramg_P_max", "4"},
                           {"-pc_hypre_boomeramg_agg_nl", "2"},
                           {"-pc_hypre_boomeramg_strong_threshold", "0.5"},
                           // One forward Gauss-Seidel sweep down, one backward up: the cycle stays
                           // symmetric (CG) at half the smoothing work of symmetric sweeps both ways.
                           {"-pc_hypre_boomeramg_relax_type_down", "SOR/Jacobi"},
                           {"-pc_hypre_boomeramg_relax_type_up", "backward-SOR/Jacobi"}});
      break;
    }
    case LinearSolver::Mumps:
      set_krylov();
      UGS_PETSC(PCSetType(pc, has_hyp ? PCLU : PCCHOLESKY));
      UGS_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
      break;
    case LinearSolver::Cholmod:
      if (lm.size > 1) throw InputError("linear solver", "cholmod runs on one process; use mumps under mpirun");
      set_krylov();
      UGS_PETSC(PCSetType(pc, PCCHOLESKY));
      UGS_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERCHOLMOD));
      break;
  }
  UGS_PETSC(KSPSetTolerances(ksp, 1e-9, 1e-300, PETSC_DEFAULT, 5000));
  UGS_PETSC(KSPSetFromOptions(ksp));
}

bool MechanicsSolver::Impl::hypre_owns_matrix() const {
  // The fault coupling reads A's rows as AIJ; GAMG and CHOLMOD (hypo-plastic) precondition with a
  // copy P of A or of its symmetric form.
  if (coupling || separate_p()) return false;
  // -ugs_aij_matrix (after "--"): a PETSc AIJ matrix that PCHYPRE converts at each setup (until
  // 2026-11-27 for hypo-plastic models; kept to compare the two and for the tests).
  if (petsc_option_given("-ugs_aij_matrix")) return false;
  PC pc;
  UGS_PETSC(KSPGetPC(ksp, &pc));
  PetscBool is_hypre = PETSC_FALSE;
  UGS_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCHYPRE, &is_hypre));
  return is_hypre == PETSC_TRUE;
}

void MechanicsSolver::Impl::assemble_symmetric_p() {
  std::vector<double> pv = assembler.vals_lin;
  for (std::size_t h = 0; h < hyp.cells.size(); ++h)
    scatter(pv, hyp.cells[h], fem::tet4_stiffness(geo[hyp.cells[h]], fem::symmetric_tangent(lm.materials[lm.cell_material[hyp.cells[h]]], hyp.trial[h])), false);
  set_constrained_diagonal(pv);
  if (!P) {
    UGS_PETSC(MatCreate(lm.comm, &P));
    const PetscInt m = 3 * lm.n_owned;
    UGS_PETSC(MatSetSizes(P, m, m, PETSC_DETERMINE, PETSC_DETERMINE));
    UGS_PETSC(MatSetType(P, MATSEQAIJ));
    UGS_PETSC(MatSeqAIJSetPreallocationCSR(P, assembler.rowptr.data(), assembler.cols.data(), pv.data()));
    UGS_PETSC(MatSetOption(P, MAT_SYMMETRIC, PETSC_TRUE));
    UGS_PETSC(MatSetOption(P, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
    UGS_PETSC(MatSetOption(P, MAT_SPD, PETSC_TRUE));
  } else {
    for (PetscInt i = 0; i < 3 * lm.n_owned; ++i)
      UGS_PETSC(MatSetValues(P, 1, &i, assembler.rowptr[i + 1] - assembler.rowptr[i], assembler.cols.data() + assembler.rowptr[i], pv.data() + assembler.rowptr[i],
                             INSERT_VALUES));
    UGS_PETSC(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
    UGS_PETSC(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  }
}

void MechanicsSolver::Impl::rebuild_pc() {
  if (reuse.valid) newton.predictor.refresh(A);
  reuse.phase = assembler.assembled_phase;
  if (separate_p()) {
    if (opt.linear == LinearSolver::Cholmod) assemble_symmetric_p();
    else if (!P) UGS_PETSC(MatDuplicate(A, MAT_COPY_VALUES, &P));
    else UGS_PETSC(MatCopy(A, P, SAME_NONZERO_PATTERN));
    UGS_PETSC(KSPSetOperators(ksp, A, P));
  }
  UGS_PETSC(KSPSetReusePreconditioner(ksp, PETSC_FALSE));
}

MechanicsSolver::Impl::SolveResult MechanicsSolver::Impl::solve_once(double rtol, bool guess, PetscInt maxit) {
  PetscReal old_rtol, abstol, dtol;
  PetscInt user_maxit;
  UGS_PETSC(KSPGetTolerances(ksp, &old_rtol, &abstol, &dtol, &user_maxit));
  UGS_PETSC(KSPSetTolerances(ksp, rtol, abstol, dtol, maxit > 0 ? std::min(maxit, reuse.user_maxit) : reuse.user_maxit));
  PetscReal bnorm = 0;
  UGS_PETSC(VecNorm(r, NORM_2, &bnorm));
  UGS_PETSC(KSPSetInitialGuessNonzero(ksp, guess ? PETSC_TRUE : PETSC_FALSE));
  UGS_PETSC(KSPSolve(ksp, r, du));
  SolveResult s;
  PetscInt its = 0;
  UGS_PETSC(KSPGetIterationNumber(ksp, &its));
  UGS_PETSC(KSPGetConvergedReason(ksp, &s.reason));
  s.iterations = static_cast<int>(its);
  PetscReal rnorm = 0;
  UGS_PETSC(KSPGetResidualNorm(ksp, &rnorm));
  s.reduction = bnorm > 0 ? rnorm / bnorm : 0;
  return s;
}

bool PreconditionerReuse::rate_ok(bool factored) const {
  // A factorization is kept while the iterations it costs beyond a fresh one, over the next
  // kFactorHorizon solves, stay within what refactoring costs in solve iterations (measured once,
  // reuse_rule.hpp); a multigrid hierarchy while it stays near its first rate (and, solve(), few
  // elements changed branch: a setup costs a few cycles). Counts only, never measured time: the decision
  // changes the numbers, and they must not depend on the machine's load.
  return factored ? keep_factorization(baseline_ipd, last_ipd, last_decades, kRefactorIterations, kFactorHorizon)
                  : keep_multigrid(baseline_ipd, last_ipd);
}

PetscInt PreconditionerReuse::budget(bool factored, double rtol) const {
  if (factored) return factor_budget(rtol);
  const double decades = std::log10(1.0 / std::max(rtol, 1e-16));
  return static_cast<PetscInt>(std::max(100.0, 4 * baseline_ipd * decades));
}

void PreconditionerReuse::record(int iterations, double reduction, bool fresh) {
  last_decades = counted_decades(reduction);
  last_ipd = iterations / last_decades;
  if (fresh) baseline_ipd = last_ipd, ++setups;
  valid = true;
}

MechanicsSolver::Impl::SolveResult MechanicsSolver::Impl::solve(double rtol, bool guess) {
  if (reuse.user_maxit < 0) {
    PetscReal a, b, c;
    UGS_PETSC(KSPGetTolerances(ksp, &a, &b, &c, &reuse.user_maxit));
  }
  bool fresh = !reuse.valid;
  const char* why = fresh ? "first" : "";
  if (!reuse.valid) rebuild_pc();
  if (assembler.mat_changed) {
    const bool rate_ok = reuse.rate_ok(factored());
    const bool keep = reuse.valid && opt.reuse_preconditioner && rate_ok && (factored() || !branches_moved());
    if (keep) UGS_PETSC(KSPSetReusePreconditioner(ksp, PETSC_TRUE));
    else rebuild_pc();
    if (!keep && !fresh) why = !opt.reuse_preconditioner ? "always" : !rate_ok ? "rate" : "branches";
    fresh = !keep;
    assembler.mat_changed = false;
  }
  // A reused preconditioner gets a budget; if it cannot make it, rebuild and solve again.
  const PetscInt budget = fresh ? -1 : reuse.budget(factored(), rtol);
  if (fresh) UGS_PETSC(KSPSetUp(ksp));
  SolveResult s = solve_once(rtol, guess, budget);
  int its_total = s.iterations;
  if (!fresh && s.reason < 0) {
    rebuild_pc();
    fresh = true;
    why = "budget";
    UGS_PETSC(KSPSetUp(ksp));
    s = solve_once(rtol, false, -1);
    its_total += s.iterations;
  }
  s.setup = why;
  reuse.record(s.iterations, s.reduction, fresh);
  s.iterations = its_total;
  zero_fixed(du);  // prescribed components stay exactly at their values (an AMG correction may touch them)
  return s;
}

}  // namespace ugs::mech
