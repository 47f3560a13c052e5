// Issue 43: the fault cut's band collapse made a flat tetrahedron at the thesis scale (two nodes of
// one plan column, two of another: four coplanar points whose rounding left a volume of 7.8e-11 m3)
// and ugs-solve refused the mesh. The smallest dihedral angle said 180 deg for it (its faces turned
// "away from" the opposite vertex by rounding only), so the collapse counted it as an improvement,
// and a signed volume "> 0" let it through. These tests hold the measures the cut and ugs-meshgen
// rely on to ugs-solve's test (solver/fem/src/tet4.cpp: |det| <= 1e-14 scale^3).
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "cut_band_improvement.hpp"
#include "ugs/formats/mesh.hpp"
#include "ugs/meshing/box_mesh.hpp"
#include "ugs/meshing/mesh_quality.hpp"

namespace {

using ugs::Point3;

// The tetrahedron of the issue, with the coordinates ugs-meshgen wrote (m, EPSG:32632): nodes 0 and
// 2 on one vertical line, 1 and 3 on another, so the four lie in one vertical plane.
const std::array<Point3, 4> kFlat = {Point3{680265.58217572048, 4953799.9010711536, -5608.2043764951413},
                                     Point3{680200.63076449838, 4953850.6999114258, -5611.4985535719297},
                                     Point3{680265.58217572048, 4953799.9010711536, -4574.1131660950687},
                                     Point3{680200.63076449838, 4953850.6999114258, -5061.6924881102368}};

double solver_ratio(const std::array<Point3, 4>& x) {  // tet4.cpp's arithmetic, written out
  double a[3], b[3], c[3], s = 0;
  for (int k = 0; k < 3; ++k) {
    a[k] = x[1][k] - x[0][k];
    b[k] = x[2][k] - x[0][k];
    c[k] = x[3][k] - x[0][k];
    s += std::abs(a[k]) + std::abs(b[k]) + std::abs(c[k]);
  }
  const double det = a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  return std::abs(det) / (s * s * s);
}

TEST(CutDegenerate, IssueTetrahedronIsFlatForTheSolverAndForTheCut) {
  const auto& x = kFlat;
  const double vol = ugs::tet_signed_volume(x[0], x[1], x[2], x[3]);
  EXPECT_GT(vol, 0.0);   // rounding: positive, which let the collapse keep it
  EXPECT_LT(vol, 1e-9);  // m3, among tetrahedra of 1e4 .. 1e9 m3
  EXPECT_LE(solver_ratio(x), 1e-14);
  EXPECT_EQ(ugs::tet_volume_ratio(x[0], x[1], x[2], x[3]), solver_ratio(x));
  EXPECT_TRUE(ugs::tet_is_degenerate(x[0], x[1], x[2], x[3]));
  // The measure the collapse and the smoothing raise: 0, not 180.
  EXPECT_EQ(ugs::min_dihedral_angle_deg(x[0], x[1], x[2], x[3]), 0.0);
  EXPECT_FALSE(ugs::kept_volume(x[0], x[1], x[2], x[3]));
}

TEST(CutDegenerate, KeptVolumeAcceptsTheThinTetrahedraOfTheLayering) {
  // A 0.5 m pinch-out layer under a 2 km plan triangle (the thinnest the strata keep): well clear.
  const Point3 a{0, 0, 0}, b{2000, 0, 0}, c{0, 2000, 0}, d{700, 700, 0.5};
  EXPECT_TRUE(ugs::kept_volume(a, b, c, d));
  EXPECT_GT(ugs::tet_volume_ratio(a, b, c, d), 1e3 * ugs::kKeptRatio);
  EXPECT_FALSE(ugs::kept_volume(a, c, b, d));  // inverted
  // The same lifted by a hair: positive, but within the margin of the solver's limit.
  const Point3 e{700, 700, 1e-9};
  EXPECT_GT(ugs::tet_signed_volume(a, b, c, e), 0.0);
  EXPECT_FALSE(ugs::kept_volume(a, b, c, e));
  EXPECT_NEAR(ugs::min_dihedral_angle_deg(a, b, c, d), std::atan(0.5 / 700) * 180 / M_PI, 1e-6);
}

TEST(CutDegenerate, QualityReportNamesTheFirstDegenerateTetrahedron) {
  // A box of 2 x 1 x 1 cells (12 tetrahedra), then tetrahedron 7 replaced by the issue's flat one.
  ugs::Mesh m = ugs::make_box_mesh({ugs::linspace(0, 2, 2), ugs::linspace(0, 1, 1), ugs::linspace(0, 1, 1), {}});
  auto q = ugs::mesh_quality(m);
  ASSERT_GT(q.tetrahedra, 7u);
  EXPECT_EQ(q.degenerate, 0u);
  EXPECT_GT(q.min_dihedral_deg, 1.0);
  const auto first = static_cast<std::uint32_t>(m.nodes.size());
  for (const auto& x : kFlat) m.nodes.push_back(x);
  m.node_tags.resize(m.nodes.size());
  for (std::size_t i = 0; i < m.node_tags.size(); ++i) m.node_tags[i] = i + 1;
  for (auto& b : m.blocks)
    if (b.type == ugs::ElementType::Tetrahedron) {
      for (int k = 0; k < 4; ++k) b.nodes[4 * 7 + k] = first + static_cast<std::uint32_t>(k);
      break;
    }
  q = ugs::mesh_quality(m);
  EXPECT_EQ(q.degenerate, 1u);
  EXPECT_EQ(q.first_degenerate, 7u);
  EXPECT_EQ(q.inverted, 0u);
  EXPECT_EQ(q.min_dihedral_deg, 0.0);
}

}  // namespace
