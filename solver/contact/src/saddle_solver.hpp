// Saddle solver of the contact solver: the linear solve of the Newton system (saddle_system.hpp)
// with PETSc, either
//   MUMPS        the block matrix converted to AIJ and factorised (LU); the factors kept while the
//                active set is unchanged and GMRES preconditioned by them converges fast (saddle_reuse.hpp), or
//   field split  FGMRES with a Schur-complement field split: the displacement block augmented with
//                the constraint rows (K + gamma C W B, augmented Lagrangian) under algebraic
//                multigrid, the multiplier block by selfp; the preconditioner's coarse levels and
//                Schur approximation are kept while the active set is unchanged and the rate
//                stays close to that of a fresh setup (saddle_reuse.hpp).
#pragma once
#include <array>
#include <string>
#include <vector>

#include <petscksp.h>

#include "pair_distribution.hpp"
#include "pattern_sum.hpp"
#include "saddle_guess.hpp"
#include "saddle_reuse.hpp"
#include "saddle_system.hpp"
#include "ugs/contact/contact.hpp"

namespace ugs::contact::detail {

class SaddlePointSolver {
public:
  SaddlePointSolver() = default;
  ~SaddlePointSolver();
  SaddlePointSolver(const SaddlePointSolver&) = delete;
  SaddlePointSolver& operator=(const SaddlePointSolver&) = delete;

  // Collective: chooses the solver (opt.solver; Auto by opt.direct_limit) and creates the KSP.
  // -contact_augmentation overrides opt.augmentation.
  void setup(const mech::CouplingContext& ctx, const PairDistribution& pd, const SaddleSystem& sys, ContactOptions& opt);

  // Collective: solves for du (zero on prescribed components, from owned_fixed) and the multiplier
  // increments, added to lam. B and D must be filled (SaddleSystem::fill).
  mech::CouplingSolve solve(Mat A, Vec r, Vec du, double rtol, const PairDistribution& pd, SaddleSystem& sys,
                            const std::vector<PairEquations>& eq, const std::vector<std::uint8_t>& owned_fixed,
                            std::vector<std::array<double, 3>>& lam, ContactStats& stats);

  SaddleSolver kind() const { return kind_; }
  const char* name() const { return kind_ == SaddleSolver::Mumps ? "MUMPS" : "field split"; }

private:
  // The active set's signature: the augmentation weight gamma / A_q of every constraint row (stick,
  // the normal of a slipping pair), 0 elsewhere; the weights W of the field split's augmentation.
  void active_set(const PairDistribution& pd, const std::vector<PairEquations>& eq);
  // K_gamma = K + C W B into Kg (kept when same_operator), and W r_lambda into wr (field split; W
  // from active_set).
  void augment(Mat A, const PairDistribution& pd, SaddleSystem& sys, PetscScalar* rl, bool same_operator);
  // The operator, the preconditioner and KSPSolve on rhs_ into sol_; throws ComputeError on a PETSc error.
  PetscInt linear_solve(Mat A, double rtol, bool same_operator, SaddleSystem& sys, ContactStats& stats,
                        KSPConvergedReason& reason);
  // Collective: whether the operator has the values of the last solve's (K by its assembly state,
  // the active set's weights, the pair equations' derivatives: B, D and through them K_gamma);
  // remembers this solve's for the next call.
  bool operator_unchanged(Mat A, const std::vector<PairEquations>& eq);
  // After a failure: drops the factorisation or hierarchy and the block operator, so that the next
  // solve sets everything up afresh.
  void reset();
  // Field split: whether the setups of its blocks' preconditioners (GAMG, the Schur block's) are
  // kept when their operators change (PCSetReusePreconditioner on each block).
  void keep_blocks(bool keep);

  MPI_Comm comm_ = MPI_COMM_NULL;
  int n_owned_ = 0;
  SaddleSolver kind_ = SaddleSolver::Mumps;
  const ContactOptions* opt_ = nullptr;
  Vec rhs_ = nullptr, sol_ = nullptr, wr_ = nullptr;
  Mat WB_ = nullptr, G_ = nullptr, Kg_ = nullptr, J_ = nullptr, Jaij_ = nullptr;
  Mat A_seen_ = nullptr;
  KSP ksp_ = nullptr;
  bool configured_ = false;  // KSPSetFromOptions done since the last reset
  bool blocks_kept_ = false;  // keep_blocks(true) in force
  PatternSum kg_sum_;  // K + G into K_gamma's values in place
  SaddleReuse reuse_;  // when the field split keeps its preconditioner
  FactorReuse factors_;  // when MUMPS keeps its factorisation
  std::vector<double> signature_;  // the augmentation weight of every multiplier row (the active set)
  SaddleGuess guess_;  // the field split's first iterate from the last solutions
  double guess_ratio_ = 1;  // ||b - J x0|| / ||b|| of the last solve's first iterate
  // What the last solve's operator was built from (operator_unchanged).
  bool have_last_ = false;
  PetscObjectId last_A_id_ = 0;
  PetscObjectState last_A_state_ = 0;
  std::vector<double> last_signature_, last_derivatives_;
};

}  // namespace ugs::contact::detail
