// The field split's preconditioner-reuse rule and MUMPS' factorisation-reuse rule
// (solver/contact/src/saddle_reuse.hpp): counts of setups over sequences of solves.
#include <gtest/gtest.h>

#include <vector>

#include "saddle_reuse.hpp"

using ugs::contact::detail::FactorReuse;
using ugs::contact::detail::SaddleReuse;

namespace {
// A solve through the rule: keeps when it may, else counts a setup; `its` iterations over `decades`.
void solve(SaddleReuse& r, const std::vector<double>& sig, int its, double decades, bool allowed = true) {
  const bool keep = r.keep(allowed, sig);
  r.record(its, decades, !keep, sig);
}
}  // namespace

TEST(SaddleReuse, UnchangedActiveSetKeepsOneSetupOverManySolves) {
  SaddleReuse r;
  const std::vector<double> stick{1.0, 1.0, 1.0, 0.5, 0.5, 0.5};
  solve(r, stick, 100, 8.0);  // 12.5 per decade: the baseline
  for (int i = 0; i < 9; ++i) solve(r, stick, 4, 1.0);  // a good first iterate: 4 per decade
  EXPECT_EQ(r.setups(), 1u);
}

TEST(SaddleReuse, ChangedActiveSetForcesASetup) {
  SaddleReuse r;
  const std::vector<double> stick{1.0, 1.0, 1.0}, slip{1.0, 0.0, 0.0};
  solve(r, stick, 100, 8.0);
  solve(r, stick, 5, 1.0);
  EXPECT_EQ(r.setups(), 1u);
  EXPECT_FALSE(r.keep(true, slip));
  solve(r, slip, 90, 8.0);
  EXPECT_EQ(r.setups(), 2u);
  EXPECT_TRUE(r.keep(true, slip));
}

TEST(SaddleReuse, DegradedRateForcesASetupAndTheOptionOffSetsUpEverySolve) {
  SaddleReuse r;
  const std::vector<double> s{1.0};
  solve(r, s, 80, 8.0);          // 10 per decade
  solve(r, s, 120, 8.0);         // 15: within max(1.5 x 10, 10 + 3) = 15, still kept
  EXPECT_EQ(r.setups(), 1u);
  solve(r, s, 128, 8.0);         // 16 per decade: beyond, the next solve sets up
  EXPECT_FALSE(r.keep(true, s));
  solve(r, s, 80, 8.0);
  EXPECT_EQ(r.setups(), 2u);
  EXPECT_TRUE(r.keep(true, s));
  r.drop();                      // after a failure
  EXPECT_FALSE(r.keep(true, s));
  SaddleReuse off;
  for (int i = 0; i < 4; ++i) solve(off, s, 10, 8.0, false);
  EXPECT_EQ(off.setups(), 4u);
}

TEST(SaddleReuse, NewtonIterationsKeepTheHierarchyWhileTheRateHolds) {
  // Production months (virgin loading, 4-5 Newton solves each): the solves of a step and of the
  // steps after it keep one setup while the rate holds (until 2026-11-27 every solve of a
  // nonlinear step set up: 26 setups for 26 solves over the coarsened history's first 6 months).
  SaddleReuse r;
  const std::vector<double> s{1.0};
  const int month[4] = {98, 20, 6, 2};  // Newton's tolerance loosens: fewer iterations, fewer decades
  const double decades[4] = {8.0, 2.0, 1.0, 0.3};
  for (int step = 0; step < 6; ++step)
    for (int k = 0; k < 4; ++k) solve(r, s, month[k], decades[k]);
  EXPECT_EQ(r.setups(), 1u);
  solve(r, s, 200, 8.0);  // 25 per decade against 12.25 after the setup: the next solve sets up
  EXPECT_FALSE(r.keep(true, s));
  solve(r, s, 98, 8.0);
  EXPECT_EQ(r.setups(), 2u);
}

namespace {
// A solve through the factorisation rule: `its` GMRES iterations reducing the residual by `reduction`.
void factor_solve(FactorReuse& r, const std::vector<double>& sig, int its, double reduction, bool allowed = true) {
  const bool keep = r.keep(allowed, sig);
  r.record(its, reduction, !keep, sig);
}
}  // namespace

TEST(SaddleFactorReuse, KeptWhileTheActiveSetTheRateAndTheExtraIterationsHold) {
  FactorReuse r;
  const std::vector<double> stick{1.0, 1.0, 1.0}, slip{1.0, 0.0, 0.0};
  factor_solve(r, stick, 1, 1e-13);  // fresh factors: 1 iteration, 13 decades (0.077 per decade)
  for (int i = 0; i < 20; ++i) factor_solve(r, stick, 1, 1e-12);  // as good as fresh: nothing extra
  // 0.56 per decade: (0.56 - 0.08) 9 x 3 = 13 <= 55 ahead, 4.3 extra per solve: 12 more solves keep
  for (int i = 0; i < 12; ++i) factor_solve(r, stick, 5, 1e-9);
  EXPECT_EQ(r.setups(), 1u);
  EXPECT_TRUE(r.keep(true, stick));
  factor_solve(r, stick, 5, 1e-9);  // 13 x 4.3 = 56 extra iterations since the factorisation: refactor
  EXPECT_FALSE(r.keep(true, stick));
  factor_solve(r, stick, 1, 1e-13);
  EXPECT_EQ(r.setups(), 2u);
  EXPECT_FALSE(r.keep(true, slip));  // a pair started slipping
  factor_solve(r, slip, 1, 1e-13);
  EXPECT_EQ(r.setups(), 3u);
  factor_solve(r, slip, 20, 1e-9);  // 2.2 per decade: (2.2 - 0.08) 9 x 3 = 58 > 55 refactorisation's worth
  EXPECT_FALSE(r.keep(true, slip));
  factor_solve(r, slip, 1, 1e-13);
  EXPECT_EQ(r.setups(), 4u);
  EXPECT_TRUE(r.keep(true, slip));
  r.drop();  // after a failure
  EXPECT_FALSE(r.keep(true, slip));
  FactorReuse off;
  for (int i = 0; i < 4; ++i) factor_solve(off, stick, 1, 1e-13, false);
  EXPECT_EQ(off.setups(), 4u);
  // A kept factorisation gets 10 iterations per decade of the tolerance.
  EXPECT_EQ(FactorReuse::budget(1e-8), 80);
  EXPECT_EQ(FactorReuse::budget(1e-3), 30);
}
