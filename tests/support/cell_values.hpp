// Per-cell inputs of a mechanics model for library-level tests, e.g. the pressure change of a
// depleted block.
#pragma once
#include <cstddef>
#include <functional>
#include <vector>

#include "ugs/mechanics/model.hpp"

namespace ugs::test {

// `value` on the tetrahedra whose centroid lies in `in`, 0 elsewhere.
inline std::vector<double> cell_values_in(const mech::Model& model, const std::function<bool(const Point3&)>& in, double value) {
  std::vector<double> v(model.tets.size(), 0.0);
  for (std::size_t e = 0; e < v.size(); ++e) {
    Point3 c{0, 0, 0};
    for (auto n : model.tets[e])
      for (int d = 0; d < 3; ++d) c[d] += 0.25 * model.x[n][d];
    if (in(c)) v[e] = value;
  }
  return v;
}

}  // namespace ugs::test
