// fault_output.hpp without a solve: the coordinates in a fault's own plane on hand-made faults
// (a planar fault striking N30E and dipping 60 degrees, the same fault described with its strike
// reversed, a horizontal fault), and fault names that would share a per-pair CSV file.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "ugs/contact/fault_output.hpp"
#include "ugs/formats/error.hpp"

using namespace ugs;
using namespace ugs::contact;

namespace {

using V3 = std::array<double, 3>;

// One fault of four nodes p(a, b) = o + a u + b v, (a, b) in {0, 300} x {0, 200}, two triangles,
// a node pair per node with the normal n.
FaultModel quad(const V3& o, const V3& u, const V3& v, const V3& n) {
  FaultModel fm;
  fm.faults.resize(1);
  fm.faults[0].name = std::string("Q");  // not = "Q": GCC 12 warns falsely (-Wrestrict) on that assignment
  const double ab[4][2] = {{0, 0}, {300, 0}, {300, 200}, {0, 200}};
  for (int i = 0; i < 4; ++i) {
    Point3 x;
    for (int k = 0; k < 3; ++k) x[k] = o[k] + ab[i][0] * u[k] + ab[i][1] * v[k];
    fm.surface.mesh.add_node(x, static_cast<std::uint64_t>(i + 1));
    fm.surface.node_pair.push_back(i);
    NodePair p;
    p.area = 1.0 + i;  // unequal areas: the mean normal is still n
    p.x = x;
    p.R = fault_frame({n[0], n[1], n[2]});
    fm.pairs.push_back(p);
  }
  fm.surface.triangles = {{0, 1, 2}, {0, 2, 3}};
  fm.surface.triangle_fault = {0, 0};
  return fm;
}

}  // namespace

TEST(FaultOutput, PlaneCoordinatesOfADippingFault) {
  // Strike N30E: s = (sin 30, cos 30, 0); dip 60 degrees towards N120E: v = cos 60 h - sin 60 e_z.
  const double d2r = M_PI / 180;
  const V3 s{std::sin(30 * d2r), std::cos(30 * d2r), 0}, h{std::cos(30 * d2r), -std::sin(30 * d2r), 0};
  const V3 v{std::cos(60 * d2r) * h[0], std::cos(60 * d2r) * h[1], -std::sin(60 * d2r)};
  const V3 n{s[1] * v[2] - s[2] * v[1], s[2] * v[0] - s[0] * v[2], s[0] * v[1] - s[1] * v[0]};
  const V3 o{681000, 4950000, -500};
  const FaultPlaneCoordinates c = fault_plane_coordinates(quad(o, s, v, n));
  ASSERT_EQ(c.along_strike.size(), 4u);
  const double a[4] = {0, 300, 300, 0}, b[4] = {0, 0, 200, 200};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(c.along_strike[i], a[i], 1e-6) << i;
    EXPECT_NEAR(c.down_dip[i], b[i], 1e-6) << i;
  }
  EXPECT_NEAR(c.dip_deg[0], 60.0, 1e-9);
  EXPECT_NEAR(c.strike[0][0], s[0], 1e-12);
  EXPECT_NEAR(c.strike[0][1], s[1], 1e-12);
  // The same fault with its strike vector reversed and its normal flipped: the strike still points
  // east, so the distances run from the same (south-west) end.
  const V3 ms{-s[0], -s[1], 0}, mn{-n[0], -n[1], -n[2]};
  const V3 o2{o[0] + 300 * s[0], o[1] + 300 * s[1], o[2]};
  const FaultPlaneCoordinates r = fault_plane_coordinates(quad(o2, ms, v, mn));
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(r.along_strike[i], 300 - a[i], 1e-6) << i;
    EXPECT_NEAR(r.down_dip[i], b[i], 1e-6) << i;
  }
  EXPECT_NEAR(r.strike[0][0], s[0], 1e-12);
}

TEST(FaultOutput, PlaneCoordinatesOfAHorizontalFault) {
  // No strike: along_strike = x - x_min, down_dip = y_max - y.
  const FaultPlaneCoordinates c = fault_plane_coordinates(quad({100, 200, -800}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}));
  const double a[4] = {0, 300, 300, 0}, b[4] = {200, 200, 0, 0};
  for (int i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(c.along_strike[i], a[i]) << i;
    EXPECT_DOUBLE_EQ(c.down_dip[i], b[i]) << i;
  }
  EXPECT_EQ(c.dip_deg[0], 0.0);
}

TEST(FaultOutput, FaultNamesSharingAFileAreRefused) {
  EXPECT_EQ(fault_file_name("back thrust/south"), "back_thrust_south");
  EXPECT_EQ(fault_file_name("local-1.b_2"), "local-1.b_2");
  FaultModel fm;
  fm.faults.resize(2);
  fm.faults[0].name = "a b";
  fm.faults[1].name = "a_b";
  try {
    FaultOutput out("", "", fm, {}, "/nonexistent/p_");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("faults 'a b' and 'a_b' would both write /nonexistent/p_a_b.csv"), std::string::npos)
        << e.what();
  }
  // Without per-pair CSVs the names do not matter.
  EXPECT_NO_THROW(FaultOutput("", "", fm, {}, ""));
}
