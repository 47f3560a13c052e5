// Friction variants (docs/ensemble.md, "Friction variants of a run that sticks"): members that
// differ only in the faults' friction angles take the results of one solver run where every fault
// sticks in it, with chi and the Coulomb stress change for their own friction. With the real
// ugs-solve on contact_make_case's faulted box (a storage cycle, 13 monthly steps):
//  - every fault sticks: 3 Latin-hypercube members of the friction in [35, 50] deg cost one solver
//    run, the other two are derived (entry.json names the source), and each derived member's fault
//    tables equal those of a real run at its friction: every column but chi and the Coulomb change
//    as text, those two to round-off, the fault table to its 6 decimals; --member K derives too, the
//    same bytes again; the emitted Makefile under make -j 3 runs one solve and derives the others;
//  - the fault slips at the lower frictions (dp 5 MPa, [20, 50] deg): no member is derived from a
//    run with slip, and a member whose own chi would reach 1 runs its own solve (and slips there);
//  - unit checks of the derivation on hand-written tables: a cohesive fault with interpolated pairs,
//    per-pair CSVs that start after the initial state or lack a step, a safe-scale search.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "run_tool.hpp"
#include "ugs/ensemble/friction_variants.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

struct Box {
  test::TempDir dir;
  explicit Box(const std::string& tag, double dp) : dir(tag) {
    const auto r = test::run(std::string(UGS_BINARY_DIR) + "/tests/fault_mechanics/contact_make_case " + dir.path.string() +
                             " --months 12 --cell 100 --dp " + std::to_string(dp));
    EXPECT_EQ(r.exit_code, 0) << r.err;
  }
  std::string solve_args() const {
    return test::tool("ugs-solve") + " " + (dir.path / "faulted.msh").string() + " --pressure " + (dir.path / "flow.h5").string() +
           " --top none --state none --fault-output none --fault-pairs-every-step -q";
  }
  std::string ensemble(const std::string& spec, const std::string& extra = "", const std::string& out = "out") const {
    test::spit(dir.path / "spec.toml", spec);
    return test::tool("ugs-ensemble") + " run --spec " + (dir.path / "spec.toml").string() + " --case " +
           (dir.path / "case.toml").string() + " --solver-command '" + solve_args() + " --case {case} -o {out}' -j 2 --cache-dir " +
           (dir.path / "cache").string() + " -o " + (dir.path / out).string() + " " + extra;
  }
  std::vector<fs::path> entries() const {
    std::vector<fs::path> v;
    for (const auto& e : fs::directory_iterator(dir.path / "cache"))
      if (e.path().filename().string().rfind("member-", 0) == 0) v.push_back(e.path());
    std::sort(v.begin(), v.end());
    return v;
  }
};

std::string lhs(double lower, double upper) {
  return "[design]\nmethod = \"lhs\"\nmembers = 3\nseed = 7\n\n[[parameter]]\npath = \"fault.F.friction_deg\"\n"
         "distribution = \"uniform\"\nlower = " + std::to_string(lower) + "\nupper = " + std::to_string(upper) + "\n";
}

std::vector<std::vector<std::string>> rows(const fs::path& csv) {
  std::vector<std::vector<std::string>> out;
  std::string text = test::slurp(csv);
  std::size_t at = 0;
  while (at < text.size()) {
    const auto end = text.find('\n', at);
    const std::string line = text.substr(at, end - at);
    at = end == std::string::npos ? text.size() : end + 1;
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::size_t s = 0;
    for (;;) {
      const auto c = line.find(',', s);
      cells.push_back(line.substr(s, c == std::string::npos ? std::string::npos : c - s));
      if (c == std::string::npos) break;
      s = c + 1;
    }
    out.push_back(std::move(cells));
  }
  return out;
}

// Derived and real tables: the same text except in `numeric` columns, there within `tol`.
void expect_same_table(const fs::path& derived, const fs::path& real, const std::map<std::string, double>& numeric) {
  const auto a = rows(derived), b = rows(real);
  ASSERT_EQ(a.size(), b.size()) << derived;
  ASSERT_GT(a.size(), 1u);
  const auto& header = a[0];
  for (std::size_t r = 1; r < a.size(); ++r)
    for (std::size_t c = 0; c < header.size(); ++c) {
      const auto t = numeric.find(header[c]);
      if (t == numeric.end()) {
        EXPECT_EQ(a[r][c], b[r][c]) << derived.filename() << " row " << r << " column " << header[c];
      } else {
        EXPECT_NEAR(std::stod(a[r][c]), std::stod(b[r][c]), t->second) << derived.filename() << " row " << r << " column " << header[c];
      }
    }
}

}  // namespace

TEST(EnsembleFrictionVariants, MembersOfARunThatSticksAreDerivedAndEqualRealRuns) {
  const Box box("friction-variants-stick", 2.0);
  const std::string cmd = box.ensemble(lhs(35, 50));
  const auto r = test::run(cmd);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto entries = box.entries();
  ASSERT_EQ(entries.size(), 3u);
  int ran = 0, derived = 0;
  for (const auto& e : entries) {
    if (fs::exists(e / "solver.log")) ++ran;
    if (fs::exists(e / "derived.txt")) {
      ++derived;
      EXPECT_NE(test::slurp(e / "entry.json").find("\"derived_from\": \"member-"), std::string::npos);
      EXPECT_FALSE(fs::exists(e / "solver.log"));
    }
  }
  EXPECT_EQ(ran, 1);
  EXPECT_EQ(derived, 2);
  EXPECT_NE(r.err.find("derived from member-"), std::string::npos) << r.err;

  // Each derived member against a real run at its friction (its entry's case copy).
  for (const auto& e : entries) {
    if (!fs::exists(e / "derived.txt")) continue;
    const fs::path real = box.dir.path / ("real-" + e.filename().string());
    fs::create_directories(real);
    const auto s = test::run(box.solve_args() + " --case " + (e / "case.toml").string() + " -o " + (real / "result.h5").string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    expect_same_table(e / "result_fault_F.csv", real / "result_fault_F.csv", {{"chi", 1e-14}, {"cfs_change_MPa", 1e-12}});
    // The fault table; where chi peaks may be another pair of equal chi (the box is symmetric): a
    // pair of the real run with the largest chi at that date.
    expect_same_table(e / "result_faults.csv", real / "result_faults.csv",
                      {{"max_chi", 1.01e-6}, {"max_cfs_change_MPa", 1.01e-6}, {"x_m", 1e300}, {"y_m", 1e300}, {"z_m", 1e300}});
    const auto table = rows(e / "result_faults.csv"), pairs = rows(real / "result_fault_F.csv");
    for (std::size_t i = 1; i < table.size(); ++i) {
      double best = 0, at = -1;
      for (std::size_t j = 1; j < pairs.size(); ++j) {
        if (pairs[j][0] != table[i][0] || pairs[j][16] != "0") continue;
        const double chi = std::stod(pairs[j][11]);
        best = std::max(best, chi);
        char xyz[128];
        std::snprintf(xyz, sizeof xyz, "%.2f,%.2f,%.2f", std::stod(pairs[j][2]), std::stod(pairs[j][3]), std::stod(pairs[j][4]));
        if (xyz == table[i][3] + "," + table[i][4] + "," + table[i][5]) at = chi;
      }
      EXPECT_NEAR(at, best, 1e-12) << "row " << i << " names a pair without the largest chi";
    }
    // The displacements too: the stick solution does not read the friction.
    FieldSeriesReader a((e / "result.h5").string()), b((real / "result.h5").string());
    ASSERT_EQ(a.steps().size(), b.steps().size());
    const auto ua = a.node_field(a.steps().size() - 1, "u").values, ub = b.node_field(b.steps().size() - 1, "u").values;
    ASSERT_EQ(ua.size(), ub.size());
    double du = 0, umax = 0;
    for (std::size_t i = 0; i < ua.size(); ++i) du = std::max(du, std::abs(ua[i] - ub[i])), umax = std::max(umax, std::abs(ub[i]));
    EXPECT_GT(umax, 0);
    EXPECT_LE(du, 1e-12 * umax);
  }
  // --member K derives again, byte for byte.
  const auto members = CsvTable::read((box.dir.path / "out" / "members.csv").string());
  for (std::size_t i = 0; i < members.rows(); ++i) {
    const fs::path e = box.dir.path / "cache" / std::string(members.text(i, members.column("entry")));
    if (!fs::exists(e / "derived.txt")) continue;
    const std::string before = test::slurp(e / "result_fault_F.csv");
    fs::remove_all(e);
    const auto m = test::run(cmd + " --member " + std::to_string(i + 1));
    ASSERT_EQ(m.exit_code, 0) << m.err;
    ASSERT_TRUE(fs::exists(e / "derived.txt"));
    EXPECT_EQ(test::slurp(e / "result_fault_F.csv"), before);
  }
}

TEST(EnsembleFrictionVariants, TheEmittedMakefileDerivesUnderMakeJ) {
  // Its friction variants wait for their group's first member: make -j 3 runs one solve.
  const Box box("friction-variants-make", 2.0);
  const auto e = test::run(box.ensemble(lhs(35, 50), "--emit make", "members.mk"));
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const auto mk = test::run("make -s -f " + (box.dir.path / "members.mk").string() + " -j 3 all");
  ASSERT_EQ(mk.exit_code, 0) << mk.err;
  int ran = 0, derived = 0;
  for (const auto& entry : box.entries()) {
    ran += fs::exists(entry / "solver.log") ? 1 : 0;
    derived += fs::exists(entry / "derived.txt") ? 1 : 0;
  }
  EXPECT_EQ(ran, 1);
  EXPECT_EQ(derived, 2);
}

TEST(EnsembleFrictionVariants, SlipMeansAMemberOfItsOwn) {
  const Box box("friction-variants-slip", 5.0);
  const auto r = test::run(box.ensemble(lhs(20, 50)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int slipping_members = 0;
  for (const auto& e : box.entries()) {
    const CsvTable t = CsvTable::read((e / "result_faults.csv").string());
    double slipping = 0;
    for (std::size_t i = 0; i < t.rows(); ++i) slipping += t.number(i, t.column("slipping"));
    if (slipping > 0) {
      ++slipping_members;
      EXPECT_FALSE(fs::exists(e / "derived.txt")) << e;  // slip: a solve of its own
    }
    if (fs::exists(e / "derived.txt")) {
      // Derived only from a run without slip.
      const std::string note = test::slurp(e / "derived.txt");
      const std::string from = note.substr(std::string("derived from ").size(), note.find(':') - std::string("derived from ").size());
      const CsvTable s = CsvTable::read((box.dir.path / "cache" / from / "result_faults.csv").string());
      for (std::size_t i = 0; i < s.rows(); ++i) EXPECT_EQ(s.number(i, s.column("slipping")), 0);
    }
  }
  EXPECT_GE(slipping_members, 1);  // the member in [20, 30) deg slips at dp 5 MPa (30 deg does)
}

namespace {

std::string fmt_row(const std::string& date, int node, double tau, double sn, double chi, double cfs, bool interpolated) {
  char b[512];
  std::snprintf(b, sizeof b, "%s,%d,%d,2,3,0,0,1,stick,%.17g,%.17g,%.17g,0,0,%.17g,10,%d\n", date.c_str(), node, node, tau, sn, chi, cfs,
                interpolated ? 1 : 0);
  return b;
}

// A hand-written run folder: fault F (cohesion `c_MPa`, friction 30) with two pairs, the second
// interpolated, on `dates`; the fault table lists `table_dates`.
void write_run(const fs::path& d, double c_MPa, const std::vector<std::string>& dates, const std::vector<std::string>& table_dates,
               double first_cfs = 0) {
  fs::create_directories(d);
  std::string p = "# ugs-solve fault F: one row per node pair and output date; units m, MPa, mm; tension positive\n"
                  "date,node,x_m,y_m,z_m,along_strike_m,down_dip_m,area_m2,state,tau_MPa,sigma_n_eff_MPa,chi,slip_mm,opening_mm,"
                  "cfs_change_MPa,p_fault_MPa,interpolated\n";
  const double mu = std::tan(30 * M_PI / 180);
  for (std::size_t k = 0; k < dates.size(); ++k)
    for (int n = 1; n <= 2; ++n) {
      const double tau = 2 + 0.5 * static_cast<double>(k) + n, sn = -20 + static_cast<double>(k);
      const double cfs = k == 0 ? first_cfs : 0.5 * static_cast<double>(k) + mu * static_cast<double>(k);
      p += fmt_row(dates[k], n, tau, sn, tau / (c_MPa - sn * mu), cfs, n == 2);
    }
  test::spit(d / "result_fault_F.csv", p);
  std::string t = "# ugs-solve fault statistics\ndate,fault,max_chi,x_m,y_m,z_m,max_slip_mm,slip_area_m2,open_area_m2,max_opening_mm,"
                  "max_cfs_change_MPa,node_pairs,slipping,open\n";
  for (const auto& date : table_dates) t += date + ",F,0.2,1.00,2.00,3.00,0,0,0,0,0,1,0,0\n";
  test::spit(d / "result_faults.csv", t);
  test::spit(d / "result.h5", "stand-in");
}

}  // namespace

TEST(EnsembleFrictionVariants, DerivationRefusesWhatItCannotKnow) {
  const test::TempDir dir("friction-variants-unit");
  CaseFile run, member;
  run.faults.push_back({"F", "case.toml:1", 0.0, 30.0});
  member.faults.push_back({"F", "case.toml:1", 0.0, 35.0});
  const std::vector<std::string> dates{"2000-01-01", "2000-02-01"};
  auto derive = [&](const fs::path& from, const CaseFile& a, const CaseFile& b) {
    const fs::path out = dir.path / ("out-" + from.filename().string());
    fs::remove_all(out);
    fs::create_directories(out);
    return ensemble::derive_friction_variant(from.string(), a, b, out.string());
  };
  // Cohesionless: derived; chi scales by tan 30 / tan 35 for every pair (the interpolated one too),
  // the Coulomb change by (tan 35 - tan 30) d sigma'_n more; the table's max chi follows pair 1.
  write_run(dir.path / "ok", 0, dates, dates);
  const auto ok = derive(dir.path / "ok", run, member);
  ASSERT_TRUE(ok.derived) << ok.reason;
  const CsvTable p = CsvTable::read((dir.path / "out-ok" / "result_fault_F.csv").string());
  const double f = std::tan(30 * M_PI / 180) / std::tan(35 * M_PI / 180), dmu = std::tan(35 * M_PI / 180) - std::tan(30 * M_PI / 180);
  for (std::size_t i = 0; i < p.rows(); ++i) {
    const double tau = p.number(i, p.column("tau_MPa")), sn = p.number(i, p.column("sigma_n_eff_MPa"));
    EXPECT_NEAR(p.number(i, p.column("chi")), tau / (-sn * std::tan(30 * M_PI / 180)) * f, 1e-15);
    const double k = static_cast<double>(i / 2);
    EXPECT_NEAR(p.number(i, p.column("cfs_change_MPa")), 0.5 * k + std::tan(30 * M_PI / 180) * k + dmu * k, 1e-14);
  }
  const CsvTable t = CsvTable::read((dir.path / "out-ok" / "result_faults.csv").string());
  EXPECT_NEAR(t.number(0, t.column("max_chi")), 3.0 / (20 * std::tan(35 * M_PI / 180)), 1e-6);
  EXPECT_NEAR(t.number(1, t.column("max_cfs_change_MPa")), 0.5 + std::tan(35 * M_PI / 180), 0.51e-6);
  EXPECT_EQ(test::slurp(dir.path / "out-ok" / "result.h5"), "stand-in");  // the other outputs linked
  // Cohesion with an interpolated pair: its chi is a mean of its neighbours' — not derived.
  CaseFile run_c = run, member_c = member;
  run_c.faults[0].cohesion_Pa = member_c.faults[0].cohesion_Pa = 1e6;
  write_run(dir.path / "cohesive", 1, dates, dates);
  const auto c = derive(dir.path / "cohesive", run_c, member_c);
  EXPECT_FALSE(c.derived);
  EXPECT_NE(c.reason.find("interpolated"), std::string::npos) << c.reason;
  // Per-pair rows that do not start at the initial state, or lack a step of the table.
  write_run(dir.path / "late", 0, dates, dates, 0.25);
  EXPECT_NE(derive(dir.path / "late", run, member).reason.find("not at the initial state"), std::string::npos);
  write_run(dir.path / "gap", 0, dates, {"2000-01-01", "2000-01-15", "2000-02-01"});
  EXPECT_NE(derive(dir.path / "gap", run, member).reason.find("does not list its pairs on 2000-01-15"), std::string::npos);
  // A safe-scale search depends on the friction.
  write_run(dir.path / "scale", 0, dates, dates);
  test::spit(dir.path / "scale" / "result_scenario.csv", "scale,critical\n1,0\n");
  EXPECT_NE(derive(dir.path / "scale", run, member).reason.find("safe-scale"), std::string::npos);
  // A member whose chi reaches 1: friction 5 deg.
  CaseFile weak = member;
  weak.faults[0].friction_deg = 5;
  const auto w = derive(dir.path / "ok", run, weak);
  EXPECT_FALSE(w.derived);
  EXPECT_NE(w.reason.find("reaches chi"), std::string::npos) << w.reason;
}
