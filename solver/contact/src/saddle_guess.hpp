// The first iterate of the saddle-point Krylov solve: the least-squares projection of the
// right-hand side on the span of the last solutions (SaddlePointSolver).
//
// The monthly increments of a storage history repeat in shape (smooth pressure fields, stuck fault
// pairs), so the new Newton correction [du; dlambda] lies close to the span of the earlier ones.
// The saddle point is not symmetric positive definite (the mechanics predictor's A-orthonormal
// Galerkin projection does not apply), so the guess minimises the residual instead:
//   x0 = X c,  c = argmin || b - J X c ||,
// with J X for the current operator (the active set, the tangent and the augmentation may have
// changed since X was stored), through the normal equations with the directions of negligible
// eigenvalue dropped. While the operator keeps its values (a storage month: a linear tangent and
// every pair stuck) the products J x_j and their Gram matrix are kept from one solve to the next
// and only the newest solution is multiplied: one product per solve instead of kKeep, the same
// bits as recomputing them. PETSc's KSPGuess (Fischer) does not help here: it
// forgets its basis whenever the operator's state changes, i.e. at every Newton iteration.
#pragma once
#include <vector>

#include <petscksp.h>

namespace ugs::contact::detail {

class SaddleGuess {
public:
  ~SaddleGuess();
  // Writes the projection into x and returns ||b - J x|| / ||b||; x = 0 and 1 when there is no history.
  // same_operator: J has the values it had at the last form() (the caller's promise; collective
  // agreement is the caller's): the products kept from then are reused. enough: the solve's
  // relative target; above it the scaled projection is tried as well (saddle_guess.cpp).
  double form(Mat J, Vec b, Vec x, bool same_operator = false, double enough = 0);
  // Keeps a copy of the solution of a converged solve (the oldest dropped beyond kKeep).
  void remember(Vec x);

  static constexpr int kKeep = 8;

  // Products computed by form() since construction (the tests count them).
  long long products() const { return products_; }

private:
  std::vector<Vec> x_, y_;    // the stored solutions, oldest first, and J times them
  std::vector<bool> have_y_;  // y_[j] = J x_[j] for the operator of the last form()
  std::vector<std::vector<double>> gram_;  // y_i . y_j where both are current
  Vec w_ = nullptr;           // the residual of the projection (work)
  long long products_ = 0;
};

}  // namespace ugs::contact::detail
