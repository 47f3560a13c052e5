// ugs-sample and ugs-calibrate from the command line: sampling an EGMS file (EPSG:3035) on a
// model in EPSG:32632 reproduces a linear field, with line-of-sight columns; bad inputs end with
// exit code 2 and one line naming the file and what is wrong.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "insar_fixtures.hpp"
#include "run_tool.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/insar/crs.hpp"
#include "ugs/insar/los.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

const test::LinearField kF1{{0.001, -0.002, 0.003}, {{1e-6, 2e-6, -3e-6}, {-2e-6, 5e-7, 1e-6}, {3e-6, -1e-6, 2e-6}}};
const test::LinearField kF2{{-0.004, 0.001, 0.002}, {{-2e-6, 1e-6, 4e-6}, {1e-6, -3e-6, 2e-6}, {-1e-6, 2e-6, -5e-6}}};

struct Model {
  fs::path dir;
  Mesh mesh;
};

// Mesh, results at 2015-05-01 (field 1) and 2015-11-01 (field 2), and an EGMS file of 4 points
// (3 inside, 1 outside) with dates 2015-06-01 and 2015-09-01.
Model write_model(const std::string& tag) {
  Model m{test::temp_dir(tag), test::undulating_box(680000, 4950000, 1000, 800, 500, 10, 8, 5, 20)};
  write_msh(m.mesh, (m.dir / "model.msh").string());
  FieldSeriesWriter w((m.dir / "run.h5").string(), m.mesh);
  const Field f1[] = {kF1.field(m.mesh)};
  const Field f2[] = {kF2.field(m.mesh)};
  w.add_step("2015-05-01", double(*parse_iso_date("2015-05-01")), f1);
  w.add_step("2015-11-01", double(*parse_iso_date("2015-11-01")), f2);
  w.commit();
  std::vector<double> x{680123.4, 680555.5, 680987.6, 681500.0}, y{4950111.1, 4950400.0, 4950777.7, 4950400.0};
  insar::CoordinateTransform ct(insar::any_crs_wkt("EPSG:32632", "t"), insar::any_crs_wkt("EPSG:3035", "t"), "t");
  ct.apply(x, y, {});
  std::string csv = "pid,easting,northing,height,rmse,20150601,20150901\n";
  for (int i = 0; i < 4; ++i) csv += fmt::format("P{},{:.4f},{:.4f},10,1,0,1.5\n", i + 1, x[i], y[i]);
  test::spit(m.dir / "ps.csv", csv);
  return m;
}

// Exit code 2 and the error is one line, the last on stderr (warnings may come before it).
bool one_line_error(const test::RunResult& r, const std::string& tool, const std::string& needle) {
  const auto at = r.err.find(tool + ": error: ");
  return r.exit_code == 2 && at != std::string::npos && (at == 0 || r.err[at - 1] == '\n') &&
         r.err.find('\n', at) == r.err.size() - 1 && r.err.find(needle, at) != std::string::npos;
}

}  // namespace

TEST(SampleCli, EgmsPointsOnTheModelReproduceTheLinearField) {
  const Model m = write_model("sample-cli");
  const std::string d = m.dir.string() + "/";
  const auto r = test::run(test::tool("ugs-sample") + " --results " + d + "run.h5 --mesh " + d + "model.msh --points " + d +
                           "ps.csv --crs EPSG:32632 --at-ps-dates --ascending 35/-10 --descending 40/190 -o " + d + "s.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("point 'P4'"), std::string::npos) << r.err;  // outside: reported
  const CsvTable t = CsvTable::read(d + "s.csv");
  ASSERT_EQ(t.rows(), 3u * 2u);  // 3 points inside, 2 PS dates
  const std::int64_t t1 = *parse_iso_date("2015-05-01"), t2 = *parse_iso_date("2015-11-01");
  const std::int64_t ref = *parse_iso_date("2015-06-01");
  auto field_at = [&](const Point3& p, std::int64_t t) {
    const double w = double(t - t1) / double(t2 - t1);
    const auto a = kF1.at(p), b = kF2.at(p);
    return std::array<double, 3>{(1 - w) * a[0] + w * b[0], (1 - w) * a[1] + w * b[1], (1 - w) * a[2] + w * b[2]};
  };
  const insar::LosGeometry asc{"asc", 35, -10}, desc{"desc", 40, 190};
  for (std::size_t i = 0; i < t.rows(); ++i) {
    const Point3 p{t.number(i, t.column("x_surface_m")), t.number(i, t.column("y_surface_m")), t.number(i, t.column("z_surface_m"))};
    EXPECT_NEAR(p[0], t.number(i, t.column("x_m")), 1e-3);  // inside: sampled where asked
    EXPECT_EQ(t.number(i, t.column("offset_m")), 0.0);
    const auto u = field_at(p, t.date(i, t.column("date"))), u0 = field_at(p, ref);
    const std::array<double, 3> du{u[0] - u0[0], u[1] - u0[1], u[2] - u0[2]};
    // The surface height is printed to 1 mm: the field's z-gradient (5e-6) makes that 5e-9 m.
    EXPECT_NEAR(t.number(i, t.column("east_mm")), du[0] * 1e3, 2e-5);
    EXPECT_NEAR(t.number(i, t.column("north_mm")), du[1] * 1e3, 2e-5);
    EXPECT_NEAR(t.number(i, t.column("up_mm")), du[2] * 1e3, 2e-5);
    EXPECT_NEAR(t.number(i, t.column("los_asc_mm")), insar::los_displacement(du, asc) * 1e3, 2e-5);
    EXPECT_NEAR(t.number(i, t.column("los_desc_mm")), insar::los_displacement(du, desc) * 1e3, 2e-5);
  }
  // The reprojected locations match the EPSG:32632 ones to a millimetre.
  EXPECT_NEAR(t.number(0, t.column("x_m")), 680123.4, 1e-3);
  EXPECT_NEAR(t.number(0, t.column("y_m")), 4950111.1, 1e-3);
  // --keep-outside: P4 sampled at the nearest surface point, 500 m away.
  const auto k = test::run(test::tool("ugs-sample") + " --results " + d + "run.h5 --mesh " + d + "model.msh --points " + d +
                           "ps.csv --crs EPSG:32632 --keep-outside -o " + d + "k.csv");
  ASSERT_EQ(k.exit_code, 0) << k.err;
  const CsvTable kt = CsvTable::read(d + "k.csv");
  ASSERT_EQ(kt.rows(), 4u * 2u);  // every point at both result steps
  EXPECT_NEAR(kt.number(7, kt.column("offset_m")), 500.0, 1e-3);
  EXPECT_EQ(kt.text(7, kt.column("inside")), "0");
  fs::remove_all(m.dir);
}

TEST(SampleCli, BadInputs) {
  const Model m = write_model("sample-bad");
  const std::string d = m.dir.string() + "/";
  const std::string base = test::tool("ugs-sample") + " --results " + d + "run.h5 --mesh " + d + "model.msh --crs EPSG:32632 ";
  test::spit(m.dir / "nocol.csv", "pid,easting,height,20150601\nA,4300000,1,0\n");
  auto r = test::run(base + "--points " + d + "nocol.csv -o " + d + "o.csv");
  EXPECT_TRUE(one_line_error(r, "ugs-sample", "nocol.csv:1: no column 'northing'")) << r.err;
  test::spit(m.dir / "baddate.csv", "pid,easting,northing,20150601,20151301\nA,4300000,2400000,0,1\n");
  r = test::run(base + "--points " + d + "baddate.csv -o " + d + "o.csv");
  EXPECT_TRUE(one_line_error(r, "ugs-sample", "baddate.csv:1: column '20151301' is not a date")) << r.err;
  test::spit(m.dir / "nodata.csv", "pid,easting,northing,20150601,20150901\nA,4300000,2400000,0,1\nB,4300000,2400010,,\n");
  r = test::run(base + "--points " + d + "nodata.csv -o " + d + "o.csv");
  EXPECT_TRUE(one_line_error(r, "ugs-sample", "nodata.csv:3: point 'B' has no data")) << r.err;
  test::spit(m.dir / "far.csv", "pid,x,y\nA,0,0\n");
  r = test::run(base + "--points " + d + "far.csv -o " + d + "o.csv");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("none of the 1 points lies on the top surface"), std::string::npos) << r.err;
  r = test::run(test::tool("ugs-sample") + " --results " + d + "run.h5 --mesh " + d + "model.msh --points " + d + "ps.csv -o " + d + "o.csv");
  EXPECT_TRUE(one_line_error(r, "ugs-sample", "but the model CRS (--crs) is unknown: give it, or a case with crs")) << r.err;
  // The library names the settings in words (AnalysisMessages.NameTheSettingsInWordsNotFlags); the
  // tool's line names the flags the user typed.
  r = test::run(base + "--points " + d + "ps.csv --points-crs EPSG:nothing -o " + d + "o.csv");
  EXPECT_TRUE(one_line_error(r, "ugs-sample", "error: --points-crs: unknown coordinate reference system 'EPSG:nothing'")) << r.err;
  r = test::run(test::tool("ugs-sample") + " --results " + d + "run.h5 --mesh " + d + "model.msh --crs EPSG:nothing --points " + d +
                "ps.csv -o " + d + "o.csv");
  EXPECT_TRUE(one_line_error(r, "ugs-sample", "error: --crs: unknown coordinate reference system 'EPSG:nothing'")) << r.err;
  r = test::run(base + "--points " + d + "ps.csv --ascending 35 -o " + d + "o.csv");
  EXPECT_TRUE(one_line_error(r, "ugs-sample", "INCIDENCE/HEADING")) << r.err;
  r = test::run(base + "--points " + d + "ps.csv --reference 2030-01-01 -o " + d + "o.csv");
  EXPECT_TRUE(one_line_error(r, "ugs-sample", "outside the results")) << r.err;
  EXPECT_FALSE(fs::exists(m.dir / "o.csv"));  // nothing written on any error
  fs::remove_all(m.dir);
}

// Issue 20: a GeoJSON without "crs" member holding projected coordinates (GDAL takes it as WGS 84,
// and PROJ failed with a message that did not say why): refused, naming the missing CRS; with
// --points-crs it is read; a GeoJSON in longitude/latitude is WGS 84 (RFC 7946).
TEST(SampleCli, GeoJsonWithoutCrs) {
  const Model m = write_model("sample-nocrs");
  const std::string d = m.dir.string() + "/";
  const std::string base = test::tool("ugs-sample") + " --results " + d + "run.h5 --mesh " + d + "model.msh --crs EPSG:32632 ";
  auto geojson = [](double x, double y) {
    return fmt::format(R"({{"type":"FeatureCollection","features":[{{"type":"Feature","properties":{{"pid":"G1"}},)"
                       R"("geometry":{{"type":"Point","coordinates":[{:.9f},{:.9f}]}}}}]}})",
                       x, y);
  };
  test::spit(m.dir / "nocrs.geojson", geojson(680555.5, 4950400.0));
  auto r = test::run(base + "--points " + d + "nocrs.geojson -o " + d + "o.csv");
  EXPECT_TRUE(one_line_error(r, "ugs-sample", "nocrs.geojson: the layer has no coordinate reference system (expected a \"crs\" "
                                              "member, e.g. EPSG:32632, or the points CRS (--points-crs)); (680556, 4.9504e+06) is no "
                                              "longitude/latitude"))
      << r.err;
  EXPECT_FALSE(fs::exists(m.dir / "o.csv"));
  r = test::run(base + "--points " + d + "nocrs.geojson --points-crs EPSG:32632 -o " + d + "o.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable a = CsvTable::read(d + "o.csv");
  EXPECT_NEAR(a.number(0, a.column("x_m")), 680555.5, 1e-6);
  std::vector<double> x{680555.5}, y{4950400.0};
  insar::CoordinateTransform ct(insar::any_crs_wkt("EPSG:32632", "t"), insar::any_crs_wkt("EPSG:4326", "t"), "t");
  ct.apply(x, y, {});
  test::spit(m.dir / "lonlat.geojson", geojson(x[0], y[0]));
  r = test::run(base + "--points " + d + "lonlat.geojson -o " + d + "o2.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable b = CsvTable::read(d + "o2.csv");
  EXPECT_NEAR(b.number(0, b.column("x_m")), 680555.5, 1e-3);
  EXPECT_NEAR(b.number(0, b.column("y_m")), 4950400.0, 1e-3);
  if (!HasFailure()) fs::remove_all(m.dir);
}

TEST(CalibrateCli, BadInputs) {
  const auto dir = test::temp_dir("calibrate-bad");
  const std::string d = dir.string() + "/";
  test::spit(dir / "case.toml", "crs = \"EPSG:32632\"\n[[material]]\nname = \"pool_c\"\nlaw = \"hypoplastic\"\nc_R = 3.0\n");
  test::spit(dir / "up.csv", "pid,easting,northing,20150601,20150901\nA,4300000,2400000,0,1\n");
  const std::string base = test::tool("ugs-calibrate") + " --case " + d + "case.toml --measured " + d + "up.csv --solver-command 'true {case} {out}' -o " + d + "out ";
  auto r = test::run(base + "--param material.pool_c.c_R=6:2");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "error: --param material.pool_c.c_R=6:2: lower bound 6 is not below upper bound 2 "
                                                 "(bounds reversed?)")) << r.err;
  r = test::run(base + "--param material.pool_x.c_R=2:6");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "no [[material]] named 'pool_x'")) << r.err;
  r = test::run(base + "--param material.pool_c.E_MPa=2:6");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "has no key 'E_MPa'")) << r.err;
  r = test::run(base + "--param material.pool_c.c_R=0:6");  // c_R = 0 is not a valid case
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "error: --param material.pool_c.c_R: the case is not valid at")) << r.err;
  r = test::run(base + "--param material.pool_c.c_R=2:6 --window 2020-01-01/2010-01-01");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "start after end")) << r.err;
  test::spit(dir / "nocol.csv", "pid,northing,20150601\nA,2400000,0\n");
  r = test::run(test::tool("ugs-calibrate") + " --case " + d + "case.toml --measured " + d +
                "nocol.csv --solver-command 'true {case} {out}' --param material.pool_c.c_R=2:6 -o " + d + "out");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "nocol.csv:1: no column 'easting'")) << r.err;
  r = test::run(test::tool("ugs-calibrate") + " --case " + d + "case.toml --measured " + d +
                "up.csv --solver-command 'true {case}' --param material.pool_c.c_R=2:6 -o " + d + "out");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "{out}")) << r.err;
  r = test::run(test::tool("ugs-calibrate") + " --case " + d + "case.toml --measured " + d +
                "up.csv --solver-command 'x {case} {out} {results}' --param material.pool_c.c_R=2:6 -o " + d + "out");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "unknown placeholder {results}")) << r.err;
  r = test::run(test::tool("ugs-calibrate") + " --case " + d + "case.toml --measured " + d +
                "up.csv --solver-command 'x {case} {out} {mesh}' --param material.pool_c.c_R=2:6 -o " + d + "out");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "--solver-command: uses {mesh} but no solver mesh (--mesh) was given")) << r.err;
  // --response reciprocal: one parameter with positive linear bounds, its own three runs, four
  // evaluations at least; refused before any cache exists.
  r = test::run(base + "--response reciprocal --param material.pool_c.c_R=2:6 --param material.pool_a.c_R=3:8 --cache-dir " + d + "recip.cache");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "error: --response: reciprocal calibrates one parameter, 2 were given (expected one "
                                                 "parameter to calibrate (--param); several paths sharing one value are one)")) << r.err;
  r = test::run(base + "--response reciprocal --param material.pool_c.c_R=0:6 --cache-dir " + d + "recip.cache");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "error: --response: reciprocal needs positive bounds, parameter to calibrate (--param) "
                                                 "material.pool_c.c_R has lower bound 0 (expected 0 < LOWER < UPPER: the model is in 1/x)")) << r.err;
  r = test::run(base + "--response reciprocal --param material.pool_c.c_R=-1:6 --cache-dir " + d + "recip.cache");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "has lower bound -1")) << r.err;
  r = test::run(base + "--response reciprocal --param material.pool_c.c_R=2:6:log --cache-dir " + d + "recip.cache");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "asks for :log")) << r.err;
  r = test::run(base + "--response reciprocal --param material.pool_c.c_R=2:6 --scan 5 --cache-dir " + d + "recip.cache");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "error: --response: reciprocal makes its own three runs (expected no scan values per "
                                                 "parameter (--scan))")) << r.err;
  r = test::run(base + "--response reciprocal --param material.pool_c.c_R=2:6 --max-evals 3 --cache-dir " + d + "recip.cache");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "error: --response: reciprocal needs 4 evaluations, the evaluation budget (--max-evals) "
                                                 "is 3 (expected at least 4)")) << r.err;
  r = test::run(base + "--response linear --param material.pool_c.c_R=2:6 --cache-dir " + d + "recip.cache");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--response"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "recip.cache"));
  // A solver that fails: exit 1, naming the evaluation and the log (the shell's ${VAR} is left alone).
  r = test::run(test::tool("ugs-calibrate") + " --case " + d + "case.toml --measured " + d +
                "up.csv --solver-command 'V=diverged; echo ${V}; exit 3; {case} {out}' --param material.pool_c.c_R=2:6 -o " + d + "out");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("the solver exited with code 3: diverged"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
  // TOML errors: one line naming the file and line, as the other tools' (issue 20).
  test::spit(dir / "bad.toml", "crs = \"EPSG:32632\"\n[[material]]\nname = \"pool_c\"\nc_R = = 3.0\n");
  r = test::run(test::tool("ugs-calibrate") + " --case " + d + "bad.toml --measured " + d +
                "up.csv --solver-command 'true {case} {out}' --param material.pool_c.c_R=2:6 -o " + d + "out");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "bad.toml:4: TOML syntax error")) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  test::spit(dir / "dup.toml", "crs = \"EPSG:32632\"\ncrs = \"EPSG:3035\"\n");
  r = test::run(test::tool("ugs-calibrate") + " --case " + d + "dup.toml --measured " + d +
                "up.csv --solver-command 'true {case} {out}' --param material.pool_c.c_R=2:6 -o " + d + "out");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "dup.toml:")) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  r = test::run(test::tool("ugs-calibrate") + " --case " + d + " --measured " + d +
                "up.csv --solver-command 'true {case} {out}' --param material.pool_c.c_R=2:6 -o " + d + "out");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "is a folder (expected a TOML case file)")) << r.err;
  // Refused inputs leave no cache folder (issue 20); a failed solver run leaves its log in
  // failed-<entry>/, never a temporary folder.
  r = test::run(base + "--param material.pool_c.c_R=0:6 --cache-dir " + d + "refused.cache");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_FALSE(fs::exists(dir / "refused.cache"));
  std::size_t failed = 0;
  for (const auto& e : fs::directory_iterator(dir / "out.cache")) {
    const std::string name = e.path().filename().string();
    EXPECT_EQ(name.rfind(".tmp", 0), std::string::npos) << name;
    failed += name.rfind("failed-eval-", 0) == 0;
  }
  EXPECT_GE(failed, 1u);
  fs::remove_all(dir);
}

// Issue 23: the libraries name the settings in words (AnalysisMessages.NameTheSettingsInWordsNotFlags);
// ugs-calibrate's lines and its stop reason name the flags the user typed.
TEST(CalibrateCli, LibraryMessagesShowTheFlags) {
  const Model m = write_model("calibrate-flags");
  const std::string d = m.dir.string() + "/";
  test::spit(m.dir / "case.toml", "crs = \"EPSG:32632\"\n[[material]]\nname = \"pool_c\"\nlaw = \"hypoplastic\"\nc_R = 3.0\n");
  test::spit(m.dir / "up.csv", "pid,x,y,20150601,20150901\nA,680300,4950300,0,1.5\nB,680600,4950500,0,-2\n");
  test::spit(m.dir / "trace.geojson",
             R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32632"}},)"
             R"("features":[{"type":"Feature","properties":{"name":"A"},"geometry":{"type":"Polygon",)"
             R"("coordinates":[[[680000,4950000],[681000,4950000],[681000,4950800],[680000,4950000]]]}}]})");
  const std::string base = test::tool("ugs-calibrate") + " --case " + d + "case.toml --mesh " + d + "model.msh --measured " + d +
                           "up.csv --param material.pool_c.c_R=2:6 --scan 2 --max-evals 2 --solver-command 'cp " + d +
                           "run.h5 {out} && test -s {case}' --cache-dir " + d + "cache ";
  auto r = test::run(base + "--crs EPSG:nothing -o " + d + "out");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "error: --crs: unknown coordinate reference system 'EPSG:nothing'")) << r.err;
  r = test::run(base + "--points-crs EPSG:nothing -o " + d + "out");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "error: --points-crs: unknown coordinate reference system 'EPSG:nothing'")) << r.err;
  r = test::run(base + "--inside " + d + "trace.geojson --inside-where \"name = 'B'\" -o " + d + "out");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "trace.geojson: has no polygon: none in the file, or none kept by the polygon filter "
                                                 "(--inside-where)")) << r.err;
  r = test::run(base + "--window 2016-01-01/ -o " + d + "out");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "error: no measured value of the PS selection (--points, --inside) falls in the "
                                                 "misfit window (--window) within the results' dates")) << r.err;
  EXPECT_FALSE(fs::exists(m.dir / "out"));
  // Two scan values and a budget of two: the stop reason names --max-evals on stderr, stdout and in
  // parameters.csv's header.
  r = test::run(base + "-o " + d + "out");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string stop = "evaluation budget (--max-evals) used by the scan";
  EXPECT_NE(r.err.find("ugs-calibrate: warning: the optimizer stopped before converging: " + stop + "\n"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.rfind("best (scan, " + stop + "):\n", 0), 0u) << r.out;
  EXPECT_NE(test::slurp(m.dir / "out" / "parameters.csv").find("scan; " + stop + "; RMS "), std::string::npos);
  if (!HasFailure()) fs::remove_all(m.dir);
}

namespace {

// The columns of a table that must not depend on how a run was computed (cache or not): one
// line per row, for exact comparison.
std::string columns_text(const fs::path& csv, const std::vector<std::string>& cols) {
  const CsvTable t = CsvTable::read(csv.string());
  std::string s;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    for (const auto& c : cols) s += std::string(t.text(r, t.column(c))) + ",";
    s += "\n";
  }
  return s;
}

std::string values_of(const fs::path& csv, const std::string& pid, const std::string& col) {
  const CsvTable t = CsvTable::read(csv.string());
  std::string s;
  for (std::size_t r = 0; r < t.rows(); ++r)
    if (t.text(r, t.column("pid")) == pid) s += std::string(t.text(r, t.column(col))) + " ";
  return s;
}

}  // namespace

// Issue 20: the cache key covers the PS positions (and the files the command names): a PS moved
// under the same id is sampled again at its new place, exactly as with a fresh cache; a PS moved
// off the surface is left out of the misfit as the warning says; no timing in the cache's index.
TEST(CalibrateCli, CacheKeyCoversPointPositions) {
  const Model m = write_model("calibrate-cache");
  const std::string d = m.dir.string() + "/";
  test::spit(m.dir / "case.toml", "crs = \"EPSG:32632\"\n[[material]]\nname = \"pool_c\"\nlaw = \"hypoplastic\"\nc_R = 3.0\n");
  auto measured = [&](const std::string& name, double bx, double by) {
    test::spit(m.dir / name, fmt::format("pid,x,y,20150601,20150901\nA,680300,4950300,0,1.5\nB,{},{},0,-2\n", bx, by));
  };
  measured("up1.csv", 680600, 4950500);
  measured("up2.csv", 680850, 4950650);   // B moved, still on the model
  measured("up3.csv", 682000, 4950400);   // B moved 1 km off the model
  auto calibrate = [&](const std::string& up, const std::string& cache, const std::string& out) {
    return test::run(test::tool("ugs-calibrate") + " --case " + d + "case.toml --mesh " + d + "model.msh --measured " + d + up +
                     " --param material.pool_c.c_R=2:6 --scan 2 --max-evals 2 --solver-command 'cp " + d +
                     "run.h5 {out} && test -s {case}' --cache-dir " + d + cache + " -o " + d + out);
  };
  const std::vector<std::string> sim{"pid", "date", "east_mm", "north_mm", "up_mm"};
  auto r = calibrate("up1.csv", "cache", "out1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = calibrate("up2.csv", "cache", "out2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto fresh = calibrate("up2.csv", "cache-fresh", "out2-fresh");
  ASSERT_EQ(fresh.exit_code, 0) << fresh.err;
  // The moved point's simulated series is that of its new place (the field's gradient makes it
  // differ by about 0.5 mm), the same as with a fresh cache, byte for byte.
  EXPECT_NE(values_of(m.dir / "out1" / "best_samples.csv", "B", "up_mm"),
            values_of(m.dir / "out2" / "best_samples.csv", "B", "up_mm"));
  EXPECT_EQ(values_of(m.dir / "out1" / "best_samples.csv", "A", "up_mm"),
            values_of(m.dir / "out2" / "best_samples.csv", "A", "up_mm"));
  EXPECT_EQ(columns_text(m.dir / "out2" / "best_samples.csv", sim), columns_text(m.dir / "out2-fresh" / "best_samples.csv", sim));
  EXPECT_EQ(test::slurp(m.dir / "out2" / "misfit_points.csv"), test::slurp(m.dir / "out2-fresh" / "misfit_points.csv"));
  EXPECT_EQ(columns_text(m.dir / "out2" / "profile.csv", {"entry", "rms_mm"}),
            columns_text(m.dir / "out2-fresh" / "profile.csv", {"entry", "rms_mm"}));
  EXPECT_NE(columns_text(m.dir / "out1" / "profile.csv", {"entry"}), columns_text(m.dir / "out2" / "profile.csv", {"entry"}));
  // B off the model: warned about, and really left out (no misfit row, no simulated series).
  r = calibrate("up3.csv", "cache", "out3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("PS 'B' lies 1000 m outside the top surface: left out of the misfit"), std::string::npos) << r.err;
  EXPECT_EQ(values_of(m.dir / "out3" / "misfit_points.csv", "B", "rms_mm"), "");
  EXPECT_EQ(values_of(m.dir / "out3" / "best_samples.csv", "B", "up_mm"), "");
  EXPECT_EQ(values_of(m.dir / "out3" / "misfit_points.csv", "A", "rms_mm"),
            values_of(m.dir / "out1" / "misfit_points.csv", "A", "rms_mm"));
  // The results the command copies changed (same name, other bytes): computed again.
  {
    FieldSeriesWriter w(d + "run.h5", m.mesh);
    const Field f2[] = {kF2.field(m.mesh)};
    const Field f1[] = {kF1.field(m.mesh)};
    w.add_step("2015-05-01", double(*parse_iso_date("2015-05-01")), f2);
    w.add_step("2015-11-01", double(*parse_iso_date("2015-11-01")), f1);
    w.commit();
  }
  r = calibrate("up1.csv", "cache", "out4");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(columns_text(m.dir / "out4" / "profile.csv", {"cached"}), "0,\n0,\n");
  EXPECT_NE(values_of(m.dir / "out1" / "best_samples.csv", "A", "up_mm"),
            values_of(m.dir / "out4" / "best_samples.csv", "A", "up_mm"));
  // No wall time in what a user compares: the index and the entries' JSON hold none.
  const std::string index = test::slurp(m.dir / "cache" / "index.csv");
  EXPECT_EQ(index.find("seconds"), std::string::npos) << index;
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(m.dir / "cache")) {
    const std::string name = e.path().filename().string();
    EXPECT_EQ(name.rfind(".tmp", 0), std::string::npos) << name;
    if (name.rfind("eval-", 0) != 0) continue;
    ++entries;
    EXPECT_EQ(test::slurp(e.path() / "entry.json").find("seconds"), std::string::npos);
    EXPECT_TRUE(fs::exists(e.path() / "timing.txt"));
  }
  EXPECT_EQ(entries, 8u);  // 2 values x (up1, up2, up3, up1 with other results)
  // Without --mesh (each result's own surface) the point off the model is named too.
  r = test::run(test::tool("ugs-calibrate") + " --case " + d + "case.toml --measured " + d + "up3.csv" +
                " --param material.pool_c.c_R=2:6 --scan 2 --max-evals 2 --solver-command 'cp " + d +
                "run.h5 {out} && test -s {case}' --cache-dir " + d + "cache -o " + d + "out5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("PS 'B' lies outside the results' top surface: left out of the misfit"), std::string::npos) << r.err;
  EXPECT_EQ(values_of(m.dir / "out5" / "misfit_points.csv", "B", "rms_mm"), "");
  if (!HasFailure()) fs::remove_all(m.dir);
}

// Issue 20: every number a user gives is finite and in range, or exit 2 naming the option or the
// file and line/key and the value.
TEST(CalibrateCli, NumbersMustBeFiniteAndInRange) {
  const auto dir = test::temp_dir("calibrate-numbers");
  const std::string d = dir.string() + "/";
  test::spit(dir / "case.toml", "crs = \"EPSG:32632\"\n[[material]]\nname = \"pool_c\"\nlaw = \"hypoplastic\"\nc_R = 3.0\n");
  test::spit(dir / "up.csv", "pid,easting,northing,20150601,20150901\nA,4300000,2400000,0,1\n");
  const std::string base = test::tool("ugs-calibrate") + " --measured " + d +
                           "up.csv --solver-command 'true {case} {out}' --param material.pool_c.c_R=2:6 -o " + d + "out ";
  auto r = test::run(base + "--case " + d + "case.toml --east-weight nan");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "--east-weight: nan (expected a finite number >= 0)")) << r.err;
  r = test::run(base + "--case " + d + "case.toml --east-weight -1");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "--east-weight: -1 (expected a finite number >= 0)")) << r.err;
  r = test::run(base + "--case " + d + "case.toml --xtol inf");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "--xtol: inf (expected a finite number in (0, 1])")) << r.err;
  r = test::run(base + "--case " + d + "case.toml --scan -3");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--scan"), std::string::npos) << r.err;
  test::spit(dir / "inf.toml", "crs = \"EPSG:32632\"\n[[material]]\nname = \"pool_c\"\nlaw = \"hypoplastic\"\nc_R = inf\n");
  r = test::run(base + "--case " + d + "inf.toml");
  EXPECT_TRUE(one_line_error(r, "ugs-calibrate", "inf.toml:5: ")) << r.err;  // the case reader's or the parameter's
  EXPECT_NE(r.err.find("c_R"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("= inf"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
  EXPECT_FALSE(fs::exists(dir / "out.cache"));
  fs::remove_all(dir);
}

TEST(SampleCli, NonFiniteDisplacementIsRefused) {
  const Model m = write_model("sample-nan");
  const std::string d = m.dir.string() + "/";
  {
    FieldSeriesWriter w(d + "nan.h5", m.mesh);
    Field f = kF1.field(m.mesh);
    for (std::size_t i = 2; i < f.values.size(); i += 3) f.values[i] = std::nan("");  // u_z everywhere
    const Field f1[] = {kF1.field(m.mesh)};
    const Field f2[] = {f};
    w.add_step("2015-05-01", double(*parse_iso_date("2015-05-01")), f1);
    w.add_step("2015-11-01", double(*parse_iso_date("2015-11-01")), f2);
    w.commit();
  }
  const auto r = test::run(test::tool("ugs-sample") + " --results " + d + "nan.h5 --mesh " + d + "model.msh --points " + d +
                           "ps.csv --crs EPSG:32632 -o " + d + "o.csv");
  EXPECT_TRUE(one_line_error(r, "ugs-sample", "nan.h5: node field 'u' at step 2015-11-01: top-surface node")) << r.err;
  EXPECT_NE(r.err.find("has component 2 = nan (expected finite values)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(m.dir / "o.csv"));
  if (!HasFailure()) fs::remove_all(m.dir);
}
