#include "ugs/flow/cholesky.hpp"

#include <chrono>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <cholmod.h>
#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs::flow {
namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

}  // namespace

struct StepSolver::Impl {
  cholmod_common c{};
  cholmod_sparse* A = nullptr;          // values rewritten for each new dt
  cholmod_factor* symbolic = nullptr;   // fill-reducing ordering and supernodes, shared by every dt
  cholmod_dense *B = nullptr, *X = nullptr, *Y = nullptr, *E = nullptr;  // solve workspace, reused
  std::vector<double> a_values, storage;
  std::vector<int> diag_pos;
  struct Cached {
    double dt;
    cholmod_factor* L;
    std::uint64_t last_use;
  };
  std::vector<Cached> cache;
  std::size_t capacity = 8;
  std::uint64_t clock = 0;
  CholeskyStats stats;

  ~Impl() {
    for (auto& f : cache) cholmod_free_factor(&f.L, &c);
    cholmod_free_factor(&symbolic, &c);
    cholmod_free_sparse(&A, &c);
    cholmod_free_dense(&B, &c);
    cholmod_free_dense(&X, &c);
    cholmod_free_dense(&Y, &c);
    cholmod_free_dense(&E, &c);
    cholmod_finish(&c);
  }

  cholmod_factor* factor(double dt) {
    ++clock;
    for (auto& f : cache)
      if (f.dt == dt) {
        f.last_use = clock;
        return f.L;
      }
    const double t0 = now();
    if (cache.size() >= capacity) {  // drop the least recently used before allocating the next
      std::size_t oldest = 0;
      for (std::size_t k = 1; k < cache.size(); ++k)
        if (cache[k].last_use < cache[oldest].last_use) oldest = k;
      cholmod_free_factor(&cache[oldest].L, &c);
      cache.erase(cache.begin() + static_cast<std::ptrdiff_t>(oldest));
    }
    auto* x = static_cast<double*>(A->x);
    std::memcpy(x, a_values.data(), a_values.size() * sizeof(double));
    for (std::size_t j = 0; j < storage.size(); ++j) x[diag_pos[j]] += storage[j] / dt;
    cholmod_factor* L = cholmod_copy_factor(symbolic, &c);
    if (!L) throw std::bad_alloc();
    cholmod_factorize(A, L, &c);
    if (c.status == CHOLMOD_NOT_POSDEF || L->minor < L->n) {
      const auto minor = L->minor;
      cholmod_free_factor(&L, &c);
      throw ComputeError(fmt::format("flow: the step matrix for dt = {} s is not positive definite (CHOLMOD stopped at "
                                     "column {}): check conductivities and storage",
                                     dt, minor));
    }
    if (c.status < CHOLMOD_OK) {
      cholmod_free_factor(&L, &c);
      throw ComputeError(fmt::format("flow: CHOLMOD factorization failed (status {})", c.status));
    }
    stats.factor_seconds += now() - t0;
    ++stats.factorizations;
    stats.factor_nonzeros = c.lnz;
    cache.push_back({dt, L, clock});
    return L;
  }
};

StepSolver::StepSolver(UpperCsc a, std::vector<double> storage, std::size_t cache_capacity) : impl_(new Impl) {
  Impl& I = *impl_;
  cholmod_start(&I.c);
  I.c.print = 0;
  I.c.error_handler = nullptr;
  I.capacity = cache_capacity == 0 ? 1 : cache_capacity;
  const double t0 = now();
  const std::size_t n = a.n, nnz = a.row.size();
  if (storage.size() != n || a.col_start.size() != n + 1 || a.val.size() != nnz)
    throw std::invalid_argument("StepSolver: inconsistent matrix");
  if (nnz >= static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw ComputeError("flow: the matrix has more than 2^31 entries");
  I.A = cholmod_allocate_sparse(n, n, nnz, 1, 1, 1, CHOLMOD_REAL, &I.c);
  if (!I.A) throw std::bad_alloc();
  auto* ap = static_cast<int*>(I.A->p);
  auto* ai = static_cast<int*>(I.A->i);
  for (std::size_t j = 0; j <= n; ++j) ap[j] = static_cast<int>(a.col_start[j]);
  for (std::size_t k = 0; k < nnz; ++k) ai[k] = static_cast<int>(a.row[k]);
  std::memcpy(I.A->x, a.val.data(), nnz * sizeof(double));
  I.diag_pos.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const std::int64_t last = a.col_start[j + 1] - 1;
    if (last < a.col_start[j] || a.row[last] != static_cast<std::int64_t>(j))
      throw std::invalid_argument("StepSolver: diagonal missing");
    I.diag_pos[j] = static_cast<int>(last);
  }
  I.a_values = std::move(a.val);
  I.storage = std::move(storage);
  I.symbolic = cholmod_analyze(I.A, &I.c);
  if (!I.symbolic || I.c.status < CHOLMOD_OK)
    throw ComputeError(fmt::format("flow: CHOLMOD analysis failed (status {})", I.c.status));
  I.B = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &I.c);
  if (!I.B) throw std::bad_alloc();
  I.stats.analyze_seconds = now() - t0;
}

StepSolver::~StepSolver() = default;

void StepSolver::solve(double dt, const double* b, double* x) {
  Impl& I = *impl_;
  cholmod_factor* L = I.factor(dt);
  const double t0 = now();
  std::memcpy(I.B->x, b, I.storage.size() * sizeof(double));
  if (!cholmod_solve2(CHOLMOD_A, L, I.B, nullptr, &I.X, nullptr, &I.Y, &I.E, &I.c))
    throw ComputeError(fmt::format("flow: CHOLMOD solve failed (status {})", I.c.status));
  std::memcpy(x, I.X->x, I.storage.size() * sizeof(double));
  I.stats.solve_seconds += now() - t0;
  ++I.stats.solves;
}

const CholeskyStats& StepSolver::stats() const { return impl_->stats; }

}  // namespace ugs::flow
