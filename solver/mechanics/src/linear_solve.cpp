// The linear solves of the Newton iterations: Krylov method, preconditioner, its reuse (solver_impl.hpp,
// docs/mechanics.md).
#include "solver_impl.hpp"

namespace ugs::mech {

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
      if (lm.size > 1) throw InputError("--solver", "cholmod runs on one process; use mumps under mpirun");
      set_krylov();
      UGS_PETSC(PCSetType(pc, PCCHOLESKY));
      UGS_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERCHOLMOD));
      break;
  }
  UGS_PETSC(KSPSetTolerances(ksp, 1e-9, 1e-300, PETSC_DEFAULT, 5000));
  UGS_PETSC(KSPSetFromOptions(ksp));
}

void MechanicsSolver::Impl::assemble_symmetric_p() {
  std::vector<double> pv = vals_lin;
  for (std::size_t h = 0; h < hyp_cells.size(); ++h)
    scatter(pv, hyp_cells[h], fem::tet4_stiffness(geo[hyp_cells[h]], fem::symmetric_tangent(lm.materials[lm.cell_material[hyp_cells[h]]], trial[h])), false);
  set_constrained_diagonal(pv);
  if (!P) {
    UGS_PETSC(MatCreate(lm.comm, &P));
    const PetscInt m = 3 * lm.n_owned;
    UGS_PETSC(MatSetSizes(P, m, m, PETSC_DETERMINE, PETSC_DETERMINE));
    UGS_PETSC(MatSetType(P, MATSEQAIJ));
    UGS_PETSC(MatSeqAIJSetPreallocationCSR(P, rowptr.data(), cols.data(), pv.data()));
    UGS_PETSC(MatSetOption(P, MAT_SYMMETRIC, PETSC_TRUE));
    UGS_PETSC(MatSetOption(P, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
    UGS_PETSC(MatSetOption(P, MAT_SPD, PETSC_TRUE));
  } else {
    for (PetscInt i = 0; i < 3 * lm.n_owned; ++i)
      UGS_PETSC(MatSetValues(P, 1, &i, rowptr[i + 1] - rowptr[i], cols.data() + rowptr[i], pv.data() + rowptr[i],
                             INSERT_VALUES));
    UGS_PETSC(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
    UGS_PETSC(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  }
}

void MechanicsSolver::Impl::rebuild_pc() {
  if (pc_valid) refresh_basis();
  pc_phase = assembled_phase;
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
  UGS_PETSC(KSPSetTolerances(ksp, rtol, abstol, dtol, maxit > 0 ? std::min(maxit, user_maxit_) : user_maxit_));
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

MechanicsSolver::Impl::SolveResult MechanicsSolver::Impl::timed_solve(double rtol, bool guess, PetscInt maxit, bool fresh) {
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  if (fresh) {
    UGS_PETSC(KSPSetUp(ksp));
    setup_seconds = std::chrono::duration<double>(clock::now() - t0).count();
    t0 = clock::now();
  }
  const SolveResult s = solve_once(rtol, guess, maxit);
  seconds_per_iteration = std::chrono::duration<double>(clock::now() - t0).count() / std::max(s.iterations, 1);
  // Every rank must take the same keep-or-refactor decision (the setup is collective): the
  // slowest rank's times decide.
  double t[2] = {setup_seconds, seconds_per_iteration}, tmax[2];
  MPI_Allreduce(t, tmax, 2, MPI_DOUBLE, MPI_MAX, lm.comm);
  setup_seconds = tmax[0];
  seconds_per_iteration = tmax[1];
  return s;
}

MechanicsSolver::Impl::SolveResult MechanicsSolver::Impl::solve(double rtol, bool guess) {
  if (user_maxit_ < 0) {
    PetscReal a, b, c;
    UGS_PETSC(KSPGetTolerances(ksp, &a, &b, &c, &user_maxit_));
  }
  bool fresh = !pc_valid;
  const char* why = fresh ? "first" : "";
  if (!pc_valid) rebuild_pc();
  if (mat_changed) {
    // A factorization is kept while the iterations it costs beyond a fresh one, over the next
    // kFactorHorizon solves, take less time than refactoring (both measured: a refactor costs
    // tens of solves); a multigrid hierarchy while it stays near its first rate and few
    // elements changed branch (a setup costs a few cycles).
    const double excess = (last_ipd - baseline_ipd) * last_decades * seconds_per_iteration * kFactorHorizon;
    const bool rate_ok = factored() ? excess <= setup_seconds : last_ipd <= std::max(1.5 * baseline_ipd, baseline_ipd + 3.0);
    const bool keep = rate_ok && (factored() || !branches_moved());
    const bool reuse = pc_valid && opt.reuse_preconditioner && keep;
    if (reuse) UGS_PETSC(KSPSetReusePreconditioner(ksp, PETSC_TRUE));
    else rebuild_pc();
    if (!reuse && !fresh) why = !opt.reuse_preconditioner ? "always" : !rate_ok ? "rate" : "branches";
    fresh = !reuse;
    mat_changed = false;
  }
  // A reused preconditioner gets a budget; if it cannot make it, rebuild and solve again.
  const double decades = std::log10(1.0 / std::max(rtol, 1e-16));
  const PetscInt budget = fresh ? -1
                          : factored() ? static_cast<PetscInt>(std::ceil(2 * kFactorIpd * decades))
                                       : static_cast<PetscInt>(std::max(100.0, 4 * baseline_ipd * decades));
  SolveResult s = timed_solve(rtol, guess, budget, fresh);
  int its_total = s.iterations;
  if (!fresh && s.reason < 0) {
    rebuild_pc();
    fresh = true;
    why = "budget";
    s = timed_solve(rtol, false, -1, fresh);
    its_total += s.iterations;
  }
  s.setup = why;
  last_decades = std::max(std::log10(1.0 / std::max(s.reduction, 1e-300)), 0.3);
  last_ipd = s.iterations / last_decades;
  if (fresh) baseline_ipd = last_ipd;
  s.iterations = its_total;
  if (fresh) ++pc_setups;
  pc_valid = true;
  zero_fixed(du);  // prescribed components stay exactly at their values (an AMG correction may touch them)
  return s;
}

}  // namespace ugs::mech
