// The case-file settings of the fault contact, named and checked here: the names of the
// saddle-point solvers live here only (the case file's [solver] fault_solver and ugs-solve's
// --fault-solver read them); every problem is added to `errors`.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "ugs/contact/contact.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/error.hpp"

namespace ugs::contact {

const std::vector<std::pair<std::string, SaddleSolver>>& fault_solver_names();

void check_fault_section(const CaseFile& cs, ErrorList& errors);

}  // namespace ugs::contact
