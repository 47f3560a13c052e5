// Sparse Cholesky (SuiteSparse CHOLMOD) of the backward-Euler matrix of the free unknowns,
//   S(dt) = A_FF + diag(m_F) / dt,
// analysed once (fill-reducing ordering, symbolic factor) and factorized once per distinct step
// size; factors are cached by dt (least recently used dropped beyond `cache_capacity`), so a
// monthly run factorizes four times (28, 29, 30 and 31 days) and then only solves. Supernodal
// factorization and solves: their dense kernels come from BLAS (OpenBLAS, scripts/install-deps).
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace ugs::flow {

// Upper triangle (row <= column) in compressed columns, rows sorted, the diagonal present.
struct UpperCsc {
  std::size_t n = 0;
  std::vector<std::int64_t> col_start;  // n + 1
  std::vector<std::int64_t> row;
  std::vector<double> val;
};

struct CholeskyStats {
  std::size_t factorizations = 0, solves = 0;
  double analyze_seconds = 0, factor_seconds = 0, solve_seconds = 0;
  double factor_nonzeros = 0;
};

class StepSolver {
public:
  // `a` holds A_FF, `storage` the lumped storage m_F (> 0) of the same unknowns.
  StepSolver(UpperCsc a, std::vector<double> storage, std::size_t cache_capacity = 8);
  ~StepSolver();
  StepSolver(const StepSolver&) = delete;
  StepSolver& operator=(const StepSolver&) = delete;

  // Solves S(dt) x = b (x and b of length n, may not alias). ComputeError if S is not positive definite.
  void solve(double dt, const double* b, double* x);
  const CholeskyStats& stats() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ugs::flow
