// V10 (shared/docs/VERIFICATION.md): Sobol' indices of the Ishigami function
// f = sin x1 + a sin^2 x2 + b x3^4 sin x1, x_i uniform on [-pi, pi], a = 7, b = 0.1, through the same
// path as an ensemble: the spec file, make_design, then sobol_indices. Closed forms (Ishigami &
// Homma 1990; Sobol' & Levitan 1999): S1 = 0.3139, S2 = 0.4424, S3 = 0; ST1 = 0.5576, ST2 = 0.4424,
// ST3 = 0.2437. Each must lie inside the library's 95 % interval, and the interval must be narrow.
#include <gtest/gtest.h>

#include <cmath>

#include "run_tool.hpp"
#include "ugs/ensemble/design.hpp"
#include "ugs/ensemble/statistics.hpp"

using namespace ugs;
using namespace ugs::ensemble;

namespace {

double ishigami(const std::vector<double>& x) {
  const double a = 7, b = 0.1;
  return std::sin(x[0]) + a * std::sin(x[1]) * std::sin(x[1]) + b * std::pow(x[2], 4) * std::sin(x[0]);
}

// The closed forms from the variance decomposition.
struct Exact {
  double s[3], st[3];
};
Exact exact() {
  const double a = 7, b = 0.1, pi = M_PI;
  const double v1 = 0.5 * std::pow(1 + b * std::pow(pi, 4) / 5, 2);
  const double v2 = a * a / 8;
  const double v13 = b * b * std::pow(pi, 8) * (1.0 / 18 - 1.0 / 50);
  const double v = v1 + v2 + v13;
  return {{v1 / v, v2 / v, 0}, {(v1 + v13) / v, v2 / v, v13 / v}};
}

}  // namespace

TEST(Ishigami, SobolIndicesInsideTheirConfidenceIntervals) {
  const auto dir = test::temp_dir("ishigami");
  test::spit(dir / "ishigami.toml", R"([design]
method = "sobol"
members = 20480   # N = 4096 base points x (3 + 2)
seed = 7

[[parameter]]
path = "x1"
distribution = "uniform"
lower = -3.141592653589793
upper = 3.141592653589793

[[parameter]]
path = "x2"
distribution = "uniform"
lower = -3.141592653589793
upper = 3.141592653589793

[[parameter]]
path = "x3"
distribution = "uniform"
lower = -3.141592653589793
upper = 3.141592653589793
)");
  const EnsembleSpec spec = read_spec((dir / "ishigami.toml").string());
  const Design design = make_design(spec);
  ASSERT_EQ(design.base, 4096u);
  ASSERT_EQ(design.x.size(), 20480u);
  std::vector<double> y;
  for (const auto& x : design.x) y.push_back(ishigami(x));
  const SobolIndices s = sobol_indices(design, y, std::vector<bool>(y.size(), true));
  const Exact e = exact();
  EXPECT_NEAR(e.s[0], 0.3139, 5e-5);
  EXPECT_NEAR(e.st[2], 0.2437, 5e-5);
  for (int j = 0; j < 3; ++j) {
    std::printf("x%d: S1 %.4f [%.4f, %.4f] (exact %.4f)  ST %.4f [%.4f, %.4f] (exact %.4f)\n", j + 1, s.first[j],
                s.first_low[j], s.first_high[j], e.s[j], s.total[j], s.total_low[j], s.total_high[j], e.st[j]);
    EXPECT_LE(s.first_low[j], e.s[j]);
    EXPECT_GE(s.first_high[j], e.s[j]);
    EXPECT_LE(s.total_low[j], e.st[j]);
    EXPECT_GE(s.total_high[j], e.st[j]);
    EXPECT_LT(s.first_high[j] - s.first_low[j], 0.1);
    EXPECT_LT(s.total_high[j] - s.total_low[j], 0.1);
  }
  // Failed members drop their base point whole; the estimate stays inside the intervals.
  std::vector<bool> ok(y.size(), true);
  for (std::size_t i = 0; i < 4096; i += 50) ok[2 * 4096 + i] = false;  // a pick-freeze member of x1
  const SobolIndices t = sobol_indices(design, y, ok);
  EXPECT_EQ(t.base, 4096u - 82u);
  for (int j = 0; j < 3; ++j) {
    EXPECT_LE(t.first_low[j], e.s[j]);
    EXPECT_GE(t.first_high[j], e.s[j]);
  }
  std::filesystem::remove_all(dir);
}
