// When the field split keeps its preconditioner (the displacement block's multigrid hierarchy and
// the Schur approximation) and when it builds a new one (SaddlePointSolver, docs/fault-mechanics.md);
// below, FactorReuse: when MUMPS keeps its factorisation.
//
// A kept hierarchy keeps its coarse operators (GAMG's Galerkin products P^T K P, the expensive part
// of a setup: GAMG already keeps its aggregates and prolongators from the first setup on) and the
// selfp Schur approximation; its finest level runs on the current augmented displacement block
// (smoother, residual), so that only the coarse correction lags behind the hypo-plastic tangent.
// It is rebuilt when
//   - the active set changed: the constraint rows (stick, the normal of slipping pairs) are the
//     augmented springs of K + gamma C W B, so their pattern is the active set's signature;
//   - the rate degraded: iterations per decade of residual reduction beyond those right after the
//     setup (mech::keep_multigrid: 1.5 times, or 3 more);
//   - a kept one failed (the solve is repeated after a setup).
// Across Newton iterations and load steps alike. Until 2026-11-27 every solve of a nonlinear step
// (virgin loading: the tangent changes at every Newton iteration) set up, because a hierarchy frozen
// with its fine level had cost 30 % more linear iterations there; with the fine level
// current the coarsened history's production months take the same iterations with 1 setup instead
// of 26 (docs/fault-mechanics.md, "Production months").
// Counts only, never measured time: the decision changes the numbers (reuse_rule.hpp).
#pragma once
#include <cstddef>
#include <vector>

namespace ugs::contact::detail {

class SaddleReuse {
public:
  // Whether the next solve may keep the preconditioner: `allowed` (the option), one built, the same
  // active set as when it was built (`signature`: the augmentation weight of every multiplier row),
  // and the last solve's rate within the multigrid rule.
  bool keep(bool allowed, const std::vector<double>& signature) const;
  // After a solve: its iterations and the decades of residual reduction it achieved; `fresh` when
  // the preconditioner was built for it (then `signature` becomes the reference).
  void record(int iterations, double decades, bool fresh, const std::vector<double>& signature);
  // Forget the preconditioner (after a failure).
  void drop() { built_ = false; }

  std::size_t setups() const { return setups_; }

private:
  static double per_decade(int iterations, double decades);
  bool built_ = false;
  double baseline_ipd_ = 0, last_ipd_ = 0;
  std::vector<double> signature_;
  std::size_t setups_ = 0;
};

// When MUMPS keeps its factorisation of the saddle-point matrix. A kept factorisation
// preconditions GMRES on the current matrix (the same factors for an unchanged operator: one
// iteration, the same bits as a refactorisation); it is refactored when
//   - the active set changed (`signature`, as for the field split): a pair that starts or stops
//     slipping, or opens, changes rows of B and D entirely;
//   - the iterations it costs beyond a fresh factorisation, over the next kFactorHorizon solves,
//     exceed what a refactorisation costs (mech::keep_factorization, the continuous solver's rule):
//     the hypo-plastic tangent and the friction rows move the operator away from its factors;
//   - the iterations it has cost beyond a fresh factorisation since it was computed add up to what
//     a refactorisation costs (the ski-rental rule: never more than twice the best choice made
//     knowing the future). The rule above looks 3 solves ahead only; a whole history's storage
//     steps run hundreds of solves on factors of the production's virgin-branch tangent at 14
//     iterations each, where a refactorisation on the storage branch brings them back to 1-2;
//   - a kept one fails to converge within its budget (the solve is repeated after refactoring).
// Across Newton iterations and load steps alike: the rate rule decides, counts only (reuse_rule.hpp).
class FactorReuse {
public:
  bool keep(bool allowed, const std::vector<double>& signature) const;
  // After a solve: its iterations and its residual reduction ||r|| / ||b||; `fresh` when the
  // factorisation was computed for it (then `signature` becomes the reference).
  void record(int iterations, double reduction, bool fresh, const std::vector<double>& signature);
  void drop() { built_ = false; }
  // The iteration budget of a solve to rtol with a kept factorisation, and with a fresh one (which
  // needs one or two: more means the factors are not accurate enough, a failed solve).
  static int budget(double rtol);
  std::size_t setups() const { return setups_; }

private:
  bool built_ = false;
  double baseline_ipd_ = 0, last_ipd_ = 0, last_decades_ = 0;
  double extra_ = 0;  // iterations beyond the fresh rate, summed over the solves since the factorisation
  std::vector<double> signature_;
  std::size_t setups_ = 0;
};

}  // namespace ugs::contact::detail
