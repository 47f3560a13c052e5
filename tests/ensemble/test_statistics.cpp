// Quantiles, exceedance and Morris effects against values known in closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "run_tool.hpp"
#include "ugs/ensemble/design.hpp"
#include "ugs/ensemble/morris.hpp"
#include "ugs/ensemble/statistics.hpp"

using namespace ugs;
using namespace ugs::ensemble;

TEST(EnsembleStatistics, QuantilesAndExceedance) {
  std::vector<double> v;
  for (int i = 100; i >= 0; --i) v.push_back(i);  // 0..100, any order
  const Quantiles q = quantiles(v);
  EXPECT_EQ(q.n, 101u);
  // OpenTURNS' empirical quantile: linear between order statistics placed at (k - 1/2) / n
  // (Hyndman & Fan 1996 type 5): position 0.1 * 101 - 0.5 = 9.6 in the sorted 0..100.
  EXPECT_NEAR(q.p10, 9.6, 1e-12);
  EXPECT_NEAR(q.p50, 50.0, 1e-12);
  EXPECT_NEAR(q.p90, 90.4, 1e-12);
  EXPECT_DOUBLE_EQ(q.mean, 50.0);
  EXPECT_DOUBLE_EQ(exceedance(v, 80.0), 21.0 / 101.0);
  EXPECT_DOUBLE_EQ(exceedance(v, 101.0), 0.0);
}

TEST(EnsembleStatistics, MorrisEffectsOfALinearAndAQuadraticTerm) {
  // y = 3 x1 + 0 x2 + x3^2 with x uniform on [0, 2]: a level step of Delta in probability is a step
  // of 2 Delta in x, so every effect of x1 is 6 (mu* 6, sigma 0), x2 has none, x3's vary.
  const auto dir = test::temp_dir("morris");
  test::spit(dir / "m.toml", R"([design]
method = "morris"
members = 40
levels = 4
seed = 5
[[parameter]]
path = "x1"
distribution = "uniform"
lower = 0.0
upper = 2.0
[[parameter]]
path = "x2"
distribution = "uniform"
lower = 0.0
upper = 2.0
[[parameter]]
path = "x3"
distribution = "uniform"
lower = 0.0
upper = 2.0
)");
  const Design d = make_design(read_spec((dir / "m.toml").string()));
  ASSERT_EQ(d.base, 10u);
  ASSERT_EQ(d.x.size(), 40u);
  std::vector<double> y;
  for (const auto& x : d.x) y.push_back(3 * x[0] + x[2] * x[2]);
  const MorrisEffects e = morris_effects(3, d.morris_factor, d.morris_delta, y, std::vector<bool>(y.size(), true));
  EXPECT_EQ(e.trajectories, 10u);
  EXPECT_NEAR(e.mu_star[0], 6.0, 1e-12);
  EXPECT_NEAR(e.sigma[0], 0.0, 1e-12);
  EXPECT_EQ(e.mu_star[1], 0.0);
  EXPECT_GT(e.mu_star[2], 0.5);
  // A failed member removes its trajectory.
  std::vector<bool> ok(y.size(), true);
  ok[5] = false;
  EXPECT_EQ(morris_effects(3, d.morris_factor, d.morris_delta, y, ok).trajectories, 9u);
  std::filesystem::remove_all(dir);
}
