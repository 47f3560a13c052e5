// A dipping fault in a homogeneous block under the geostatic stress (issue 6): the layered mesh of
// ugs-mesh2d + ugs-meshgen with one 35-degree fault cut by ugs-meshgen, ugs-faultinsert, then
// ugs-solve with a linear material, k0 = 0.7 and no pressure change. Nothing moves, so the fault
// tractions ugs-solve reports must be the initial stress tensor sigma_0(z) (docs/case-file.md:
// sigma'_v = -(lithostatic - alpha hydrostatic) d, sigma'_h = k0 sigma'_v, minus alpha p_0)
// projected on the prescribed plane (from the faults file's dip and dip direction, not from the
// mesh), node pair by node pair, to 1e-6 relative: normal and shear tractions. Issue 21: the same
// case in the long form (k_Hmax = k_hmin = 0.7, Hmax_azimuth_deg = 40) gives the same output bytes,
// and k0 with k_Hmax is refused (exit 2, one line).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "case_toml.hpp"
#include "pressure_files.hpp"
#include "strata_toml.hpp"
#include "run_tool.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"

namespace fs = std::filesystem;
using namespace ugs;
using namespace ugs::test;

namespace {

constexpr double kDip = 35, kDipDir = 200;                  // degrees
constexpr double kLith = 0.0226e6, kHyd = 0.0100e6, kK0 = 0.7;  // Pa/m
constexpr double kSurface = 0;
constexpr double kTrace[2][2] = {{900, 2700}, {3100, 2500}};  // as in kFaults; not perpendicular to the dip direction

const std::string kStrata = testcase::StrataToml("crs = \"EPSG:32632\"\nfaults = \"faults.geojson\"\n", testcase::Layout::Compact)
                                .surface({.name = "Ground", .constant = 0})
                                .surface({.name = "Bottom", .constant = -2000})
                                .unit({.name = "Block", .layers = 10})
                                .material({.name = "rock", .units = {"Block"}})
                                .str();

// Trace at -200 m; at -1,400 m the plane has moved 1,714 m toward 200 degrees (south-south-west).
const char* kFaults = R"({"type": "FeatureCollection",
"crs": { "type": "name", "properties": { "name": "urn:ogc:def:crs:EPSG::32632" } },
"features": [{ "type": "Feature",
  "properties": { "name": "F", "top_m": -200, "bottom_m": -1400, "dip_deg": 35, "dip_dir_deg": 200 },
  "geometry": { "type": "LineString", "coordinates": [[900, 2700], [3100, 2500]] } }]}
)";

const std::string kCase = testcase::CaseToml()
                              .initial_stress({.surface_elevation_m = kSurface, .k0 = kK0})
                              .material(testcase::linear("rock", 10000, 0.25))
                              .boundary(testcase::fixed_sides())
                              .fault({"F", 1, 35})
                              .table("solver", "linear_solver = \"mumps\"\n")
                              .str();

TEST(DippingFaultSolve, TractionsEqualTheInitialStressProjectedOnThePlane) {
  const fs::path dir = temp_dir("dipping-fault-solve");
  std::ofstream(dir / "strata.toml") << kStrata;
  std::ofstream(dir / "faults.geojson") << kFaults;
  std::ofstream(dir / "case.toml") << kCase;
  const std::string cd = "cd " + dir.string() + " && ";
  auto r = run(cd + tool("ugs-mesh2d") + " --box 0/4000/0/3000 --hmax 400 -q -o plan.msh");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run(cd + tool("ugs-meshgen") + " plan.msh --strata strata.toml -o model.msh");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_NE(r.err.find("fault:F"), std::string::npos) << r.err;
  r = run(cd + tool("ugs-faultinsert") + " model.msh --faults faults.geojson -o faulted.msh");
  ASSERT_EQ(r.exit_code, 0) << r.err;

  // No pressure change: dp = 0 at two dates.
  const Mesh faulted = read_msh((dir / "faulted.msh").string());
  testcase::write_pressure(dir / "flow.h5", testcase::tetrahedra_of(faulted),
                           testcase::uniform_series({"2000-01-01", "2001-01-01"}, {0.0, 0.0}));
  r = run(cd + tool("ugs-solve") + " faulted.msh --case case.toml --pressure flow.h5 --solver mumps -o out.h5");
  ASSERT_EQ(r.exit_code, 0) << r.err;

  FieldSeriesReader faults((dir / "out_faults.h5").string());
  ASSERT_EQ(faults.steps().size(), 2u);
  const auto X = faults.coordinates();
  ASSERT_GT(X.size(), 100u);
  // The prescribed plane (docs/dipping-faults.md): the trace swept along w = the dip direction
  // descending at the dip. Its unit normal from side 1 (hanging wall) to side 2: down, against the
  // dip direction.
  const double d = kDip * M_PI / 180, az = kDipDir * M_PI / 180;
  const std::array<double, 3> e{kTrace[1][0] - kTrace[0][0], kTrace[1][1] - kTrace[0][1], 0};
  const std::array<double, 3> w{std::sin(az) * std::cos(d), std::cos(az) * std::cos(d), -std::sin(d)};
  std::array<double, 3> n{e[1] * w[2] - e[2] * w[1], e[2] * w[0] - e[0] * w[2], e[0] * w[1] - e[1] * w[0]};
  const double ln = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const double sign = n[2] > 0 ? -1.0 : 1.0;
  for (auto& c : n) c *= sign / ln;
  for (std::size_t step = 0; step < 2; ++step) {
    const Field t = faults.node_field(step, "traction"), sn = faults.node_field(step, "sigma_n"),
                tau = faults.node_field(step, "tau"), interp = faults.node_field(step, "interpolated");
    ASSERT_EQ(sn.count(), X.size());
    double worst_n = 0, worst_t = 0, worst_vec = 0;
    std::size_t checked = 0;
    for (std::size_t i = 0; i < X.size(); ++i) {
      if (interp.values[i] != 0) continue;  // tips and pairs on fixed boundaries: means of neighbours
      const double depth = kSurface - X[i][2];
      const double p0 = kHyd * depth, sv = -(kLith - kHyd) * depth, sh = kK0 * sv;
      const double s[3] = {sh - p0, sh - p0, sv - p0};  // principal: x, y horizontal; z vertical
      const std::array<double, 3> expect{s[0] * n[0], s[1] * n[1], s[2] * n[2]};
      const double en = expect[0] * n[0] + expect[1] * n[1] + expect[2] * n[2];
      const std::array<double, 3> etau{expect[0] - en * n[0], expect[1] - en * n[1], expect[2] - en * n[2]};
      const double scale = std::sqrt(expect[0] * expect[0] + expect[1] * expect[1] + expect[2] * expect[2]);
      worst_n = std::max(worst_n, std::abs(sn.values[i] - en) / scale);
      for (int k = 0; k < 3; ++k) {
        worst_t = std::max(worst_t, std::abs(tau.values[3 * i + k] - etau[k]) / scale);
        worst_vec = std::max(worst_vec, std::abs(t.values[3 * i + k] - expect[k]) / scale);
      }
      ++checked;
    }
    std::printf("step %zu: %zu of %zu node pairs, max relative error: sigma_n %.2e, tau %.2e, traction %.2e\n", step, checked,
                X.size(), worst_n, worst_t, worst_vec);
    EXPECT_GT(checked, X.size() / 2);
    EXPECT_LE(worst_n, 1e-6);
    EXPECT_LE(worst_t, 1e-6);
    EXPECT_LE(worst_vec, 1e-6);
  }

  // Issue 21: k0 is the shorthand for k_Hmax = k_hmin = k0 (whatever the azimuth): the same case
  // written in the long form gives the same bytes in every output file.
  std::string long_form = kCase;
  long_form.replace(long_form.find("k0 = 0.7"), 8, "k_Hmax = 0.7\nk_hmin = 0.7\nHmax_azimuth_deg = 40");
  std::ofstream(dir / "case_long.toml") << long_form;
  fs::create_directories(dir / "long");  // same output names (the .xdmf names its .h5)
  r = run(cd + tool("ugs-solve") + " faulted.msh --case case_long.toml --pressure flow.h5 --solver mumps -o long/out.h5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::size_t compared = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("out", 0) != 0) continue;
    const fs::path other = dir / "long" / name;
    ASSERT_TRUE(fs::exists(other)) << other;
    // The tables' comment lines name the command (another case file); the data must match.
    auto data = [](const fs::path& p) {
      std::string all = slurp(p), kept;
      if (p.extension() != ".csv") return all;
      std::istringstream in(all);
      for (std::string line; std::getline(in, line);)
        if (line.rfind("#", 0) != 0) kept += line + "\n";
      return kept;
    };
    EXPECT_EQ(data(entry.path()), data(other)) << name << " differs";
    ++compared;
  }
  EXPECT_GE(compared, 2u);  // out.h5, out_faults.h5 and the tables

  // Both forms at once: exit 2, one line naming the file, line, key and value.
  std::string both = kCase;
  both.replace(both.find("k0 = 0.7"), 8, "k0 = 0.7\nk_Hmax = 1.3");
  std::ofstream(dir / "case_both.toml") << both;
  r = run(cd + tool("ugs-solve") + " faulted.msh --case case_both.toml --pressure flow.h5 --solver mumps -o both.h5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "ugs-solve: error: case_both.toml:6: 'initial_stress.k_Hmax': 1.3 given together with k0 = 0.7 (k0 is the "
                   "shorthand for k_Hmax = k_hmin; give one form)\n");
  EXPECT_FALSE(fs::exists(dir / "both.h5"));
  fs::remove_all(dir);
}

}  // namespace
