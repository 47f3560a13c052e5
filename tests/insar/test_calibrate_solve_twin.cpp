// Calibration twin with the real solver (solve_twin.hpp): ugs-calibrate, starting from c_R = 4.5,
// must recover c_R(Pool C) = 3 within +-0.3 from the noisy "measured" series of a ugs-solve run.
// ugs-report is then run on the truth run, as a user would.
#include <gtest/gtest.h>

#include <filesystem>

#include "solve_twin.hpp"
#include "ugs/formats/csv.hpp"

using namespace ugs;
namespace fs = std::filesystem;

TEST(SolveTwin, CrOfPoolCRecoveredWithinPointThree) {
  if (!test::have_solver()) GTEST_SKIP() << "ugs-solve is not built";
  const fs::path dir = test::make_truth("solve-twin1");
  test::spit(dir / "start.toml", test::solve_box_case(4.5, 5.0));
  const auto r = test::run(test::tool("ugs-calibrate") + " --case " + (dir / "start.toml").string() + " --mesh " +
                           (dir / "model.msh").string() + " --param material.pool_c.c_R=2:6 --measured " + (dir / "up.csv").string() +
                           " --window 2009-01-01/2014-12-31 --solver-command '" + test::solver_command(dir) + "' -j 2 --scan 3 --xtol 0.01 -o " +
                           (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable t = CsvTable::read((dir / "out" / "parameters.csv").string());
  const double best = t.number(0, t.column("best"));
  EXPECT_NEAR(best, 3.0, 0.3) << r.out;
  std::printf("recovered c_R(Pool C) = %.4f (truth 3)\n", best);
  const CsvTable pts = CsvTable::read((dir / "out" / "misfit_points.csv").string());
  EXPECT_NEAR(pts.numbers("rms_mm").back(), 1.5, 0.2);
  // The report on the truth run, with the solver's own top-surface file beside it.
  test::spit(dir / "sections.geojson", R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32632"}},"features":[{"type":"Feature","properties":{"name":"A-A"},
"geometry":{"type":"LineString","coordinates":[[677000,4952500],[686000,4952500]]}}]})");
  const auto rep = test::run(test::tool("ugs-report") + " --thesis --results " + (dir / "truth.h5").string() + " --mesh " +
                             (dir / "model.msh").string() + " --case " + (dir / "case.toml").string() + " --measured " +
                             (dir / "up.csv").string() + " --sections " + (dir / "sections.geojson").string() +
                             " --phase storage=2013-05-01/2013-11-01 --calibration " + (dir / "out").string() + " -o " +
                             (dir / "report").string());
  ASSERT_EQ(rep.exit_code, 0) << rep.err;
  for (const char* f : {"uz_storage.png", "uz_storage.tif", "sec_a_a_storage_sz.png", "series_up_c11.png", "calibration_profile.png",
                        "summary.html"})
    EXPECT_TRUE(fs::exists(dir / "report" / f)) << f;
  if (!HasFailure() && !std::getenv("UGS_TEST_KEEP")) fs::remove_all(dir);
}
