// V2 (VERIFICATION.md): Geertsma's disk reservoir in a homogeneous isotropic half-space, through
// ugs-solve on 2 MPI processes. D = R = 1500 m (eta = 1, the tabulated A and B), h = 50 m,
// dp = -10 MPa, E = 10 GPa, nu = 0.25, alpha = 1; a quarter domain 10 R wide and 10 D deep with
// symmetry rollers (mech_make_case geertsma). Surface u_z and u_r within 5 % of their maxima for
// 0 <= r/R <= 2.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "solve_support.hpp"

using namespace ugs;

TEST(V2, GeertsmaDiskSurfaceDisplacement) {
  const auto dir = test::temp_dir("solve-v2");
  ASSERT_EQ(test::run(test::make_case() + " geertsma " + dir.string()).exit_code, 0);
  const std::string d = dir.string();
  const auto r = test::run(test::solve_cmd(2) + " " + d + "/mesh.msh --case " + d + "/case.toml --pressure " + d +
                           "/flow.h5 -o " + d + "/out.h5 -v");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  FieldSeriesReader top(d + "/out_top.h5");
  const auto x = top.coordinates();
  const Field u = top.node_field(top.steps().size() - 1, "u_mm");
  // The surface line y = 0 (a symmetry plane: u_y = 0 there, u_x = u_r).
  std::vector<std::array<double, 3>> line;  // x, u_x, u_z [m]
  for (std::size_t i = 0; i < x.size(); ++i)
    if (std::abs(x[i][1]) < 1e-9) line.push_back({x[i][0], u.values[3 * i] * 1e-3, u.values[3 * i + 2] * 1e-3});
  std::sort(line.begin(), line.end());
  ASSERT_GT(line.size(), 20u);
  auto at = [&](double xq, int k) {
    const auto it = std::lower_bound(line.begin(), line.end(), std::array<double, 3>{xq, -1e300, -1e300});
    if (it == line.begin()) return (*it)[k];
    const auto& b = *it;
    const auto& a = *(it - 1);
    const double w = (xq - a[0]) / (b[0] - a[0]);
    return (1 - w) * a[k] + w * b[k];
  };
  const double R = 1500, h = 50, dp = -10e6, E = 1e10, nu = 0.25;
  const double cm = (1 + nu) * (1 - 2 * nu) / (E * (1 - nu));
  const double scale = 2 * cm * (1 - nu) * dp * h;
  const double rho[] = {0, 0.5, 1, 1.5, 2};
  const double A[] = {0.2928932188, 0.2605531222, 0.1786811591, 0.0985328389, 0.05185272};
  const double B[] = {0, 0.0819773405, 0.1251515367, 0.1162240667, 0.0884955003};
  const double uz_max = std::abs(scale) * A[0], ur_max = std::abs(scale) * B[2];
  double worst_z = 0, worst_r = 0;
  for (int k = 0; k < 5; ++k) {
    const double uz = at(rho[k] * R, 2), ur = at(rho[k] * R, 1);
    std::printf("V2 r/R = %.1f: u_z %8.3f mm (Geertsma %8.3f), u_r %8.3f mm (Geertsma %8.3f)\n", rho[k], uz * 1e3,
                scale * A[k] * 1e3, ur * 1e3, scale * B[k] * 1e3);
    worst_z = std::max(worst_z, std::abs(uz - scale * A[k]) / uz_max);
    worst_r = std::max(worst_r, std::abs(ur - scale * B[k]) / ur_max);
  }
  std::printf("V2: worst error %.2f %% of max|u_z|, %.2f %% of max|u_r|\n", 100 * worst_z, 100 * worst_r);
  EXPECT_LT(worst_z, 0.05);
  EXPECT_LT(worst_r, 0.05);
  std::filesystem::remove_all(dir);
}
