// The names of the solver choices, each list owned by the library that uses it (mechanics:
// linear solvers and partition methods; contact: saddle-point solvers), looked up here for the
// tool's options and the driver.
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ugs/contact/case_section.hpp"
#include "ugs/mechanics/case_section.hpp"

namespace ugs::driver {

template <class E>
using Names = std::vector<std::pair<std::string, E>>;

using contact::fault_solver_names;
using mech::linear_solver_names;
using mech::partition_names;

// The value named `s`, or nullopt.
template <class E>
std::optional<E> lookup(const Names<E>& names, std::string_view s) {
  for (const auto& [n, v] : names)
    if (n == s) return v;
  return std::nullopt;
}

}  // namespace ugs::driver
