// The two-parameter calibration twin with the real solver (solve_twin.hpp): c_R of Pool C (3)
// and of Pool A (5) recovered together by BOBYQA from other starting values. Long (two dozen
// solver runs): label bench-long.
#include <gtest/gtest.h>

#include <filesystem>

#include "solve_twin.hpp"
#include "ugs/formats/csv.hpp"

using namespace ugs;
namespace fs = std::filesystem;

TEST(SolveTwin, TwoParametersConverge) {
  if (!test::have_solver()) GTEST_SKIP() << "ugs-solve is not built";
  const fs::path dir = test::make_truth("solve-twin2");
  test::spit(dir / "start.toml", test::solve_box_case(4.5, 6.5));
  const auto r = test::run(test::tool("ugs-calibrate") + " --case " + (dir / "start.toml").string() + " --mesh " +
                           (dir / "model.msh").string() + " --param material.pool_c.c_R=2:6 --param material.pool_a.c_R=3:8" +
                           " --measured " + (dir / "up.csv").string() + " --window 2009-01-01/2014-12-31 --solver-command '" +
                           test::solver_command(dir) + "' -j 2 --xtol 0.01 -o " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("before converging"), std::string::npos) << r.err;
  const CsvTable t = CsvTable::read((dir / "out" / "parameters.csv").string());
  std::printf("recovered c_R(Pool C) = %.4f (truth 3), c_R(Pool A) = %.4f (truth 5)\n", t.number(0, t.column("best")),
              t.number(1, t.column("best")));
  EXPECT_NEAR(t.number(0, t.column("best")), 3.0, 0.3) << r.out;
  EXPECT_NEAR(t.number(1, t.column("best")), 5.0, 0.6) << r.out;
  if (!HasFailure() && !std::getenv("UGS_TEST_KEEP")) fs::remove_all(dir);
}
