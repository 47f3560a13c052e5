// ugs-seismicity on small files the tests write (docs/seismicity.md): a single patch whose history is
// V11's rate change gives the closed form in every table; bad input exits 2 with one line and
// writes nothing; on a small faulted ugs-solve run (contact_make_case, a monthly storage cycle) the
// per-pair CSV and the faults HDF5 give the same R/r at every node pair, the node fields hold the
// per-pair table's values, and the fault table is the area-weighted sum of the pairs.
#include <cmath>
#include <filesystem>
#include <map>

#include <gtest/gtest.h>

#include "run_tool.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

using Dir = test::TempDir;

const char* kSection =
    "[seismicity]\nA_sigma_MPa = 0.05\nstressing_rate_MPa_per_yr = 1e-3\nbackground_rate_per_yr_km2 = 0.2\nM_c = 1.5\n"
    "b_value = 1.0\nmagnitudes = [2.0, 3.0]\n";

std::string seis(const std::string& args) { return test::tool("ugs-seismicity") + " " + args; }

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

std::vector<std::string> files_in(const fs::path& d) {
  std::vector<std::string> v;
  for (const auto& e : fs::directory_iterator(d)) v.push_back(e.path().filename().string());
  std::sort(v.begin(), v.end());
  return v;
}

}  // namespace

// V11's rate change (k = 10 from 2000-01-01) as a date,dcfs_MPa table of one 4 km2 patch:
// R/r = k / (1 + (k - 1) e^{-k t / t_a}) at each date, the events from the start
// r A t_a log((e^{k t / t_a} + k - 1) / k), the window's count and P = 1 - e^-N, N(M) = N 10^{-(M - M_c)}.
TEST(SeismicityCli, PatchTableFollowsTheClosedForms) {
  Dir d("seis-patch");
  test::spit(d / "case.toml", kSection);
  const double k = 10, As = 0.05, sr = 1e-3, ta = As / sr, r = 0.2, area = 4;
  const std::vector<const char*> dates{"2000-01-01", "2000-07-01", "2001-01-01", "2005-01-01", "2030-01-01", "2050-01-01"};
  const std::int64_t t0 = *parse_iso_date(dates[0]);
  auto years = [&](std::int64_t t) { return static_cast<double>(t - t0) / kSecondsPerYear; };
  std::string csv = "date,dcfs_MPa\n";
  for (auto s : dates) csv += fmt::format("{},{}\n", s, (k - 1) * sr * years(*parse_iso_date(s)));
  test::spit(d / "patch.csv", csv);
  const auto run = test::run(seis(d / "patch.csv" + " --case " + d / "case.toml" + " --patch-area-km2 4 --window 2001-01-01/2030-01-01 -o " +
                                  d / "f.csv"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  auto events = [&](double t) { return r * area * ta * std::log((std::exp(k * t / ta) + k - 1) / k); };
  const CsvTable f = CsvTable::read(d / "f.csv");
  ASSERT_EQ(f.rows(), dates.size());
  for (std::size_t i = 0; i < f.rows(); ++i) {
    const double t = years(f.date(i, f.column("date")));
    const double R = k / (1 + (k - 1) * std::exp(-t * k * sr / As));
    // (dCFS written with 17 digits: its rounding is below 1e-15 of S / A sigma)
    EXPECT_LT(rel(f.number(i, f.column("R_over_r")), R), 1e-12) << t;
    EXPECT_EQ(f.number(i, f.column("R_over_r_max")), f.number(i, f.column("R_over_r")));
    EXPECT_LT(rel(f.number(i, f.column("rate_per_yr")), r * area * R), 1e-12) << t;
    if (t == 0) EXPECT_EQ(f.number(i, f.column("events_from_start")), 0.0);
    else EXPECT_LT(rel(f.number(i, f.column("events_from_start")), events(t)), 1e-12) << t;
  }
  const CsvTable w = CsvTable::read(d / "f_windows.csv");
  const double n = events(years(*parse_iso_date("2030-01-01"))) - events(years(*parse_iso_date("2001-01-01")));
  ASSERT_EQ(w.rows(), 6u);  // patch and all, at M 1.5, 2, 3
  for (std::size_t i = 0; i < w.rows(); ++i) {
    const double m = w.number(i, w.column("magnitude")), nm = n * std::pow(10.0, -(m - 1.5));
    EXPECT_LT(rel(w.number(i, w.column("expected_events")), nm), 1e-11) << m;
    EXPECT_LT(rel(w.number(i, w.column("p_at_least_one")), -std::expm1(-nm)), 1e-11) << m;
  }
  EXPECT_EQ(w.text(0, w.column("fault")), "patch");
  EXPECT_EQ(w.text(3, w.column("fault")), "all");
  EXPECT_TRUE(fs::exists(d / "f_pairs.csv"));
}

// Each bad input: exit 2, one line naming the problem, no file written.
TEST(SeismicityCli, BadInputExitsTwoWithOneLineAndWritesNothing) {
  Dir d("seis-bad");
  test::spit(d / "good.toml", kSection);
  test::spit(d / "patch.csv", "date,dcfs_MPa\n2020-01-01,0\n2021-01-01,0.1\n2022-01-01,0.2\n");
  test::spit(d / "backwards.csv", "date,dcfs_MPa\n2020-01-01,0\n2022-01-01,0.1\n2021-01-01,0.2\n");
  test::spit(d / "nan.csv", "date,dcfs_MPa\n2020-01-01,0\n2021-01-01,nan\n");
  test::spit(d / "pairs_fault_F.csv", "# ugs-solve fault F: one row per node pair and output date\n"
                                      "date,node,x_m,y_m,z_m,along_strike_m,down_dip_m,area_m2,cfs_change_MPa,interpolated\n"
                                      "2020-01-01,1,0,0,0,0,0,100,0,0\n2021-01-01,1,0,0,0,0,0,100,0.1,0\n");
  auto with = [&](const std::string& name, const std::string& text) {
    test::spit(d / name, text);
    return d / name;
  };
  const std::string zero_as = with("zero_as.toml", "[seismicity]\nA_sigma_MPa = 0\nstressing_rate_MPa_per_yr = 1e-3\n"
                                                   "background_rate_per_yr_km2 = 0.2\nM_c = 1.5\n");
  const std::string neg_sr = with("neg_sr.toml", "[seismicity]\nA_sigma_MPa = 0.05\nstressing_rate_MPa_per_yr = -1e-3\n"
                                                 "background_rate_per_yr_km2 = 0.2\nM_c = 1.5\n");
  const std::string missing = with("missing.toml", std::string(kSection) + "\n[[fault]]\nname = \"G\"\n");
  const std::string override_missing = with("override.toml", std::string(kSection) + "[seismicity.fault.G]\nA_sigma_MPa = 0.1\n");
  const std::string override_patch_ok = with("override_ok.toml", std::string(kSection) + "[seismicity.fault.patch]\nA_sigma_MPa = 0.1\n");
  const std::string no_section = with("none.toml", "[[fault]]\nname = \"F\"\n");
  const std::vector<std::pair<std::string, std::string>> cases{
      {d / "patch.csv" + " --case " + zero_as, "zero_as.toml:2: 'seismicity.A_sigma_MPa': must be positive, got 0"},
      {d / "patch.csv" + " --case " + neg_sr, "neg_sr.toml:3: 'seismicity.stressing_rate_MPa_per_yr': must be positive"},
      {d / "backwards.csv --case " + d / "good.toml", "backwards.csv:4: date 2021-01-01 does not follow 2022-01-01"},
      {d / "nan.csv --case " + d / "good.toml", "nan.csv:3: column 'dcfs_MPa'"},
      {d / "patch.csv --case " + d / "good.toml" + " --window 2019-01-01/2021-01-01", "--window"},
      {d / "patch.csv --case " + d / "good.toml" + " --window 2021-01-01/2022-01-02", "lies outside the stress history (2020-01-01 .. 2022-01-01)"},
      {d / "patch.csv --case " + d / "good.toml" + " --start 2023-01-01", "--start: 2023-01-01 lies outside"},
      {d / "pairs_fault_F.csv --case " + missing, "fault 'G' of the case is missing from the results (faults: F"},
      {d / "pairs_fault_F.csv --case " + override_missing, "[seismicity.fault.G]: the results have no fault 'G' (faults: F)"},
      {d / "patch.csv --case " + no_section, "has no [seismicity] section"},
      {d / "patch.csv --case " + d / "good.toml --patch-area-km2 0", "--patch-area-km2: 0 (expected a finite number in (0, 1000000])"},
      {d / "pairs_fault_F.csv --case " + d / "good.toml --field-output " + d / "x.h5", "need the faults HDF5 as input"},
  };
  const auto before = files_in(d.path);
  for (const auto& [args, expected] : cases) {
    const auto r = test::run(seis(args + " -o " + d / "out.csv"));
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("ugs-seismicity: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(files_in(d.path), before) << args;
  }
  // An override naming the patch is fine and is used.
  const auto r = test::run(seis(d / "patch.csv --case " + override_patch_ok + " -o " + d / "ok.csv"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(test::slurp(d / "ok.csv").find("fault patch: A_sigma_MPa = 0.1,"), std::string::npos);
}

// A faulted ugs-solve run over a monthly storage cycle (contact_make_case --months 12): the forecast
// from the per-pair CSV and from the faults HDF5 agree pair by pair; the HDF5 node field R_over_r is
// the per-pair table's; the fault's rate is r times the area-weighted sum of the pairs. ugs-report
// --seismicity draws the R/r series and the event density map (its data: the per-pair table's
// cumulative density at the window's end minus at its start) and puts the windows' counts in the
// headlines.
TEST(SeismicityCli, SolvedFaultFromCsvAndHdf5) {
  Dir d("seis-solve");
  auto mk = test::run(std::string(UGS_BINARY_DIR) + "/tests/fault_mechanics/contact_make_case " + d.path.string() +
                      " --dp 6 --cell 100 --months 12");
  ASSERT_EQ(mk.exit_code, 0) << mk.err;
  {
    std::ofstream(d / "case.toml", std::ios::app) << "\n" << kSection;
  }
  const auto s = test::run(test::tool("ugs-solve") + " " + d / "faulted.msh" + " --case " + d / "case.toml" + " --pressure " +
                           d / "flow.h5" + " -o " + d / "out.h5");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const std::string common = " --case " + d / "case.toml" + " --start 2000-03-01 --window 2000-02-01/2000-12-01";
  auto a = test::run(seis(d / "out_fault_F.csv" + common + " -o " + d / "csv.csv"));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  auto b = test::run(seis(d / "out_faults.h5 --mesh " + d / "faulted.msh" + common + " -o " + d / "h5.csv"));
  ASSERT_EQ(b.exit_code, 0) << b.err;
  ASSERT_TRUE(fs::exists(d / "h5_pairs.h5") && fs::exists(d / "h5_pairs.xdmf"));
  const CsvTable pc = CsvTable::read(d / "csv_pairs.csv"), ph = CsvTable::read(d / "h5_pairs.csv");
  std::map<std::pair<std::string, std::string>, double> from_h5;
  for (std::size_t i = 0; i < ph.rows(); ++i) {
    EXPECT_EQ(ph.text(i, ph.column("fault")), "F");
    from_h5[{std::string(ph.text(i, 0)), std::string(ph.text(i, ph.column("node")))}] = ph.number(i, ph.column("R_over_r"));
  }
  double peak = 0;
  std::size_t compared = 0;
  for (std::size_t i = 0; i < pc.rows(); ++i) {
    const auto it = from_h5.find({std::string(pc.text(i, 0)), std::string(pc.text(i, pc.column("node")))});
    ASSERT_NE(it, from_h5.end());
    const double R = pc.number(i, pc.column("R_over_r"));
    peak = std::max(peak, R);
    // (the CSV's cfs_change_MPa is the HDF5's Pa value written as the shortest decimal in MPa)
    EXPECT_LT(rel(it->second, R), 1e-12) << pc.where(i);
    ++compared;
  }
  EXPECT_GT(compared, 20u);
  EXPECT_GT(peak, 1.01);  // the storage cycle moves the rate
  // The node field R_over_r at the last date is the per-pair table's.
  FieldSeriesReader fr(d / "h5_pairs.h5");
  ASSERT_EQ(fr.steps().size(), 13u);
  const Field R = fr.node_field(12, "R_over_r");
  const auto tags = fr.node_tags();
  for (std::size_t n = 0; n < tags.size(); ++n) {
    const auto it = from_h5.find({"2001-01-01", std::to_string(tags[n])});
    ASSERT_NE(it, from_h5.end()) << tags[n];
    EXPECT_EQ(R.values[n], it->second);
  }
  // The fault table: rate = r sum A_q (R/r)_q, per date, from the per-pair CSV's rows.
  const CsvTable f = CsvTable::read(d / "csv.csv");
  ASSERT_EQ(f.rows(), 13u);
  for (std::size_t k = 0; k < f.rows(); ++k) {
    double sum = 0;
    for (std::size_t i = 0; i < pc.rows(); ++i)
      if (pc.text(i, 0) == f.text(k, 0)) sum += pc.number(i, pc.column("area_m2")) * pc.number(i, pc.column("R_over_r"));
    EXPECT_LT(rel(f.number(k, f.column("rate_per_yr")), 0.2 * sum / 1e6), 1e-12) << f.text(k, 0);
  }
  // ugs-report: pictures, the density map's data and the headline of all faults at M_c.
  const auto rep = test::run(test::tool("ugs-report") + " --thesis --results " + d / "out.h5" + " --mesh " + d / "faulted.msh" + " --case " +
                             d / "case.toml" + " --seismicity " + d / "csv.csv" + " --width 600 --height 400 --keep-work -q -o " +
                             d / "report");
  ASSERT_EQ(rep.exit_code, 0) << rep.err;
  EXPECT_TRUE(fs::exists(d / "report/seismicity_rate_series.png"));
  EXPECT_TRUE(fs::exists(d / "report/seismicity_density.png"));
  std::map<std::string, double> at_a, at_b;
  for (std::size_t i = 0; i < pc.rows(); ++i) {
    const std::string node(pc.text(i, pc.column("node")));
    if (pc.text(i, 0) == "2000-02-01") at_a[node] = pc.number(i, pc.column("events_per_km2_from_start"));
    if (pc.text(i, 0) == "2000-12-01") at_b[node] = pc.number(i, pc.column("events_per_km2_from_start"));
  }
  const CsvTable dens = CsvTable::read(d / "report/work/seismicity_density.csv");
  ASSERT_EQ(dens.rows(), at_b.size());
  for (std::size_t i = 0; i < dens.rows(); ++i) {
    const std::string node(dens.text(i, dens.column("node")));
    EXPECT_EQ(dens.number(i, dens.column("events_per_km2")), at_b.at(node) - at_a.at(node)) << node;
  }
  const CsvTable w = CsvTable::read(d / "csv_windows.csv");
  const double n_all = w.number(w.rows() - 3, w.column("expected_events"));  // "all" at M_c = 1.5
  ASSERT_EQ(w.text(w.rows() - 3, w.column("fault")), "all");
  EXPECT_NE(test::slurp(d / "report/summary.md").find(fmt::format("expected events M ≥ 1.5, all faults | {:.3g} (P(at least one)", n_all)),
            std::string::npos);
}
