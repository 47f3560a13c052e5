// The box model of the calibration twins (tests/insar/solve_twin.hpp) as an ugs-ensemble case: the
// case with a [scenario] section (scale_tolerance: read by the case, unused by a run without
// --find-safe-scale), the ugs-ensemble command line on it, and a table's data lines.
#pragma once
#include <filesystem>
#include <sstream>
#include <string>

#include "solve_twin.hpp"

namespace ugs::test {

// An [[parameter]] entry, uniform on [lower, upper].
inline std::string uniform_parameter(const std::string& path, double lower, double upper) {
  return fmt::format("\n[[parameter]]\npath = \"{}\"\ndistribution = \"uniform\"\nlower = {}\nupper = {}\n", path,
                     testcase::toml_number(lower, testcase::Numbers::Decimal),
                     testcase::toml_number(upper, testcase::Numbers::Decimal));
}
// Parameters of the box: c_R of Pool C (decides the storage uplift), c_R of Pool A (its pressure is
// the same on both dates of the storage phase), scale_tolerance (unused without a safe-scale search).
inline const std::string kParamPoolC = uniform_parameter("material.pool_c.c_R", 2.0, 6.0);
inline const std::string kParamPoolA = uniform_parameter("material.pool_a.c_R", 3.0, 7.0);
inline const std::string kParamTolerance = uniform_parameter("scenario.scale_tolerance", 0.005, 0.05);

inline std::filesystem::path make_ensemble_box(const std::string& tag) {
  const std::filesystem::path dir = make_truth(tag);  // the box, a truth run and its noisy PS series up.csv
  spit(dir / "case.toml", slurp(dir / "case.toml") + "\n[scenario]\nscale_tolerance = 0.01\n");
  return dir;
}

// ugs-ensemble MODE on the box with ugs-solve, the storage phase of 2013 and the PS series.
inline std::string ensemble_cmd(const std::filesystem::path& dir, const std::string& mode, const std::string& spec,
                                const std::string& extra) {
  return tool("ugs-ensemble") + " " + mode + " --spec " + (dir / spec).string() + " --case " + (dir / "case.toml").string() +
         " --mesh " + (dir / "model.msh").string() + " --solver-command '" + solver_command(dir) +
         "' --phase storage=2013-05-01/2013-11-01 --measured " + (dir / "up.csv").string() +
         " --window 2009-01-01/2014-12-31 " + extra;
}

// The table's data lines (comments, which hold the command line, left out).
inline std::string data_lines(const std::filesystem::path& p) {
  std::string out, line;
  std::istringstream in(slurp(p));
  while (std::getline(in, line))
    if (line.empty() || line[0] != '#') out += line + "\n";
  return out;
}

}  // namespace ugs::test
