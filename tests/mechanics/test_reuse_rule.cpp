// The preconditioner reuse rule of ugs-solve (reuse_rule.hpp, docs/mechanics.md): a pure function
// of iteration counts and residual reductions, so the same input gives the same
// decisions — and the same numbers — whatever the machine's load (issue 20: the rule compared
// measured seconds, and a busy machine flipped it).
#include <cmath>

#include <gtest/gtest.h>

#include "ugs/mechanics/reuse_rule.hpp"

using namespace ugs::mech;

TEST(ReuseRule, ARefactorizationCostsTensOfSolveIterations) {
  // CHOLMOD on 5,265 to 112,545 unknowns: 55-59 solve iterations per factorization (measured).
  EXPECT_GE(kRefactorIterations, 40.0);
  EXPECT_LE(kRefactorIterations, 70.0);
}

TEST(ReuseRule, FactorizationKeptWhileItsExtraIterationsCostLessThanARefactor) {
  // As fast as right after the factorization: kept.
  EXPECT_TRUE(keep_factorization(3.0, 3.0, 8.0, 10.0, 3.0));
  EXPECT_TRUE(keep_factorization(3.0, 2.0, 8.0, 10.0, 3.0));
  // 1 iteration per decade more over 8 decades and 3 solves: 24 extra iterations.
  EXPECT_TRUE(keep_factorization(3.0, 4.0, 8.0, 24.0, 3.0));
  EXPECT_FALSE(keep_factorization(3.0, 4.0, 8.0, 23.9, 3.0));
  // Counts that are not numbers never keep it.
  EXPECT_FALSE(keep_factorization(3.0, NAN, 8.0, 100.0, 3.0));
  // The same counts give the same decision every time (nothing else is an input).
  for (int k = 0; k < 1000; ++k) ASSERT_FALSE(keep_factorization(3.0, 4.0, 8.0, 23.9, 3.0));
}

TEST(ReuseRule, MultigridKeptWithinOneAndAHalfTimesItsFirstRate) {
  EXPECT_TRUE(keep_multigrid(10.0, 15.0));
  EXPECT_FALSE(keep_multigrid(10.0, 15.1));
  EXPECT_TRUE(keep_multigrid(2.0, 5.0));  // few iterations: 3 more are allowed
  EXPECT_FALSE(keep_multigrid(2.0, 5.1));
}
