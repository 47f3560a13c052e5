// The first iterate of the saddle-point Krylov solve: the least-squares projection of the
// right-hand side on the span of the last solutions (SaddlePointSolver).
//
// The monthly increments of a storage history repeat in shape (smooth pressure fields, stuck fault
// pairs), so the new Newton correction [du; dlambda] lies close to the span of the earlier ones.
// The saddle point is not symmetric positive definite (the mechanics predictor's A-orthonormal
// Galerkin projection does not apply), so the guess minimises the residual instead:
//   x0 = X c,  c = argmin || b - J X c ||,
// with J X recomputed for the current operator at each solve (the active set, the tangent and the
// augmentation may have changed since X was stored), through the normal equations with the
// directions of negligible eigenvalue dropped. PETSc's KSPGuess (Fischer) does not help here: it
// forgets its basis whenever the operator's state changes, i.e. at every Newton iteration.
#pragma once
#include <vector>

#include <petscksp.h>

namespace ugs::contact::detail {

class SaddleGuess {
public:
  ~SaddleGuess();
  // Writes the projection into x and returns ||b - J x|| / ||b||; x = 0 and 1 when there is no history.
  double form(Mat J, Vec b, Vec x);
  // Keeps a copy of the solution of a converged solve (the oldest dropped beyond kKeep).
  void remember(Vec x);

  static constexpr int kKeep = 8;

private:
  std::vector<Vec> x_, y_;  // the stored solutions, and J times them (work)
  Vec w_ = nullptr;         // the residual of the projection (work)
};

}  // namespace ugs::contact::detail
