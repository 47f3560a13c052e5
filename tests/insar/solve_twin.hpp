// The truth run of the ugs-solve calibration twins: ugs-solve on the two-pool box model
// (solve_box.hpp) with c_R(Pool C) = 3 and c_R(Pool A) = 5, and the "measured" series: its
// top-surface displacement at 11 PS points (9 over Pool C, one over Pool A, one outside), at the
// solver's dates from 2009, plus 1.5 mm Gaussian noise, in the EGMS layout.
#pragma once
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "run_tool.hpp"
#include "solve_box.hpp"
#include "twin_data.hpp"

namespace ugs::test {

inline std::string solver_command(const std::filesystem::path& dir) {
  return tool("ugs-solve") + " {mesh} --case {case} --pressure " + (dir / "dp_c.h5").string() + " --pressure " +
         (dir / "dp_a.h5").string() + " --top {out} -o {dir}/solve.h5 --solver cholmod -q";
}

// Truth run and measured series; returns the folder.
inline std::filesystem::path make_truth(const std::string& tag) {
  const std::filesystem::path dir = temp_dir(tag);
  write_solve_box(dir, 3.0, 5.0);
  const auto r = run(tool("ugs-solve") + " " + (dir / "model.msh").string() + " --case " + (dir / "case.toml").string() +
                     " --pressure " + (dir / "dp_c.h5").string() + " --pressure " + (dir / "dp_a.h5").string() + " -o " +
                     (dir / "truth.h5").string() + " --solver cholmod -q");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::vector<TwinPoint> pts;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j) pts.push_back({fmt::format("C{}{}", i + 1, j + 1), kPoolXc + 900.0 * i, kPoolYc + 900.0 * j});
  pts.push_back({"A1", kPoolAXc, kPoolAYc});
  pts.push_back({"OUT", 685500, 4949500});
  std::vector<std::int64_t> dates;
  for (auto t : solve_box_dates())
    if (t >= days_from_civil(2009, 1, 1) * 86400) dates.push_back(t);
  write_twin_egms((dir / "truth_top.h5").string(), pts, dates, 2, 1.5, 1948, (dir / "up.csv").string());
  // East-west series of the nine Pool C points only (a misfit adds them where they exist).
  write_twin_egms((dir / "truth_top.h5").string(), std::vector<TwinPoint>(pts.begin(), pts.begin() + 9), dates, 0, 1.5, 2015,
                  (dir / "east.csv").string());
  return dir;
}

inline bool have_solver() { return std::filesystem::exists(tool("ugs-solve")); }

}  // namespace ugs::test
