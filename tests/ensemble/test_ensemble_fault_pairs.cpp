// The probability that chi reaches 0.8 and 1 at each fault node pair (ugs-ensemble collect's
// chi_exceedance_pairs.csv) and ugs-report's maps of it, with a stand-in solver whose per-pair
// CSVs make every probability known by construction: 4 Latin-hypercube members of c_R in [1, 5),
// one per unit stratum, so member rank r = floor(c_R) - 1 is 0, 1, 2, 3, and chi of pair k reaches
// 1 in the members of rank >= 4 - q_k. A member whose pair set differs (one pair moved by 1 m) is
// a failure line and left out of every statistic. No real solver: a few seconds.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include "run_tool.hpp"
#include "solve_box.hpp"
#include "still_result.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

// Pairs of fault F1: a vertical fault at y = 4952000 through Pool C, 3 along strike x 2 deep;
// q (members of 4 reaching chi = 1 on 2013-11-01) and the value below 1 (0.8 for pair 6).
const int kQ[6] = {0, 1, 2, 4, 3, 0};

// The stand-in solver: `sh fake.sh {case} {out}`; with `shift` the member of rank 1 moves pair 4 by 1 m.
std::string fake_solver(const fs::path& dir, bool shift) {
  return "cp " + (dir / "template.h5").string() + " \"$2\"\n"
         "c=$(sed -n 's/^c_R = //p' \"$1\" | head -1)\n"
         "awk -v c=\"$c\" -v shift=" + std::string(shift ? "1" : "0") + " 'BEGIN {\n"
         "  r = int(c) - 1; split(\"0 1 2 4 3 0\", q, \" \")\n"
         "  print \"# ugs-solve fault F1 (stand-in)\"\n"
         "  print \"date,node,x_m,y_m,z_m,along_strike_m,down_dip_m,area_m2,state,tau_MPa,sigma_n_eff_MPa,chi,slip_mm,opening_mm,"
         "cfs_change_MPa,p_fault_MPa,interpolated\"\n"
         "  for (d = 1; d <= 2; d++) for (k = 1; k <= 6; k++) {\n"
         "    s = 1000 * ((k - 1) % 3); z = -1400 - 200 * int((k - 1) / 3); x = 680000 + s\n"
         "    if (shift && r == 1 && k == 4) x += 1\n"
         "    if (d == 1) chi = (k == 1 && r == 0) ? 1.5 : 0.3\n"
         "    else chi = (r >= 4 - q[k]) ? 1.0 : (k == 6 ? 0.8 : 0.5)\n"
         "    printf \"%s,%d,%.17g,4952000,%.17g,%.17g,%.17g,1e4,stick,1,-10,%.17g,0,0,0,10,0\\n\", d == 1 ? \"2013-05-01\" : "
         "\"2013-11-01\", 100 + k, x, z, s, -1400 - z, chi\n"
         "  }\n"
         "}' > \"$(dirname \"$2\")/result_fault_F1.csv\"\n"
         // F2: three pairs, chi 0.9 in every member at both dates.
         "printf 'date,node,x_m,y_m,z_m,along_strike_m,down_dip_m,chi\\n2013-05-01,7,0,0,0,0,0,0.9\\n2013-05-01,8,1,0,0,1,0,0.9\\n"
         "2013-05-01,9,0,0,-1,0,1,0.9\\n2013-11-01,7,0,0,0,0,0,0.9\\n2013-11-01,8,1,0,0,1,0,0.9\\n2013-11-01,9,0,0,-1,0,1,0.9\\n' > "
         "\"$(dirname \"$2\")/result_fault_F2.csv\"\n";
}

fs::path make_case() {
  const fs::path dir = test::temp_dir("ensemble-fault-pairs");
  const Mesh m = test::solve_box_mesh();
  write_msh(m, (dir / "model.msh").string());
  test::spit(dir / "pool_c.csv", "date,p_MPa\n2013-01-01,10\n2014-01-01,12\n");
  test::spit(dir / "case.toml", test::solve_box_case(3.0) + "\n[[pool]]\nname = \"Pool C\"\nmaterials = [\"pool_c\"]\nschedule = \"" +
                                    (dir / "pool_c.csv").string() + "\"\nreference_pressure_MPa = 15.2\n");
  // A result to copy: u = 0 at the two dates (the members' surface metrics are 0, not the subject).
  test::write_still_result((dir / "template.h5").string(), m, {"2013-05-01", "2013-11-01"});
  test::spit(dir / "fake.sh", fake_solver(dir, false));
  test::spit(dir / "fake_shift.sh", fake_solver(dir, true));
  test::spit(dir / "lhs.toml", "[design]\nmethod = \"lhs\"\nmembers = 4\nseed = 5\n\n[[parameter]]\npath = \"material.pool_c.c_R\"\n"
                               "distribution = \"uniform\"\nlower = 1.0\nupper = 5.0\n");
  return dir;
}

test::RunResult ensemble(const fs::path& dir, const std::string& script, const std::string& out) {
  return test::run(test::tool("ugs-ensemble") + " run --spec " + (dir / "lhs.toml").string() + " --case " + (dir / "case.toml").string() +
                   " --solver-command 'sh " + (dir / script).string() + " {case} {out}' -o " + (dir / out).string());
}

// (fault, date, node) -> row of chi_exceedance_pairs.csv
std::map<std::string, std::size_t> rows_of(const CsvTable& t) {
  std::map<std::string, std::size_t> out;
  for (std::size_t r = 0; r < t.rows(); ++r)
    out[std::string(t.text(r, t.column("fault"))) + "|" + std::string(t.text(r, t.column("date"))) + "|" +
        std::string(t.text(r, t.column("node")))] = r;
  return out;
}

}  // namespace

TEST(EnsembleFaultPairs, ExceedancePerPairMismatchAndReportMap) {
  const fs::path dir = make_case();

  // 1. Four members: every probability known.
  const auto r = ensemble(dir, "fake.sh", "out");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable t = CsvTable::read((dir / "out" / "chi_exceedance_pairs.csv").string());
  ASSERT_EQ(t.rows(), 3u * 6 + 3u * 3);  // F1: 2 dates + max, 6 pairs; F2: 3 pairs
  const auto row = rows_of(t);
  auto p = [&](const std::string& fault, const std::string& date, int node, const char* col) {
    return t.number(row.at(fault + "|" + date + "|" + std::to_string(node)), t.column(col));
  };
  for (int k = 0; k < 6; ++k) {
    const int node = 101 + k;
    const double q = kQ[k] / 4.0;
    // 2013-05-01: chi 0.3, except pair 1 of the rank-0 member (1.5).
    EXPECT_EQ(p("F1", "2013-05-01", node, "p_chi_ge_1"), k == 0 ? 0.25 : 0.0) << node;
    EXPECT_EQ(p("F1", "2013-05-01", node, "p_chi_ge_0.8"), k == 0 ? 0.25 : 0.0) << node;
    EXPECT_EQ(p("F1", "2013-11-01", node, "p_chi_ge_1"), q) << node;
    EXPECT_EQ(p("F1", "2013-11-01", node, "p_chi_ge_0.8"), k == 5 ? 1.0 : q) << node;
    EXPECT_EQ(p("F1", "max", node, "p_chi_ge_1"), k == 0 ? 0.25 : q) << node;
    EXPECT_EQ(p("F1", "max", node, "p_chi_ge_0.8"), k == 0 ? 0.25 : k == 5 ? 1.0 : q) << node;
    const std::size_t i = row.at("F1|max|" + std::to_string(node));
    EXPECT_EQ(t.integer(i, t.column("n_members")), 4);
    EXPECT_EQ(t.number(i, t.column("x_m")), 680000 + 1000.0 * (k % 3));
    EXPECT_EQ(t.number(i, t.column("z_m")), -1400 - 200.0 * (k / 3));
    EXPECT_EQ(t.number(i, t.column("along_strike_m")), 1000.0 * (k % 3));
  }
  for (int node : {7, 8, 9}) {
    EXPECT_EQ(p("F2", "max", node, "p_chi_ge_0.8"), 1.0);
    EXPECT_EQ(p("F2", "max", node, "p_chi_ge_1"), 0.0);
  }
  EXPECT_EQ(CsvTable::read((dir / "out" / "failures.csv").string()).rows(), 0u);

  // 2. One member's pairs differ (rank 1 moved pair 4 by 1 m): its failure line, left out.
  const auto s = ensemble(dir, "fake_shift.sh", "shifted");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const CsvTable mem = CsvTable::read((dir / "shifted" / "members.csv").string());
  std::int64_t rank1 = 0;
  for (std::size_t i = 0; i < mem.rows(); ++i)
    if (static_cast<int>(mem.number(i, mem.column("material.pool_c.c_R"))) == 2) rank1 = mem.integer(i, mem.column("member"));
  ASSERT_GT(rank1, 0);
  const CsvTable fl = CsvTable::read((dir / "shifted" / "failures.csv").string());
  ASSERT_EQ(fl.rows(), 1u);
  EXPECT_EQ(fl.integer(0, fl.column("member")), rank1);
  const std::string err(fl.text(0, fl.column("error")));
  EXPECT_NE(err.find("fault node pairs differ"), std::string::npos) << err;
  EXPECT_NE(err.find("fault F1: pair 4 is node 104 at (680001, 4952000, -1600) m"), std::string::npos) << err;
  EXPECT_NE(s.err.find(fmt::format("member {} excluded from the statistics", rank1)), std::string::npos) << s.err;
  const CsvTable q = CsvTable::read((dir / "shifted" / "quantiles.csv").string());
  EXPECT_EQ(q.integer(0, q.column("n")), 3);
  const CsvTable ts = CsvTable::read((dir / "shifted" / "chi_exceedance_pairs.csv").string());
  const auto rs = rows_of(ts);
  // Ranks 0, 2, 3 left: pair k reaches 1 on 2013-11-01 in the ranks >= 4 - q_k among them.
  const double left[6] = {0.0, 1.0 / 3, 2.0 / 3, 1.0, 2.0 / 3, 0.0};
  for (int k = 0; k < 6; ++k) {
    const std::size_t i = rs.at("F1|2013-11-01|" + std::to_string(101 + k));
    EXPECT_EQ(ts.number(i, ts.column("p_chi_ge_1")), left[k]) << k;
    EXPECT_EQ(ts.integer(i, ts.column("n_members")), 3);
  }

  // 3. ugs-report draws the maps from the first folder, and its CSV holds collect's values.
  const auto rep = test::run(test::tool("ugs-report") + " --thesis --results " + (dir / "template.h5").string() + " --mesh " +
                             (dir / "model.msh").string() + " --case " + (dir / "case.toml").string() + " --ensemble " +
                             (dir / "out").string() + " --keep-work -o " + (dir / "report").string());
  ASSERT_EQ(rep.exit_code, 0) << rep.err;
  for (const char* png : {"ensemble_p_chi_ge_1.png", "ensemble_p_chi_ge_0.8.png"})
    EXPECT_GT(fs::file_size(dir / "report" / png), 10000u) << png;
  const fs::path plotted = dir / "report" / "work" / "ensemble_chi_exceedance.csv";
  ASSERT_TRUE(fs::exists(plotted));
  const CsvTable pc = CsvTable::read(plotted.string());
  ASSERT_EQ(pc.rows(), 9u);  // the "max" rows of both faults
  for (std::size_t i = 0; i < pc.rows(); ++i) {
    const std::string key = std::string(pc.text(i, pc.column("fault"))) + "|max|" + std::string(pc.text(i, pc.column("node")));
    for (const char* col : {"p_chi_ge_0.8", "p_chi_ge_1", "along_strike_m", "z_m"})
      EXPECT_EQ(pc.number(i, pc.column(col)), t.number(row.at(key), t.column(col))) << key << " " << col;
  }
  // Pool C's outline on F1's plane (its nodes span x 679666.67 .. 683333.33 on the box's 916.67 m
  // grid, z -1520 .. -1500): along strike x - 680000, written to 3 decimals.
  const CsvTable ol = CsvTable::read((dir / "report" / "work" / "ensemble_pools_on_f1.csv").string());
  const auto os = ol.numbers("s"), oz = ol.numbers("z");
  ASSERT_FALSE(os.empty());
  EXPECT_NEAR(*std::min_element(os.begin(), os.end()), test::kBoxX0 + 11000.0 * 4 / 12 - 680000, 5e-4);
  EXPECT_NEAR(*std::max_element(os.begin(), os.end()), test::kBoxX0 + 11000.0 * 8 / 12 - 680000, 5e-4);
  EXPECT_EQ(*std::min_element(oz.begin(), oz.end()), -1520.0);
  EXPECT_EQ(*std::max_element(oz.begin(), oz.end()), -1500.0);

  // 3b. The seismicity metrics' quantiles (ugs-ensemble --seismic-window) as headlines: P50 (P10 - P90),
  // P(event) on every fault, the count and the other magnitudes for all faults; chi_max rows are not
  // seismicity headlines.
  fs::create_directories(dir / "seismic");
  fs::copy_file(dir / "out" / "members.csv", dir / "seismic" / "members.csv");
  test::spit(dir / "seismic" / "quantiles.csv",
             "metric,n,mean,p10,p50,p90,min,max\n"
             "chi_max.F1,4,0.5,0.3,0.5,0.7,0.2,0.8\n"
             "seismic_events.F1.forecast,4,1,0.5,1,2,0.25,3\n"
             "seismic_events.all.forecast,4,12.5,10.25,12.5,14.75,9,16\n"
             "p_event.F1.forecast,4,0.5,0.375,0.625,0.875,0.25,0.9\n"
             "p_event.all.forecast,4,0.9,0.75,0.875,0.9375,0.5,1\n"
             "p_event_M2.F1.forecast,4,0.1,0.05,0.1,0.2,0.01,0.3\n"
             "p_event_M2.all.forecast,4,0.5,0.25,0.5,0.75,0.125,0.875\n");
  const auto rs3 = test::run(test::tool("ugs-report") + " --thesis --results " + (dir / "template.h5").string() + " --mesh " +
                             (dir / "model.msh").string() + " --case " + (dir / "case.toml").string() + " --ensemble " +
                             (dir / "seismic").string() + " -o " + (dir / "report_seismic").string());
  ASSERT_EQ(rs3.exit_code, 0) << rs3.err;
  const CsvTable hl = CsvTable::read((dir / "report_seismic" / "headlines.csv").string());
  std::map<std::string, std::pair<std::string, double>> seismic;  // quantity -> value text, value_number
  for (std::size_t i = 0; i < hl.rows(); ++i)
    if (hl.text(i, hl.column("group")) == "ensemble, seismicity window forecast")
      seismic[std::string(hl.text(i, hl.column("quantity")))] = {std::string(hl.text(i, hl.column("value"))),
                                                                  hl.number(i, hl.column("value_number"))};
  const std::map<std::string, std::pair<std::string, double>> expected{
      {"expected events M ≥ M_c, all faults: P50 (P10 - P90) of 4 members", {"12.5 (10.2 - 14.8)", 12.5}},
      {"P(event M ≥ M_c) on F1: P50 (P10 - P90) of 4 members", {"0.625 (0.375 - 0.875)", 0.625}},
      {"P(event M ≥ M_c) on all faults: P50 (P10 - P90) of 4 members", {"0.875 (0.75 - 0.938)", 0.875}},
      {"P(event M ≥ 2), all faults: P50 (P10 - P90) of 4 members", {"0.5 (0.25 - 0.75)", 0.5}}};
  EXPECT_EQ(seismic, expected);

  // 4. Two faults whose names differ only in case (F2 renamed f1): their work files stay apart,
  // F1 (first in byte order) keeps the plain stem f1, f1 gets f1_2.
  fs::create_directories(dir / "cased");
  for (const char* f : {"members.csv", "chi_exceedance_pairs.csv"}) {
    std::string text = test::slurp(dir / "out" / f);
    for (std::size_t at = 0; (at = text.find("\nF2,", at)) != std::string::npos;) text.replace(at, 4, "\nf1,");
    test::spit(dir / "cased" / f, text);
  }
  const auto rc = test::run(test::tool("ugs-report") + " --thesis --results " + (dir / "template.h5").string() + " --mesh " +
                            (dir / "model.msh").string() + " --case " + (dir / "case.toml").string() + " --ensemble " +
                            (dir / "cased").string() + " --keep-work -o " + (dir / "report_cased").string());
  ASSERT_EQ(rc.exit_code, 0) << rc.err;
  const fs::path work = dir / "report_cased" / "work";
  for (const char* tag : {"1", "0.8"}) {
    const fs::path upper = work / fmt::format("ensemble_p_chi_ge_{}_f1.npy", tag), lower = work / fmt::format("ensemble_p_chi_ge_{}_f1_2.npy", tag);
    ASSERT_TRUE(fs::exists(upper) && fs::exists(lower)) << tag;
    EXPECT_EQ(fs::file_size(upper), fs::file_size(lower) + 3 * sizeof(double)) << tag;  // F1's 6 pairs, f1's 3
  }
  EXPECT_TRUE(fs::exists(work / "ensemble_pools_on_f1.csv"));
  EXPECT_TRUE(fs::exists(work / "ensemble_pools_on_f1_2.csv"));
  if (!HasFailure() && !std::getenv("UGS_TEST_KEEP")) fs::remove_all(dir);
}
