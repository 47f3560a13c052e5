#include <algorithm>
#include <cmath>

#include "ugs/formats/horizon_grid.hpp"

namespace ugs {

GridPoint horizon_grid_value(const HorizonGrid& g, double x, double y, double& value) {
  const double a = g.rotation_deg * (M_PI / 180.0), ca = std::cos(a), sa = std::sin(a);
  const double nxm = static_cast<double>(g.nx - 1), nym = static_cast<double>(g.ny - 1);
  constexpr double eps = 1e-9;
  const double ex = x - g.x0, ey = y - g.y0;
  const double pu = (ca * ex + sa * ey) / g.dx, pv = (-sa * ex + ca * ey) / g.dy;
  if (!(pu >= -eps && pu <= nxm + eps && pv >= -eps && pv <= nym + eps)) return GridPoint::Outside;
  const double u = std::clamp(pu, 0.0, nxm), v = std::clamp(pv, 0.0, nym);
  const std::size_t i0 = std::min(static_cast<std::size_t>(std::floor(u)), g.nx - 2);
  const std::size_t j0 = std::min(static_cast<std::size_t>(std::floor(v)), g.ny - 2);
  const double fx = u - static_cast<double>(i0), fy = v - static_cast<double>(j0);
  const double w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
  const double z[4] = {g.at(i0, j0), g.at(i0 + 1, j0), g.at(i0, j0 + 1), g.at(i0 + 1, j0 + 1)};
  double sum = 0;
  for (int c = 0; c < 4; ++c) {
    if (w[c] == 0) continue;  // a node without weight may be undefined
    if (std::isnan(z[c])) return GridPoint::Undefined;
    sum += w[c] * z[c];
  }
  value = sum;
  return GridPoint::Value;
}

}  // namespace ugs
