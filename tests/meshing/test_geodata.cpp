// Geodata as ugs-meshgen uses it: bilinear sampling of GeoTIFFs (exact on planes, no-data and
// coverage reported per point, reprojection of the points), OGR features with attribute filters
// reprojected to the model CRS, and point-in-polygon with holes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <fmt/format.h>

#include "geo_fixtures.hpp"
#include "run_tool.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/meshing/geodata.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {
double plane(double x, double y) { return -1200.0 + 0.01 * (x - 680000) - 0.004 * (y - 4950000); }
const test::Grid grid{680000, 4952000, 100, 30, 20};  // 3 x 2 km, pixel centres 680050 .. 682950
}  // namespace

class Geodata : public ::testing::Test {
protected:
  void SetUp() override { dir_ = test::temp_dir("geodata"); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string wkt32632() { return geo::crs_wkt("EPSG:32632", "test"); }
  fs::path dir_;
};

TEST_F(Geodata, BilinearSamplingIsExactOnPlanesAndReportsCoverage) {
  const auto tif = (dir_ / "plane.tif").string();
  test::write_raster(tif, grid, plane);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> ux(680050, 682950), uy(4950050, 4951950);
  std::vector<XY> pts;
  for (int i = 0; i < 100; ++i) pts.push_back({ux(rng), uy(rng)});
  pts.push_back({680020, 4951000});   // in the outer half pixel: clamped to the edge pixels
  pts.push_back({679990, 4951000});   // beyond the raster
  pts.push_back({681000, 4952010});   // beyond the raster
  const auto r = geo::sample_raster(tif, 1, pts, wkt32632());
  for (int i = 0; i < 100; ++i) EXPECT_NEAR(r.values[i], plane(pts[i][0], pts[i][1]), 1e-9);
  EXPECT_NEAR(r.values[100], plane(680050, 4951000), 1e-9);
  EXPECT_EQ(r.outside, (std::vector<std::uint32_t>{101, 102}));
  EXPECT_TRUE(r.nodata.empty());
  EXPECT_EQ(r.crs, "EPSG:32632");
}

TEST_F(Geodata, NoDataIsReportedOnlyWhereTheStencilTouchesIt) {
  const auto tif = (dir_ / "holes.tif").string();
  test::write_raster(tif, grid, plane, 32632, [](int i, int j) { return i == 10 && j == 5; });
  // Pixel (10, 5) has its centre at x = 681050, y = 4951450.
  const std::vector<XY> pts = {{681060, 4951440}, {681200, 4951450}, {681050, 4951450}, {682000, 4950500}};
  const auto r = geo::sample_raster(tif, 1, pts, wkt32632());
  EXPECT_EQ(r.nodata, (std::vector<std::uint32_t>{0, 2}));
  EXPECT_NEAR(r.values[1], plane(681200, 4951450), 1e-9);
  EXPECT_NEAR(r.values[3], plane(682000, 4950500), 1e-9);
  EXPECT_TRUE(std::isnan(r.values[0]));
}

TEST_F(Geodata, PointsAreReprojectedToTheRasterCrs) {
  const auto tif = (dir_ / "plane.tif").string();
  test::write_raster(tif, grid, plane);
  // The same places given in UTM 33N.
  const std::vector<XY> here = {{681234, 4951111}, {682500, 4950300}};
  std::vector<XY> there;
  for (const auto& p : here) {
    const auto q = test::transform_point(p[0], p[1], 32632, 32633);
    there.push_back({q[0], q[1]});
  }
  const auto r = geo::sample_raster(tif, 1, there, geo::crs_wkt("EPSG:32633", "test"));
  for (std::size_t i = 0; i < here.size(); ++i) EXPECT_NEAR(r.values[i], plane(here[i][0], here[i][1]), 1e-6);
}

TEST_F(Geodata, MissingFilesAndBandsAreInputErrors) {
  const std::vector<XY> pts = {{681000, 4951000}};
  EXPECT_THROW(geo::sample_raster((dir_ / "none.tif").string(), 1, pts, wkt32632()), InputError);
  const auto tif = (dir_ / "plane.tif").string();
  test::write_raster(tif, grid, plane);
  EXPECT_THROW(geo::sample_raster(tif, 2, pts, wkt32632()), InputError);
  EXPECT_THROW(geo::crs_wkt("EPSG:999999", "x"), InputError);
  EXPECT_THROW(geo::crs_wkt("EPSG:4326", "x"), InputError);  // not projected
}

TEST_F(Geodata, VectorFeaturesAreFilteredAndReprojected) {
  const auto gj = (dir_ / "traces.geojson").string();
  const auto a = test::transform_point(681000, 4951000, 32632, 4326);
  const auto b = test::transform_point(682000, 4951500, 32632, 4326);
  test::write_vector(gj, {{"Pool A", fmt::format("LINESTRING ({:.12f} {:.12f}, {:.12f} {:.12f})", a[0], a[1], b[0], b[1]), {{"top_m", -500}}},
                          {"Pool C", "POLYGON ((10 45, 10.1 45, 10.1 45.1, 10 45))", {}}},
                     4326);
  const auto all = geo::read_vector(gj, wkt32632());
  ASSERT_EQ(all.features.size(), 2u);
  EXPECT_EQ(geo::crs_label(all.source_crs), "EPSG:4326");
  const auto one = geo::read_vector(gj, wkt32632(), "name = 'Pool A'");
  ASSERT_EQ(one.features.size(), 1u);
  ASSERT_EQ(one.features[0].lines.size(), 1u);
  EXPECT_NEAR(one.features[0].lines[0][0][0], 681000, 1e-5);
  EXPECT_NEAR(one.features[0].lines[0][1][1], 4951500, 1e-5);
  EXPECT_EQ(one.features[0].number_of("top_m"), -500.0);
  EXPECT_EQ(one.features[0].text_of("name"), "Pool A");
  EXPECT_THROW(geo::read_vector(gj, wkt32632(), "nosuchfield = 3"), InputError);
  EXPECT_THROW(geo::read_vector((dir_ / "none.geojson").string(), wkt32632()), InputError);
}

TEST(PolygonSet, HolesAndSeveralPolygons) {
  geo::Polygon ring;
  ring.outer = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  ring.holes = {{{4, 4}, {6, 4}, {6, 6}, {4, 6}}};
  geo::Polygon tri;
  tri.outer = {{20, 0}, {30, 0}, {20, 10}};
  const geo::PolygonSet s({ring, tri});
  EXPECT_TRUE(s.contains({1, 1}));
  EXPECT_FALSE(s.contains({5, 5}));
  EXPECT_TRUE(s.contains({21, 1}));
  EXPECT_FALSE(s.contains({29, 9}));
  EXPECT_FALSE(s.contains({-1, 5}));
}

// The slab index visits only the edges whose y-range holds the point: the answer must be the
// every-edge even-odd rule's, also for points at a vertex's height and on the ring's y-range ends.
TEST(PolygonSet, SlabsGiveTheEveryEdgeAnswer) {
  auto every_edge = [](const std::vector<XY>& r, const XY& p) {
    bool in = false;
    for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
      if ((r[i][1] > p[1]) != (r[j][1] > p[1]) &&
          p[0] < (r[j][0] - r[i][0]) * (p[1] - r[i][1]) / (r[j][1] - r[i][1]) + r[i][0])
        in = !in;
    return in;
  };
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.2, 1.0);
  geo::Polygon star;  // a star-shaped ring of 301 vertices around (500, 500), radius 100 .. 500, and a hole
  for (int k = 0; k < 301; ++k) {
    const double a = 2 * 3.14159265358979 * k / 301, r = 500 * u(rng);
    star.outer.push_back({500 + r * std::cos(a), 500 + r * std::sin(a)});
  }
  star.outer.push_back({600, 500});  // a horizontal edge back to the start's height band
  star.holes = {{{480, 480}, {520, 480}, {520, 520}, {480, 520}}};
  const geo::PolygonSet s({star});
  std::uniform_real_distribution<double> w(-10, 1010);
  int inside = 0, checked = 0;
  for (int k = 0; k < 20000; ++k) {
    XY p{w(rng), w(rng)};
    if (k % 4 == 0) p[1] = star.outer[static_cast<std::size_t>(k / 4) % star.outer.size()][1];  // a vertex's height
    const bool expect = every_edge(star.outer, p) != every_edge(star.holes[0], p);
    ASSERT_EQ(s.contains(p), expect) << p[0] << " " << p[1];
    inside += expect;
    ++checked;
  }
  EXPECT_GT(inside, 2000);  // the test exercised both answers
  EXPECT_LT(inside, checked - 2000);
}
