// When ugs-solve keeps a preconditioner and when it builds a new one (docs/mechanics.md,
// "Preconditioner reuse"). The decision changes the numbers (a kept preconditioner gives other
// Krylov iterates than a fresh one), so it is a function of counts only — iterations, residual
// reductions, numbers of unknowns — never of measured time: the same input gives the same output
// on an idle and on a busy machine (issue 20).
#pragma once

namespace ugs::mech {

// The cost of refactoring, in iterations of a Krylov solve preconditioned by the factorization
// (a forward and backward substitution, a product with the matrix). Measured with CHOLMOD on the
// two-pool case of mech_make_case (`small`, one process, -log_view; PCSetUp time over the time of
// one PCApply): 59 at 5,265 unknowns, 58 at 41,625, 55 at 112,545 (the factorization runs at 2-8
// times the flop rate of the substitutions, which makes up for its O(n^2) against O(n^(4/3))
// flops at these sizes); 60 on the 26,547-node po-plain mesh (2.9 s against 48 ms).
inline constexpr double kRefactorIterations = 55.0;

// A kept factorization gets this many iterations per decade of the solve's tolerance, twice over,
// before it is refactored and the solve repeated; a refactorization must pay off over this many solves.
inline constexpr double kFactorIterationsPerDecade = 5.0;
inline constexpr double kFactorHorizon = 3.0;

// A factorization is kept while the iterations it costs beyond those right after it was computed,
// over the next `horizon` solves, stay within what a refactorization costs (kRefactorIterations):
//   (last_ipd - baseline_ipd) * last_decades * horizon <= refactor_iterations
// with ipd the iterations per decade of residual reduction (baseline: the first solve after the
// factorization; last: the last solve) and last_decades the decades the last solve reduced.
bool keep_factorization(double baseline_ipd, double last_ipd, double last_decades, double refactor_iterations,
                        double horizon);

// The decades of residual reduction a solve is counted for, at least 0.3 (a solve that had little
// to reduce must not look expensive).
double counted_decades(double reduction);

// The iterations a kept factorization gets for a solve to `rtol` (kFactorIterationsPerDecade per
// decade, twice over).
int factor_budget(double rtol);

// A multigrid hierarchy is kept while its iterations per decade stay within 1.5 times (or 3 more
// than) those right after its setup.
bool keep_multigrid(double baseline_ipd, double last_ipd);

}  // namespace ugs::mech
