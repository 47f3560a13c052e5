#include "ugs/mechanics/case_section.hpp"

#include <fmt/format.h>

namespace ugs::mech {

const std::vector<std::pair<std::string, LinearSolver>>& linear_solver_names() {
  static const std::vector<std::pair<std::string, LinearSolver>> n{
      {"cg-hypre", LinearSolver::CgHypre}, {"cg-gamg", LinearSolver::CgGamg}, {"mumps", LinearSolver::Mumps},
      {"cholmod", LinearSolver::Cholmod}};
  return n;
}

const std::vector<std::pair<std::string, PartitionMethod>>& partition_names() {
  static const std::vector<std::pair<std::string, PartitionMethod>> n{{"ptscotch", PartitionMethod::PtScotch},
                                                                      {"rcb", PartitionMethod::Rcb}};
  return n;
}

void check_solver_section(const CaseFile& cs, ErrorList& errors) {
  bool known = false;
  std::string list;
  for (const auto& [name, value] : linear_solver_names()) {
    known = known || name == cs.linear_solver;
    list += (list.empty() ? "" : ", ") + name;
  }
  if (!known) errors.add(cs.where("solver.linear_solver"), fmt::format("[solver] linear_solver = \"{}\": must be one of {}", cs.linear_solver, list));
}

}  // namespace ugs::mech
