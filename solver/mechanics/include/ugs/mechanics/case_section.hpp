// The [solver] settings the continuous solver takes from the case file, named and checked by the
// library that uses them: the names of the linear solvers and partition methods live here only
// (the case file's linear_solver, ugs-solve's --solver and --partition read them), and every
// problem is added to `errors` (the caller reports them all at once).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "ugs/formats/case_file.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/mechanics/partition.hpp"
#include "ugs/mechanics/solver.hpp"

namespace ugs::mech {

const std::vector<std::pair<std::string, LinearSolver>>& linear_solver_names();
const std::vector<std::pair<std::string, PartitionMethod>>& partition_names();

// linear_solver is one of linear_solver_names(). The numbers the reader takes as they come
// (positive, at least 1) must also be usable: a Newton tolerance of 1 or more accepts the first
// iterate of every step (no equilibrium, exit 0), one below 1e-14 is beyond double precision (every
// step would fail after all its sub-steps), and 10^9 Newton iterations per sub-step never end.
void check_solver_section(const CaseFile& cs, ErrorList& errors);

}  // namespace ugs::mech
