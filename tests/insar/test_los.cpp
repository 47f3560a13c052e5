// Line-of-sight projection against values computed by hand (los.hpp states the convention):
// l = (-sin(theta) cos(alpha), sin(theta) sin(alpha), cos(theta)), ground to satellite.
#include <gtest/gtest.h>

#include <cmath>

#include "ugs/formats/error.hpp"
#include "ugs/insar/los.hpp"

using namespace ugs::insar;

TEST(Los, AscendingGeometry) {
  // Sentinel-1-like ascending pass: flying north-north-west (heading -10 deg), looking east, 35 deg.
  const LosGeometry asc{"asc", 35, -10};
  const auto l = los_unit_vector(asc);
  EXPECT_NEAR(l[0], -0.5648625, 1e-7);  // -sin35 cos(-10)
  EXPECT_NEAR(l[1], -0.0996005, 1e-7);  //  sin35 sin(-10)
  EXPECT_NEAR(l[2], 0.8191520, 1e-7);   //  cos35
  // sin and cos come from libm, whose last bit differs between its CPU variants (glibc picks FMA code
  // paths at run time): each component carries a few ulps, so |l|^2 = 1 to ~12 u, not to 1e-15.
  EXPECT_NEAR(l[0] * l[0] + l[1] * l[1] + l[2] * l[2], 1.0, 1e-14);
  // 10 mm uplift is seen as +8.19 mm towards the satellite; 10 mm eastward as -5.65 mm.
  EXPECT_NEAR(los_displacement({0, 0, 0.010}, asc), 0.0081915204, 1e-10);
  EXPECT_NEAR(los_displacement({0.010, 0, 0}, asc), -0.0056486252, 1e-10);
  EXPECT_NEAR(los_displacement({0.002, -0.001, 0.004}, asc), 0.002 * -0.5648625215 - 0.001 * -0.0996005029 + 0.004 * 0.8191520443, 1e-12);
}

TEST(Los, DescendingGeometry) {
  // Descending pass: flying south-south-west (heading 190 deg), looking west, 40 deg.
  const LosGeometry desc{"desc", 40, 190};
  const auto l = los_unit_vector(desc);
  EXPECT_NEAR(l[0], 0.6330222, 1e-7);
  EXPECT_NEAR(l[1], -0.1116189, 1e-7);
  EXPECT_NEAR(l[2], 0.7660444, 1e-7);
  // Eastward motion approaches a satellite that sees from the east.
  EXPECT_NEAR(los_displacement({0.010, 0, 0}, desc), 0.006330222, 1e-9);
  EXPECT_NEAR(los_displacement({0, 0, -0.005}, desc), -0.003830222, 1e-9);
}

TEST(Los, ZenithAndParsing) {
  const auto l = los_unit_vector(0, 123);
  EXPECT_NEAR(l[2], 1.0, 1e-15);
  const auto g = parse_los_geometry("asc", "34.5/-12.25", "--ascending");
  EXPECT_DOUBLE_EQ(g.incidence_deg, 34.5);
  EXPECT_DOUBLE_EQ(g.heading_deg, -12.25);
  EXPECT_THROW(parse_los_geometry("asc", "34.5", "--ascending"), ugs::InputError);
  EXPECT_THROW(parse_los_geometry("asc", "95/10", "--ascending"), ugs::InputError);
  EXPECT_THROW(parse_los_geometry("asc", "abc/10", "--ascending"), ugs::InputError);
}
