#include "ugs/contact/case_section.hpp"

#include <fmt/format.h>

namespace ugs::contact {

const std::vector<std::pair<std::string, SaddleSolver>>& fault_solver_names() {
  static const std::vector<std::pair<std::string, SaddleSolver>> n{
      {"auto", SaddleSolver::Auto}, {"mumps", SaddleSolver::Mumps}, {"fieldsplit", SaddleSolver::FieldSplit}};
  return n;
}

void check_fault_section(const CaseFile& cs, ErrorList& errors) {
  bool known = false;
  std::string list;
  for (const auto& [name, value] : fault_solver_names()) {
    known = known || name == cs.fault_solver;
    list += (list.empty() ? "" : ", ") + name;
  }
  if (!known) errors.add(cs.where("solver.fault_solver"), fmt::format("[solver] fault_solver = \"{}\": must be one of {}", cs.fault_solver, list));
}

}  // namespace ugs::contact
