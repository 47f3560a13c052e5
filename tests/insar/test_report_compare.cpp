// ugs-report --compare (issue 22: the report compares the uplift from a reservoir simulator's
// pressures with that of the schedule-driven flow model): two runs on the same mesh whose vertical
// displacement differs by a known factor; the comparison table, the figure and the headline ratio
// must say so, and runs that do not fit are refused with one line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "run_tool.hpp"
#include "solve_box.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

// A Gaussian bump of vertical displacement over Pool C, amplitude a (m) at its centre node.
void write_run(const Mesh& m, const fs::path& path, const std::vector<std::pair<std::string, double>>& steps) {
  FieldSeriesWriter w(path.string(), m);
  for (const auto& [date, a] : steps) {
    Field u{"u", 3, {}};
    for (const auto& p : m.nodes) {
      const double dx = p[0] - test::kPoolXc, dy = p[1] - test::kPoolYc;
      u.values.insert(u.values.end(), {0.0, 0.0, a * std::exp(-(dx * dx + dy * dy) / (2500.0 * 2500.0))});
    }
    const Field nf[] = {u};
    w.add_step(date, double(*parse_iso_date(date)), nf, {});
  }
  w.commit();
}

struct Case {
  fs::path dir;
  std::string base;  // ugs-report with this run, the mesh and the trace
};

Case make_case(const std::string& tag) {
  Case c{test::temp_dir(tag), ""};
  const Mesh m = test::solve_box_mesh();
  write_msh(m, (c.dir / "model.msh").string());
  // This run: +3.8 mm at the centre from May to November, -1.6 mm to the next May.
  write_run(m, c.dir / "a.h5", {{"2015-05-01", -0.010}, {"2015-11-01", -0.0062}, {"2016-05-01", -0.0078}});
  // The other: twice the change, with one date more (left out: not shared) and an offset of its own.
  write_run(m, c.dir / "b.h5",
            {{"2015-05-01", 0.5}, {"2015-08-01", 0.51}, {"2015-11-01", 0.5076}, {"2016-05-01", 0.5044}});
  test::spit(c.dir / "trace.geojson", R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32632"}},
"features":[{"type":"Feature","properties":{"name":"Pool C"},"geometry":{"type":"Polygon","coordinates":[[[680000,4951000],[683000,4951000],[683000,4954000],[680000,4954000],[680000,4951000]]]}}]})");
  const std::string d = c.dir.string() + "/";
  c.base = test::tool("ugs-report") + " --thesis --results " + d + "a.h5 --mesh " + d + "model.msh --trace " + d + "trace.geojson" +
           " --crs EPSG:32632 --width 400 --height 300";
  return c;
}

bool one_line_error(const test::RunResult& r) {
  return r.exit_code == 2 && r.err.rfind("ugs-report: error: ", 0) == 0 && r.err.find('\n') == r.err.size() - 1;
}

}  // namespace

TEST(ReportCompare, TableFigureAndRatioOfTwoRuns) {
  const Case c = make_case("report-compare");
  const std::string d = c.dir.string() + "/";
  const auto r = test::run(c.base + " --compare 'flow model=" + d + "b.h5' -o " + d + "rep");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable t = CsvTable::read((c.dir / "rep" / "comparison.csv").string());
  ASSERT_EQ(t.rows(), 6u);  // 2 runs x the 3 shared dates (2015-08-01 is only in b.h5)
  const auto run = t.column("run"), mean = t.column("uz_mean_mm"), peak = t.column("uz_peak_mm");
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(t.text(k, run), "this run");
    EXPECT_EQ(t.text(3 + k, run), "flow model");
    // Twice the change everywhere: the mean and the peak over the trace double.
    EXPECT_NEAR(t.number(3 + k, mean), 2 * t.number(k, mean), 2e-4);
    EXPECT_NEAR(t.number(3 + k, peak), 2 * t.number(k, peak), 2e-4);
  }
  EXPECT_EQ(t.number(0, mean), 0.0);  // changes since the first shared date
  EXPECT_NEAR(t.number(1, peak), 3.8, 1e-4);   // the centre node lies inside the trace
  EXPECT_NEAR(t.number(2, peak), 2.2, 1e-4);
  EXPECT_GT(t.number(1, mean), 0.5);
  EXPECT_LT(t.number(1, mean), 3.8);
  const std::string md = test::slurp(c.dir / "rep" / "summary.md");
  EXPECT_NE(md.find("| Run comparison | mean u_z change, this run / 'flow model' | 0.50 .. 0.50"), std::string::npos) << md;
  EXPECT_NE(md.find("![Vertical displacement: this run vs flow model](comparison.png)"), std::string::npos) << md;
  EXPECT_NE(md.find("at the 3 dates they share"), std::string::npos) << md;
  EXPECT_TRUE(fs::exists(c.dir / "rep" / "comparison.png"));
  // From a later date: the changes count from there.
  const auto r2 = test::run(c.base + " --compare 'flow model=" + d + "b.h5' --compare-since 2015-11-01 -o " + d + "rep2");
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  const CsvTable t2 = CsvTable::read((c.dir / "rep2" / "comparison.csv").string());
  ASSERT_EQ(t2.rows(), 4u);
  EXPECT_NEAR(t2.number(1, t2.column("uz_peak_mm")), -1.6, 1e-4);
  EXPECT_NEAR(t2.number(3, t2.column("uz_peak_mm")), -3.2, 1e-4);
  if (!HasFailure() && !std::getenv("UGS_TEST_KEEP")) fs::remove_all(c.dir);
}

TEST(ReportCompare, RunsThatDoNotFitAreRefused) {
  const Case c = make_case("report-compare-bad");
  const std::string d = c.dir.string() + "/";
  auto r = test::run(c.base + " --compare " + d + "b.h5 -o " + d + "x");
  EXPECT_TRUE(one_line_error(r)) << r.err;
  EXPECT_NE(r.err.find("is not LABEL=FILE"), std::string::npos) << r.err;
  r = test::run(c.base + " --compare 'this run=" + d + "b.h5' -o " + d + "x");
  EXPECT_TRUE(one_line_error(r)) << r.err;
  EXPECT_NE(r.err.find("given twice"), std::string::npos) << r.err;
  // One shared date only.
  write_run(test::solve_box_mesh(), c.dir / "one.h5", {{"2015-05-01", 0.0}, {"2020-01-01", 0.1}});
  r = test::run(c.base + " --compare 'other=" + d + "one.h5' -o " + d + "x");
  EXPECT_TRUE(one_line_error(r)) << r.err;
  EXPECT_NE(r.err.find("shares 1 dates"), std::string::npos) << r.err;
  // From a date after which the runs share one date only, or a date not shared.
  r = test::run(c.base + " --compare 'other=" + d + "b.h5' --compare-since 2016-05-01 -o " + d + "x");
  EXPECT_TRUE(one_line_error(r)) << r.err;
  EXPECT_NE(r.err.find("shares 1 dates"), std::string::npos) << r.err;
  r = test::run(c.base + " --compare 'other=" + d + "b.h5' --compare-since 2015-08-01 -o " + d + "x");
  EXPECT_TRUE(one_line_error(r)) << r.err;
  EXPECT_NE(r.err.find("not a date every compared run holds"), std::string::npos) << r.err;
  // A run on another mesh (its nodes elsewhere).
  Mesh moved = test::solve_box_mesh();
  for (auto& p : moved.nodes) p[0] += 10;
  write_run(moved, c.dir / "moved.h5", {{"2015-05-01", 0.0}, {"2015-11-01", 0.1}, {"2016-05-01", 0.1}});
  r = test::run(c.base + " --compare 'moved=" + d + "moved.h5' -o " + d + "x");
  EXPECT_TRUE(one_line_error(r)) << r.err;
  EXPECT_FALSE(fs::exists(c.dir / "x"));
  for (const auto& e : fs::directory_iterator(c.dir)) EXPECT_EQ(e.path().filename().string().find(".x.tmp"), std::string::npos);
  if (!HasFailure() && !std::getenv("UGS_TEST_KEEP")) fs::remove_all(c.dir);
}
