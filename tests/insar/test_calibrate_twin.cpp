// Calibration twins with a closed-form stand-in solver (geertsma_evaluator: two disk pools in a
// half-space, hypo-plastic compaction with c_R from the case): "measured" series generated with
// c_R(Pool C) = 3 (and c_R(Pool A) = 5) plus 1.5 mm Gaussian noise must be recovered by
// ugs-calibrate through its whole machinery — case copies, subprocess runs, in-process sampling,
// the cache, concurrent evaluations, Brent and BOBYQA.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "run_tool.hpp"
#include "twin_data.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/runner/case_params.hpp"
#include "ugs/runner/subprocess.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

const std::string kEvaluator = std::string(UGS_BINARY_DIR) + "/tests/insar/geertsma_evaluator";

std::string case_text(double crc, double cra) {
  return fmt::format(R"(# twin case for the calibration tests
crs = "EPSG:32632"

[[material]]
name = "surrounding_rock"
law = "elastic"

[[material]]
name = "pool_c"
law = "hypoplastic"
c_R = {}   # the truth is 3

[[material]]
name = "pool_a"
law = "hypoplastic"
c_R = {}   # the truth is 5
)",
                     runner::toml_float(crc), runner::toml_float(cra));
}

const std::vector<test::TwinPoint> kPoints = {
    {"C1", 681500, 4952300}, {"C2", 682300, 4951900}, {"C3", 680900, 4952900}, {"A1", 678000, 4953500},
    {"A2", 677200, 4954000}, {"A3", 678600, 4952800}, {"OUT1", 686500, 4948000}, {"OUT2", 675000, 4958000}};

struct Twin {
  fs::path dir;
};

// Truth run, then the measured files.
Twin make_twin(const std::string& tag) {
  Twin t{test::temp_dir(tag)};
  test::spit(t.dir / "truth.toml", case_text(3.0, 5.0));
  const auto r = test::run(kEvaluator + " --case " + (t.dir / "truth.toml").string() + " -o " + (t.dir / "truth.h5").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto dates = test::monthly_dates(2003, 10, 2021, 10);
  test::write_twin_egms((t.dir / "truth.h5").string(), kPoints, dates, 2, 1.5, 1948, (t.dir / "up.csv").string());
  test::write_twin_egms((t.dir / "truth.h5").string(), kPoints, dates, 0, 1.5, 2015, (t.dir / "east.csv").string());
  return t;
}

std::vector<double> best_values(const fs::path& out) {
  const CsvTable t = CsvTable::read((out / "parameters.csv").string());
  return t.numbers("best");
}

std::string calibrate(const Twin& t, const std::string& params, const std::string& out, const std::string& extra = "") {
  return test::tool("ugs-calibrate") + " --case " + (t.dir / "case.toml").string() + " " + params + " --measured " +
         (t.dir / "up.csv").string() + " --window 2003-01-01/2021-12-31 --solver-command '" + kEvaluator +
         " --case {case} -o {out}' --cache-dir " + (t.dir / "cache").string() + " -o " + (t.dir / out).string() + " " +
         extra;
}

}  // namespace

TEST(CalibrationTwin, OneParameterRecoversCrOfPoolC) {
  const Twin t = make_twin("twin1");
  test::spit(t.dir / "case.toml", case_text(4.5, 5.0));
  const auto r = test::run("UGS_TEST_EVALUATOR_SLEEP=0.3 " + calibrate(t, "--param material.pool_c.c_R=2:6", "out", "-j 2"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto best = best_values(t.dir / "out");
  ASSERT_EQ(best.size(), 1u);
  EXPECT_NEAR(best[0], 3.0, 0.3) << r.out;
  std::printf("recovered c_R(Pool C) = %.4f (truth 3)\n", best[0]);
  // At the optimum the misfit is the noise: 1.5 mm.
  const CsvTable pts = CsvTable::read((t.dir / "out" / "misfit_points.csv").string());
  const auto rms = pts.numbers("rms_mm");
  EXPECT_NEAR(rms.back(), 1.5, 0.15);
  // The profile: the scan's five values, then Brent; every evaluation once.
  const CsvTable prof = CsvTable::read((t.dir / "out" / "profile.csv").string());
  std::size_t scan = 0, fresh = 0;
  for (std::size_t i = 0; i < prof.rows(); ++i) {
    scan += prof.text(i, prof.column("phase")) == "scan";
    fresh += prof.text(i, prof.column("cached")) == "0";
  }
  EXPECT_EQ(scan, 5u);
  EXPECT_GE(prof.rows(), 8u);
  EXPECT_LE(prof.rows(), 30u);
  // -j 2: the scan's solver runs overlapped in time (their logs hold start and end).
  std::vector<std::pair<long long, long long>> spans;
  for (const auto& e : fs::directory_iterator(t.dir / "cache")) {
    if (e.path().filename().string().rfind("eval-", 0) != 0) continue;
    const std::string log = test::slurp(e.path() / "solver.log");
    long long a = 0, b = 0;
    std::sscanf(log.c_str() + log.find("start_ms"), "start_ms %lld", &a);
    std::sscanf(log.c_str() + log.find("end_ms"), "end_ms %lld", &b);
    spans.emplace_back(a, b);
  }
  EXPECT_EQ(spans.size(), fresh);
  bool overlap = false;
  for (std::size_t i = 0; i < spans.size(); ++i)
    for (std::size_t j = i + 1; j < spans.size(); ++j)
      overlap = overlap || (spans[i].first < spans[j].second && spans[j].first < spans[i].second);
  EXPECT_TRUE(overlap) << "no two evaluations ran at the same time with -j 2";
  EXPECT_TRUE(fs::exists(t.dir / "cache" / "index.csv"));
  EXPECT_TRUE(fs::exists(t.dir / "out" / "best.toml"));
  EXPECT_TRUE(fs::exists(t.dir / "out" / "best_samples.csv"));

  // The same calibration again: every evaluation comes from the cache, same answer.
  const auto again = test::run(calibrate(t, "--param material.pool_c.c_R=2:6", "out2", "-j 2"));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const CsvTable prof2 = CsvTable::read((t.dir / "out2" / "profile.csv").string());
  for (std::size_t i = 0; i < prof2.rows(); ++i) EXPECT_EQ(prof2.text(i, prof2.column("cached")), "1");
  EXPECT_EQ(best_values(t.dir / "out2"), best);

  // Relative paths, as Make passes them: the solver runs inside its evaluation folder, so {case},
  // {out} and {dir} must not be relative to the caller's folder.
  const auto rel = test::run("cd " + t.dir.string() + " && " + test::tool("ugs-calibrate") +
                             " --case case.toml --param material.pool_c.c_R=2:6 --measured up.csv"
                             " --window 2003-01-01/2021-12-31 --solver-command '" + kEvaluator +
                             " --case {case} -o {out}' --cache-dir rel/cache --scan 3 --max-evals 3 -o rel/out");
  ASSERT_EQ(rel.exit_code, 0) << rel.err;
  EXPECT_TRUE(fs::exists(t.dir / "rel" / "out" / "best.toml"));
  EXPECT_EQ(CsvTable::read((t.dir / "rel" / "out" / "profile.csv").string()).rows(), 3u);
  if (!HasFailure() && !std::getenv("UGS_TEST_KEEP")) fs::remove_all(t.dir);
}

// --response reciprocal on the same twin: Pool C's cycles stay below its preconsolidation stress
// over the window, so its compaction there is c_M / c_R times the stress change and the series are
// affine in 1 / c_R: the model is exact, and three runs and one check find the misfit's minimum,
// which the scan + Brent of the general method approaches within its xtol (0.005 of the range).
TEST(CalibrationTwin, ReciprocalResponseRecoversCrInFourRuns) {
  const Twin t = make_twin("twin-recip");
  test::spit(t.dir / "case.toml", case_text(4.5, 5.0));
  const auto r = test::run(calibrate(t, "--param material.pool_c.c_R=2:6", "out", "-j 2 --response reciprocal"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("best (reciprocal response, model minimum checked by one run: RMS ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("; 4 evaluations, 4 solver runs (0 from the cache); "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("reciprocal response model: runs at material.pool_c.c_R = 2, 3, 6: RMS "), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  const auto best = best_values(t.dir / "out");
  ASSERT_EQ(best.size(), 1u);
  EXPECT_NEAR(best[0], 3.0, 0.3) << r.out;
  const CsvTable prof = CsvTable::read((t.dir / "out" / "profile.csv").string());
  ASSERT_EQ(prof.rows(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(prof.text(i, prof.column("phase")), i < 3 ? "reciprocal" : "check");
    EXPECT_EQ(prof.text(i, prof.column("cached")), "0");
  }
  // The check is the best evaluation, and the model predicted its misfit (an exact model).
  const auto rms = prof.numbers("rms_mm");
  EXPECT_EQ(*std::min_element(rms.begin(), rms.end()), rms[3]);
  EXPECT_EQ(prof.number(3, prof.column("material.pool_c.c_R")), best[0]);
  const auto check = r.out.find("check run: RMS ");
  ASSERT_NE(check, std::string::npos) << r.out;
  const auto diff = r.out.find("(check - predicted = ", check);
  ASSERT_NE(diff, std::string::npos) << r.out;
  EXPECT_LT(std::abs(std::stod(r.out.substr(diff + 21))), 1e-6) << r.out;
  EXPECT_NE(test::slurp(t.dir / "out" / "parameters.csv").find("reciprocal response; model minimum checked"), std::string::npos);
  EXPECT_NE(test::slurp(t.dir / "out" / "best.toml").find("; reciprocal response)"), std::string::npos);
  EXPECT_EQ(CsvTable::read((t.dir / "out" / "model_profile.csv").string()).rows(), 41u);
  std::printf("recovered c_R(Pool C) = %.4f (truth 3) in 4 solver runs\n", best[0]);

  // The general method on the same cache (its scan's bounds come from it): Brent's answer within
  // its tolerance of the model's, and no better.
  const auto g = test::run(calibrate(t, "--param material.pool_c.c_R=2:6", "general", "-j 2"));
  ASSERT_EQ(g.exit_code, 0) << g.err;
  const auto brent = best_values(t.dir / "general");
  EXPECT_NEAR(brent[0], best[0], 0.005 * 4) << g.out;
  const auto g_rms = CsvTable::read((t.dir / "general" / "profile.csv").string()).numbers("rms_mm");
  EXPECT_GE(*std::min_element(g_rms.begin(), g_rms.end()), rms[3] - 1e-9);
  std::printf("scan + Brent: c_R(Pool C) = %.4f in %zu evaluations\n", brent[0], g_rms.size());
  if (!HasFailure() && !std::getenv("UGS_TEST_KEEP")) fs::remove_all(t.dir);
}

TEST(CalibrationTwin, TwoParametersConverge) {
  const Twin t = make_twin("twin2");
  test::spit(t.dir / "case.toml", case_text(4.5, 6.5));
  const auto r = test::run(calibrate(t, "--param material.pool_c.c_R=2:6 --param material.pool_a.c_R=3:8", "out",
                                     "-j 2 --measured-east " + (t.dir / "east.csv").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("BOBYQA"), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("before converging"), std::string::npos) << r.err;
  const auto best = best_values(t.dir / "out");
  ASSERT_EQ(best.size(), 2u);
  EXPECT_NEAR(best[0], 3.0, 0.3) << r.out;
  EXPECT_NEAR(best[1], 5.0, 0.5) << r.out;
  std::printf("recovered c_R(Pool C) = %.4f (truth 3), c_R(Pool A) = %.4f (truth 5)\n", best[0], best[1]);
  if (!HasFailure() && !std::getenv("UGS_TEST_KEEP")) fs::remove_all(t.dir);
}
