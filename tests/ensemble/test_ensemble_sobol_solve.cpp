// Sobol' indices on a real ugs case: ugs-ensemble's sobol design with ugs-solve on the two-pool box
// model of the calibration twins (ensemble_box.hpp), three parameters:
//   material.pool_c.c_R       decides the storage uplift: Pool C is reloaded by 6 MPa from 1 May to
//                             1 November with compressibility c_M(sigma_max) / c_R (docs/theory.md),
//                             so its compaction, and the uplift above it, goes as 1 / c_R;
//   material.pool_a.c_R       Pool A's pressure is the same (-4 MPa) on both dates: next to no influence;
//   scenario.scale_tolerance  read by the case, unused by a run without --find-safe-scale: none at all.
// A metric that depends on one parameter only has S1 = ST = 1 for it and 0 for the others. Martinez'
// estimator (S1_i = corr(y_B, y_Ei), ST_i = 1 - corr(y_A, y_Ei), E_i = A with column i from B) gives
// exactly ST = 0 for the unused parameter (its block E_i repeats A's runs bit for bit) and S1 = 1 for
// c_R (E_i repeats B's) to the last bits of a correlation, while S1 of the others and ST of c_R carry the design's sampling noise
// corr(y_A, y_B), of order 1 / sqrt(N): with N = 8 base points it is not small, so those are asserted
// through their 95 % intervals and the identity S1(unused) + ST(c_R) = 1 of the estimator.
// 40 members + the truth run: about 63 s CPU (load 5: 147 s wall). Skipped when ugs-solve is not built.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "ensemble_box.hpp"
#include "ugs/formats/csv.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

const std::string kSpec = std::string("[design]\nmethod = \"sobol\"\nmembers = 40\nseed = 1\n") + test::kParamPoolC +
                          test::kParamPoolA + test::kParamTolerance;

struct Index {
  double s1, s1_low, s1_high, st, st_low, st_high;
};

}  // namespace

TEST(EnsembleSobolSolve, UnusedParameterGetsZeroAndReloadingCompressibilityDecides) {
  if (!test::have_solver()) GTEST_SKIP() << "ugs-solve is not built";
  const fs::path dir = test::make_ensemble_box("ensemble-sobol");
  test::spit(dir / "sobol.toml", kSpec);
  const auto r = test::run(test::ensemble_cmd(dir, "run", "sobol.toml", "-j 2 -o " + (dir / "out").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;

  // The members: blocks A, B, E_c (Pool C's c_R from B), E_a, E_tol, of N = 8 each.
  const std::size_t n = 8;
  const CsvTable mem = CsvTable::read((dir / "out" / "members.csv").string());
  ASSERT_EQ(mem.rows(), 5 * n);
  const char* metrics[] = {"uplift_max_mm.storage", "ps_uplift_max_mm.storage", "insar_rms_mm"};
  for (std::size_t k = 0; k < n; ++k) {
    EXPECT_EQ(mem.text(k, mem.column("status")), "ok");
    // E_tol differs from A only in the unused parameter: the same run, bit for bit.
    for (const char* m : metrics) EXPECT_EQ(mem.number(4 * n + k, mem.column(m)), mem.number(k, mem.column(m))) << m << " " << k;
  }
  // The metric's closed form in c_R: uplift x c_R the same for every member within 10 % (the pool's
  // compaction is exactly c_M h dp / c_R; the stiffer elastic rock around it takes the rest).
  double lo = 1e300, hi = 0;
  for (std::size_t i = 0; i < mem.rows(); ++i) {
    const double p = mem.number(i, mem.column("uplift_max_mm.storage")) * mem.number(i, mem.column("material.pool_c.c_R"));
    lo = std::min(lo, p);
    hi = std::max(hi, p);
  }
  EXPECT_LT(hi / lo, 1.10) << lo << " .. " << hi;
  std::printf("uplift x c_R: %.3f .. %.3f mm\n", lo, hi);

  const CsvTable t = CsvTable::read((dir / "out" / "sobol.csv").string());
  std::map<std::string, Index> ix;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    EXPECT_EQ(t.integer(i, t.column("base_points")), static_cast<long long>(n));
    ix[std::string(t.text(i, t.column("metric"))) + "|" + std::string(t.text(i, t.column("parameter")))] = {
        t.number(i, t.column("s1")), t.number(i, t.column("s1_low")), t.number(i, t.column("s1_high")),
        t.number(i, t.column("st")), t.number(i, t.column("st_low")), t.number(i, t.column("st_high"))};
  }
  ASSERT_EQ(t.rows(), 9u);  // the three metrics with a spread (settlements are 0 in every member: no indices)
  for (const char* m : metrics) {
    const std::string k(m);
    const Index c = ix.at(k + "|material.pool_c.c_R"), a = ix.at(k + "|material.pool_a.c_R"),
                tol = ix.at(k + "|scenario.scale_tolerance");
    std::printf("%s: c_R(C) S1 %.7f ST %.4f [%.4f, %.4f]; c_R(A) S1 %.4f ST %.3g; tolerance S1 %.4f [%.4f, %.4f] ST %.3g [%.3g, %.3g]\n",
                m, c.s1, c.st, c.st_low, c.st_high, a.s1, a.st, tol.s1, tol.s1_low, tol.s1_high, tol.st, tol.st_low, tol.st_high);
    // No influence: ST = 1 - corr(y_A, y_E) with y_E = y_A bit for bit (E_tol repeats A's runs on this
    // machine, asserted above), so ST is 0 to the last bits of that correlation on any machine. Its
    // asymptotic interval is not: its half-width is 1.96 x the square root of a variance that is
    // itself made of round-off (~1e-16 in the members' metrics), of order 1e-8, and which value it
    // takes depends on the CPU's BLAS kernels, the compiler and the library builds (issue 39: 2.2e-9
    // on another machine). What holds everywhere: the interval contains 0 (to ST's own 1e-12) and is
    // orders of magnitude narrower than the c_R intervals (~1), here below 1e-6.
    EXPECT_LT(std::abs(tol.st), 1e-12) << m;
    EXPECT_LE(tol.st_low, tol.st) << m;
    EXPECT_GE(tol.st_high, tol.st) << m;
    EXPECT_LE(tol.st_low, 1e-12) << m;
    EXPECT_GE(tol.st_high, -1e-12) << m;
    EXPECT_LT(tol.st_high - tol.st_low, 1e-6) << m;
    EXPECT_LE(tol.s1_low, 0.0) << m;
    EXPECT_GE(tol.s1_high, 0.0) << m;
    // c_R of Pool C decides: S1 = 1 but for Pool A's share, ST's interval contains 1, and it has the largest ST.
    EXPECT_GT(c.s1, 0.998) << m;
    EXPECT_LE(c.st_low, 1.0) << m;
    EXPECT_GE(c.st_high, 1.0) << m;
    EXPECT_GT(c.st, std::max(a.st, tol.st) + 0.5) << m;
    // Pool A: ST below 1e-3 (its pressure returns to the same value; on the misfit's window it moves a little).
    EXPECT_LT(std::abs(a.st), 1e-3) << m;
  }
  // Where Pool A plays no part at all (the phase's uplift), the estimator's identity holds to 1e-3.
  for (const char* m : {"uplift_max_mm.storage", "ps_uplift_max_mm.storage"}) {
    const std::string k(m);
    EXPECT_NEAR(ix.at(k + "|scenario.scale_tolerance").s1 + ix.at(k + "|material.pool_c.c_R").st, 1.0, 1e-3) << m;
    EXPECT_LT(std::abs(ix.at(k + "|material.pool_a.c_R").st), 1e-5) << m;
  }

  // ugs-report's tornado chart from the Sobol' folder; the CSV it draws = sobol.csv's rows.
  const auto rep = test::run(test::tool("ugs-report") + " --thesis --results " + (dir / "truth.h5").string() + " --mesh " +
                             (dir / "model.msh").string() + " --case " + (dir / "case.toml").string() +
                             " --phase storage=2013-05-01/2013-11-01 --ensemble " + (dir / "out").string() + " --keep-work -o " +
                             (dir / "report").string());
  ASSERT_EQ(rep.exit_code, 0) << rep.err;
  EXPECT_GT(fs::file_size(dir / "report" / "ensemble_tornado_sobol.png"), 10000u);
  EXPECT_FALSE(fs::exists(dir / "report" / "ensemble_tornado_morris.png"));
  EXPECT_EQ(test::data_lines(dir / "report" / "work" / "ensemble_sobol.csv"), test::data_lines(dir / "out" / "sobol.csv"));
  EXPECT_NE(test::slurp(dir / "report" / "summary.html").find("40 of 40"), std::string::npos);
  if (!HasFailure() && !std::getenv("UGS_TEST_KEEP")) fs::remove_all(dir);
}
