#include "saddle_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include <fmt/format.h>
#include <petscksp.h>
// PetscObjectStateGet (an advanced-level function PETSc declares with its object internals): K's
// state tells whether its values changed since the last solve.
#include <petsc/private/petscimpl.h>

#include "petsc_call.hpp"
#include "ugs/contact/dof_mask.hpp"
#include "ugs/formats/error.hpp"

#define CHK UGS_CONTACT_PETSC

namespace ugs::contact::detail {
namespace {

bool has_option(const char* name) {
  PetscBool has = PETSC_FALSE;
  CHK(PetscOptionsHasName(nullptr, nullptr, name, &has));
  return has == PETSC_TRUE;
}

void default_option(const char* name, const char* value) {
  if (!has_option(name)) CHK(PetscOptionsSetValue(nullptr, name, value));
}


// MUMPS' own code behind a failed factorisation or solve, for the failure line: INFOG(1) and
// INFOG(2) of the MUMPS factor of the KSP's preconditioner or of a field-split block's (MUMPS
// user's guide, "Error diagnostics"); "" when there is no MUMPS factor or it reports no error.
// Read before reset(), which destroys the factor; probing errors are ignored (the failure stands).
std::string mumps_infog(KSP ksp) {
  PC pc = nullptr;
  PCType type = nullptr;
  if (KSPGetPC(ksp, &pc) || PCGetType(pc, &type) || !type) return "";
  if (!std::strcmp(type, PCFIELDSPLIT)) {
    PetscInt n = 0;
    KSP* sub = nullptr;
    if (PCFieldSplitGetSubKSP(pc, &n, &sub)) return "";
    std::string note;
    for (PetscInt i = 0; i < n && note.empty(); ++i) note = mumps_infog(sub[i]);
    PetscFree(sub);
    return note;
  }
  if (std::strcmp(type, PCLU) && std::strcmp(type, PCCHOLESKY)) return "";
  Mat f = nullptr;
  MatSolverType solver = nullptr;
  if (PCFactorGetMatrix(pc, &f) || !f || MatFactorGetSolverType(f, &solver) || !solver || std::strcmp(solver, MATSOLVERMUMPS))
    return "";
  PetscInt i1 = 0, i2 = 0;
  if (MatMumpsGetInfog(f, 1, &i1) || MatMumpsGetInfog(f, 2, &i2) || i1 >= 0) return "";
  const char* what = "see the MUMPS user's guide";
  switch (i1) {
    case -3: what = "solve called without a valid factorisation"; break;
    case -5: case -7: case -13: what = "out of memory"; break;
    case -6: what = "structurally singular matrix, INFOG(2) = its structural rank"; break;
    case -8: case -9: case -11: case -14: case -15: case -17: case -20:
      what = "workspace too small (raise -contact_mat_mumps_icntl_14)"; break;
    case -10: what = "numerically singular matrix"; break;
  }
  return fmt::format(" (MUMPS INFOG(1) = {}: {}; INFOG(2) = {})", i1, what, i2);
}

}  // namespace

SaddlePointSolver::~SaddlePointSolver() {
  if (ksp_) KSPDestroy(&ksp_);
  for (Mat* a : {&WB_, &G_, &Kg_, &J_, &Jaij_})
    if (*a) MatDestroy(a);
  for (Vec* v : {&rhs_, &sol_, &wr_})
    if (*v) VecDestroy(v);
}

void SaddlePointSolver::setup(const mech::CouplingContext& c, const PairDistribution& pd, const SaddleSystem& sys,
                              ContactOptions& opt) {
  comm_ = c.comm;
  n_owned_ = c.n_owned;
  opt_ = &opt;
  const PetscInt n3 = 3 * c.n_owned, m3 = 3 * pd.m;
  CHK(VecCreateMPI(comm_, n3 + m3, PETSC_DETERMINE, &rhs_));
  CHK(VecDuplicate(rhs_, &sol_));
  CHK(VecDuplicate(sys.dl, &wr_));

  // The linear solver (-contact_augmentation overrides the augmentation of the field split).
  {
    PetscReal g = opt.augmentation;
    PetscBool set = PETSC_FALSE;
    CHK(PetscOptionsGetReal(nullptr, nullptr, "-contact_augmentation", &g, &set));
    if (set) opt.augmentation = g;
  }
  const double unknowns = 3.0 * static_cast<double>(c.n_global_nodes) + 3.0 * static_cast<double>(pd.M);
  kind_ = opt.solver;
  if (kind_ == SaddleSolver::Auto) kind_ = unknowns <= static_cast<double>(opt.direct_limit) ? SaddleSolver::Mumps : SaddleSolver::FieldSplit;
  CHK(KSPCreate(comm_, &ksp_));
  CHK(KSPSetOptionsPrefix(ksp_, "contact_"));
  PC pc;
  CHK(KSPGetPC(ksp_, &pc));
  if (kind_ == SaddleSolver::Mumps) {
    // GMRES on the current matrix, preconditioned by its factors or by kept ones (FactorReuse):
    // with fresh factors one iteration, as a direct solve; right preconditioning, so that the
    // tolerance applies to the true residual.
    CHK(KSPSetType(ksp_, KSPGMRES));
    CHK(KSPGMRESSetRestart(ksp_, 100));
    CHK(KSPSetPCSide(ksp_, PC_RIGHT));
    CHK(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED));
    CHK(PCSetType(pc, PCLU));
    CHK(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
    // Extra workspace: pivoting on the multiplier rows fills more than MUMPS' estimate.
    default_option("-contact_mat_mumps_icntl_14", "60");
  } else {
    CHK(KSPSetType(ksp_, KSPFGMRES));
    // Restart 30: FGMRES keeps two vectors of the whole system per iteration (6.3 MB each per
    // process at the thesis scale), allocated as the iterations go; with restart 200 a 66-iteration
    // solve of a production month held 830 MB of them per process. Restarted at 30 the coarsened
    // history (COARSEN=2) takes 214 instead of 213 iterations in its first six production months
    // and 170 instead of 167 in the storage half-cycle (2026-11-27).
    CHK(KSPGMRESSetRestart(ksp_, 30));
    CHK(PCSetType(pc, PCFIELDSPLIT));
    CHK(PCFieldSplitSetType(pc, PC_COMPOSITE_SCHUR));
    // Upper block-triangular: one multigrid cycle per iteration (full: two, for ~20 % fewer iterations).
    CHK(PCFieldSplitSetSchurFactType(pc, PC_FIELDSPLIT_SCHUR_FACT_UPPER));
    CHK(PCFieldSplitSetSchurPre(pc, PC_FIELDSPLIT_SCHUR_PRE_SELFP, nullptr));
    default_option("-contact_fieldsplit_u_ksp_type", "preonly");
    // GAMG on the displacement block, whatever the continuous solver: the faster here
    // (docs/fault-mechanics.md). BoomerAMG is one PETSc option away
    // (-contact_fieldsplit_u_pc_type hypre), with these settings: variant 3 of the vector
    // interpolation (as the continuous solver uses) crashes inside BoomerAMG on this block
    // (hypre 2.26, hypre_BoomerAMG_LNExpandInterp); variant 2 works.
    default_option("-contact_fieldsplit_u_pc_type", "gamg");
    default_option("-contact_fieldsplit_u_pc_hypre_type", "boomeramg");
    default_option("-contact_fieldsplit_u_pc_hypre_boomeramg_nodal_coarsen", "6");
    default_option("-contact_fieldsplit_u_pc_hypre_boomeramg_vec_interp_variant", "2");
    default_option("-contact_fieldsplit_u_pc_hypre_boomeramg_strong_threshold", "0.5");
    default_option("-contact_fieldsplit_lambda_ksp_type", "preonly");
    default_option("-contact_fieldsplit_lambda_pc_type", "bjacobi");
  }
  CHK(KSPSetTolerances(ksp_, 1e-9, 1e-300, PETSC_DEFAULT, 2000));
}

// Augmented Lagrangian for the field split: rows that are pure constraints (no multiplier
// coefficient) are added to the displacement rows with weight gamma / A_q, turning the twin
// constraints into springs of stiffness gamma k A_q in the (0,0) block: K_gamma = K + C W B.
void SaddlePointSolver::active_set(const PairDistribution& pd, const std::vector<PairEquations>& eq) {
  const int m = pd.m;
  signature_.assign(3 * m, 0.0);
  for (int q = 0; q < m; ++q)
    for (int j = 0; j < 3; ++j) {
      const auto& e = eq[q];
      const bool constraint = e.Jl[3 * j] == 0 && e.Jl[3 * j + 1] == 0 && e.Jl[3 * j + 2] == 0 &&
                              (e.Jg[3 * j] != 0 || e.Jg[3 * j + 1] != 0 || e.Jg[3 * j + 2] != 0);
      if (constraint) signature_[3 * q + j] = opt_->augmentation / pd.pairs[q].area;
    }
}

void SaddlePointSolver::augment(Mat A, const PairDistribution& pd, SaddleSystem& sys, PetscScalar* rl, bool same_operator) {
  const int m = pd.m;
  const std::vector<double>& wdiag = signature_;
  PetscScalar* a = nullptr;
  if (!same_operator || !Kg_) {  // (kept: K_gamma holds K + C W B of these values already)
    CHK(VecGetArray(wr_, &a));
    for (int i = 0; i < 3 * m; ++i) a[i] = wdiag[i];
    CHK(VecRestoreArray(wr_, &a));
    if (!WB_) CHK(MatDuplicate(sys.B, MAT_COPY_VALUES, &WB_));
    else CHK(MatCopy(sys.B, WB_, SAME_NONZERO_PATTERN));
    CHK(MatDiagonalScale(WB_, wr_, nullptr));
    if (!G_) CHK(MatMatMult(sys.C, WB_, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &G_));
    else CHK(MatMatMult(sys.C, WB_, MAT_REUSE_MATRIX, PETSC_DEFAULT, &G_));
    if (!Kg_) {
      CHK(MatDuplicate(A, MAT_COPY_VALUES, &Kg_));
      CHK(MatAXPY(Kg_, 1.0, G_, DIFFERENT_NONZERO_PATTERN));
      MatNullSpace nsp = nullptr;
      CHK(MatGetNearNullSpace(A, &nsp));
      if (nsp) CHK(MatSetNearNullSpace(Kg_, nsp));
    } else if (!kg_sum_.sum(A, G_, Kg_)) {
      CHK(MatCopy(A, Kg_, SUBSET_NONZERO_PATTERN));
      CHK(MatAXPY(Kg_, 1.0, G_, SUBSET_NONZERO_PATTERN));
    }
  }
  // Right-hand side: r_u += C W r_lambda.
  CHK(VecGetArray(wr_, &a));
  for (int i = 0; i < 3 * m; ++i) a[i] = wdiag[i] * rl[i];
  CHK(VecRestoreArray(wr_, &a));
}

mech::CouplingSolve SaddlePointSolver::solve(Mat A, Vec r, Vec du, double rtol, const PairDistribution& pd, SaddleSystem& sys,
                                             const std::vector<PairEquations>& eq, const std::vector<std::uint8_t>& owned_fixed,
                                             std::vector<std::array<double, 3>>& lam, ContactStats& stats) {
  const int m = pd.m;
  const PetscInt n3 = 3 * n_owned_;
  // Right-hand side [r; -F].
  PetscScalar* b = nullptr;
  const PetscScalar* ra = nullptr;
  CHK(VecGetArray(rhs_, &b));
  CHK(VecGetArrayRead(r, &ra));
  std::copy(ra, ra + n3, b);
  CHK(VecRestoreArrayRead(r, &ra));
  for (int q = 0; q < m; ++q)
    for (int j = 0; j < 3; ++j) b[n3 + 3 * q + j] = -eq[q].F[j];
  active_set(pd, eq);
  const bool same_operator = kind_ == SaddleSolver::FieldSplit && operator_unchanged(A, eq);
  if (kind_ == SaddleSolver::FieldSplit) {
    augment(A, pd, sys, b + n3, same_operator);
    CHK(VecRestoreArray(rhs_, &b));
    CHK(MatMult(sys.C, wr_, sys.fc));  // C W r_lambda
    CHK(VecGetArray(rhs_, &b));
    const PetscScalar* f = nullptr;
    CHK(VecGetArrayRead(sys.fc, &f));
    for (PetscInt i = 0; i < n3; ++i)
      if (f[i] != 0) b[i] += f[i];
    CHK(VecRestoreArrayRead(sys.fc, &f));
  }
  CHK(VecRestoreArray(rhs_, &b));
  mech::CouplingSolve out;
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  PetscInt its = 0;
  // A failed factorisation or solve (MUMPS: a zero pivot, too little workspace; PETSc errors
  // inside the KSP) is a failed Newton iteration, not the end of the run: the caller restores the
  // state and retries with a smaller sub-step. PETSc keeps a MUMPS instance whose factorisation
  // failed (a retry skips the factorisation and calls the solve phase: INFOG(1)=-3), so the
  // KSP is reset and the next solve starts from a fresh analysis.
  try {
    its = linear_solve(A, rtol, same_operator, sys, stats, reason);
  } catch (const ComputeError& e) {
    const std::string mumps = mumps_infog(ksp_);
    reset();
    out.ok = false;
    out.failure = fmt::format("the saddle-point solver ({}) failed: {}{}", name(), e.what(), mumps);
    return out;
  }
  out.iterations = static_cast<int>(its);
  if (reason < 0) {
    const std::string mumps = mumps_infog(ksp_);
    reset();
    out.ok = false;
    out.failure = fmt::format("the saddle-point solver ({}) failed: {}{} after {} iterations", name(), KSPConvergedReasons[reason],
                              mumps, its);
    return out;
  }
  // du (zero on prescribed components) and lambda += dlambda.
  const PetscScalar* x = nullptr;
  PetscScalar* d = nullptr;
  CHK(VecGetArrayRead(sol_, &x));
  CHK(VecGetArray(du, &d));
  for (int a = 0; a < n_owned_; ++a)
    for (int k = 0; k < 3; ++k) d[3 * a + k] = is_fixed(owned_fixed[a], k) ? 0.0 : x[3 * a + k];
  CHK(VecRestoreArray(du, &d));
  for (int q = 0; q < m; ++q)
    for (int j = 0; j < 3; ++j) lam[q][j] += x[n3 + 3 * q + j];
  CHK(VecRestoreArrayRead(sol_, &x));
  return out;
}

bool SaddlePointSolver::operator_unchanged(Mat A, const std::vector<PairEquations>& eq) {
  PetscObjectState state = 0;
  PetscObjectId id = 0;  // (unique per object: a matrix created anew at the same address differs)
  CHK(PetscObjectStateGet(reinterpret_cast<PetscObject>(A), &state));
  CHK(PetscObjectGetId(reinterpret_cast<PetscObject>(A), &id));
  std::vector<double> derivatives;
  derivatives.reserve(18 * eq.size());
  for (const PairEquations& e : eq) {
    derivatives.insert(derivatives.end(), e.Jl.begin(), e.Jl.end());
    derivatives.insert(derivatives.end(), e.Jg.begin(), e.Jg.end());
  }
  auto same_bits = [](const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
  };
  int same = have_last_ && id == last_A_id_ && state == last_A_state_ && same_bits(signature_, last_signature_) &&
             same_bits(derivatives, last_derivatives_);
  have_last_ = true;
  last_A_id_ = id;
  last_A_state_ = state;
  last_signature_ = signature_;
  last_derivatives_ = std::move(derivatives);
  if (MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_INT, MPI_MIN, comm_) != MPI_SUCCESS)
    throw ComputeError("MPI_Allreduce failed in the saddle-point solver");
  return same != 0;
}

void SaddlePointSolver::reset() {
  CHK(KSPReset(ksp_));
  have_last_ = false;  // the next solve's guess multiplies afresh
  for (Mat* a : {&J_, &Jaij_})
    if (*a) CHK(MatDestroy(a));
  A_seen_ = nullptr;
  configured_ = false;
  blocks_kept_ = false;  // KSPReset destroyed the blocks' solvers
  reuse_.drop();
  factors_.drop();
}

void SaddlePointSolver::keep_blocks(bool keep) {
  if (keep == blocks_kept_) return;
  PC pc;
  CHK(KSPGetPC(ksp_, &pc));
  PetscInt n = 0;
  KSP* sub = nullptr;
  CHK(PCFieldSplitGetSubKSP(pc, &n, &sub));
  for (PetscInt i = 0; i < n; ++i) {
    PC block;
    CHK(KSPGetPC(sub[i], &block));
    CHK(PCSetReusePreconditioner(block, keep ? PETSC_TRUE : PETSC_FALSE));
  }
  CHK(PetscFree(sub));
  blocks_kept_ = keep;
}

PetscInt SaddlePointSolver::linear_solve(Mat A, double rtol, bool same_operator, SaddleSystem& sys, ContactStats& stats,
                                         KSPConvergedReason& reason) {
  const bool iterative = kind_ == SaddleSolver::FieldSplit;
  Mat op = nullptr;
  if (!J_ || A != A_seen_) {
    if (J_) CHK(MatDestroy(&J_));
    Mat blocks[4] = {iterative ? Kg_ : A, sys.C, sys.B, sys.D};
    CHK(MatCreateNest(comm_, 2, nullptr, 2, nullptr, blocks, &J_));
    A_seen_ = A;
    reuse_.drop();
    factors_.drop();
    if (iterative) {
      IS isr[2];
      CHK(MatNestGetISs(J_, isr, nullptr));
      // The rigid-body modes reach the displacement block's multigrid through its index set
      // (GAMG's aggregates, BoomerAMG's interpolation vectors).
      MatNullSpace nsp = nullptr;
      CHK(MatGetNearNullSpace(A, &nsp));
      if (nsp) CHK(PetscObjectCompose(reinterpret_cast<PetscObject>(isr[0]), "nearnullspace", reinterpret_cast<PetscObject>(nsp)));
      PC pc;
      CHK(KSPGetPC(ksp_, &pc));
      CHK(PCFieldSplitSetIS(pc, "u", isr[0]));
      CHK(PCFieldSplitSetIS(pc, "lambda", isr[1]));
    }
  } else {
    CHK(MatAssemblyBegin(J_, MAT_FINAL_ASSEMBLY));
    CHK(MatAssemblyEnd(J_, MAT_FINAL_ASSEMBLY));
  }
  if (kind_ == SaddleSolver::Mumps) {
    CHK(MatConvert(J_, MATAIJ, Jaij_ ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, &Jaij_));
    op = Jaij_;
  } else {
    op = J_;
  }
  PetscReal old_rtol, abstol, dtol;
  PetscInt maxit;
  PetscInt its = 0;
  // The field split keeps its preconditioner, MUMPS its factors, while the active set is the one
  // they were built for and the rate stays near that right after the setup (saddle_reuse.hpp); a
  // kept one that fails is rebuilt and the solve repeated.
  // Each rank compares its own pairs' active set: every rank must keep, or all set up (collective).
  int keep_here = iterative ? reuse_.keep(opt_->reuse_preconditioner, signature_) : factors_.keep(opt_->reuse_preconditioner, signature_);
  int keep_all = 0;
  if (MPI_Allreduce(&keep_here, &keep_all, 1, MPI_INT, MPI_MIN, comm_) != MPI_SUCCESS)
    throw ComputeError("MPI_Allreduce failed in the saddle-point solver");
  bool keep = keep_all != 0;
  for (;;) {
    // Kept: the field split does not set up (KSPSetReusePreconditioner below) and the blocks'
    // solvers must not set up on K_gamma's new values either: the multigrid's coarse levels and the
    // Schur approximation stay, its finest level (smoother, residual) runs on the current K_gamma
    // (saddle_reuse.hpp). Not kept: J's state, bumped by its assembly at every solve, tells the
    // field split to set up.
    if (iterative) keep_blocks(keep);
    CHK(KSPSetOperators(ksp_, op, op));
    if (!configured_) CHK(KSPSetFromOptions(ksp_));
    configured_ = true;
    CHK(KSPGetTolerances(ksp_, &old_rtol, &abstol, &dtol, &maxit));
    // Newton's own tolerance (at most 0.5; on the last iterations the target over the residual
    // left: reaching the target in one more iteration of a linear problem). Capped at 1e-3 until
    // 2026-11-27, the last Newton iteration of a production month needed 81-105 of the month's
    // 104-200 field-split iterations to reach 1e-3 where 2.6e-2 to 6.4e-2 was asked.
    const double tol = rtol;
    CHK(KSPSetTolerances(ksp_, tol, abstol, dtol, iterative ? maxit : FactorReuse::budget(tol)));
    CHK(KSPSetReusePreconditioner(ksp_, keep ? PETSC_TRUE : PETSC_FALSE));
    PetscReal bnorm = 0;
    if (iterative) {
      guess_ratio_ = guess_.form(op, rhs_, sol_, same_operator, tol);
      same_operator = true;  // (a repeated solve: the products are those of this operator)
      CHK(KSPSetInitialGuessNonzero(ksp_, guess_ratio_ < 1 ? PETSC_TRUE : PETSC_FALSE));
    }
    CHK(VecNorm(rhs_, NORM_2, &bnorm));
    CHK(KSPSolve(ksp_, rhs_, sol_));
    CHK(KSPGetIterationNumber(ksp_, &its));
    CHK(KSPGetConvergedReason(ksp_, &reason));
    stats.linear_iterations += its;
    if (keep && reason < 0) {
      keep = false;
      continue;
    }
    if (iterative && reason >= 0) {
      // Decades of residual reduction (FGMRES: the true residual; from the first iterate's).
      PetscReal rnorm = 0;
      CHK(KSPGetResidualNorm(ksp_, &rnorm));
      const double r0 = std::min(guess_ratio_, 1.0) * bnorm;
      const double decades = rnorm > 0 && r0 > 0 ? std::log10(r0 / rnorm) : 0.0;
      reuse_.record(static_cast<int>(its), decades, !keep, signature_);
    } else if (reason >= 0) {
      PetscReal rnorm = 0;  // GMRES, right preconditioning: the true residual, from x0 = 0
      CHK(KSPGetResidualNorm(ksp_, &rnorm));
      factors_.record(static_cast<int>(its), bnorm > 0 ? rnorm / bnorm : 0.0, !keep, signature_);
    }
    break;
  }
  if (!keep) ++stats.preconditioner_setups;
  if (iterative && reason >= 0) guess_.remember(sol_);
  return its;
}

}  // namespace ugs::contact::detail
