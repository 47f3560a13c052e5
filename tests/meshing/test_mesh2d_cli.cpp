// ugs-mesh2d as users run it: a box or polygon domain, a refinement polygon with its target size,
// a reservoir trace, a fault and a section (written by the test with OGR). The plan must cover the
// domain exactly, carry region:/trace:/fault:/section: groups, have every constraint line as mesh
// edges along the input lines (in their direction), respect the sizes, and reproject inputs given
// in another CRS. Bad input exits 2 with one line and no output.
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <set>

#include <fmt/format.h>

#include "geo_fixtures.hpp"
#include "run_tool.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/plan.hpp"

namespace fs = std::filesystem;
using namespace ugs;

namespace {

double seg_distance(const XY& p, const XY& a, const XY& b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double t = std::clamp(((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
  return std::hypot(a[0] + t * dx - p[0], a[1] + t * dy - p[1]);
}

class Mesh2dCli : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = test::temp_dir("mesh2d");
    test::write_vector(p("refine.geojson").string(),
                       {{"reservoir", "POLYGON ((682000 4951000, 684000 4951000, 684000 4952500, 682000 4952500, 682000 4951000))",
                         {{"size_m", 100}}}});
    test::write_vector(p("traces.geojson").string(),
                       {{"Pool A", "POLYGON ((682500 4951500, 683500 4951400, 683600 4952200, 682600 4952300, 682500 4951500))", {}}});
    test::write_vector(p("faults.geojson").string(),
                       {{"f1", "LINESTRING (680500 4950500, 683000 4952000, 685500 4953500)",
                         {{"top_m", -500}, {"bottom_m", -5000}, {"dip_deg", 60}, {"dip_dir_deg", 15}}},
                        {"f2", "LINESTRING (689000 4950500, 690000 4951000)", {}}});  // outside: ignored
    test::write_vector(p("sections.geojson").string(), {{"A-A", "LINESTRING (685000 4950200, 681000 4953800)", {}}});
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path p(const std::string& f) const { return dir_ / f; }
  static std::string tool() { return test::tool("ugs-mesh2d"); }

  void expect_bad(const std::string& args, const std::string& fragment) {
    const auto out = p("bad.msh");
    const auto r = test::run(tool() + " " + args + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(std::regex_match(r.err, std::regex("^ugs-mesh2d: error: [^\n]+\n$"))) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << "missing '" << fragment << "' in: " << r.err;
    EXPECT_FALSE(fs::exists(out));
  }

  fs::path dir_;
};

}  // namespace

TEST_F(Mesh2dCli, GradedPlanWithRegionsAndConstraintLines) {
  const auto out = p("plan.msh");
  const auto r = test::run(tool() + " --box 680000/686000/4950000/4954000 --hmax 800 --grading 0.3 --refine " +
                           p("refine.geojson").string() + " --trace " + p("traces.geojson").string() + " --fault " +
                           p("faults.geojson").string() + " --section " + p("sections.geojson").string() + " -o " +
                           out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("outside the domain; ignored"), std::string::npos) << r.err;  // f2
  const Mesh m = read_msh(out.string());
  const Plan plan = plan_from_mesh(m, "plan");  // valid: no inverted, duplicate or overlapping triangles

  for (const auto& [dim, name] : std::vector<std::pair<int, std::string>>{
           {2, "region:domain"}, {2, "region:reservoir"}, {2, "region:Pool A"}, {1, "trace:Pool A"},
           {1, "fault:f1"}, {1, "section:A-A"}})
    EXPECT_NE(m.find_physical(dim, name), nullptr) << name;
  EXPECT_EQ(m.find_physical(1, "fault:f2"), nullptr);

  // The triangles tile the box.
  double area = 0;
  for (std::size_t t = 0; t < plan.triangles.size(); ++t) area += plan.area(t);
  EXPECT_NEAR(area, 6000.0 * 4000.0, 1e-6 * 24e6);

  // Sizes: fine inside the refinement, coarser far away, never beyond hmax (with gmsh's slack).
  double max_in = 0, max_all = 0;
  for (std::size_t t = 0; t < plan.triangles.size(); ++t) {
    const auto& tri = plan.triangles[t];
    double longest = 0;
    for (int k = 0; k < 3; ++k) {
      const auto &a = plan.xy[tri[k]], &b = plan.xy[tri[(k + 1) % 3]];
      longest = std::max(longest, std::hypot(a[0] - b[0], a[1] - b[1]));
    }
    const XY c = plan.centroid(t);
    if (c[0] > 682100 && c[0] < 683900 && c[1] > 4951100 && c[1] < 4952400) max_in = std::max(max_in, longest);
    max_all = std::max(max_all, longest);
  }
  EXPECT_LT(max_in, 1.6 * 100);
  EXPECT_GT(max_all, 400.0);
  EXPECT_LT(max_all, 1.6 * 800);

  // Constraint lines are edges of the triangles, lie on the input lines and follow their direction.
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const auto& t : plan.triangles)
    for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
  const std::vector<XY> f1 = {{680500, 4950500}, {683000, 4952000}, {685500, 4953500}};
  const PlanLineGroup* g = plan.find_line_group("fault:f1");
  ASSERT_NE(g, nullptr);
  double length = 0;
  for (const auto& [a, b] : g->edges) {
    EXPECT_TRUE(edges.count(std::minmax(a, b)));
    for (auto c : {a, b})
      EXPECT_LT(std::min(seg_distance(plan.xy[c], f1[0], f1[1]), seg_distance(plan.xy[c], f1[1], f1[2])), 1e-6);
    const double dx = plan.xy[b][0] - plan.xy[a][0], dy = plan.xy[b][1] - plan.xy[a][1];
    EXPECT_GT(dx * 5000 + dy * 3000, 0.0);  // along the trace, from west to east
    length += std::hypot(dx, dy);
  }
  EXPECT_NEAR(length, 2 * std::hypot(2500.0, 1500.0), 1e-6);
  for (const auto& [a, b] : plan.find_line_group("section:A-A")->edges) EXPECT_TRUE(edges.count(std::minmax(a, b)));
  for (const auto& [a, b] : plan.find_line_group("trace:Pool A")->edges) EXPECT_TRUE(edges.count(std::minmax(a, b)));
  // The trace region is bounded by its outline: every Pool A triangle's centroid lies inside it.
  EXPECT_EQ(m.provenance.size(), 1u);
}

TEST_F(Mesh2dCli, InputsInAnotherCrsAreReprojected) {
  // A domain given in geographic coordinates, meshed in UTM 32N.
  std::string wkt = "POLYGON ((";
  const std::vector<XY> utm = {{680000, 4950000}, {684000, 4950000}, {684000, 4953000}, {680000, 4953000}, {680000, 4950000}};
  for (std::size_t i = 0; i < utm.size(); ++i) {
    const auto g = test::transform_point(utm[i][0], utm[i][1], 32632, 4326);
    wkt += fmt::format("{}{:.15f} {:.15f}", i ? ", " : "", g[0], g[1]);
  }
  test::write_vector(p("domain4326.geojson").string(), {{"field", wkt + "))", {{"size_m", 1000}}}}, 4326);
  const auto out = p("plan.msh");
  const auto r = test::run(tool() + " --domain " + p("domain4326.geojson").string() + " --crs EPSG:32632 -v -o " +
                           out.string() + " --ascii");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Mesh m = read_msh(out.string());
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (const auto& x : m.nodes) xmin = std::min(xmin, x[0]), xmax = std::max(xmax, x[0]), ymin = std::min(ymin, x[1]), ymax = std::max(ymax, x[1]);
  EXPECT_NEAR(xmin, 680000, 1e-4);
  EXPECT_NEAR(xmax, 684000, 1e-4);
  EXPECT_NEAR(ymin, 4950000, 1e-4);
  EXPECT_NEAR(ymax, 4953000, 1e-4);
  EXPECT_NE(m.find_physical(2, "region:field"), nullptr);  // named by the feature, hmax from size_m
  // Without --crs the model CRS is the domain's, which is not projected: refused.
  const auto bad = test::run(tool() + " --domain " + p("domain4326.geojson").string() + " -o " + p("x.msh").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("not projected"), std::string::npos) << bad.err;
}

TEST_F(Mesh2dCli, SameInputSameBytes) {
  const std::string cmd = tool() + " --box 680000/686000/4950000/4954000 --hmax 700 --refine " + p("refine.geojson").string() +
                          " --fault " + p("faults.geojson").string() + " -q";
  ASSERT_EQ(test::run(cmd + " > " + p("a.msh").string()).exit_code, 0);  // same command line: it is recorded
  ASSERT_EQ(test::run(cmd + " > " + p("b.msh").string()).exit_code, 0);
  EXPECT_TRUE(test::slurp(p("a.msh")) == test::slurp(p("b.msh")));
}

TEST_F(Mesh2dCli, BadInputs) {
  expect_bad("--hmax 100", "give the domain");
  expect_bad("--box 1/0/0/1 --hmax 100", "--box: xmin/xmax/ymin/ymax must be increasing");
  expect_bad("--box 0/1/0 --hmax 100", "expected xmin/xmax/ymin/ymax");
  expect_bad("--box 0/1/a/1 --hmax 100", "'a' is not a number");
  expect_bad("--box 0/1000/0/1000", "--box: no size for the far field: give the far-field size (--hmax) or");
  expect_bad("--box 0/1000/0/1000 --hmax 100 --refine " + p("nope.geojson").string(), "nope.geojson: cannot open");
  expect_bad("--box 680000/686000/4950000/4954000 --hmax 500 --refine " + p("traces.geojson").string(),
             "has no 'size_m' field");
  expect_bad("--box 680000/686000/4950000/4954000 --hmax 500 --fault " + p("refine.geojson").string(),
             "is not a line");
  expect_bad("--box 680000/686000/4950000/4954000 --hmax 500 --crs EPSG:99999", "unknown coordinate reference system");
  expect_bad("--box 680000/686000/4950000/4954000 --hmax -5", "--hmax");
}

// Issue 20: a directory, a missing file or a file GDAL cannot read, given as a vector input: one
// line naming the file and what was expected (GDAL said "no reason given").
TEST_F(Mesh2dCli, DirectoryOrUnreadableVectorFile) {
  fs::create_directory(p("adir"));
  test::spit(p("text.geojson"), "not json at all\n");
  const std::string box = "--box 680000/686000/4950000/4954000 --hmax 500 ";
  expect_bad("--domain " + p("adir").string(),
             p("adir").string() + ": is a directory (expected a vector file: GeoJSON, GeoPackage, Shapefile, ...)");
  expect_bad(box + "--refine " + p("adir").string(), p("adir").string() + ": is a directory (expected a vector file");
  expect_bad(box + "--fault " + p("nope.geojson").string(), p("nope.geojson").string() + ": cannot open: No such file or directory");
  expect_bad(box + "--fault " + p("text.geojson").string(), p("text.geojson").string() + ": cannot open as a vector file: ");
}

namespace {
// Area of the triangles of a 2D physical group.
double group_area(const Mesh& m, const std::string& name) {
  const PhysicalGroup* g = m.find_physical(2, name);
  if (!g) return 0;
  double a = 0;
  for (const auto& b : m.blocks) {
    if (b.type != ElementType::Triangle) continue;
    const Entity* e = m.find_entity(b.entity_dim, b.entity_tag);
    if (!e || std::find(e->physicals.begin(), e->physicals.end(), g->tag) == e->physicals.end()) continue;
    for (std::size_t i = 0; i < b.size(); ++i) {
      const auto &A = m.nodes[b.element(i)[0]], &B = m.nodes[b.element(i)[1]], &C = m.nodes[b.element(i)[2]];
      a += 0.5 * std::abs((B[0] - A[0]) * (C[1] - A[1]) - (B[1] - A[1]) * (C[0] - A[0]));
    }
  }
  return a;
}
}  // namespace

// Issue 20: a refinement polygon with a hole, clipped by the domain (GEOS winds its hole against
// its outer ring) and overlapped by another polygon, lost its region group and refinement without a
// word (OpenCASCADE took the hole as area added). Its triangles now cover exactly its area, and the
// size inside is the refinement's.
TEST_F(Mesh2dCli, RefinementWithHoleOverlappedAndClippedKeepsItsRegion) {
  test::spit(p("ring.geojson"), R"({"type": "FeatureCollection",
"crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32632"}},
"features": [
{"type": "Feature", "properties": {"name": "ring", "size_m": 150}, "geometry": {"type": "Polygon", "coordinates": [
  [[679000, 4951000], [685000, 4951000], [685000, 4953000], [679000, 4953000], [679000, 4951000]],
  [[682000, 4951500], [684000, 4951500], [684000, 4952500], [682000, 4952500], [682000, 4951500]]]}},
{"type": "Feature", "properties": {"name": "over", "size_m": 300}, "geometry": {"type": "Polygon", "coordinates": [
  [[680500, 4950500], [682500, 4950500], [682500, 4952000], [680500, 4952000], [680500, 4950500]]]}}
]})");
  const auto out = p("ring.msh");
  const auto r = test::run(tool() + " -q --box 680000/686000/4950000/4954000 --hmax 800 --refine " + p("ring.geojson").string() +
                           " -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Mesh m = read_msh(out.string());
  // 5 km x 2 km inside the domain, less the 2 km x 1 km hole.
  EXPECT_NEAR(group_area(m, "region:ring"), 8.0e6, 1.0);
  EXPECT_NEAR(group_area(m, "region:over"), 3.0e6, 1.0);
  EXPECT_NEAR(group_area(m, "region:domain"), 24.0e6, 1.0);
  // The refinement is applied: edges inside the ring are near 150 m, not the 800 m far field.
  double longest = 0;
  for (const auto& b : m.blocks) {
    if (b.type != ElementType::Triangle) continue;
    for (std::size_t i = 0; i < b.size(); ++i) {
      const auto &A = m.nodes[b.element(i)[0]], &B = m.nodes[b.element(i)[1]], &C = m.nodes[b.element(i)[2]];
      const double cx = (A[0] + B[0] + C[0]) / 3, cy = (A[1] + B[1] + C[1]) / 3;
      const bool in_ring = cx > 680100 && cx < 684900 && cy > 4951100 && cy < 4952900 &&
                           !(cx > 681900 && cx < 684100 && cy > 4951400 && cy < 4952600);
      if (in_ring) longest = std::max({longest, std::hypot(B[0] - A[0], B[1] - A[1]), std::hypot(C[0] - B[0], C[1] - B[1])});
    }
  }
  EXPECT_LT(longest, 300.0);
}

// Issue 20: a fault line with a coordinate that is not a number ("abc", null) was dropped by GDAL
// and the plan had one fault group fewer with exit 0. Now exit 2 naming file, feature and value;
// a feature without geometry is refused too.
TEST_F(Mesh2dCli, CoordinateThatIsNotANumberIsRefused) {
  const std::string head = R"({"type": "FeatureCollection",
"crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32632"}}, "features": [
{"type": "Feature", "properties": {"name": "good"}, "geometry": {"type": "LineString", "coordinates": [[680500, 4951500], [685500, 4952500]]}},
)";
  const std::string box = "--box 680000/686000/4950000/4954000 --hmax 800 --fault ";
  test::spit(p("abc.geojson"), head + R"({"type": "Feature", "properties": {"name": "f1"}, "geometry": {"type": "LineString",
  "coordinates": [[680500, 4950500], [683000, "abc"], [685500, 4953500]]}}]})");
  expect_bad(box + p("abc.geojson").string(),
             p("abc.geojson").string() + ": feature 1 ('f1'): coordinate \"abc\" in position [683000,\"abc\"] is not a number");
  test::spit(p("null.geojson"), head + R"({"type": "Feature", "properties": {"name": "f3"}, "geometry": {"type": "LineString",
  "coordinates": [[680500, 4952500], [null, 4953000]]}}]})");
  expect_bad(box + p("null.geojson").string(),
             p("null.geojson").string() + ": feature 1 ('f3'): coordinate null in position [null,4953000] is not a number");
  test::spit(p("short.geojson"), head + R"({"type": "Feature", "properties": {"name": "f4"}, "geometry": {"type": "LineString",
  "coordinates": [[680500, 4952500], [681000]]}}]})");
  expect_bad(box + p("short.geojson").string(), "feature 1 ('f4'): position [681000] has fewer than 2 numbers");
  test::spit(p("nogeom.geojson"), head + R"({"type": "Feature", "properties": {"name": "f5"}, "geometry": null}]})");
  expect_bad("--box 680000/686000/4950000/4954000 --hmax 800 --section " + p("nogeom.geojson").string(),
             p("nogeom.geojson").string() + ": feature 1 ('f5') has no geometry");
  expect_bad(box + p("nogeom.geojson").string(),
             p("nogeom.geojson").string() + ": feature 1: fault 'f5': the feature is not a line");
}

// Issue 20: a GeoJSON file without "crs" is WGS 84 longitude/latitude for GDAL (RFC 7946); with
// projected coordinates PROJ failed with "Invalid coordinate". The message says the crs is missing.
TEST_F(Mesh2dCli, GeoJsonWithoutCrsSaysSo) {
  test::spit(p("nocrs.geojson"), R"({"type": "FeatureCollection", "features": [
{"type": "Feature", "properties": {"name": "f2"}, "geometry": {"type": "LineString", "coordinates": [[680500, 4951500], [685500, 4952500]]}}]})");
  const std::string want = p("nocrs.geojson").string() + ": has no \"crs\" member, so GeoJSON takes its coordinates as WGS 84 "
                           "longitude/latitude (RFC 7946), but they reach x 680500 .. 685500, y 4951500 .. 4952500, which are "
                           "not degrees";
  expect_bad("--box 680000/686000/4950000/4954000 --hmax 800 --fault " + p("nocrs.geojson").string(), want);
  expect_bad("--crs EPSG:32632 --box 680000/686000/4950000/4954000 --hmax 800 --fault " + p("nocrs.geojson").string(), want);
  expect_bad("--domain " + p("nocrs.geojson").string(), want);
}

// Issue 20: a tiny refinement size (1e-9 m, 0.001 m) grew memory without bound until SIGABRT. The
// triangle count the sizes ask for is estimated before meshing and refused above --max-elements
// (default 20 million) with the estimate; std::bad_alloc anywhere is exit 1, one line, no output.
TEST_F(Mesh2dCli, TinySizesAreRefusedBeforeMeshing) {
  const std::string box = "--box 680000/686000/4950000/4954000 --hmax 800 --refine " + p("refine.geojson").string();
  for (const char* size : {"0.001", "1e-9"}) {
    test::write_vector(p("tiny.geojson").string(),
                       {{"tiny", "POLYGON ((682000 4951000, 684000 4951000, 684000 4952500, 682000 4952500, 682000 4951000))",
                         {{"size_m", std::stod(size)}}}});
    expect_bad("--box 680000/686000/4950000/4954000 --hmax 800 --refine " + p("tiny.geojson").string(),
               fmt::format("more than the limit of 20000000: the smallest size is {:g} m (region 'tiny')", std::stod(size)));
  }
  // The estimate of the 100 m refinement: 3e6 m2 / 100^2 plus its graded band and the far field,
  // times 4 / sqrt(3), within a factor of 2 of what gmsh makes; a limit below it refuses.
  const auto out = p("plan.msh");
  const auto r = test::run(tool() + " -v " + box + " -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.err, m, std::regex("estimated ([0-9.e+]+) triangles"))) << r.err;
  const double estimate = std::stod(m[1]);
  const double made = static_cast<double>(read_msh(out.string()).count(ElementType::Triangle));
  EXPECT_GT(estimate, 0.5 * made);
  EXPECT_LT(estimate, 2.0 * made);
  expect_bad(box + " --max-elements " + std::to_string(static_cast<long>(estimate / 2)), "--max-elements: the sizes ask for about");
}

// A coordinate out of place (4294967295 for 690000, mutation_tools seed 5301017) made a domain 4.3
// million km long: 8e6 triangles, under the element limit, meshed for minutes. A domain more
// than 1,000 km across is refused before meshing.
TEST_F(Mesh2dCli, ADomainWiderThanAThousandKilometresIsRefused) {
  test::write_vector(p("sliver.geojson").string(),
                     {{"field", "POLYGON ((680000 4950000, 4294967295 4950000, 690000 4960000, 680000 4960000, 680000 4950000))", {}}});
  expect_bad("--domain " + p("sliver.geojson").string() + " --hmax 2500",
             "the domain spans 4294287 km x 10 km (x 680000.0 .. 4294967295.0, y 4950000.0 .. 4960000.0), more than 1000 km "
             "across: a coordinate out of place?");
  // 999 km across is meshed (coarsely).
  test::write_vector(p("wide.geojson").string(),
                     {{"field", "POLYGON ((0 0, 999000 0, 999000 1000, 0 1000, 0 0))", {}}});
  const auto r = test::run(tool() + " -q --domain " + p("wide.geojson").string() + " --hmax 50000 -o " + p("wide.msh").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(Mesh2dCli, OutOfMemoryIsExitOneWithOneLine) {
  // A 0.5 m refinement with the limit lifted, in 420 MB of address space: gmsh runs out of memory.
  test::write_vector(p("small.geojson").string(),
                     {{"small", "POLYGON ((682000 4951000, 684000 4951000, 684000 4952500, 682000 4952500, 682000 4951000))",
                       {{"size_m", 0.5}}}});
  const auto out = p("oom.msh");
  const auto r = test::run("ulimit -v 420000; " + tool() + " -q --box 680000/686000/4950000/4954000 --hmax 800 --refine " +
                           p("small.geojson").string() + " --max-elements 1e15 -o " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err, "ugs-mesh2d: error: out of memory while meshing the plan with gmsh\n");
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(dir_)) EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}
