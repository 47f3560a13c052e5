// ugs-ensemble on the two-pool box model of the calibration twins (tests/insar/solve_box.hpp) with
// the real solver: a Morris design over c_R of Pool C (decides the storage uplift) and
// scenario.scale_tolerance (read by the case, unused by a run without --find-safe-scale: no
// influence), members equal to a single ugs-solve run bit for bit, a rerun that only reads the
// cache and writes the same bytes, the emitted Makefile reproducing a local run, and bad input.
// Skipped (reported) when ugs-solve is not built.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <regex>

#include "ensemble_box.hpp"
#include "ugs/ensemble/metrics.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/insar/inputs.hpp"
#include "ugs/insar/ps_data.hpp"
#include "ugs/runner/case_params.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

const std::string kParams = test::kParamPoolC + test::kParamTolerance;

fs::path make_box() { return test::make_ensemble_box("ensemble-solve"); }

// The misfit adds the east-west series of Pool C's nine points at half weight (ugs-calibrate's misfit).
std::string east(const fs::path& dir) { return " --measured-east " + (dir / "east.csv").string() + " --east-weight 0.5 "; }

std::string ens_cmd(const fs::path& dir, const std::string& mode, const std::string& spec, const std::string& extra) {
  return test::ensemble_cmd(dir, mode, spec, extra);
}

using test::data_lines;

}  // namespace

TEST(EnsembleSolve, MorrisMembersCacheMakefileAndBadInput) {
  if (!test::have_solver()) GTEST_SKIP() << "ugs-solve is not built";
  const fs::path dir = make_box();
  test::spit(dir / "morris.toml", "[design]\nmethod = \"morris\"\nmembers = 9\nlevels = 4\nseed = 3\n" + kParams);

  // 1. Morris: 3 trajectories of 3 members.
  const auto r = test::run(ens_cmd(dir, "run", "morris.toml", east(dir) + "-j 2 -o " + (dir / "out").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable m = CsvTable::read((dir / "out" / "morris.csv").string());
  ASSERT_GT(m.rows(), 0u);
  std::map<std::string, double> mu_star;
  for (std::size_t i = 0; i < m.rows(); ++i) {
    EXPECT_EQ(m.integer(i, m.column("trajectories")), 3);
    mu_star[std::string(m.text(i, m.column("metric"))) + "|" + std::string(m.text(i, m.column("parameter")))] =
        m.number(i, m.column("mu_star"));
  }
  // No influence: the same answer bit for bit, so every effect is exactly 0.
  for (const auto& [k, v] : mu_star) {
    if (k.find("scale_tolerance") != std::string::npos) {
      EXPECT_EQ(v, 0.0) << k;
    }
  }
  // c_R of Pool C decides how far the ground rises over the storage half-cycle.
  EXPECT_GT(mu_star.at("uplift_max_mm.storage|material.pool_c.c_R"), 0.5);
  std::printf("mu*(uplift, c_R) = %.4f mm, mu*(uplift, scale_tolerance) = %g\n",
              mu_star.at("uplift_max_mm.storage|material.pool_c.c_R"), mu_star.at("uplift_max_mm.storage|scenario.scale_tolerance"));

  // The fan charts' data: 11 PS points at every PS date of the results, the band ordered.
  const CsvTable ps = CsvTable::read((dir / "out" / "ps_series.csv").string());
  ASSERT_GT(ps.rows(), 11u);
  for (std::size_t i = 0; i < ps.rows(); ++i) {
    EXPECT_EQ(ps.integer(i, ps.column("n")), 9);
    EXPECT_LE(ps.number(i, ps.column("p10_mm")), ps.number(i, ps.column("p50_mm")));
    EXPECT_LE(ps.number(i, ps.column("p50_mm")), ps.number(i, ps.column("p90_mm")));
  }

  // The report's ensemble pictures from that folder (tornado of morris.csv, fan charts of ps_series.csv).
  const auto rep = test::run(test::tool("ugs-report") + " --thesis --results " + (dir / "truth.h5").string() + " --mesh " +
                             (dir / "model.msh").string() + " --case " + (dir / "case.toml").string() +
                             " --phase storage=2013-05-01/2013-11-01 --ensemble " + (dir / "out").string() + " -o " +
                             (dir / "report").string());
  ASSERT_EQ(rep.exit_code, 0) << rep.err;
  for (const char* png : {"ensemble_tornado_morris.png", "ensemble_fan_ps.png"})
    EXPECT_GT(fs::file_size(dir / "report" / png), 10000u) << png;
  EXPECT_NE(test::slurp(dir / "report" / "summary.html").find("9 of 9"), std::string::npos);

  // 2. A member equals a single ugs-solve run with its parameters, bit for bit.
  const CsvTable mem = CsvTable::read((dir / "out" / "members.csv").string());
  ASSERT_EQ(mem.rows(), 9u);
  const runner::CaseTemplate tmpl((dir / "case.toml").string());
  const double c_R = mem.number(0, mem.column("material.pool_c.c_R")), tol = mem.number(0, mem.column("scenario.scale_tolerance"));
  fs::create_directories(dir / "single");
  test::spit(dir / "single" / "case.toml", tmpl.render({{"material.pool_c.c_R", c_R}, {"scenario.scale_tolerance", tol}}));
  std::string cmd = test::solver_command(dir);
  auto put = [&](const std::string& key, const std::string& v) { cmd.replace(cmd.find(key), key.size(), v); };
  put("{mesh}", (dir / "model.msh").string());
  put("{case}", (dir / "single" / "case.toml").string());
  put("{out}", (dir / "single" / "result.h5").string());
  put("{dir}", (dir / "single").string());
  ASSERT_EQ(test::run(cmd).exit_code, 0);
  ensemble::MetricOptions mo;
  mo.phases.push_back(ensemble::parse_phase("storage=2013-05-01/2013-11-01"));
  insar::PsReadOptions ro;
  ro.model_crs = insar::model_crs("", (dir / "case.toml").string());
  mo.ps = insar::read_ps((dir / "up.csv").string(), ro);
  mo.window = insar::parse_window("2009-01-01/2014-12-31", "--window");
  const double vertical_only = ensemble::member_metrics((dir / "single").string(), mo).back().second;
  mo.ps_east = insar::read_ps((dir / "east.csv").string(), ro);
  mo.east_weight = 0.5;
  const ensemble::Metrics single = ensemble::member_metrics((dir / "single").string(), mo);
  ASSERT_EQ(single.size(), 5u);  // uplift, settlement, at the PS points too, and the misfit
  EXPECT_EQ(single.back().first, "insar_rms_mm");
  for (const auto& [name, v] : single) EXPECT_EQ(mem.number(0, mem.column(name)), v) << name;
  // The east series count: 11 vertical and 9 east series at 1.5 mm noise each, so the misfit moves.
  EXPECT_NE(single.back().second, vertical_only);
  EXPECT_GT(single.back().second, 0.5);
  EXPECT_GT(vertical_only, 0.5);

  // 3. A rerun runs nothing and writes the same bytes.
  const auto again = test::run(ens_cmd(dir, "run", "morris.toml", east(dir) + "-j 2 -o " + (dir / "out2").string() + " --cache-dir " +
                                                                       (dir / "out.cache").string()));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(std::count(again.err.begin(), again.err.end(), '\n') >= 9, true);
  EXPECT_EQ(again.err.find(" s\n"), std::string::npos) << again.err;  // no member timed: all cached
  for (const char* f : {"members.csv", "quantiles.csv", "morris.csv", "failures.csv", "exceedance.csv", "ps_series.csv"})
    EXPECT_EQ(data_lines(dir / "out" / f), data_lines(dir / "out2" / f)) << f;

  // 4. The emitted Makefile, run by make into a fresh cache, reproduces a local run.
  test::spit(dir / "lhs.toml", std::string("[design]\nmethod = \"lhs\"\nmembers = 3\nseed = 9\n") + kParams);
  ASSERT_EQ(test::run(ens_cmd(dir, "run", "lhs.toml", east(dir) + "-j 2 -o " + (dir / "local").string())).exit_code, 0);
  const auto e = test::run(ens_cmd(dir, "run", "lhs.toml", east(dir) + "--emit make --cache-dir " + (dir / "make.cache").string() + " -o " +
                                                               (dir / "members.mk").string()));
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const auto mk = test::run("make -s -f " + (dir / "members.mk").string() + " -j 2 collect");
  ASSERT_EQ(mk.exit_code, 0) << mk.err;
  for (const char* f : {"members.csv", "quantiles.csv"})
    EXPECT_EQ(data_lines(dir / "local" / f), data_lines(dir / "members.mk.out" / f)) << f;
  EXPECT_EQ(test::run("make -q -f " + (dir / "members.mk").string() + " all").exit_code, 0);  // nothing left to do
  const auto sl = test::run(ens_cmd(dir, "run", "lhs.toml", "--emit slurm -o " + (dir / "members.sbatch").string()));
  ASSERT_EQ(sl.exit_code, 0) << sl.err;
  EXPECT_NE(test::slurp(dir / "members.sbatch").find("#SBATCH --array=1-3\n"), std::string::npos);

  // 5. A failed member: recorded with its error line, excluded, listed; the others stand.
  test::spit(dir / "fake.sh", "grep -q 'c_R = [23]\\.' \"$1\" && { echo 'fake solver: c_R below 4 refused' >&2; exit 3; }\n"
                              "cp " + (dir / "single" / "result.h5").string() + " \"$2\"\ncp " +
                                  (dir / "single" / "result.xdmf").string() + " \"${2%.h5}.xdmf\"\n"
                              // Fault and safe-scale tables as ugs-solve writes them: chi of F1 = c_R / 5 on 2013-05-01.
                              "c=$(sed -n 's/^c_R = //p' \"$1\" | head -1)\n"
                              "awk -v c=\"$c\" 'BEGIN { printf \"date,fault,max_chi\\n2013-05-01,F1,%.17g\\n2013-11-01,F1,0.1\\n"
                              "2013-05-01,F2,0.5\\n\", c / 5 }' > \"$(dirname \"$2\")/solve_faults.csv\"\n"
                              "printf 'scale,critical\\n1,0\\n2,0\\n4,1\\n3,1\\n2.5,0\\n' > \"$(dirname \"$2\")/solve_scenario.csv\"\n"
                              // The caprock table: the seal's tensile margin c_R MPa at its lowest, shear 2 MPa.
                              "awk -v c=\"$c\" 'BEGIN { printf \"date,seal,min_tensile_margin_MPa,min_shear_margin_MPa\\n"
                              "2013-05-01,S,%.17g,3\\n2013-11-01,S,%.17g,2\\n\", c + 1, c }' > \"$(dirname \"$2\")/solve_caprock.csv\"\n");
  test::spit(dir / "lhs4.toml", std::string("[design]\nmethod = \"lhs\"\nmembers = 4\nseed = 9\n") + kParams);
  const auto f = test::run(test::tool("ugs-ensemble") + " run --spec " + (dir / "lhs4.toml").string() + " --case " +
                           (dir / "case.toml").string() + " --solver-command 'sh " + (dir / "fake.sh").string() +
                           " {case} {out}' -o " + (dir / "failing").string());
  ASSERT_EQ(f.exit_code, 0) << f.err;
  const CsvTable fl = CsvTable::read((dir / "failing" / "failures.csv").string());
  ASSERT_EQ(fl.rows(), 2u);  // the strata [2, 3) and [3, 4) of c_R
  EXPECT_NE(std::string(fl.text(0, fl.column("error"))).find("fake solver: c_R below 4 refused"), std::string::npos);
  EXPECT_NE(f.err.find("excluded from the statistics"), std::string::npos) << f.err;
  const CsvTable q = CsvTable::read((dir / "failing" / "quantiles.csv").string());
  EXPECT_EQ(q.integer(0, q.column("n")), 2);
  // The two members left have c_R in [4, 5) and [5, 6): chi of F1 in [0.8, 1) and [1, 1.2).
  const CsvTable ex = CsvTable::read((dir / "failing" / "exceedance.csv").string());
  ASSERT_EQ(ex.rows(), 2u);
  EXPECT_EQ(ex.text(0, ex.column("fault")), "F1");
  EXPECT_EQ(ex.number(0, ex.column("p_chi_ge_0.8")), 1.0);
  EXPECT_EQ(ex.number(0, ex.column("p_chi_ge_1")), 0.5);
  EXPECT_EQ(ex.number(1, ex.column("p_chi_ge_0.8")), 0.0);
  bool safe = false, per_date = false, seal = false, seal_shear = false;
  for (std::size_t i = 0; i < q.rows(); ++i) {
    const std::string name(q.text(i, q.column("metric")));
    if (name == "safe_scale") safe = q.number(i, q.column("p50")) == 2.5;  // below the smallest critical 3
    if (name == "chi_max.F1.2013-11-01") per_date = q.number(i, q.column("max")) == 0.1;
    // The members' c_R in [4, 5) and [5, 6): the seal's smallest tensile margin is c_R, its shear one 2.
    if (name == "seal_tensile_margin_min.S")
      seal = q.number(i, q.column("min")) >= 4 && q.number(i, q.column("min")) < 5 && q.number(i, q.column("max")) >= 5 &&
             q.number(i, q.column("max")) < 6;
    if (name == "seal_shear_margin_min.S") seal_shear = q.number(i, q.column("min")) == 2 && q.number(i, q.column("max")) == 2;
  }
  EXPECT_TRUE(safe);
  EXPECT_TRUE(per_date);
  EXPECT_TRUE(seal);
  EXPECT_TRUE(seal_shear);

  // 6. Bad input: exit 2, one line, nothing run.
  auto one_line = [](const test::RunResult& x) {
    return x.exit_code == 2 && std::count(x.err.begin(), x.err.end(), '\n') == 1 && x.err.rfind("ugs-ensemble: error: ", 0) == 0;
  };
  test::spit(dir / "unknown.toml", "[design]\nmethod = \"lhs\"\nmembers = 4\n[[parameter]]\npath = \"material.pool_x.c_R\"\n"
                                   "distribution = \"uniform\"\nlower = 1.0\nupper = 2.0\n");
  const auto u = test::run(ens_cmd(dir, "run", "unknown.toml", "-o " + (dir / "bad").string()));
  EXPECT_TRUE(one_line(u)) << u.err;
  EXPECT_NE(u.err.find("material.pool_x.c_R"), std::string::npos) << u.err;
  test::spit(dir / "invalid.toml", "[design]\nmethod = \"lhs\"\nmembers = 4\n[[parameter]]\npath = \"material.pool_c.c_R\"\n"
                                   "distribution = \"uniform\"\nlower = -1.0\nupper = 2.0\n");
  const auto iv = test::run(ens_cmd(dir, "run", "invalid.toml", "-o " + (dir / "bad").string()));
  EXPECT_TRUE(one_line(iv)) << iv.err;
  EXPECT_NE(iv.err.find("the case is not valid at material.pool_c.c_R = -1"), std::string::npos) << iv.err;
  test::spit(dir / "few.toml", std::string("[design]\nmethod = \"sobol\"\nmembers = 7\n") + kParams);
  const auto fw = test::run(ens_cmd(dir, "run", "few.toml", "-o " + (dir / "bad").string()));
  EXPECT_TRUE(one_line(fw)) << fw.err;
  EXPECT_NE(fw.err.find("fewer than the sobol design needs"), std::string::npos) << fw.err;
  // East-west series of no point of --measured, and a negative weight.
  test::spit(dir / "east_other.csv", std::regex_replace(test::slurp(dir / "east.csv"), std::regex("\\bC([0-9])([0-9])\\b"), "X$1$2"));
  const auto eo = test::run(ens_cmd(dir, "run", "lhs.toml", "--measured-east " + (dir / "east_other.csv").string() + " -o " + (dir / "bad").string()));
  EXPECT_TRUE(one_line(eo)) << eo.err;
  EXPECT_NE(eo.err.find("has none of the PS points of --measured"), std::string::npos) << eo.err;
  const auto ew = test::run(ens_cmd(dir, "run", "lhs.toml", "--measured-east " + (dir / "east.csv").string() + " --east-weight -1 -o " + (dir / "bad").string()));
  EXPECT_TRUE(one_line(ew)) << ew.err;
  EXPECT_NE(ew.err.find("--east-weight"), std::string::npos) << ew.err;
  // The libraries name these settings in words; the line names the flags typed (issue 23).
  const auto bc = test::run(ens_cmd(dir, "run", "lhs.toml", "--crs EPSG:nothing -o " + (dir / "bad").string()));
  EXPECT_TRUE(one_line(bc)) << bc.err;
  EXPECT_EQ(bc.err, "ugs-ensemble: error: --crs: unknown coordinate reference system 'EPSG:nothing' (e.g. \"EPSG:32632\")\n");
  const auto bp = test::run(ens_cmd(dir, "run", "lhs.toml", "--phase storage -o " + (dir / "bad").string()));
  EXPECT_TRUE(one_line(bp)) << bp.err;
  EXPECT_EQ(bp.err, "ugs-ensemble: error: --phase storage: expected NAME=START/END, e.g. storage=2015-05-01/2015-11-01\n");
  EXPECT_FALSE(fs::exists(dir / "bad"));
  EXPECT_FALSE(fs::exists(dir / "bad.cache"));
  if (!HasFailure() && !std::getenv("UGS_TEST_KEEP")) fs::remove_all(dir);
}
