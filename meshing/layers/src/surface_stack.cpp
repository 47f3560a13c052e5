#include "ugs/meshing/surface_stack.hpp"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs {

std::string thousands(std::size_t n) {
  const std::string digits = std::to_string(n);
  std::string s;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) s += ',';
    s += digits[i];
  }
  return s;
}

StackReport apply_stack_rules(std::vector<std::vector<double>>& z, const std::vector<StackSurface>& surfaces,
                              const Plan& plan, const StackRules& rules) {
  const std::size_t ns = z.size(), nc = plan.num_columns();
  if (surfaces.size() != ns) throw std::invalid_argument("apply_stack_rules: one description per surface");
  StackReport r;
  r.truncated.assign(ns, 0);
  r.clamped.assign(ns, 0);
  r.max_clamp.assign(ns, 0.0);
  r.collapsed.assign(ns ? ns - 1 : 0, 0);

  for (std::size_t k = 0; k < ns; ++k) {
    if (!surfaces[k].unconformity) continue;
    for (std::size_t j = k + 1; j < ns; ++j)
      for (std::size_t c = 0; c < nc; ++c)
        if (z[j][c] > z[k][c]) {
          z[j][c] = z[k][c];
          ++r.truncated[j];
        }
  }

  for (std::size_t i = 1; i < ns; ++i) {
    std::size_t bad = 0, first = 0;
    double worst = 0;
    for (std::size_t c = 0; c < nc; ++c) {
      const double excess = z[i][c] - z[i - 1][c];
      if (excess <= 0) continue;
      if (excess > rules.tolerance) {
        if (bad++ == 0) first = c;
        worst = std::max(worst, excess);
        continue;
      }
      z[i][c] = z[i - 1][c];
      ++r.clamped[i];
      r.max_clamp[i] = std::max(r.max_clamp[i], excess);
    }
    if (bad)
      throw InputError(surfaces[i].where,
                       fmt::format("surface '{}' lies above '{}' at {} columns, by up to {:.2f} m (first: plan node {} "
                                   "at x={:.2f}, y={:.2f}, {:.2f} m above); the order rule lowers it only within {} m",
                                   surfaces[i].name, surfaces[i - 1].name, thousands(bad), worst, plan.node_tags[first],
                                   plan.xy[first][0], plan.xy[first][1], z[i][first] - z[i - 1][first], rules.tolerance));
  }

  for (std::size_t u = 0; u + 1 < ns; ++u)
    for (std::size_t c = 0; c < nc; ++c) {
      if (z[u][c] - z[u + 1][c] < rules.min_thickness) z[u + 1][c] = z[u][c];
      r.collapsed[u] += z[u + 1][c] == z[u][c];
    }
  return r;
}

}  // namespace ugs
