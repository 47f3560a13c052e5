// The [solver] names the continuous solver takes from the case file, named and checked by the
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

// linear_solver is one of linear_solver_names(). The numbers of [solver] (tolerance, Newton
// iterations, sub-steps, turning-point tolerance) are range-checked in one place, where the case
// file is read (read_solver_numbers in formats/src/case_file.cpp), with file:line messages.
void check_solver_section(const CaseFile& cs, ErrorList& errors);

}  // namespace ugs::mech
