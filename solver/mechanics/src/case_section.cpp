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
  if (!(cs.newton_tolerance >= 1e-14 && cs.newton_tolerance < 1))
    errors.add(cs.where("solver.tolerance"), fmt::format("[solver] tolerance = {}: outside [1e-14, 1) (a relative residual ||r|| / ||r_0||)",
                                    cs.newton_tolerance));
  if (cs.max_newton_iterations > 1000)
    errors.add(cs.where("solver.max_newton_iterations"), fmt::format("[solver] max_newton_iterations = {}: more than 1000 (a step takes 2-25)",
                                    cs.max_newton_iterations));
}

}  // namespace ugs::mech
