// The predictor of Newton's first correction (predictor.cpp). Private to ugs_mechanics.
#pragma once
#include <vector>

#include <petscksp.h>

namespace ugs::mech {

// Predictor of Newton's first correction (predictor.cpp). The increments of earlier steps span
// most of a new one (the seasonal cycles repeat and the flow fields are smooth in time): the first
// Newton correction starts from the Galerkin projection on them. The basis W is A-orthonormal
// (W^T A W = I), so the projection du0 = W (W^T r) costs dot products only. A W is not kept (24
// vectors of the size of u): A v is recomputed when a direction is added, A w_j when W is
// re-orthonormalized. W is orthonormal for the matrix it was built with; when the matrix changes it
// stays a good (no longer optimal) guess until the preconditioner is rebuilt, when W is
// re-orthonormalized for the new matrix (refresh). The prediction is used only when it reduces the residual
// (||r - A du0|| < ||r||); otherwise the basis is refreshed for the current matrix and the
// projection tried again, else dropped.
// It reads the matrix and vectors it is given and changes only du and its own basis.
class Predictor {
 public:
  Predictor() = default;
  Predictor(const Predictor&) = delete;
  Predictor& operator=(const Predictor&) = delete;
  ~Predictor();
  // Work vectors are laid out like u (ghosted, owned displacements); u is not written.
  void setup(Vec u);
  // du = W (W^T r) if it reduces the residual (returns true), else du = 0.
  bool predict(Mat A, Vec r, Vec du);
  // Re-orthonormalizes the basis for the current matrix A (after a preconditioner rebuild).
  void refresh(Mat A);
  // Adds the increment v of a converged (sub-)step (its prescribed components zero; the predictor
  // takes it over), A-orthogonalized against the basis. When the basis is full the direction the
  // recent increments used least goes (or the new one, if it is the least).
  void remember(Mat A, Vec v);
  // Frees the basis (MechanicsSolver::release_linear_system: no step follows).
  void release();
  // The relative residual the last prediction left (-ugs_newton_monitor): -1 none tried, inf dropped.
  double predicted() const { return predicted_; }

 private:
  // 48, not 24 (until 2026-11-29): a year of monthly storage steps and the aquifers' slower shapes
  // do not fit in 24 directions. On the scale-0.1 history box's InSAR-window months the projection
  // then left 1e-2 .. 6e-2 of the residual and the linear solve took 11-15 iterations; with 48 it
  // leaves ~1e-5 and takes 2-8 (docs/mechanics.md, "Speed of the hypo-plastic history").
  static constexpr int kRecycle = 48;
  // Per remembered increment, the weights of the older directions decay by this factor.
  static constexpr double kDecay = 0.9;
  // du = W (W^T r); returns ||r - A du|| / ||r|| (A du in aw_).
  double projection_residual(Mat A, Vec r, Vec du);
  // W <- W C in place: new direction t = sum_i coef[t][i] w_i; the directions past coef.size() go.
  void combine_in_place(const std::vector<std::vector<PetscScalar>>& coef);
  std::vector<Vec> basis_;  // W (A-orthonormal); A W is not kept (recomputed where needed)
  // Per direction: how much of the recent increments lay along it (their energy in it, c_i^2 with
  // c = W^T A v, decayed by kDecay per increment).
  std::vector<double> weight_;
  Vec aw_ = nullptr;        // work vector: A du, A v, A w_j
  Vec like_ = nullptr;  // u: the layout of new basis vectors (not owned)
  double predicted_ = -1;
};

}  // namespace ugs::mech
