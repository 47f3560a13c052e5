// The transient run: backward Euler with lumped storage on the free unknowns,
//   (diag(m)/dt + A) p^{n+1} = diag(m)/dt p^n     (pool unknowns on their schedules),
// from p = 0 (the pressure change is zero at the run start). The water each step moves into a
// pool is the reaction at its unknowns, m_d (p_d^{n+1} - p_d^n) + dt (A p^{n+1})_d, with the sign
// flipped: positive when aquifer water encroaches into a depleted pool. Summed over the run it
// equals the loss of water stored in the aquifer (the material balance of thesis 4.2.1).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "ugs/flow/cholesky.hpp"
#include "ugs/flow/flow_model.hpp"
#include "ugs/flow/schedule.hpp"

namespace ugs::flow {

struct TransientOptions {
  int substeps = 1;                 // equal sub-steps per interval between grid dates
  std::size_t cache_capacity = 8;   // factorizations kept (one per distinct step size)
  std::size_t last_date = SIZE_MAX; // stop after this grid date (calibration runs stop at the target)
};

// What an observer sees at each grid date.
struct DateState {
  std::size_t index = 0;                 // into TimeGrid::dates
  std::int64_t date = 0;
  const std::vector<double>* dp = nullptr;      // pressure change per unknown [Pa]
  const std::vector<double>* influx = nullptr;  // cumulative water into each pool [m3]
  double stored = 0;                     // change of water stored in the aquifer [m3]
};

struct TransientResult {
  std::vector<std::int64_t> dates;                 // grid dates computed
  std::vector<std::vector<double>> influx;         // [pool][date] cumulative water into the pool [m3]
  std::vector<double> stored;                      // [date] change of stored water [m3]
  std::vector<double> dp;                          // final pressure change per unknown [Pa]
  std::size_t steps = 0;
  CholeskyStats solver;
  double assemble_seconds = 0;

  // max over dates of |stored + sum of influx| / max(|stored|, sum |influx|): zero in exact arithmetic.
  double balance_error() const;
};

TransientResult run_transient(const FlowModel& model, const TimeGrid& grid, const TransientOptions& options = {},
                              const std::function<void(const DateState&)>& on_date = {});

}  // namespace ugs::flow
