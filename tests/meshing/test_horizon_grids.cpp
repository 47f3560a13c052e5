// Issue 40 item 1: one analytic surface written in every horizon format (GeoTIFF through GDAL,
// ZMAP+ through GDAL's ZMap driver, IRAP classic ASCII, CPS-3 ASCII, GOCAD TSurf) gives the same
// elevations at the plan's points to 1e-9 m, unrotated and rotated, with undefined nodes, through
// the stratigraphy file too; and the bad inputs (a ZMAP+ header that disagrees with its values, a
// grid without CRS or in another one, TSurf horizons that are not surfaces) are refused.
//
// What the comparison proves: the node values are multiples of 1/1024 m printed exactly, so every
// format carries the same doubles; a grid format then agrees with the closed-form bilinear
// interpolant of those nodes (computed here from the grid's own axes) at every point, which is
// what geo::sample_raster gives between pixel centres. A TSurf made of the grid's cells split into
// two triangles is linear on each triangle: it equals the bilinear interpolant on the cells' sides
// and at the nodes for any surface, and everywhere for a surface whose node values have no twist
// (z = F(i) + G(j)); inside a cell of a twisted surface the two differ by design, so it is compared
// there only in the second case.
#include <gtest/gtest.h>

#include <fstream>

#include <fmt/format.h>

#include "geo_fixtures.hpp"
#include "horizon_writers.hpp"
#include "input_error.hpp"
#include "run_tool.hpp"
#include "ugs/meshing/gdal_util.hpp"
#include "ugs/meshing/geodata.hpp"
#include "ugs/meshing/horizon_grids.hpp"
#include "ugs/meshing/strata.hpp"

using namespace ugs;
using ugs::test::input_error_of;
using ugs::test::NodeGrid;

namespace {

constexpr double X0 = 684000.0, Y0 = 4950000.0;

double q(double v) { return std::round(v * 1024.0) / 1024.0; }  // exact in every format's text

// The surface: not bilinear, twisted in every cell.
double wavy(double x, double y) {
  return -1000.0 + 0.01 * (x - X0) + 20.0 * std::sin((x - X0) / 500.0) * std::cos((y - Y0) / 700.0);
}

NodeGrid make_grid(double rotation, const std::function<double(const NodeGrid&, int, int)>& f) {
  NodeGrid g{X0 + 100.0, Y0 + 50.0, 250.0, 200.0, rotation, 41, 31, {}};
  g.z.resize(static_cast<std::size_t>(g.nx) * g.ny);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) g.z[static_cast<std::size_t>(j) * g.nx + i] = q(f(g, i, j));
  return g;
}

NodeGrid wavy_grid(double rotation) {
  return make_grid(rotation, [](const NodeGrid& g, int i, int j) {
    const auto p = g.point(i, j);
    return wavy(p[0], p[1]);
  });
}

// No twist: F(i) + G(j), bilinear = linear on both triangles of every cell.
NodeGrid untwisted_grid(double rotation) {
  return make_grid(rotation, [](const NodeGrid&, int i, int j) {
    return q(-1000.0 + 2.5 * i + 15.0 * std::sin(i / 4.0)) + q(-0.75 * j + 9.0 * std::cos(j / 3.0));
  });
}

// Points by their fractional node coordinates (u, v): inside cells, on the cells' sides, on nodes.
struct Points {
  std::vector<std::array<double, 2>> uv;
  std::vector<XY> xy;
  std::vector<char> on_sides;  // on a cell side or a node: where TSurf equals bilinear for any surface
};

Points points_on(const NodeGrid& g) {
  Points p;
  std::uint64_t s = 12345;
  auto rnd = [&] {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(s >> 11) / 9007199254740992.0;
  };
  auto add = [&](double u, double v, bool side) {
    p.uv.push_back({u, v});
    p.xy.push_back(g.point(u, v));
    p.on_sides.push_back(side);
  };
  for (int k = 0; k < 400; ++k) add(rnd() * (g.nx - 1), rnd() * (g.ny - 1), false);
  for (int k = 0; k < 100; ++k) add(std::floor(rnd() * g.nx), rnd() * (g.ny - 1), true);
  for (int k = 0; k < 100; ++k) add(rnd() * (g.nx - 1), std::floor(rnd() * g.ny), true);
  for (int i = 0; i < g.nx; i += 5)
    for (int j = 0; j < g.ny; j += 3) add(i, j, true);
  add(g.nx - 1, g.ny - 1, true);
  return p;
}

// The closed-form bilinear interpolant of the nodes at (u, v).
double bilinear(const NodeGrid& g, double u, double v) {
  const int i = std::min(static_cast<int>(std::floor(u)), g.nx - 2), j = std::min(static_cast<int>(std::floor(v)), g.ny - 2);
  const double fx = u - i, fy = v - j;
  return (1 - fx) * (1 - fy) * g.at(i, j) + fx * (1 - fy) * g.at(i + 1, j) + (1 - fx) * fy * g.at(i, j + 1) +
         fx * fy * g.at(i + 1, j + 1);
}

struct Dir {
  ugs::test::TempDir dir{"horizon-grids"};
  std::string path(const std::string& name) const { return (dir.path / name).string(); }
};

std::string utm() { return geo::crs_wkt("EPSG:32632", "test"); }

std::vector<double> sample(const std::string& path, const std::vector<XY>& xy) {
  if (path.ends_with(".tif")) {
    const auto r = geo::sample_raster(path, 1, xy, utm());
    EXPECT_TRUE(r.outside.empty() && r.nodata.empty()) << path;
    return r.values;
  }
  const auto r = geo::sample_horizon(path, utm(), xy, utm());
  EXPECT_TRUE(r.outside.empty() && r.undefined.empty()) << path;
  return r.values;
}

// Every format of `g` against the closed form; `tsurf_everywhere`: the TSurf too inside cells.
void expect_same_elevations(const NodeGrid& g, const std::vector<std::string>& formats, bool tsurf_everywhere) {
  Dir d;
  const Points p = points_on(g);
  double worst = 0;
  for (const auto& ext : formats) {
    const std::string file = d.path("top." + ext);
    if (ext == "tif") ugs::test::write_geotiff(file, g);
    if (ext == "zmap") ugs::test::write_zmap(file, g);
    if (ext == "irap") ugs::test::write_irap(file, g);
    if (ext == "cps") ugs::test::write_cps3(file, g);
    if (ext == "ts") ugs::test::write_tsurf(file, g);
    const auto z = sample(file, p.xy);
    ASSERT_EQ(z.size(), p.xy.size());
    std::size_t compared = 0;
    for (std::size_t k = 0; k < z.size(); ++k) {
      if (ext == "ts" && !tsurf_everywhere && !p.on_sides[k]) continue;
      const double want = bilinear(g, p.uv[k][0], p.uv[k][1]);
      ASSERT_NEAR(z[k], want, 1e-9) << ext << " at u=" << p.uv[k][0] << " v=" << p.uv[k][1];
      worst = std::max(worst, std::fabs(z[k] - want));
      ++compared;
    }
    EXPECT_GE(compared, 200u) << ext;
  }
  ::testing::Test::RecordProperty("max_abs_difference_m", fmt::format("{:.3g}", worst));
}

}  // namespace

TEST(HorizonGrids, OneSurfaceGivesTheSameElevationsInEveryFormat) {
  expect_same_elevations(wavy_grid(0), {"tif", "zmap", "irap", "cps", "ts"}, false);
}

TEST(HorizonGrids, RotatedGridGivesTheSameElevations) {
  expect_same_elevations(wavy_grid(30), {"tif", "irap", "ts"}, false);
  expect_same_elevations(wavy_grid(-117.5), {"tif", "irap", "ts"}, false);
}

TEST(HorizonGrids, TsurfEqualsBilinearInsideCellsWithoutTwist) {
  expect_same_elevations(untwisted_grid(0), {"tif", "zmap", "irap", "cps", "ts"}, true);
  expect_same_elevations(untwisted_grid(30), {"tif", "irap", "ts"}, true);
}

TEST(HorizonGrids, NodesAreWhereTheHeaderPutsThem) {
  // At the nodes every format gives the node value itself: no half-cell shift (GDAL's ZMap driver
  // without ZMAP_PIXEL_IS_POINT spreads the grid over one cell less).
  const NodeGrid g = wavy_grid(0);
  Dir d;
  std::vector<XY> nodes;
  std::vector<double> want;
  for (int i = 0; i < g.nx; i += 4)
    for (int j = 0; j < g.ny; j += 5) nodes.push_back(g.point(i, j)), want.push_back(g.at(i, j));
  ugs::test::write_zmap(d.path("n.zmap"), g);
  const auto z = sample(d.path("n.zmap"), nodes);
  for (std::size_t k = 0; k < z.size(); ++k) EXPECT_EQ(z[k], want[k]);
  // The same file as a `raster` (GDAL's generic path, ZMAP_PIXEL_IS_POINT set by gdal_init).
  const auto r = geo::sample_raster(d.path("n.zmap"), 1, nodes, utm());
  ASSERT_TRUE(r.outside.empty() && r.nodata.empty());
  for (std::size_t k = 0; k < z.size(); ++k) EXPECT_NEAR(r.values[k], want[k], 1e-9);
}

TEST(HorizonGrids, UndefinedNodesAreReportedWhereTheirCellsAre) {
  NodeGrid g = wavy_grid(0);
  g.z[static_cast<std::size_t>(10) * g.nx + 20] = std::nan("");  // node (20, 10)
  Dir d;
  const Points p = points_on(g);
  std::vector<std::uint32_t> want;
  for (std::size_t k = 0; k < p.uv.size(); ++k) {
    const double u = p.uv[k][0], v = p.uv[k][1];
    if (std::fabs(u - 20) < 1 && std::fabs(v - 10) < 1) want.push_back(static_cast<std::uint32_t>(k));
  }
  ASSERT_FALSE(want.empty());
  for (const std::string ext : {"zmap", "irap", "cps"}) {
    const std::string file = d.path("u." + ext);
    if (ext == "zmap") ugs::test::write_zmap(file, g);
    if (ext == "irap") ugs::test::write_irap(file, g);
    if (ext == "cps") ugs::test::write_cps3(file, g);
    const auto r = geo::sample_horizon(file, utm(), p.xy, utm());
    EXPECT_EQ(r.undefined, want) << ext;
    EXPECT_TRUE(r.outside.empty()) << ext;
  }
  ugs::test::write_geotiff(d.path("u.tif"), g);
  EXPECT_EQ(geo::sample_raster(d.path("u.tif"), 1, p.xy, utm()).nodata, want);
  // The TSurf has no triangle there: those points are outside it.
  ugs::test::write_tsurf(d.path("u.ts"), g);
  EXPECT_EQ(geo::sample_horizon(d.path("u.ts"), utm(), p.xy, utm()).outside, want);
}

TEST(HorizonGrids, ZmapWhoseHeaderDisagreesWithItsValuesIsRefusedNamingTheLine) {
  const NodeGrid g = wavy_grid(0);
  Dir d;
  ugs::test::write_zmap(d.path("ok.zmap"), g);
  std::vector<std::string> lines;
  {
    std::ifstream in(d.path("ok.zmap"));
    for (std::string l; std::getline(in, l);) lines.push_back(l);
  }
  auto write = [&](const std::string& name, const std::vector<std::string>& ls) {
    std::ofstream out(d.path(name));
    for (const auto& l : ls) out << l << "\n";
    return d.path(name);
  };
  auto fewer = lines;
  fewer.erase(fewer.begin() + 10);  // line 11, in column 1 (31 values: lines 7-13, the last with 1)
  EXPECT_NE(input_error_of([&] { geo::read_zmap_grid(write("fewer.zmap", fewer)); })
                .find("fewer.zmap:12: 1 value(s) where column 1 of 41 expects 5"),
            std::string::npos);
  auto more = lines;
  more.push_back(more.back());
  EXPECT_NE(input_error_of([&] { geo::read_zmap_grid(write("more.zmap", more)); })
                .find(fmt::format("more.zmap:{}: values after the last of the header's 41 columns of 31 rows",
                                  more.size())),
            std::string::npos);
  // A damaged field keeps its width: GDAL alone would read its leading digits (-21 for -2194.5).
  auto damaged = lines;
  damaged[6].replace(3, 10, "     -21\xff\xff");
  EXPECT_NE(input_error_of([&] { geo::read_zmap_grid(write("damaged.zmap", damaged)); })
                .find("damaged.zmap:7: field 1 '-21\\xff\\xff")
                ,
            std::string::npos);
  auto nodot = lines;
  nodot[7].replace(0, 24, std::string(20, ' ') + "-999");
  EXPECT_NE(input_error_of([&] { geo::read_zmap_grid(write("nodot.zmap", nodot)); })
                .find("nodot.zmap:8: field 1 '-999' is not a finite number with a decimal point"),
            std::string::npos);
  auto rows = lines;
  rows[3] = "32" + rows[3].substr(2);  // 32 rows in the header, 31 in each column
  EXPECT_NE(input_error_of([&] { geo::read_zmap_grid(write("rows.zmap", rows)); }).find("rows.zmap:13: 1 value(s) where column 1 of 41 expects 2"),
            std::string::npos);
}

// ---- through the stratigraphy file -------------------------------------------------------------

namespace {

// A plan of (n+1)^2 columns over the grid's inside, not aligned with its cells.
Plan plan_over(const NodeGrid& g, int n = 12) {
  Plan p;
  p.source = "plan.msh";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      p.node_tags.push_back(p.xy.size() + 1);
      p.xy.push_back(g.point(0.37 + (g.nx - 1.8) * i / n, 0.21 + (g.ny - 1.6) * j / n));
    }
  for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(n); ++j)
    for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(n); ++i) {
      const std::uint32_t a = j * (n + 1) + i;
      p.triangles.push_back({a, a + 1, a + n + 2});
      p.triangles.push_back({a, a + n + 2, a + n + 1});
    }
  for (std::size_t t = 0; t < p.triangles.size(); ++t) p.triangle_tags.push_back(t + 1);
  return p;
}

NodeGrid shifted(NodeGrid g, double dz) {
  for (double& v : g.z) v += dz;
  return g;
}

std::string strata_text(const std::string& file_crs, const std::vector<std::string>& surfaces) {
  std::string s = file_crs.empty() ? "" : "crs = \"" + file_crs + "\"\n";
  s += "[[surface]]\nname = \"top\"\nconstant = 0.0\n";
  for (std::size_t k = 0; k < surfaces.size(); ++k) s += fmt::format("[[surface]]\nname = \"s{}\"\n{}\n", k + 1, surfaces[k]);
  for (std::size_t k = 0; k < surfaces.size(); ++k) s += fmt::format("[[unit]]\nname = \"u{}\"\nlayers = 1\n", k + 1);
  s += "[[material]]\nname = \"rock\"\nunits = [";
  for (std::size_t k = 0; k < surfaces.size(); ++k) s += fmt::format("{}\"u{}\"", k ? ", " : "", k + 1);
  return s + "]\n";
}

std::string write_text(const Dir& d, const std::string& name, const std::string& text) {
  std::ofstream(d.path(name)) << text;
  return d.path(name);
}

}  // namespace

TEST(HorizonGrids, StratigraphyFileTakesEveryFormat) {
  const NodeGrid g = untwisted_grid(0);
  Dir d;
  ugs::test::write_geotiff(d.path("s1.tif"), g);
  ugs::test::write_irap(d.path("s2.irap"), shifted(g, -100));
  ugs::test::write_cps3(d.path("s3.cps"), shifted(g, -200));
  ugs::test::write_zmap(d.path("s4.zmap"), shifted(g, -300));
  ugs::test::write_tsurf(d.path("s5.ts"), shifted(g, -400));
  const std::string strata = write_text(
      d, "strata.toml",
      strata_text("EPSG:32632", {"raster = \"s1.tif\"", "grid = \"s2.irap\"", "grid = \"s3.cps\"",
                                 "grid = \"s4.zmap\"", "grid = \"s5.ts\"\ncrs = \"EPSG:32632\""}));
  const Plan plan = plan_over(g);
  const PreparedModel pm = prepare_model(read_strata(strata), plan);
  ASSERT_EQ(pm.input.surfaces.size(), 6u);
  for (std::size_t c = 0; c < plan.num_columns(); ++c) {
    // The column's (u, v) in the grid: the plan is unrotated over it.
    const double u = (plan.xy[c][0] - g.x0) / g.dx, v = (plan.xy[c][1] - g.y0) / g.dy;
    const double want = bilinear(g, u, v);
    for (std::size_t k = 1; k <= 5; ++k)
      ASSERT_NEAR(pm.input.surfaces[k][c] + 100.0 * (k - 1), want, 1e-9) << "surface s" << k << " column " << c;
  }
}

TEST(HorizonGrids, AGridWithoutCrsOrInAnotherOneIsRefused) {
  const NodeGrid g = wavy_grid(0);
  Dir d;
  ugs::test::write_irap(d.path("top.irap"), g);
  const std::string none = write_text(d, "none.toml", strata_text("", {"grid = \"top.irap\""}));
  EXPECT_NE(input_error_of([&] { read_strata(none); })
                .find("none.toml:4: surface 's1': the grid file " + d.path("top.irap") +
                      " carries no CRS and none is named: add crs = \"EPSG:...\""),
            std::string::npos);
  // The plan in ETRS89-LAEA (EPSG:3035) coordinates, the grid's CRS not named: it lies kilometres away.
  const std::string wrong = write_text(d, "wrong.toml", strata_text("EPSG:3035", {"grid = \"top.irap\""}));
  Plan far = plan_over(g);
  for (auto& p : far.xy) p = {p[0] - X0 + 4.3e6, p[1] - Y0 + 2.4e6};
  EXPECT_NE(input_error_of([&] { prepare_model(read_strata(wrong), far); })
                .find("lies apart from every plan column"),
            std::string::npos);
  // Named: the plan's columns are transformed into the grid's CRS and sampled there.
  const std::string named = write_text(d, "named.toml", strata_text("EPSG:3035", {"grid = \"top.irap\"\ncrs = \"EPSG:32632\""}));
  Plan laea = plan_over(g);
  {
    const auto ct = geo::transformation(utm(), geo::crs_wkt("EPSG:3035", "t"), "t");
    for (auto& p : laea.xy) ct->Transform(1, &p[0], &p[1]);
  }
  const PreparedModel pm = prepare_model(read_strata(named), laea);
  const Plan utm_plan = plan_over(g);
  for (std::size_t c = 0; c < utm_plan.num_columns(); ++c) {
    const double u = (utm_plan.xy[c][0] - g.x0) / g.dx, v = (utm_plan.xy[c][1] - g.y0) / g.dy;
    ASSERT_NEAR(pm.input.surfaces[1][c], bilinear(g, u, v), 1e-4);  // after a round trip through PROJ
  }
}

TEST(HorizonGrids, UndefinedNodesUnderTheModelAreRefusedNamingTheColumns) {
  NodeGrid g = wavy_grid(0);
  g.z[static_cast<std::size_t>(15) * g.nx + 20] = std::nan("");
  Dir d;
  ugs::test::write_cps3(d.path("top.cps"), g);
  const std::string strata = write_text(d, "s.toml", strata_text("EPSG:32632", {"grid = \"top.cps\""}));
  const std::string e = input_error_of([&] { prepare_model(read_strata(strata), plan_over(g)); });
  EXPECT_NE(e.find("s.toml:5: surface 's1': " + d.path("top.cps") + " (CPS-3 ASCII, EPSG:32632) has undefined nodes under "),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("of the 169 plan columns"), std::string::npos) << e;
}

// ---- TSurf horizons that are not surfaces ------------------------------------------------------

namespace {

TriangulatedSurface soup(std::vector<std::array<double, 3>> v, std::vector<std::array<std::uint32_t, 3>> t) {
  TriangulatedSurface s;
  s.path = "h.ts";
  s.vertices = std::move(v);
  for (std::size_t k = 0; k < s.vertices.size(); ++k) s.vertex_line.push_back(10 + k);
  s.triangles = std::move(t);
  for (std::size_t k = 0; k < s.triangles.size(); ++k) s.triangle_line.push_back(100 + k);
  return s;
}

}  // namespace

TEST(HorizonGrids, TsurfThatIsNotAHorizonIsRefusedNamingTheTriangle) {
  const std::vector<std::array<double, 3>> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  EXPECT_NO_THROW(geo::check_horizon_surface(soup(square, {{0, 1, 2}, {0, 2, 3}})));
  auto v = square;
  v.push_back({0.5, -1, 1});
  EXPECT_NE(input_error_of([&] { geo::check_horizon_surface(soup(v, {{0, 1, 2}, {0, 2, 3}, {0, 1, 4}})); })
                .find("h.ts:102: inconsistent orientation: this triangle and its neighbour of line 100"),
            std::string::npos);
  v.push_back({0.5, -2, -1});
  EXPECT_NE(input_error_of([&] { geo::check_horizon_surface(soup(v, {{0, 1, 2}, {0, 2, 3}, {1, 0, 4}, {1, 0, 5}})); })
                .find("h.ts:103: non-manifold edge: the edge from the vertex of line 10 (0.00, 0.00, 0.00) to the vertex "
                      "of line 11 (1.00, 0.00, 0.00) is shared by 3 triangles (lines 100, 102, 103)"),
            std::string::npos);
  // Two squares touching at one corner (vertex 2).
  auto w = square;
  w.insert(w.end(), {{2, 1, 0}, {2, 2, 0}, {1, 2, 0}});
  EXPECT_NE(input_error_of([&] { geo::check_horizon_surface(soup(w, {{0, 1, 2}, {0, 2, 3}, {2, 4, 5}, {2, 5, 6}})); })
                .find("non-manifold vertex: the vertex of line 12 (1.00, 1.00, 0.00)"),
            std::string::npos);
  // A fold: the third triangle turns back over the first two.
  auto f = square;
  f.push_back({0.5, 0.5, 1});
  EXPECT_NE(input_error_of([&] { geo::check_horizon_surface(soup(f, {{0, 1, 2}, {0, 2, 3}, {2, 1, 4}})); })
                .find("h.ts:102: the surface folds over itself: 1 triangle(s) face down in plan while 2 face up"),
            std::string::npos);
  // A separate triangle facing up that pierces the square.
  auto x = square;
  x.insert(x.end(), {{0.2, 0.3, -1}, {0.8, 0.3, -1}, {0.5, 0.7, 1}});
  EXPECT_NE(input_error_of([&] { geo::check_horizon_surface(soup(x, {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}})); })
                .find("self-intersection: the triangle crosses the one of line 10"),
            std::string::npos);
}

TEST(HorizonGrids, TsurfCleaningIsSaid) {
  Dir d;
  const std::string ts = write_text(d, "m.ts",
                                    "GOCAD TSurf 1\nTFACE\nVRTX 1 0 0 -10\nVRTX 2 100 0 -10\nVRTX 3 0 100 -10\nTRGL 1 2 3\n"
                                    "TFACE\nVRTX 4 100 0 -10\nVRTX 5 100 100 -10\nVRTX 6 0 100 -10\nTRGL 4 5 6\nEND\n");
  const auto r = geo::sample_horizon(ts, utm(), std::vector<XY>{{50, 50}, {90, 90}}, utm());
  ASSERT_EQ(r.cleaned.size(), 1u);
  EXPECT_NE(r.cleaned[0].find("2 vertices at the same x, y, z as an earlier one were merged into it"), std::string::npos);
  EXPECT_EQ(r.values, (std::vector<double>{-10, -10}));
}
