// ugs-report on the faulted solver's outputs (contact_make_case at 100 m cells: fault F, the plane
// x = z + 1300 striking north, crossing a reservoir whose pressure rises by 6 MPa; a pool "Pool R"
// on the reservoir's material added to the case for the report, 10 MPa in 2000, 16 MPa in 2001):
//  - one max chi: the report's table (headlines.csv), ugs-solve's faults CSV and the largest HDF5
//    node value of chi agree for each fault and date (the table showed per-element means before:
//    0.851 where the CSV said 1.000 on the demo);
//  - the scenario dates: the lowest and highest pool pressure;
//  - the time plot's data (work/max_chi.csv) is the faults CSV's max_chi at every step, with the
//    pool pressures (work/pressure.csv);
//  - the pools' outline on the fault plane (work/pools_on_f.csv) spans the reservoir's y and z
//    range, shifted by the fault's along-strike origin (y = 100);
//  - the figures exist; a faults table without max_chi: exit 2, one line, nothing left.
#include <cmath>
#include <filesystem>
#include <map>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "run_tool.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

using Dir = test::TempDir;

}  // namespace

TEST(ReportFaults, OneMaxChiAndThePlotData) {
  Dir d("report-faults");
  auto r = test::run(std::string(UGS_BINARY_DIR) + "/tests/fault_mechanics/contact_make_case " + d.path.string() + " --dp 6 --cell 100");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run(test::tool("ugs-solve") + " " + d / "faulted.msh" + " --case " + d / "case.toml" + " --pressure " + d / "flow.h5" +
                " -o " + d / "out.h5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  test::spit(d / "report.toml", test::slurp(d / "case.toml") +
                                    "\n[[pool]]\nname = \"Pool R\"\nmaterials = [\"reservoir\"]\nschedule = \"pool.csv\"\n"
                                    "column = \"p_MPa\"\n");
  test::spit(d / "pool.csv", "date,p_MPa\n1999-01-01,10\n2000-01-01,10\n2001-01-01,16\n2002-01-01,16\n");
  r = test::run(test::tool("ugs-report") + " --thesis --results " + d / "out.h5" + " --mesh " + d / "faulted.msh" + " --case " +
                d / "report.toml" + " --faults " + d / "out_faults.h5" + " --keep-work -o " + d / "rep");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("differs from the fault results"), std::string::npos) << r.err;

  // The HDF5's largest node value of chi per date, and ugs-solve's max_chi.
  FieldSeriesReader h5(d / "out_faults.h5");
  std::map<std::string, double> h5_max;
  for (std::size_t s = 0; s < h5.steps().size(); ++s) {
    double m = -1;
    for (double v : h5.node_field(s, "chi").values) m = std::max(m, v);
    h5_max[h5.steps()[s].date] = m;
  }
  const CsvTable stats = CsvTable::read(d / "out_faults.csv");
  std::map<std::string, double> csv_max;
  for (std::size_t i = 0; i < stats.rows(); ++i) {
    ASSERT_EQ(stats.text(i, stats.column("fault")), "F");
    csv_max[std::string(stats.text(i, stats.column("date")))] = stats.number(i, stats.column("max_chi"));
  }
  ASSERT_EQ(csv_max.size(), 2u);
  for (const auto& [date, v] : csv_max) EXPECT_NEAR(v, h5_max.at(date), 5e-7) << date;

  // The table: the minimum pressure scenario on 2000-01-01 (10 MPa), the maximum on 2001-01-01.
  const CsvTable head = CsvTable::read(d / "rep/headlines.csv");
  std::size_t seen = 0;
  for (std::size_t i = 0; i < head.rows(); ++i) {
    const std::string group(head.text(i, head.column("group"))), q(head.text(i, head.column("quantity")));
    const std::string value(head.text(i, head.column("value")));
    if (q == "maximum χ on F") {
      const std::string date = group.find("minimum") != std::string::npos ? "2000-01-01" : "2001-01-01";
      EXPECT_NE(group.find(date), std::string::npos) << group;
      EXPECT_EQ(value, fmt::format("{:.3f}", h5_max.at(date))) << group;
      EXPECT_EQ(value, fmt::format("{:.3f}", csv_max.at(date))) << group;
      ++seen;
    }
    if (q == "largest χ on F") {
      EXPECT_EQ(value, fmt::format("{:.3f} (2001-01-01)", csv_max.at("2001-01-01")));
      ++seen;
    }
  }
  EXPECT_EQ(seen, 3u);
  EXPECT_EQ(csv_max.at("2001-01-01"), 1.0);  // a pair slips or opens at +6 MPa

  // The time plot's data: the faults CSV's max_chi at every step; the pool pressures beside it.
  const CsvTable series = CsvTable::read(d / "rep/work/max_chi.csv");
  ASSERT_EQ(series.rows(), stats.rows());
  for (std::size_t i = 0; i < series.rows(); ++i) {
    EXPECT_EQ(series.text(i, series.column("fault")), stats.text(i, stats.column("fault")));
    EXPECT_EQ(series.text(i, series.column("date")), stats.text(i, stats.column("date")));
    EXPECT_EQ(series.number(i, series.column("value")), stats.number(i, stats.column("max_chi")));
  }
  const CsvTable pressure = CsvTable::read(d / "rep/work/pressure.csv");
  EXPECT_EQ(pressure.rows(), 4u);
  const std::string manifest = test::slurp(d / "rep/work/manifest.json");
  EXPECT_NE(manifest.find("\"kind\": \"chi_series\""), std::string::npos);
  EXPECT_NE(manifest.find("\"pressure\": \"work/pressure.csv\""), std::string::npos);

  // The pools' outline: the reservoir's nodes projected on F's plane, s = y - 100 (F's south end).
  const Mesh mesh = read_msh(d / "faulted.msh");
  double y0 = 1e300, y1 = -1e300, z0 = 1e300, z1 = -1e300;
  for (const auto& b : mesh.blocks)
    if (b.type == ElementType::Tetrahedron && mesh.physical_name_of(b.entity_dim, b.entity_tag) == "mat:reservoir")
      for (auto v : b.nodes) {
        y0 = std::min(y0, mesh.nodes[v][1]), y1 = std::max(y1, mesh.nodes[v][1]);
        z0 = std::min(z0, mesh.nodes[v][2]), z1 = std::max(z1, mesh.nodes[v][2]);
      }
  ASSERT_LT(y0, y1);
  const CsvTable outline = CsvTable::read(d / "rep/work/pools_on_f.csv");
  ASSERT_GE(outline.rows(), 5u);  // a closed ring
  double s0 = 1e300, s1 = -1e300, oz0 = 1e300, oz1 = -1e300;
  for (std::size_t i = 0; i < outline.rows(); ++i) {
    EXPECT_EQ(outline.text(i, outline.column("pool")), "Pool R");
    const double s = outline.number(i, outline.column("s")), z = outline.number(i, outline.column("z"));
    s0 = std::min(s0, s), s1 = std::max(s1, s), oz0 = std::min(oz0, z), oz1 = std::max(oz1, z);
  }
  EXPECT_EQ(outline.number(0, 1), outline.number(outline.rows() - 1, 1));
  EXPECT_EQ(outline.number(0, 2), outline.number(outline.rows() - 1, 2));
  EXPECT_NEAR(s0, y0 - 100, 1e-3);
  EXPECT_NEAR(s1, y1 - 100, 1e-3);
  EXPECT_NEAR(oz0, z0, 1e-3);
  EXPECT_NEAR(oz1, z1, 1e-3);
  std::printf("max chi %.6f / %.6f; pool outline s %.1f..%.1f m, z %.1f..%.1f m\n", csv_max.begin()->second,
              csv_max.rbegin()->second, s0, s1, oz0, oz1);

  for (const char* png : {"chi_minimum_pressure.png", "chi_maximum_pressure.png", "chi_max_series.png"})
    EXPECT_GT(fs::file_size(d / ("rep/" + std::string(png))), 10000u) << png;

  // A faults table without max_chi: exit 2, one line naming the file and the column, no report.
  test::spit(d / "bad.csv", "date,fault\n2000-01-01,F\n");
  r = test::run(test::tool("ugs-report") + " --thesis --results " + d / "out.h5" + " --faults " + d / "out_faults.h5" + " --fault-table " +
                d / "bad.csv" + " -q -o " + d / "bad");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err, "ugs-report: error: " + d / "bad.csv" + ": no column 'max_chi' (columns: date, fault)\n");
  EXPECT_FALSE(fs::exists(d / "bad"));
  std::size_t left = 0;
  for (const auto& e : fs::directory_iterator(d.path)) left += e.path().filename().string().find(".tmp") != std::string::npos;
  EXPECT_EQ(left, 0u);
}
