// The fault outputs of ugs-solve for people who plot (docs/fault-mechanics.md "Outputs"), on
// contact_make_case at 100 m cells (fault F: the plane x = z + 1300, dipping 45 degrees east,
// striking north, y in 100..500, top edge at z = -300; +6 MPa in the reservoir it crosses):
//  - <stem>_fault_F.csv: one row per node pair and output date; every value the HDF5 node field's
//    at that node (same doubles, in MPa / mm); along_strike = y - 100, down_dip = (-300 - z) sqrt(2)
//    and x = z + 1300 (the plane's geometry);
//  - one max chi: the statistics CSV's max_chi, the largest chi over the per-pair CSV's rows with
//    interpolated = 0 and the largest HDF5 node value of chi agree at each date; so do max slip,
//    max opening, max CFS change, the slip and open areas (sums of the rows' area_m2) and the counts
//    of pairs, slipping and open pairs; the rows' areas split each triangle over its paired corners
//    (tip nodes' thirds counted);
//  - --fault-pairs-csv PREFIX and 'none'; --fault-pairs-every-step with one output date; a prefix in a
//    missing folder: exit 2, one line, no results.
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "run_tool.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

using Dir = test::TempDir;

std::string solve(const Dir& d, const std::string& args) {
  return test::tool("ugs-solve") + " " + d / "faulted.msh" + " --case " + d / "case.toml" + " --pressure " + d / "flow.h5" + " " +
         args;
}

void make_case(const Dir& d) {
  const auto r = test::run(std::string(UGS_BINARY_DIR) + "/tests/fault_mechanics/contact_make_case " + d.path.string() + " --dp 6 --cell 100");
  ASSERT_EQ(r.exit_code, 0) << r.err;
}

}  // namespace

TEST(FaultOutputCli, PairCsvMatchesTheHdf5AndTheGeometry) {
  Dir d("fault-pairs");
  make_case(d);
  const auto r = test::run(solve(d, "-o " + d / "out.h5"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The log names the fault's node pairs: "fault F: 40 interface elements, ..., 15 node pairs, ...".
  const auto at = r.err.find(" node pairs, ");
  ASSERT_NE(at, std::string::npos) << r.err;
  const std::size_t pairs = std::stoul(r.err.substr(r.err.rfind(' ', at - 1) + 1));
  ASSERT_GT(pairs, 5u);

  const CsvTable t = CsvTable::read(d / "out_fault_F.csv");
  for (const char* c : {"date", "node", "x_m", "y_m", "z_m", "along_strike_m", "down_dip_m", "area_m2", "state", "tau_MPa", "sigma_n_eff_MPa",
                        "chi", "slip_mm", "opening_mm", "cfs_change_MPa", "p_fault_MPa", "interpolated"})
    EXPECT_NO_THROW(t.column(c)) << c;
  FieldSeriesReader h5(d / "out_faults.h5");
  ASSERT_EQ(h5.steps().size(), 2u);
  EXPECT_EQ(t.rows(), pairs * h5.steps().size());  // one row per node pair and output date

  const auto tags = h5.node_tags();
  std::map<std::uint64_t, std::size_t> index;
  for (std::size_t i = 0; i < tags.size(); ++i) index[tags[i]] = i;
  const CsvTable stats = CsvTable::read(d / "out_faults.csv");
  std::size_t checked = 0;
  for (std::size_t s = 0; s < h5.steps().size(); ++s) {
    const std::string date = h5.steps()[s].date;
    std::map<std::string, Field> f;
    for (const char* n : {"tau_abs", "sigma_n_eff", "chi", "slip_abs", "opening", "cfs_change", "p_fault", "state", "interpolated",
                          "along_strike", "down_dip"})
      f[n] = h5.node_field(s, n);
    const auto coords = h5.coordinates();
    std::size_t rows = 0, direct = 0, slipping = 0, open = 0;
    double csv_max = -1, h5_max = -1, max_slip = 0, max_opening = 0, max_cfs = -1e300, slip_area = 0, open_area = 0, area = 0;
    for (std::size_t i = 0; i < t.rows(); ++i) {
      if (t.text(i, t.column("date")) != date) continue;
      ++rows;
      const auto it = index.find(static_cast<std::uint64_t>(t.integer(i, t.column("node"))));
      ASSERT_NE(it, index.end()) << "row " << i;
      const std::size_t n = it->second;
      auto num = [&](const char* c) { return t.number(i, t.column(c)); };
      // The same doubles as the node fields (shortest round-trip text), in MPa and mm.
      EXPECT_EQ(num("tau_MPa"), f["tau_abs"].values[n] * 1e-6);
      EXPECT_EQ(num("sigma_n_eff_MPa"), f["sigma_n_eff"].values[n] * 1e-6);
      EXPECT_EQ(num("chi"), f["chi"].values[n]);
      EXPECT_EQ(num("slip_mm"), f["slip_abs"].values[n] * 1e3);
      EXPECT_EQ(num("opening_mm"), f["opening"].values[n] * 1e3);
      EXPECT_EQ(num("cfs_change_MPa"), f["cfs_change"].values[n] * 1e-6);
      EXPECT_EQ(num("p_fault_MPa"), f["p_fault"].values[n] * 1e-6);
      EXPECT_EQ(num("along_strike_m"), f["along_strike"].values[n]);
      EXPECT_EQ(num("down_dip_m"), f["down_dip"].values[n]);
      static const char* kState[3] = {"stick", "slip", "open"};
      EXPECT_EQ(t.text(i, t.column("state")), kState[static_cast<int>(f["state"].values[n])]);
      EXPECT_EQ(num("interpolated"), f["interpolated"].values[n]);
      // The plane x = z + 1300, strike north from y = 100, dip 45 degrees from z = -300.
      const double x = num("x_m"), y = num("y_m"), z = num("z_m");
      EXPECT_EQ(x, coords[n][0]);
      EXPECT_NEAR(x, z + 1300, 1e-6);
      EXPECT_NEAR(num("along_strike_m"), y - 100, 1e-9);
      EXPECT_NEAR(num("down_dip_m"), (-300 - z) * std::sqrt(2.0), 1e-9);
      if (num("interpolated") == 0) {
        ++direct, csv_max = std::max(csv_max, num("chi"));
        max_slip = std::max(max_slip, num("slip_mm")), max_opening = std::max(max_opening, num("opening_mm"));
        max_cfs = std::max(max_cfs, num("cfs_change_MPa"));
        slipping += t.text(i, t.column("state")) == "slip", open += t.text(i, t.column("state")) == "open";
        if (t.text(i, t.column("state")) == "slip") slip_area += num("area_m2");
        if (t.text(i, t.column("state")) == "open") open_area += num("area_m2");
      }
      area += num("area_m2");
      ++checked;
    }
    EXPECT_EQ(rows, pairs) << date;
    // The pairs' shares: each triangle's area split evenly over its corners that are pairs (tip
    // nodes' thirds are not lost at the fault's edges), out of the fault's 400 m along strike x
    // 500 sqrt 2 m down dip: the rows add up to the area of the triangles with a pair corner
    // (275,772 of 282,843 m2 here; the pairs' thirds alone were 190,919 m2).
    {
      std::set<std::uint64_t> in_csv;
      for (std::size_t i = 0; i < t.rows(); ++i) in_csv.insert(static_cast<std::uint64_t>(t.integer(i, t.column("node"))));
      const auto tri = h5.cells(ElementType::Triangle);
      double expected = 0, total = 0, thirds = 0;
      for (std::size_t e = 0; e + 2 < tri.size(); e += 3) {
        const Point3 &a = coords[tri[e]], &b = coords[tri[e + 1]], &c = coords[tri[e + 2]];
        const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double A = 0.5 * std::sqrt(std::pow(u[1] * v[2] - u[2] * v[1], 2) + std::pow(u[2] * v[0] - u[0] * v[2], 2) +
                                         std::pow(u[0] * v[1] - u[1] * v[0], 2));
        total += A;
        int paired = 0;
        for (int k = 0; k < 3; ++k) paired += static_cast<int>(in_csv.count(tags[tri[e + k]]));
        expected += paired ? A : 0.0;
        thirds += paired * A / 3;
      }
      EXPECT_NEAR(total, 400 * 500 * std::sqrt(2.0), 1e-6 * total);
      EXPECT_NEAR(area, expected, 1e-9 * expected) << date;
      EXPECT_LT(thirds, 0.95 * total);  // the pairs' coupling shares alone: tip nodes carry the rest
      if (s == 0) std::printf("node pairs report %.0f of the fault's %.0f m2 (their thirds alone: %.0f)\n", area, total, thirds);
    }
    for (std::size_t n = 0; n < f["chi"].values.size(); ++n) h5_max = std::max(h5_max, f["chi"].values[n]);
    // One max chi: the statistics CSV (6 decimals), the per-pair CSV and the HDF5 node field.
    bool found = false;
    for (std::size_t i = 0; i < stats.rows(); ++i) {
      if (stats.text(i, stats.column("date")) != date) continue;
      found = true;
      EXPECT_NEAR(stats.number(i, stats.column("max_chi")), csv_max, 5e-7) << date;
      EXPECT_EQ(static_cast<std::size_t>(stats.integer(i, stats.column("node_pairs"))), direct) << date;
      // The other statistics from the same pairs.
      EXPECT_NEAR(stats.number(i, stats.column("max_slip_mm")), max_slip, 5e-7) << date;
      EXPECT_NEAR(stats.number(i, stats.column("max_opening_mm")), max_opening, 5e-7) << date;
      EXPECT_NEAR(stats.number(i, stats.column("max_cfs_change_MPa")), max_cfs, 5e-7) << date;
      EXPECT_EQ(static_cast<std::size_t>(stats.integer(i, stats.column("slipping"))), slipping) << date;
      EXPECT_EQ(static_cast<std::size_t>(stats.integer(i, stats.column("open"))), open) << date;
      EXPECT_NEAR(stats.number(i, stats.column("slip_area_m2")), slip_area, 0.05 + 1e-9 * slip_area) << date;
      EXPECT_NEAR(stats.number(i, stats.column("open_area_m2")), open_area, 0.05 + 1e-9 * open_area) << date;
    }
    EXPECT_TRUE(found) << date;
    EXPECT_EQ(csv_max, h5_max) << date;
    std::printf("%s: %zu rows, %zu on free dofs (%zu slipping, %zu open), max chi %.6f, max slip %.6f mm, max opening %.6f mm\n",
                date.c_str(), rows, direct, slipping, open, csv_max, max_slip, max_opening);
  }
  EXPECT_EQ(checked, t.rows());
  // The +6 MPa date: some pair at chi = 1 (slip or open).
  EXPECT_EQ(stats.number(stats.rows() - 1, stats.column("max_chi")), 1.0);

  // A prefix, and 'none'.
  fs::create_directories(d / "pairs");
  ASSERT_EQ(test::run(solve(d, "-o " + d / "p.h5 --fault-pairs-csv " + d / "pairs/run1_")).exit_code, 0);
  EXPECT_TRUE(fs::exists(d / "pairs/run1_F.csv"));
  EXPECT_FALSE(fs::exists(d / "p_fault_F.csv"));
  EXPECT_EQ(test::slurp(d / "pairs/run1_F.csv").substr(test::slurp(d / "pairs/run1_F.csv").find("\ndate,")),
            test::slurp(d / "out_fault_F.csv").substr(test::slurp(d / "out_fault_F.csv").find("\ndate,")));
  ASSERT_EQ(test::run(solve(d, "-o " + d / "n.h5 --fault-pairs-csv none")).exit_code, 0);
  EXPECT_FALSE(fs::exists(d / "n_fault_F.csv"));
  EXPECT_TRUE(fs::exists(d / "n_faults.csv"));
  // --fault-pairs-every-step: [output] dates naming the last date only; the per-pair rows of every
  // step all the same (the bytes of the run that output every step), the volume and fault fields
  // at the last date only; without the flag the rows of the last date only.
  const std::string last = h5.steps().back().date;
  ASSERT_EQ(test::slurp(d / "case.toml").find("[output]"), std::string::npos);
  test::spit(d / "case_last.toml", test::slurp(d / "case.toml") + "\n[output]\ndates = [\"" + last + "\"]\n");
  const std::string last_case = test::tool("ugs-solve") + " " + d / "faulted.msh" + " --case " + d / "case_last.toml" + " --pressure " +
                                d / "flow.h5";
  ASSERT_EQ(test::run(last_case + " -o " + d / "e.h5 --fault-pairs-every-step").exit_code, 0);
  auto rows_of = [](const std::string& text) { return text.substr(text.find("\ndate,")); };
  EXPECT_EQ(rows_of(test::slurp(d / "e_fault_F.csv")), rows_of(test::slurp(d / "out_fault_F.csv")));
  EXPECT_EQ(FieldSeriesReader(d / "e.h5").steps().size(), 1u);
  EXPECT_EQ(FieldSeriesReader(d / "e_faults.h5").steps().size(), 1u);
  ASSERT_EQ(test::run(last_case + " -o " + d / "l.h5").exit_code, 0);
  const CsvTable only_last = CsvTable::read(d / "l_fault_F.csv");
  EXPECT_EQ(only_last.rows(), pairs);
  EXPECT_EQ(only_last.text(0, only_last.column("date")), last);

  // A prefix in a folder that does not exist: exit 2, one line naming it, no results.
  const auto bad = test::run(solve(d, "-o " + d / "bad.h5 --fault-pairs-csv " + d / "missing/p_"));
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  const auto line = bad.err.rfind("ugs-solve: error: ");
  ASSERT_NE(line, std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("missing/p_F.csv", line), std::string::npos) << bad.err;
  EXPECT_EQ(bad.err.find('\n', line), bad.err.size() - 1) << bad.err;
  for (const char* f : {"bad.h5", "bad_faults.h5", "bad_faults.csv", "bad_top.h5"}) EXPECT_FALSE(fs::exists(d / f)) << f;
}
