// Checks of the counts, indices and values ugs-solve reads from files (pressure fields, restart
// states), before they are used: a bad file is exit 2 with one line naming the file, the dataset
// and the value, never an out-of-range access (issue 20: a tetrahedron holding node 4294967295 in
// a pressure file ended in PETSc's segfault handler; node indices and coordinates are checked by
// FieldSeriesReader itself). Private to ugs_mechanics.
#pragma once
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs::mech {

// Every value of a field is finite (and, with a bound, within [-bound, bound]).
inline void check_finite(const std::string& path, const std::string& what, const std::vector<double>& v, int components,
                         const char* expected, double bound = INFINITY) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i]))
      throw InputError(path, fmt::format("{}: value {} at entry {} is not a finite number (expected {})", what, v[i],
                                         i / static_cast<std::size_t>(components), expected));
    if (std::abs(v[i]) > bound)
      throw InputError(path, fmt::format("{}: value {:g} at entry {} is beyond +-{:g} (expected {})", what, v[i],
                                         i / static_cast<std::size_t>(components), bound, expected));
  }
}

// A pressure change beyond 1 GPa is no reservoir's (the lithostatic stress at 10 km is 0.23 GPa).
inline constexpr double kMaxPressureChangePa = 1e9;

}  // namespace ugs::mech
