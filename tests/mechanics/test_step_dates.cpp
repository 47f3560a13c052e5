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

// Turning windows (steps = "turning-windows"): a turn is secured by any date where its element is
// within the tolerance of its extreme; the fewest dates that meet every window.
namespace {

// The windows of the turns of a one-element history (both passes over it, as turning_points makes).
ugs::mech::TurnWindows windows_of(const std::vector<std::vector<double>>& h, double tolerance) {
  TurningPoints tp(tolerance);
  for (const auto& dp : h) tp.add(dp);
  ugs::mech::TurnWindows tw(tp.turn_list(), 1, tolerance);
  for (const auto& dp : h) tw.add(dp);
  return tw;
}

}  // namespace

TEST(TurnWindows, AFlatLowHasAWideWindow) {
  const std::vector<std::vector<double>> h{{0}, {-2e6}, {-3e6}, {-3e6 + 500}, {-3e6 + 800}, {-1e6}, {-1e6}};
  TurningPoints tp(1e3);
  for (const auto& dp : h) tp.add(dp);
  ASSERT_EQ(tp.turn_list().size(), 1u);
  EXPECT_EQ(tp.turn_list()[0].date, 2);
  EXPECT_EQ(tp.turn_list()[0].last_within, 4);
  const ugs::mech::TurnWindows tw = windows_of(h, 1e3);
  ASSERT_EQ(tw.windows().size(), 1u);
  EXPECT_EQ(tw.windows()[0].first, 2);
  EXPECT_EQ(tw.windows()[0].last, 4);
}

TEST(TurnWindows, AWindowStartsBeforeTheLowWhenThePressureIsAlreadyWithinIt) {
  // -3e6 + 900 on date 1 is within 1 kPa of the low -3e6 on date 2: the window is [1, 2].
  const std::vector<std::vector<double>> h{{0}, {-3e6 + 900}, {-3e6}, {-1e6}};
  const ugs::mech::TurnWindows tw = windows_of(h, 1e3);
  ASSERT_EQ(tw.windows().size(), 1u);
  EXPECT_EQ(tw.windows()[0].first, 1);
  EXPECT_EQ(tw.windows()[0].last, 2);
}

TEST(FewestDates, OneDateServesOverlappingWindowsAndForcedDatesCountFirst) {
  using ugs::mech::fewest_dates;
  const std::vector<ugs::mech::TurnWindow> w{{1, 4}, {3, 6}, {5, 8}};
  EXPECT_EQ(fewest_dates(w, std::vector<char>(10, 0)), (std::vector<char>{0, 0, 0, 0, 1, 0, 0, 0, 1, 0}));
  // Date 5 is stepped on anyway: it meets [3, 6] and [5, 8]; [1, 4] still needs one.
  std::vector<char> forced(10, 0);
  forced[5] = 1;
  EXPECT_EQ(fewest_dates(w, forced), (std::vector<char>{0, 0, 0, 0, 1, 1, 0, 0, 0, 0}));
}

TEST(FewestDates, LaggingRingsNeedFewerDatesAndEveryLowIsSecured) {
  // 40 rings, each a slow cosine low lagging the previous by one date: 40 turns. Near its low a
  // ring stays within 10 kPa for 3 dates (2.74 kPa x dates^2), so a date serves about 3 rings.
  const double tol = 1e4;
  std::vector<std::vector<double>> h;
  for (int k = 0; k < 120; ++k) {
    std::vector<double> dp;
    for (int r = 0; r < 40; ++r) dp.push_back(-2e6 * (1 - std::cos(6.283185307179586 * (k - r) / 120.0)));
    h.push_back(dp);
  }
  TurningPoints tp(tol);
  for (const auto& dp : h) tp.add(dp);
  ugs::mech::TurnWindows tw(tp.turn_list(), 40, tol);
  for (const auto& dp : h) tw.add(dp);
  const auto take = ugs::mech::fewest_dates(tw.windows(), std::vector<char>(h.size(), 0));
  int turns = 0, dates = 0;
  for (std::size_t k = 0; k < h.size(); ++k) turns += tp.turns()[k], dates += take[k];
  EXPECT_GT(turns, 30);
  EXPECT_LE(dates, turns / 2);
  for (const auto& t : tp.turn_list()) {
    bool secured = false;
    for (std::size_t k = 0; k < h.size(); ++k)
      secured = secured || (take[k] && h[k][static_cast<std::size_t>(t.element)] <= t.value + tol);
    EXPECT_TRUE(secured) << "element " << t.element << " low on date " << t.date;
  }
}
