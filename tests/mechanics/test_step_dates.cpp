// Turning-point steps (docs/mechanics.md): which dates of a pressure history a sigma-max run must
// step on.
#include <gtest/gtest.h>

#include <cmath>

#include "ugs/mechanics/step_dates.hpp"

using ugs::mech::TurningPoints;

namespace {

std::vector<char> turns(const std::vector<std::vector<double>>& dates, double tol = 1e3) {
  TurningPoints tp(tol);
  for (const auto& dp : dates) tp.add(dp);
  return tp.turns();
}

}  // namespace

TEST(TurningPoints, MonotonicDepletionHasNone) {
  EXPECT_EQ(turns({{0}, {-1e6}, {-2e6}, {-3e6}}), (std::vector<char>{0, 0, 0, 0}));
}

TEST(TurningPoints, TheLowBeforeARiseIsOne) {
  // Down to -3 MPa on date 2, up, then down to the same low (not lower): one turning point.
  EXPECT_EQ(turns({{0}, {-2e6}, {-3e6}, {-1e6}, {-2e6}, {-3e6}, {-1e6}}), (std::vector<char>{0, 0, 1, 0, 0, 0, 0}));
  // A deeper low later is another.
  EXPECT_EQ(turns({{0}, {-3e6}, {-1e6}, {-4e6}, {-2e6}}), (std::vector<char>{0, 1, 0, 1, 0}));
}

TEST(TurningPoints, APlateauAtTheLowCountsOnItsFirstDate) {
  EXPECT_EQ(turns({{0}, {-3e6}, {-3e6}, {-3e6}, {-1e6}}), (std::vector<char>{0, 1, 0, 0, 0}));
}

TEST(TurningPoints, PressureAboveTheStartIsUnloading) {
  // Injection above the initial pressure and back to it: never below the undisturbed state.
  EXPECT_EQ(turns({{0}, {2e6}, {0}, {3e6}, {-500}}), (std::vector<char>{0, 0, 0, 0, 0}));
}

TEST(TurningPoints, MovesWithinTheToleranceAreNone) {
  // Lows 0.5 kPa deeper than the secured one, and a rise of 0.5 kPa: below the 1 kPa tolerance.
  EXPECT_EQ(turns({{0}, {-3e6}, {-1e6}, {-3e6 - 500}, {-1e6}, {-4e6}, {-4e6 + 500}, {-5e6}}),
            (std::vector<char>{0, 1, 0, 0, 0, 0, 0, 0}));
}

TEST(TurningPoints, EveryElementCounts) {
  // Element 0 turns on date 1, element 1 (lagging) on date 2.
  EXPECT_EQ(turns({{0, 0}, {-2e6, -1e6}, {-1e6, -2e6}, {0, -1e6}}), (std::vector<char>{0, 1, 1, 0}));
}

TEST(TurningPoints, ElementCountMustNotChange) {
  TurningPoints tp(1e3);
  tp.add({0, 0});
  EXPECT_THROW(tp.add({0}), std::logic_error);
}

namespace {

// The faulted model's rule (TurningRule::Extremes): every low and every high.
std::vector<char> extremes(const std::vector<std::vector<double>>& dates, double tol = 1e3) {
  TurningPoints tp(tol, ugs::mech::TurningRule::Extremes);
  for (const auto& dp : dates) tp.add(dp);
  return tp.turns();
}

}  // namespace

TEST(TurningPointExtremes, EveryLowAndHighOfACycleIsOne) {
  // Production, then cycles inside the envelope: NewLows keeps the first low only.
  const std::vector<std::vector<double>> h{{0}, {-2e6}, {-3e6}, {-1e6}, {-2e6}, {-3e6}, {-1e6}, {-2e6}};
  EXPECT_EQ(extremes(h), (std::vector<char>{0, 0, 1, 1, 0, 1, 1, 0}));
  EXPECT_EQ(turns(h), (std::vector<char>{0, 0, 1, 0, 0, 0, 0, 0}));
}

TEST(TurningPointExtremes, InjectionAboveTheStartCounts) {
  // A high above the undisturbed pressure is an extremum too (NewLows has none here).
  EXPECT_EQ(extremes({{0}, {2e6}, {0}, {3e6}, {-500}}), (std::vector<char>{0, 1, 1, 1, 0}));
}

TEST(TurningPointExtremes, PlateausAndMovesWithinTheTolerance) {
  // A plateau counts on its first date; a 0.5 kPa dip on a rise (tolerance 1 kPa) is no extremum.
  EXPECT_EQ(extremes({{0}, {-3e6}, {-3e6}, {-1e6}, {-1e6 - 500}, {0}, {-1e6}}), (std::vector<char>{0, 1, 0, 0, 0, 1, 0}));
}

TEST(TurningPointExtremes, ContainEveryNewLow) {
  // Lagging elements and cycles of growing depth: every date NewLows takes, Extremes takes too.
  std::vector<std::vector<double>> h;
  for (int k = 0; k < 60; ++k) {
    const double t = k / 12.0;
    h.push_back({-1e6 * t - 2e6 * std::sin(6.283 * t), -1e6 * t - 2e6 * std::sin(6.283 * (t - 0.2)), 0.0});
  }
  const auto lows = turns(h), all = extremes(h);
  int n_lows = 0, n_all = 0;
  for (std::size_t k = 0; k < h.size(); ++k) {
    if (lows[k]) {
      EXPECT_TRUE(all[k]) << "date " << k;
    }
    n_lows += lows[k];
    n_all += all[k];
  }
  EXPECT_GT(n_lows, 0);
  EXPECT_GT(n_all, n_lows);
}
