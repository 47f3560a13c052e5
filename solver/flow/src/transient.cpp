#include "ugs/flow/transient.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs::flow {
namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

}  // namespace

double TransientResult::balance_error() const {
  double worst = 0;
  for (std::size_t k = 0; k < stored.size(); ++k) {
    double sum = stored[k], mag = std::abs(stored[k]), in = 0;
    for (const auto& p : influx) sum += p[k], in += std::abs(p[k]);
    mag = std::max(mag, in);
    if (mag > 0) worst = std::max(worst, std::abs(sum) / mag);
  }
  return worst;
}

TransientResult run_transient(const FlowModel& fm, const TimeGrid& grid, const TransientOptions& opt,
                              const std::function<void(const DateState&)>& on_date) {
  if (opt.substeps < 1) throw std::invalid_argument("run_transient: substeps must be at least 1");
  if (grid.pool_dp.size() != fm.pools.size()) throw std::invalid_argument("run_transient: one schedule per pool expected");
  const double t0 = now();
  TransientResult res;
  const std::size_t n = fm.num_dofs;
  const std::vector<double> a = fm.conductance_values();
  const CsrMatrix& P = fm.pattern;

  // 1. Free unknowns F and pool (Dirichlet) unknowns D; S(dt) on F, couplings A_FD, rows A_D*.
  std::vector<std::int64_t> free_index(n, -1);
  std::vector<std::uint32_t> free_dofs, dir_dofs;
  for (std::uint32_t d = 0; d < n; ++d) {
    if (fm.pool_of_dof[d] < 0) {
      free_index[d] = static_cast<std::int64_t>(free_dofs.size());
      free_dofs.push_back(d);
    } else {
      dir_dofs.push_back(d);
    }
  }
  const std::size_t nf = free_dofs.size();
  UpperCsc S;
  S.n = nf;
  S.col_start.assign(nf + 1, 0);
  std::vector<std::size_t> fd_start(nf + 1, 0);
  std::vector<std::uint32_t> fd_col;
  std::vector<double> fd_val;
  std::vector<double> m_free(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    const std::uint32_t d = free_dofs[f];
    m_free[f] = fm.storage[d];
    for (std::size_t k = P.row_start[d]; k < P.row_start[d + 1]; ++k) {
      const std::uint32_t j = P.col[k];
      if (free_index[j] < 0) {
        fd_col.push_back(j);
        fd_val.push_back(a[k]);
      } else if (j <= d) {
        S.row.push_back(free_index[j]);
        S.val.push_back(a[k]);
      }
    }
    S.col_start[f + 1] = static_cast<std::int64_t>(S.row.size());
    fd_start[f + 1] = fd_col.size();
  }
  for (std::size_t f = 0; f < nf; ++f)
    if (!(m_free[f] > 0)) throw ComputeError("flow: an aquifer unknown has no storage (internal error)");
  res.assemble_seconds = now() - t0;
  std::unique_ptr<StepSolver> solver;
  if (nf > 0) solver = std::make_unique<StepSolver>(std::move(S), m_free, opt.cache_capacity);

  // 2. March through the grid dates, sub-stepping each interval.
  std::vector<double> p(n, 0.0), p_old(n, 0.0), b(nf), x(nf);
  std::vector<double> influx(fm.pools.size(), 0.0);
  const std::size_t last = std::min(opt.last_date, grid.dates.size() - 1);
  res.influx.assign(fm.pools.size(), {});
  auto record = [&](std::size_t k) {
    const double stored = fm.stored_water(p);
    res.dates.push_back(grid.dates[k]);
    res.stored.push_back(stored);
    for (std::size_t q = 0; q < influx.size(); ++q) res.influx[q].push_back(influx[q]);
    if (on_date) on_date(DateState{k, grid.dates[k], &p, &influx, stored});
  };
  record(0);
  for (std::size_t k = 1; k <= last; ++k) {
    const double interval = static_cast<double>(grid.dates[k] - grid.dates[k - 1]);
    const double dt = interval / opt.substeps;
    for (int s = 1; s <= opt.substeps; ++s) {
      p_old = p;
      const double w = static_cast<double>(s) / opt.substeps;
      for (auto d : dir_dofs) {
        const auto& v = grid.pool_dp[fm.pool_of_dof[d]];
        p[d] = s == opt.substeps ? v[k] : v[k - 1] + w * (v[k] - v[k - 1]);
      }
      if (nf > 0) {
        for (std::size_t f = 0; f < nf; ++f) {
          double r = m_free[f] / dt * p_old[free_dofs[f]];
          for (std::size_t q = fd_start[f]; q < fd_start[f + 1]; ++q) r -= fd_val[q] * p[fd_col[q]];
          b[f] = r;
        }
        solver->solve(dt, b.data(), x.data());
        for (std::size_t f = 0; f < nf; ++f) p[free_dofs[f]] = x[f];
      }
      // Reactions: the water the step moves from each pool into the aquifer.
      for (auto d : dir_dofs) {
        double ap = 0;
        for (std::size_t q = P.row_start[d]; q < P.row_start[d + 1]; ++q) ap += a[q] * p[P.col[q]];
        influx[fm.pool_of_dof[d]] -= fm.storage[d] * (p[d] - p_old[d]) + dt * ap;
      }
      ++res.steps;
    }
    record(k);
  }
  res.dp = p;
  if (solver) res.solver = solver->stats();
  return res;
}

}  // namespace ugs::flow
