// HexLocator: points in corner-point cells with non-planar faces tile space without gap or
// overlap, ties go to the lowest index, pinched cells hold nothing, and map coordinates of 5e6 m
// give the same answers as local ones.
#include <gtest/gtest.h>

#include <random>

#include "ugs/meshing/cell_locator.hpp"

using namespace ugs;

namespace {

// n x n x n cells on a lattice whose interior nodes are jittered (shared by neighbours, so faces
// are twisted bilinear patches), shifted by `shift`.
std::vector<HexCorners> jittered(int n, double jitter, const Point3& shift, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  auto id = [&](int i, int j, int k) { return (k * (n + 1) + j) * (n + 1) + i; };
  std::vector<Point3> node((n + 1) * (n + 1) * (n + 1));
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        Point3 p{double(i), double(j), double(k)};
        if (i > 0 && i < n && j > 0 && j < n && k > 0 && k < n)
          for (auto& c : p) c += u(rng);
        else
          p[2] += 0.3 * u(rng) * (i > 0 && i < n && j > 0 && j < n);  // twisted top and bottom
        for (int d = 0; d < 3; ++d) p[d] += shift[d];
        node[id(i, j, k)] = p;
      }
  std::vector<HexCorners> cells;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        cells.push_back({node[id(i, j, k)], node[id(i + 1, j, k)], node[id(i, j + 1, k)], node[id(i + 1, j + 1, k)],
                         node[id(i, j, k + 1)], node[id(i + 1, j, k + 1)], node[id(i, j + 1, k + 1)], node[id(i + 1, j + 1, k + 1)]});
  return cells;
}

}  // namespace

TEST(HexLocator, BoxCellsAndTies) {
  std::vector<HexCorners> cells;
  for (int i = 0; i < 2; ++i)
    cells.push_back({Point3{double(i), 0, 0}, {i + 1.0, 0, 0}, {double(i), 1, 0}, {i + 1.0, 1, 0}, {double(i), 0, 1}, {i + 1.0, 0, 1},
                     {double(i), 1, 1}, {i + 1.0, 1, 1}});
  const HexLocator loc(cells);
  EXPECT_EQ(loc.locate({0.5, 0.5, 0.5}), 0);
  EXPECT_EQ(loc.locate({1.5, 0.2, 0.9}), 1);
  EXPECT_EQ(loc.locate({1.0, 0.5, 0.5}), 0);  // on the shared face: the lower index
  EXPECT_EQ(loc.locate({2.5, 0.5, 0.5}), -1);
  EXPECT_EQ(loc.locate({0.5, 0.5, 1.0001}), -1);
  EXPECT_EQ(loc.extent(), (std::array<double, 6>{0, 0, 0, 2, 1, 1}));
}

TEST(HexLocator, TwistedCellsTileWithoutGapOrOverlap) {
  const auto cells = jittered(4, 0.25, {0, 0, 0}, 7);
  const HexLocator all(cells);
  std::vector<HexLocator> one;
  for (const auto& c : cells) one.emplace_back(std::span<const HexCorners>(&c, 1));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.3, 3.7);  // inside the jittered block
  std::size_t found = 0;
  for (int n = 0; n < 4000; ++n) {
    const Point3 p{u(rng), u(rng), u(rng)};
    int holders = 0, first = -1;
    for (std::size_t c = 0; c < cells.size(); ++c)
      if (one[c].locate(p) == 0) {
        ++holders;
        if (first < 0) first = static_cast<int>(c);
      }
    ASSERT_EQ(holders, 1) << "point " << p[0] << " " << p[1] << " " << p[2];
    ASSERT_EQ(all.locate(p), first);
    ++found;
  }
  EXPECT_EQ(found, 4000u);
}

TEST(HexLocator, MapCoordinatesKeepPrecision) {
  const Point3 shift{612345.678, 5012345.678, -1234.5};
  const auto local = jittered(3, 0.2, {0, 0, 0}, 11), map = jittered(3, 0.2, shift, 11);
  const HexLocator a(local), b(map);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.5, 3.5);
  std::vector<Point3> pl, pm;
  for (int n = 0; n < 2000; ++n) {
    const Point3 p{u(rng), u(rng), u(rng)};
    pl.push_back(p);
    pm.push_back({p[0] + shift[0], p[1] + shift[1], p[2] + shift[2]});
  }
  EXPECT_EQ(a.locate(pl), b.locate(pm));
}

TEST(HexLocator, PinchedCellHoldsNothing) {
  // The middle layer has zero thickness: points on it go to a neighbour, never to the pinched cell.
  std::vector<HexCorners> cells;
  const double z[4] = {0, 1, 1, 2};
  for (int k = 0; k < 3; ++k)
    cells.push_back({Point3{0, 0, z[k]}, {1, 0, z[k]}, {0, 1, z[k]}, {1, 1, z[k]}, {0, 0, z[k + 1]}, {1, 0, z[k + 1]}, {0, 1, z[k + 1]},
                     {1, 1, z[k + 1]}});
  const HexLocator loc(cells);
  EXPECT_EQ(loc.locate({0.5, 0.5, 0.5}), 0);
  EXPECT_EQ(loc.locate({0.5, 0.5, 1.0}), 0);
  EXPECT_EQ(loc.locate({0.5, 0.5, 1.5}), 2);
}
