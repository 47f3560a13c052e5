// Pieces of the calibration: parameter specs and modified case copies, the offset-free RMS
// misfit, Brent's minimiser.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "input_error.hpp"
#include "run_tool.hpp"
#include "ugs/calibration/optimizer.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/insar/inputs.hpp"
#include "ugs/insar/misfit.hpp"
#include "ugs/runner/case_params.hpp"
#include "ugs/runner/solver_runs.hpp"

using namespace ugs;
using namespace ugs::insar;
using namespace ugs::runner;
using namespace ugs::calibration;

namespace {
const std::string kCase = std::string(UGS_SOURCE_DIR) + "/data-samples/po-plain/case.toml";

}  // namespace

TEST(CaseParameters, ParseSpecs) {
  const auto p = parse_parameter("material.pool_c.c_R=2:6");
  ASSERT_EQ(p.paths.size(), 1u);
  EXPECT_EQ(p.paths[0], "material.pool_c.c_R");
  EXPECT_EQ(p.lower, 2.0);
  EXPECT_EQ(p.upper, 6.0);
  EXPECT_FALSE(p.log_scale);
  const auto q = parse_parameter("material.pool_c.c_R,material.aquifer_pool_c.c_R=2.5:5.5");
  EXPECT_EQ(q.paths.size(), 2u);
  const auto k = parse_parameter("material.aquifer_pool_c.K_m_per_s[0]=1e-8:1e-6:log");
  EXPECT_TRUE(k.log_scale);
  EXPECT_EQ(k.upper, 1e-6);
  EXPECT_NE(test::input_error_of([] { parse_parameter("material.pool_c.c_R=6:2"); }).find("bounds reversed"), std::string::npos);
  EXPECT_NE(test::input_error_of([] { parse_parameter("material.pool_c.c_R=3:3"); }).find("not below"), std::string::npos);
  EXPECT_NE(test::input_error_of([] { parse_parameter("material.pool_c.c_R"); }).find("PATH=LOWER:UPPER"), std::string::npos);
  EXPECT_NE(test::input_error_of([] { parse_parameter("material.pool_c.c_R=a:3"); }).find("LOWER:UPPER"), std::string::npos);
  EXPECT_NE(test::input_error_of([] { parse_parameter("x=-1:3:log"); }).find("positive"), std::string::npos);
}

TEST(CaseParameters, ValuesAndMissingParameters) {
  const CaseTemplate c(kCase);
  EXPECT_EQ(c.value("material.pool_c.c_R"), 3.0);
  EXPECT_EQ(c.value("material.pool_a.c_R"), 5.0);
  EXPECT_EQ(c.value("initial_stress.k0"), 0.9);
  EXPECT_EQ(c.value("material.aquifer_pool_c.K_m_per_s[2]"), 2.04e-8);
  EXPECT_EQ(c.value("pool.\"Pool C\".reference_pressure_MPa"), 15.2055);
  EXPECT_NE(test::input_error_of([&] { c.value("material.pool_x.c_R"); }).find("no [[material]] named 'pool_x'"), std::string::npos);
  EXPECT_NE(test::input_error_of([&] { c.value("material.surrounding_rock.c_R"); }).find("has no key 'c_R'"), std::string::npos);
  EXPECT_NE(test::input_error_of([&] { c.value("material.pool_c.name"); }).find("not a number"), std::string::npos);
  EXPECT_NE(test::input_error_of([&] { c.value("nothing.here"); }).find("no parameter 'nothing.here'"), std::string::npos);
}

// Found by fuzz_case_params (tests/fuzz/corpus/case_params/regress-literal-not-utf8.toml, the case
// part before its "%%" line): a string that is not UTF-8 (here the overlong form e0 80 af) made toml11
// 3.7.1 read out of bounds; the case is refused before toml11 sees it.
TEST(CaseParameters, CaseThatIsNotUtf8IsOneLine) {
  const std::string path = std::string(UGS_SOURCE_DIR) + "/tests/fuzz/corpus/case_params/regress-literal-not-utf8.toml";
  EXPECT_EQ(test::input_error_of([&] { CaseTemplate c(path); }),
            path + ":13: byte 0xe0 at column 13 is not UTF-8 (expected a UTF-8 text file)");
}

// Found by fuzz_case_params (tests/fuzz/corpus/case_params/regress-alias-double-edit.toml): two
// spellings of one value in a parameter (material.pool_x.c_R,material.1.c_R=2.25:5.5) made two edits
// of the same text, "3.0" -> "2.25" -> "2.255": the copies had c_R = 2.255, a valid case, so the
// tools ran with values they were not asked for. The render makes one edit for equal values and
// refuses different ones; check_parameters refuses any value named twice, in one parameter or two.
TEST(CaseParameters, TwoSpellingsOfOneValue) {
  const CaseTemplate c(kCase);
  for (const char* alias : {"material.\"pool_c\".c_R", "material.6.c_R"}) {
    const std::string out = c.render({{"material.pool_c.c_R", 2.25}, {alias, 2.25}});
    EXPECT_NE(out.find("\nc_R = 2.25                 # loading"), std::string::npos) << alias;
    EXPECT_EQ(out.find("2.255"), std::string::npos) << alias;
  }
  EXPECT_EQ(test::input_error_of([&] { c.render({{"material.pool_c.c_R", 2.25}, {"material.6.c_R", 3.5}}); }),
            kCase + ":116: 'material.pool_c.c_R' and 'material.6.c_R' name the same value, set to 2.25 and 3.5 (expected each value "
                    "named once)");
  EXPECT_EQ(test::input_error_of([] { check_parameters(CaseTemplate(kCase), {parse_parameter("material.pool_c.c_R,material.6.c_R=2.25:5.5")}); }),
            "parameter to calibrate material.pool_c.c_R,material.6.c_R: 'material.pool_c.c_R' and 'material.6.c_R' name the same value "
            "of the case (" + kCase + ":116; expected each value named once)");
  EXPECT_EQ(test::input_error_of([] {
              check_parameters(CaseTemplate(kCase), {parse_parameter("material.pool_c.c_R=2:6"), parse_parameter("material.\"pool_c\".c_R=3:5")});
            }),
            "parameter to calibrate material.\"pool_c\".c_R: 'material.pool_c.c_R' and 'material.\"pool_c\".c_R' name the same value "
            "of the case (" + kCase + ":116; expected each value named once)");
  // Pool C and its aquifer are two values: accepted.
  EXPECT_EQ(test::input_error_of([] {
              check_parameters(CaseTemplate(kCase), {parse_parameter("material.pool_c.c_R,material.aquifer_pool_c.c_R=2.25:5.5")});
            }),
            "(no InputError)");
}

TEST(CaseParameters, RenderedCopyKeepsTextChangesValuesAndReadsBack) {
  const CaseTemplate c(kCase);
  const std::string out = c.render({{"material.pool_c.c_R", 3.75}, {"material.aquifer_pool_c.c_R", 3.75},
                                    {"material.aquifer_pool_c.K_m_per_s[0]", 4e-7}});
  // Comments survive; only the values changed; schedules became absolute.
  EXPECT_NE(out.find("# Case file of the po-plain synthetic twin"), std::string::npos);
  EXPECT_NE(out.find("c_R = 3.75                 # loading / unloading-reloading compressibility"), std::string::npos);
  EXPECT_NE(out.find("K_m_per_s = [4e-07, 2.04e-7, 2.04e-8]"), std::string::npos);
  const std::string abs_dir = std::filesystem::weakly_canonical(std::filesystem::path(kCase).parent_path()).string();
  EXPECT_NE(out.find("schedule = \"" + abs_dir + "/pressure_pool_c.csv\""), std::string::npos);
  const auto dir = test::temp_dir("case-render");
  test::spit(dir / "case.toml", out);
  const CaseFile cf = read_case_file((dir / "case.toml").string());
  EXPECT_EQ(cf.material("pool_c")->c_R, 3.75);
  EXPECT_EQ(cf.material("aquifer_pool_c")->c_R, 3.75);
  EXPECT_EQ(cf.material("pool_a")->c_R, 5.0);
  EXPECT_EQ((*cf.material("aquifer_pool_c")->K)[0], 4e-7);
  EXPECT_EQ(cf.pools[1].schedule, abs_dir + "/pressure_pool_c.csv");
  EXPECT_EQ(toml_float(3.0), "3.0");
  EXPECT_EQ(toml_float(0.1), "0.1");
}

TEST(Misfit, OffsetIsRemovedAndRmsPooled) {
  PsData meas;
  meas.dates = {0, 86400, 2 * 86400, 3 * 86400};
  meas.points = {{"a", 0, 0, {}, ""}, {"b", 0, 0, {}, ""}};
  // a: simulated = measured + 5 mm + (+1, -1, +1, -1); b: measured has a gap.
  meas.values_mm = {0, 1, 2, 3, 10, NAN, 12, 13};
  Samples sim;
  sim.dates = meas.dates;
  sim.points = {{meas.points[0], {}}, {meas.points[1], {}}};
  sim.enu.assign(2 * 4 * 3, 0.0);
  const double da[] = {6, 5, 8, 7};   // meas + 5 + (1, -1, 1, -1)
  const double db[] = {10, 99, 12, 16};
  for (int d = 0; d < 4; ++d) {
    sim.enu[(0 * 4 + d) * 3 + 2] = da[d] * 1e-3;
    sim.enu[(1 * 4 + d) * 3 + 2] = db[d] * 1e-3;
  }
  const auto up = series_misfits(meas, sim, 2, {});
  ASSERT_EQ(up.size(), 2u);
  EXPECT_EQ(up[0].n, 4u);
  EXPECT_NEAR(up[0].offset_mm, 5.0, 1e-12);
  EXPECT_NEAR(up[0].rms_mm, 1.0, 1e-12);
  EXPECT_EQ(up[1].n, 3u);  // the gap is skipped
  EXPECT_NEAR(up[1].offset_mm, 1.0, 1e-12);  // residuals 0, 0, 3
  EXPECT_NEAR(up[1].rms_mm, std::sqrt(6.0 / 3.0), 1e-12);
  const Misfit m = combine_misfits(up, {}, 0);
  EXPECT_NEAR(m.rms_mm, std::sqrt((4.0 + 6.0) / 7.0), 1e-12);
  // A window keeping the first two dates only.
  MisfitWindow w{0, 86400};
  const auto win = series_misfits(meas, sim, 2, w);
  EXPECT_EQ(win[0].n, 2u);
  EXPECT_EQ(win[1].n, 1u);
  EXPECT_NEAR(win[1].rms_mm, 0.0, 1e-12);
  MisfitWindow none{5 * 86400, 6 * 86400};
  EXPECT_THROW(combine_misfits(series_misfits(meas, sim, 2, none), {}, 0), InputError);
}

TEST(Brent, FindsTheMinimumOfAParabolaAndOfAnAsymmetricFunction) {
  int calls = 0;
  auto f = [&](double x) {
    ++calls;
    return (x - 0.3217) * (x - 0.3217) + 2.0;
  };
  const auto r = brent_minimize(f, 0, 1, 0.5, f(0.5), 1e-6, 100);
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.x, 0.3217, 1e-5);
  EXPECT_LT(r.evaluations, 15);
  auto g = [](double x) { return std::exp(3 * x) - 8 * x; };  // minimum at ln(8/3)/3
  const auto q = brent_minimize(g, 0, 1, 0.9, g(0.9), 1e-7, 100);
  EXPECT_NEAR(q.x, std::log(8.0 / 3.0) / 3.0, 1e-5);
  // At a bound.
  auto h = [](double x) { return x; };
  const auto b = brent_minimize(h, 0, 1, 0.5, 0.5, 1e-4, 100);
  EXPECT_LT(b.x, 1e-3);
}

// Library messages name the settings in words; each tool's main maps them to its flags
// (Tool::name_setting; CalibrateCli.BadInputs checks the tool's line).
TEST(SolverCommand, ErrorsNameTheSettingInWordsNotAFlag) {
  using ugs::runner::check_command_template;
  const auto message = [](const std::string& cmd, bool have_mesh) {
    try {
      check_command_template(cmd, have_mesh);
    } catch (const ugs::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message("run {case}", false).rfind("solver command: the command must contain {case}", 0), 0u);
  EXPECT_EQ(message("run {case} {out} {results}", false), "solver command: unknown placeholder {results} (known: {case} {out} {mesh} {dir})");
  EXPECT_EQ(message("run {case} {out} {mesh}", false), "solver command: uses {mesh} but no solver mesh was given");
  EXPECT_EQ(message("run {case} {out} {mesh}", true), "");
  for (const auto& cmd : {"run {case}", "run {case} {out} {x}", "run {case} {out} {mesh}"})
    EXPECT_EQ(message(cmd, false).find("--"), std::string::npos) << cmd;
}

// A case with several problems at a bound: each problem names the case, none the temporary copy it
// was checked in (the mutation test found the copy's name in all but the first).
TEST(CaseParameters, EveryProblemOfAnInvalidCopyNamesTheCase) {
  const auto dir = test::temp_dir("case-check-names");
  std::string text = test::slurp(kCase);
  const auto at = text.find("[initial_stress]\n");
  ASSERT_NE(at, std::string::npos);
  text.insert(at + 17, "bogus_one = 1.0\nbogus_two = 2.0\n");
  test::spit(dir / "case.toml", text);
  const std::string invalid = test::input_error_of(
      [&] { check_parameters(CaseTemplate((dir / "case.toml").string()), {parse_parameter("material.pool_c.c_R=2:6")}); });
  EXPECT_NE(invalid.find("case.toml:"), std::string::npos) << invalid;
  EXPECT_NE(invalid.find("bogus_one"), std::string::npos) << invalid;
  EXPECT_NE(invalid.find("bogus_two"), std::string::npos) << invalid;
  EXPECT_EQ(invalid.find("ugs-case-check"), std::string::npos) << invalid;
  EXPECT_GE(std::count(invalid.begin(), invalid.end(), '\n'), 1) << invalid;
  std::filesystem::remove_all(dir);
}

// The same for the parameters, the misfit, the CRSs, the polygons and the points (issue 23: library
// code names no tool's flags). CalibrateCli.LibraryMessagesShowTheFlags and SampleCli.BadInputs
// check the tools' lines.
TEST(AnalysisMessages, NameTheSettingsInWordsNotFlags) {
  const std::string bounds = test::input_error_of([] { parse_parameter("material.pool_c.c_R=6:2"); });
  EXPECT_EQ(bounds, "parameter to calibrate material.pool_c.c_R=6:2: lower bound 6 is not below upper bound 2 (bounds reversed?)");
  const std::string invalid = test::input_error_of([] { check_parameters(CaseTemplate(kCase), {parse_parameter("material.pool_c.c_R=0:6")}); });
  EXPECT_EQ(invalid.rfind("parameter to calibrate material.pool_c.c_R: the case is not valid at material.pool_c.c_R = 0: ", 0), 0u)
      << invalid;
  const std::string twice = test::input_error_of([] {
    check_parameters(CaseTemplate(kCase), {parse_parameter("material.pool_c.c_R=2:6"), parse_parameter("material.pool_c.c_R=3:5")});
  });
  EXPECT_EQ(twice, "parameter to calibrate material.pool_c.c_R: 'material.pool_c.c_R' is named twice");
  const std::string window = test::input_error_of([] { combine_misfits({}, {}, 0.0); });
  EXPECT_EQ(window, "no measured value of the PS selection falls in the misfit window within the results' dates");
  const std::string crs = test::input_error_of([] { model_crs("EPSG:nothing", ""); });
  EXPECT_EQ(crs, "model CRS: unknown coordinate reference system 'EPSG:nothing' (e.g. \"EPSG:32632\")");
  const auto dir = test::temp_dir("analysis-messages");
  test::spit(dir / "ps.csv", "pid,x,y,20150601\nA,680300,4950300,0\n");
  test::spit(dir / "lonlat.csv", "pid,lon,lat,20150601\nA,11.3,44.7,0\n");
  test::spit(dir / "none.geojson",
             R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32632"}},)"
             R"("features":[{"type":"Feature","properties":{"name":"A"},"geometry":{"type":"Polygon",)"
             R"("coordinates":[[[680000,4950000],[680500,4950000],[680500,4950500],[680000,4950000]]]}}]})");
  PsReadOptions ro;
  ro.points_crs = "EPSG:nothing";
  const std::string points_crs = test::input_error_of([&] { read_ps((dir / "ps.csv").string(), ro); });
  EXPECT_EQ(points_crs, "points CRS: unknown coordinate reference system 'EPSG:nothing' (e.g. \"EPSG:32632\")");
  const std::string lonlat = test::input_error_of([&] { read_ps((dir / "lonlat.csv").string(), PsReadOptions{}); });
  EXPECT_NE(lonlat.find("the model CRS is needed to place them (give it, or a case file with crs)"), std::string::npos) << lonlat;
  const std::string polygons = test::input_error_of([&] { read_polygons((dir / "none.geojson").string(), "", "name = 'B'"); });
  EXPECT_EQ(polygons, (dir / "none.geojson").string() + ": has no polygon: none in the file, or none kept by the polygon filter");
  for (const auto& m : {bounds, invalid, twice, window, crs, points_crs, lonlat, polygons}) {
    EXPECT_FALSE(m.empty());
    EXPECT_EQ(m.find("--"), std::string::npos) << m;
  }
  std::filesystem::remove_all(dir);
}
