// Forecast-only parameters (docs/ensemble.md): `seismicity.*` values are read by the metrics, never
// by the solver, so members that differ only in them share one solver run. A stand-in solver
// counts its runs and writes one fault pair under a stressing-rate change k = c_R (V11's rate
// change); a Morris design over c_R (2 levels) and seismicity.A_sigma_MPa has 6 members but only
// as many runs as distinct c_R values, and every member's expected events equal the closed form
// with its own A sigma and its own c_R. No real solver: a few seconds.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>

#include "run_tool.hpp"
#include "solve_box.hpp"
#include "still_result.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

constexpr double kRate = 1e-3;   // background stressing rate, MPa/yr
constexpr double kR = 0.2;       // background rate, /yr/km2
constexpr double kAreaKm2 = 2.0; // the pair's area

// `sh fake.sh {case} {out}`: one line per run in runs.log; pair 1 of F1 with dCFS = (k - 1) s_r t,
// k = c_R of the member's case copy, monthly through 2020.
std::string fake_solver(const fs::path& dir) {
  return "echo run >> " + (dir / "runs.log").string() + "\n"
         "cp " + (dir / "template.h5").string() + " \"$2\"\n"
         "c=$(sed -n 's/^c_R = //p' \"$1\" | head -1)\n"
         "awk -v k=\"$c\" 'BEGIN {\n"
         "  print \"# ugs-solve fault F1 (stand-in)\"\n"
         "  print \"date,node,x_m,y_m,z_m,along_strike_m,down_dip_m,area_m2,chi,cfs_change_MPa,interpolated\"\n"
         "  split(\"0 31 60 91 121 152 182 213 244 274 305 335 366\", day, \" \")\n"
         "  for (m = 1; m <= 13; m++)\n"
         "    printf \"%s,1,0,0,-1000,0,0,2e6,0.5,%.17g,0\\n\", m == 13 ? \"2021-01-01\" : sprintf(\"2020-%02d-01\", m),\n"
         "      (k - 1) * 1e-3 * day[m] * 86400 / 31557600\n"
         "}' > \"$(dirname \"$2\")/result_fault_F1.csv\"\n";
}

}  // namespace

TEST(EnsembleForecastParams, MembersDifferingOnlyInSeismicityShareOneRun) {
  const fs::path dir = test::temp_dir("ensemble-forecast-params");
  const Mesh m = test::solve_box_mesh();
  write_msh(m, (dir / "model.msh").string());
  test::spit(dir / "case.toml", test::solve_box_case(3.0) +
                                    "\n[seismicity]\nA_sigma_MPa = 0.05\nstressing_rate_MPa_per_yr = 1e-3\n"
                                    "background_rate_per_yr_km2 = 0.2\nM_c = 1.5\nb_value = 1.0\n");
  test::write_still_result((dir / "template.h5").string(), m, {"2020-01-01", "2021-01-01"});
  test::spit(dir / "fake.sh", fake_solver(dir));
  test::spit(dir / "morris.toml",
             "[design]\nmethod = \"morris\"\nmembers = 6\nlevels = 2\nseed = 3\n\n"
             "[[parameter]]\npath = \"material.pool_c.c_R\"\ndistribution = \"uniform\"\nlower = 2.0\nupper = 6.0\n\n"
             "[[parameter]]\npath = \"seismicity.A_sigma_MPa\"\ndistribution = \"uniform\"\nlower = 0.02\nupper = 0.1\n");
  const std::string cmd = test::tool("ugs-ensemble") + " run --spec " + (dir / "morris.toml").string() + " --case " +
                          (dir / "case.toml").string() + " --solver-command 'sh " + (dir / "fake.sh").string() +
                          " {case} {out}' --seismic-window w=2020-03-01/2020-12-01 -j 2 -o " + (dir / "out").string();
  const auto r = test::run(cmd);
  ASSERT_EQ(r.exit_code, 0) << r.err;

  const CsvTable t = CsvTable::read((dir / "out" / "members.csv").string());
  ASSERT_EQ(t.rows(), 6u);
  std::set<double> c_values;
  std::set<std::string> entries;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    const double k = t.number(i, t.column("material.pool_c.c_R"));
    const double a_sigma = t.number(i, t.column("seismicity.A_sigma_MPa"));
    c_values.insert(k);
    entries.insert(std::string(t.text(i, t.column("entry"))));
    // N = r A [t_a (g(t2) - g(t1))], g(t) = log((e^{k t / t_a} + k - 1) / k), t_a = A sigma / s_r.
    const double ta = a_sigma / kRate;
    auto g = [&](double y) { return std::log((std::exp(k * y / ta) + k - 1) / k); };
    const double a = 60 * 86400 / 31557600.0, e = 335 * 86400 / 31557600.0;
    const double n = kR * kAreaKm2 * ta * (g(e) - g(a));
    EXPECT_LT(std::abs(t.number(i, t.column("seismic_events.F1.w")) - n), 1e-9 * n) << "member " << i + 1;
  }
  // Morris moves A sigma once per trajectory with c_R fixed: shared entries, one run for each.
  EXPECT_EQ(entries.size(), c_values.size());
  EXPECT_LT(entries.size(), 6u);
  EXPECT_EQ(test::slurp(dir / "runs.log").size(), 4 * c_values.size());  // "run\n" per run
  // A second run finds every entry in the cache: no solver run, the same members.csv.
  const std::string before = test::slurp(dir / "out" / "members.csv");
  fs::remove_all(dir / "out");
  const auto again = test::run(cmd);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(test::slurp(dir / "runs.log").size(), 4 * c_values.size());
  EXPECT_EQ(test::slurp(dir / "out" / "members.csv"), before);
}
