// ugs-submesh and ugs-flow as users run them: outputs, bad input (exit 2, one line naming
// file:line, nothing written), calibration, and the sample twin (Pool C's aquifer pressure maps
// in 1960 and 1964, thesis Figs. 4.7-4.8).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <regex>

#include "case_toml.hpp"
#include "run_tool.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/box_mesh.hpp"
#include "ugs/meshing/geodata.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

const std::string kCase = [] {
  namespace tc = testcase;
  const std::string conductivity = "K_m_per_s = [2.04e-7, 2.04e-7, 2.04e-8]\n";
  tc::CaseToml c("", tc::Numbers::Decimal);
  c.table("model", "start = \"1950-01-01\"\nend = \"1952-01-01\"\n");
  c.initial_stress({.surface_elevation_m = 50, .lithostatic_gradient_MPa_per_m = {}, .hydrostatic_gradient_MPa_per_m = {}});
  c.material({.name = "pool", .more = conductivity + "porosity = 0.2\n"});
  c.material({.name = "aquifer", .more = conductivity + "porosity = 0.2\n"});
  c.material({.name = "ghost", .more = "porosity = 0.2\n"});
  c.pool({.name = "Pool", .materials = {"pool"}, .schedule = "pool.csv", .more = "reference_pressure_MPa = 15.0\n"});
  return c.str();
}();

std::string schedule_rows(int months) {
  std::string s = "date,p_MPa\n";
  for (int m = 0; m <= months; ++m)
    s += fmt::format("{}-{:02d}-01,{:.4f}\n", 1950 + m / 12, m % 12 + 1, 15.0 - 4.0 * (1 - std::exp(-m / 8.0)));
  return s;
}

struct Case {
  fs::path dir;
  std::string flow(const std::string& args) const {
    return "cd " + dir.string() + " && " + test::tool("ugs-flow") + " mesh.msh --case case.toml " + args;
  }
};

Case make_case(const std::string& tag, const std::string& case_text = kCase, const std::string& schedule = schedule_rows(24)) {
  Case c{test::temp_dir("flow-" + tag)};
  BoxMeshSpec s;
  s.x = linspace(0, 3000, 10);
  s.y = linspace(0, 2000, 6);
  s.z = linspace(-1520, -1500, 2);
  s.material = [](const Point3& p) { return std::string(p[0] < 600 && p[1] < 800 ? "pool" : "aquifer"); };
  write_msh(make_box_mesh(s), (c.dir / "mesh.msh").string());
  test::spit(c.dir / "case.toml", case_text);
  test::spit(c.dir / "pool.csv", schedule);
  return c;
}

// One line on stderr, "ugs-flow: error: <where>: ...", exit code 2, and no output left behind.
void expect_bad_input(const Case& c, const test::RunResult& r, const std::string& where, const std::string& what) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("ugs-flow: error: " + where, 0), 0u) << r.err;
  EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
  for (const auto& e : fs::directory_iterator(c.dir))
    EXPECT_TRUE(e.path().extension() != ".h5" && e.path().extension() != ".xdmf" && e.path().string().find("influx") == std::string::npos)
        << "left behind: " << e.path();
}

std::string replace_line(std::string text, int line, const std::string& by) {
  std::vector<std::string> lines;
  std::size_t a = 0;
  while (a < text.size()) {
    const auto b = text.find('\n', a);
    lines.push_back(text.substr(a, b - a));
    a = b + 1;
  }
  lines[line - 1] = by;
  std::string out;
  for (const auto& l : lines)
    if (l != "\x01") out += l + "\n";
  return out;
}

}  // namespace

TEST(FlowCli, WritesFieldsAndInflux) {
  const Case c = make_case("ok");
  const auto r = test::run(c.flow("-o dp.h5 -v"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("mass balance"), std::string::npos);
  ASSERT_TRUE(fs::exists(c.dir / "dp.xdmf"));
  const Mesh mesh = read_msh((c.dir / "mesh.msh").string());
  FieldSeriesReader rd((c.dir / "dp.h5").string());
  ASSERT_EQ(rd.steps().size(), 25u);
  EXPECT_EQ(rd.steps().front().date, "1950-01-01");
  EXPECT_EQ(rd.node_tags(), mesh.node_tags);
  const Field dp = rd.node_field(24, "dp"), norm = rd.node_field(24, "dp_norm");
  const double expected = -4.0e6 * (1 - std::exp(-24 / 8.0));
  // A pool node (x = 0, y = 0) follows the schedule; dp_norm = dp / 15 MPa.
  EXPECT_NEAR(dp.values[0], std::round(expected / 100) * 100, 60.0);  // the CSV carries 4 decimals of MPa
  EXPECT_NEAR(norm.values[0], dp.values[0] / 15e6, 1e-15);
  const CsvTable t = CsvTable::read((c.dir / "dp_influx.csv").string());
  EXPECT_EQ(t.columns(), (std::vector<std::string>{"date", "Pool_influx_m3", "storage_change_m3"}));
  ASSERT_EQ(t.rows(), 25u);
  EXPECT_GT(t.number(24, 1), 0.0);                                  // water entered the depleted pool
  EXPECT_NEAR(t.number(24, 1), -t.number(24, 2), 1e-9 * t.number(24, 1));  // = the aquifer's loss
}

TEST(FlowCli, SameInputSameOutput) {
  const Case c = make_case("same");
  ASSERT_EQ(test::run(c.flow("-o a.h5 --substeps 2")).exit_code, 0);
  ASSERT_EQ(test::run(c.flow("-o b.h5 --substeps 2")).exit_code, 0);
  EXPECT_EQ(test::slurp(c.dir / "a.h5"), test::slurp(c.dir / "b.h5"));
  EXPECT_EQ(test::slurp(c.dir / "a_influx.csv"), test::slurp(c.dir / "b_influx.csv"));
}

TEST(FlowCli, OutputDatesSubstepsAndEnd) {
  const Case c = make_case("dates");
  const auto r = test::run(c.flow("-o a.h5 --output-dates 1950-07-01,1951-01-15 --substeps 3 --end 1951-06-01"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  FieldSeriesReader rd((c.dir / "a.h5").string());
  ASSERT_EQ(rd.steps().size(), 2u);
  EXPECT_EQ(rd.steps()[1].date, "1951-01-15");  // not a schedule date: inserted, the schedule interpolated
  EXPECT_EQ(CsvTable::read((c.dir / "a_influx.csv").string()).rows(), 19u);  // 18 months + the inserted date
}

TEST(FlowCli, BadSchedules) {
  const std::string good = schedule_rows(24);
  struct Bad {
    std::string tag;
    int line;
    std::string row, what;
  } bad[] = {
      {"unsorted", 5, "1950-02-15,14.0", "dates must increase"},
      {"duplicate", 5, "1950-03-01,14.0", "duplicate date 1950-03-01"},
      {"gap", 5, "\x01", "gap of 61 days after 1950-03-01"},
      {"number", 6, "1950-05-01,abc", "'abc' is not a number"},
  };
  for (const auto& b : bad) {
    SCOPED_TRACE(b.tag);
    const Case c = make_case("bad-" + b.tag, kCase, replace_line(good, b.line, b.row));
    const int line = b.tag == "gap" ? 5 : b.line;
    expect_bad_input(c, test::run(c.flow("-o dp.h5")), "pool.csv:" + std::to_string(line), b.what);
  }
  {
    const Case c = make_case("early", kCase, "date,p_MPa\n1949-12-01,15.0\n" + good.substr(good.find('\n') + 1));
    expect_bad_input(c, test::run(c.flow("-o dp.h5")), "pool.csv:2", "lies before the run start 1950-01-01");
  }
  {
    const Case c = make_case("late", kCase, good + "1952-02-01,11.0\n");
    expect_bad_input(c, test::run(c.flow("-o dp.h5")), "pool.csv:27", "lies after the run end 1952-01-01");
  }
  {
    const Case c = make_case("short", kCase, schedule_rows(20));
    expect_bad_input(c, test::run(c.flow("-o dp.h5")), "pool.csv:22", "before the run end");
  }
}

TEST(FlowCli, BadCases) {
  {  // an aquifer material without conductivity: the error points at its [[material]] table
    std::string text = kCase;
    const std::string k = "K_m_per_s = [2.04e-7, 2.04e-7, 2.04e-8]\n";
    text.erase(text.find(k, text.find("\"aquifer\"")), k.size());
    const Case c = make_case("nok", text);
    expect_bad_input(c, test::run(c.flow("-o dp.h5")), "case.toml:13", "material 'aquifer' has no conductivity");
  }
  {  // a pool material that is not in the mesh
    std::string text = kCase;
    text.replace(text.find("materials = [\"pool\"]"), 20, "materials = [\"pool\", \"ghost\"]");
    const Case c = make_case("ghost", text);
    expect_bad_input(c, test::run(c.flow("-o dp.h5")), "case.toml:22", "material 'ghost' is not in mesh.msh");
  }
  {
    const Case c = make_case("opts");
    expect_bad_input(c, test::run(c.flow("-o dp.h5 --end 1953-01-01")), "--end", "outside the run");
    expect_bad_input(c, test::run(c.flow("-o dp.h5 --calibrate-k 1e5")), "--calibrate-k", "TARGET_M3@DATE");
    expect_bad_input(c, test::run(c.flow("-o dp.h5 --pool Nope")), "case.toml", "no pool 'Nope'");
  }
}

TEST(FlowCli, CalibratesTheAquiferConductivity) {
  // The influx with K x 2.5, then the calibration from K must find 2.5.
  std::string doubled = kCase;
  for (std::size_t at = doubled.find("2.04e-7"); at != std::string::npos; at = doubled.find("2.04e-7", at + 1))
    doubled.replace(at, 7, "5.1e-7 ");
  for (std::size_t at = doubled.find("2.04e-8"); at != std::string::npos; at = doubled.find("2.04e-8", at + 1))
    doubled.replace(at, 7, "5.1e-8 ");
  const Case ref = make_case("cal-ref", doubled);
  ASSERT_EQ(test::run(ref.flow("-o dp.h5")).exit_code, 0);
  const CsvTable t = CsvTable::read((ref.dir / "dp_influx.csv").string());
  const double target = t.number(15, 1);  // 1951-04-01
  const Case c = make_case("cal");
  const auto r = test::run(c.flow(fmt::format("-o dp.h5 --calibrate-k {:.17g}@1951-04-01 --calibrate-tolerance 1e-8", target)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("calibration  1 (bracket)"), std::string::npos) << r.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, std::regex("aquifer,([^,]+),([^,]+),([^,]+),([^,\\n]+)"))) << r.out;
  EXPECT_NEAR(std::stod(m[4]), 2.5, 2.5e-5);
  EXPECT_NEAR(std::stod(m[1]), 5.1e-7, 5.1e-11);
  // The outputs are those of the calibrated run.
  const CsvTable tc = CsvTable::read((c.dir / "dp_influx.csv").string());
  EXPECT_NEAR(tc.number(15, 1), target, 1e-6 * target);
}

TEST(SubmeshCli, MaterialsPolygonAndErrors) {
  const Case c = make_case("submesh");
  const std::string tool = "cd " + c.dir.string() + " && " + test::tool("ugs-submesh") + " mesh.msh ";
  auto r = test::run(tool + "--materials aquifer,pool -o sub.msh");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_msh((c.dir / "sub.msh").string()).num_nodes(), 11u * 7u * 3u);
  test::spit(c.dir / "square.geojson",
             R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"name":"west"},)"
             R"("geometry":{"type":"Polygon","coordinates":[[[-10,-10],[1510,-10],[1510,2010],[-10,2010],[-10,-10]]]}}]})");
  r = test::run(tool + "--materials aquifer,pool --polygon square.geojson --where \"name = 'west'\" > half.msh");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Mesh half = read_msh((c.dir / "half.msh").string());
  EXPECT_EQ(half.count(ElementType::Tetrahedron), 5u * 6u * 2u * 6u);
  // The pool's materials from the case file (this case lists no aquifer_materials: a warning).
  r = test::run(tool + "--case case.toml --pool Pool -o pool_only.msh");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("lists no aquifer_materials"), std::string::npos) << r.err;
  EXPECT_EQ(read_msh((c.dir / "pool_only.msh").string()).count(ElementType::Tetrahedron), 2u * 2u * 2u * 6u);
  r = test::run(tool + "--case case.toml -o x.msh");
  EXPECT_EQ(r.exit_code, 2);
  r = test::run(tool + "--materials rock");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.rfind("ugs-submesh: error: mesh.msh: no material 'rock' in the mesh (materials: ", 0), 0u) << r.err;
  r = test::run(tool + "--materials pool --barrier fault:F1 -o x.msh");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no fault 'fault:F1'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(c.dir / "x.msh"));
}

// The sample twin (data-samples/po-plain): Pool C's flow mesh cut from a layered box mesh of the
// sample's plan (materials from the sample's Pool C trace and aquifer polygons; the real mesh of
// ugs-meshgen takes minutes, the box gives the same pipeline), the sample's case file and Pool C
// schedule, primary production 1950-1964.
TEST(FlowTwin, PoolCAquiferMapsIn1960And1964) {
  const fs::path sample = fs::path(UGS_SOURCE_DIR) / "data-samples" / "po-plain";
  if (!fs::exists(sample / "case.toml") || !fs::exists(sample / "pressure_pool_c.csv")) GTEST_SKIP() << "no sample data";
  const std::string wkt = geo::crs_wkt("EPSG:32632", "test");
  const auto traces = geo::read_vector((sample / "reservoir_traces.geojson").string(), wkt, "name = 'Pool C'");
  const auto aquifer = geo::read_vector((sample / "aquifers.geojson").string(), wkt, "name = 'Pool C'");
  ASSERT_FALSE(traces.features.empty());
  ASSERT_FALSE(aquifer.features.empty());
  const geo::PolygonSet pool_c(traces.features[0].polygons), aquifer_c(aquifer.features[0].polygons);
  const fs::path dir = test::temp_dir("flow-twin");
  BoxMeshSpec s;
  s.x = linspace(671000, 690000, 76);  // 250 m
  s.y = linspace(4945000, 4958500, 54);
  s.z = {-1543, -1515, -1506.5, -1498};  // below Pool C, then Pool C in two layers
  s.material = [&](const Point3& c) {
    if (c[2] < -1515) return std::string("surrounding_rock");
    if (pool_c.contains({c[0], c[1]})) return std::string("pool_c");
    return std::string(aquifer_c.contains({c[0], c[1]}) ? "aquifer_pool_c" : "surrounding_rock");
  };
  write_msh(make_box_mesh(s), (dir / "model.msh").string());
  fs::copy_file(sample / "case.toml", dir / "case.toml");
  fs::copy_file(sample / "pressure_pool_c.csv", dir / "pressure_pool_c.csv");
  fs::copy_file(sample / "pressure_pool_a.csv", dir / "pressure_pool_a.csv");
  const std::string cd = "cd " + dir.string() + " && ";
  auto r = test::run(cd + test::tool("ugs-submesh") + " model.msh --case case.toml --pool 'Pool C' | " + test::tool("ugs-flow") +
                     " - --case case.toml --end 1964-01-01 --output-dates 1960-01-01,1964-01-01 -o pool_c.h5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  FieldSeriesReader rd((dir / "pool_c.h5").string());
  ASSERT_EQ(rd.steps().size(), 2u);
  EXPECT_EQ(rd.steps()[0].date, "1960-01-01");
  EXPECT_EQ(rd.steps()[1].date, "1964-01-01");
  const auto xyz = rd.coordinates();
  const double drop[2] = {-0.35, -0.52};  // thesis 4.2.1, Fig. 4.6
  double aquifer_mean[2] = {0, 0};
  for (std::size_t k = 0; k < 2; ++k) {
    const Field f = rd.node_field(k, "dp_norm");
    double pool_min = 0, pool_max = -1, aq_min = 0, far_max = -1;
    std::size_t aquifer_nodes = 0;
    for (std::size_t n = 0; n < f.values.size(); ++n) {
      if (pool_c.contains({xyz[n][0], xyz[n][1]})) {
        pool_min = std::min(pool_min, f.values[n]), pool_max = std::max(pool_max, f.values[n]);
      } else {
        aquifer_mean[k] += f.values[n], ++aquifer_nodes;
      }
      aq_min = std::min(aq_min, f.values[n]);
      far_max = std::max(far_max, f.values[n]);
    }
    aquifer_mean[k] /= aquifer_nodes;
    EXPECT_NEAR(pool_min, drop[k], 1e-9);  // the pool follows its schedule (nodes inside its trace)
    EXPECT_NEAR(pool_max, drop[k], 1e-9);
    EXPECT_GE(aq_min, drop[k] - 1e-9);    // the aquifer lies between the pool and the initial state
    EXPECT_LT(far_max, 0.0);
    EXPECT_GT(far_max, 0.5 * drop[k]);    // and its far end feels much less than the pool
    EXPECT_LT(aquifer_mean[k], 0.2 * drop[k]);
  }
  EXPECT_LT(aquifer_mean[1], aquifer_mean[0] * 0.52 / 0.35);  // the depletion spread further by 1964
  const CsvTable t = CsvTable::read((dir / "pool_c_influx.csv").string());
  EXPECT_EQ(t.columns()[1], "Pool_C_influx_m3");
  EXPECT_GT(t.number(t.rows() - 1, 1), 1e5);  // aquifer water encroached into Pool C by 1964
}

// Issue 20: every number of the case file is finite and in range, or exit 2 naming file:line, key and
// value; a directory given as the case file is named as such; a solve that still yields a NaN or an
// infinity stops with exit 1 and writes nothing.
TEST(FlowCli, NonFiniteAndOutOfRangeNumbers) {
  const std::string k = "K_m_per_s = [2.04e-7, 2.04e-7, 2.04e-8]";
  const auto aquifer_k = kCase.find(k, kCase.find("\"aquifer\""));
  auto with_k = [&](const std::string& by) { return std::string(kCase).replace(aquifer_k, k.size(), by); };
  struct Bad {
    std::string tag, text, where, what;
  } bad[] = {
      {"k-inf", with_k("K_m_per_s = [inf, 2.04e-7, 2.04e-8]"), "case.toml:15", "material[1].K_m_per_s[0] = inf is not a finite number"},
      {"k-minus-inf", with_k("K_m_per_s = [2.04e-7, -inf, 2.04e-8]"), "case.toml:15",
       "material[1].K_m_per_s[1] = -inf is not a finite number"},
      {"k-nan", with_k("K_m_per_s = [2.04e-7, 2.04e-7, nan]"), "case.toml:15", "material[1].K_m_per_s[2] = nan is not a finite number"},
      {"beta-inf", kCase + "\n[water]\ncompressibility_per_MPa = inf\n", "case.toml:30",
       "water.compressibility_per_MPa = inf is not a finite number"},
      {"beta-minus-inf", kCase + "\n[water]\ncompressibility_per_MPa = -inf\n", "case.toml:30",
       "water.compressibility_per_MPa = -inf is not a finite number"},
      {"beta-negative", kCase + "\n[water]\ncompressibility_per_MPa = -4.4e-4\n", "case.toml:30",
       "'water.compressibility_per_MPa': must not be negative, got -0.00044"},
      {"k-zero", with_k("K_m_per_s = [0, 2.04e-7, 2.04e-8]"), "case.toml:15", "conductivities must be positive, got 0"},
      {"cm-b-negative", with_k(k + "\ncm_b = -3"), "case.toml:", "'material[1].cm_b': must not be negative"},
  };
  for (const auto& b : bad) {
    SCOPED_TRACE(b.tag);
    const Case c = make_case("nf-" + b.tag, b.text);
    expect_bad_input(c, test::run(c.flow("-o dp.h5")), b.where, b.what);
  }
  {  // a directory as the case file
    const Case c = make_case("nf-dir");
    fs::remove(c.dir / "case.toml");
    fs::create_directory(c.dir / "case.toml");
    expect_bad_input(c, test::run(c.flow("-o dp.h5")), "case.toml", "case.toml: is a directory (expected a TOML file)");
  }
  {  // finite but absurd: K = 1e308 m/s overflows the conductances; never NaN with exit 0
    const Case c = make_case("nf-huge", with_k("K_m_per_s = [1e308, 1e308, 1e308]"));
    const auto r = test::run(c.flow("-q -o dp.h5"));
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(std::regex_search(r.err, std::regex("^ugs-flow: error: .*is -?(nan|inf)"))) << r.err;
    EXPECT_FALSE(fs::exists(c.dir / "dp.h5"));
    EXPECT_FALSE(fs::exists(c.dir / "dp_influx.csv"));
  }
}

// Issue 20: numeric options are finite and in range too (--reference-pressure inf made dp_norm 0
// everywhere with exit 0; --max-step inf overflowed to a negative step).
TEST(FlowCli, NonFiniteOptionsAreRefused) {
  const Case c = make_case("nf-opts");
  expect_bad_input(c, test::run(c.flow("-o dp.h5 --reference-pressure inf")), "--reference-pressure", "inf (expected a finite number >= 0)");
  expect_bad_input(c, test::run(c.flow("-o dp.h5 --reference-pressure nan")), "--reference-pressure", "nan (expected a finite number >= 0)");
  expect_bad_input(c, test::run(c.flow("-o dp.h5 --max-step inf")), "--max-step", "inf (expected a finite number in (0, 36525])");
  expect_bad_input(c, test::run(c.flow("-o dp.h5 --calibrate-tolerance nan")), "--calibrate-tolerance",
                   "nan (expected a finite number in (0, 1))");
}
