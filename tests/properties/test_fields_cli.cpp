// ugs-flow and ugs-solve with constants that vary in space, end to end: two layers given as one
// material whose constants are fields (tables by elevation stepping at the layer boundary) give the
// results of the same layers given as two materials, to round-off; and a field that does not cover
// the model is bad input (exit 2, one line, nothing written).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "case_toml.hpp"
#include "run_tool.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/box_mesh.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

// The layers: below z = -1520 "low", above "up"; the pool is the corner column x < 1000, y < 1000.
struct Layer {
  double nu, biot, cm_a, porosity, c_R;
  std::array<double, 3> K;
};
const Layer kLow{0.25, 0.9, 1.2e-2, 0.25, 2.0, {2e-6, 2e-6, 2e-7}};
const Layer kUp{0.3, 0.8, 0.8e-2, 0.15, 4.0, {5e-7, 5e-7, 5e-8}};

// Rows of a table by elevation that is the low layer's value below -1520 m and the up layer's
// above (no centroid lies within 2.5 m of the boundary: the values are the layers', exactly).
std::string step_table(double low, double up) {
  return fmt::format("{{ elevation_table = [[-1540, {0}], [-1520.01, {0}], [-1519.99, {1}], [-1500, {1}]] }}", low, up);
}

std::string head() {
  return "[model]\nstart = \"2000-01-01\"\nend = \"2001-01-01\"\n\n[initial_stress]\nsurface_elevation_m = 0.0\n\n"
         "[boundary]\nfixed = [\"bottom\"]\nrollers = [\"west\", \"east\", \"south\", \"north\"]\n\n"
         // A direct solver: the two runs differ in the order of the elements, not in an iterative
         // solver's path, so what is left is the round-off of the sums.
         "[solver]\nlinear_solver = \"cholmod\"\n\n";
}

std::string aquifer_lines(const Layer& l) {
  return fmt::format("law = \"elastic\"\nnu = {}\nbiot = {}\ncm_a = {}\nporosity = {}\nK_m_per_s = [{}, {}, {}]\n", l.nu, l.biot, l.cm_a,
                     l.porosity, l.K[0], l.K[1], l.K[2]);
}

std::string layers_case() {
  testcase::CaseToml c(head());
  c.material({.name = "pool_low", .law = "hypoplastic", .c_R = kLow.c_R, .more = "K_m_per_s = [1e-6, 1e-6, 1e-7]\nporosity = 0.2\n"});
  c.material({.name = "pool_up", .law = "hypoplastic", .c_R = kUp.c_R, .more = "K_m_per_s = [1e-6, 1e-6, 1e-7]\nporosity = 0.2\n"});
  c.material({.name = "aq_low", .more = aquifer_lines(kLow)});
  c.material({.name = "aq_up", .more = aquifer_lines(kUp)});
  c.pool({.name = "P", .materials = {"pool_low", "pool_up"}, .aquifer_materials = {"aq_low", "aq_up"}, .schedule = "pool.csv"});
  return c.str();
}

std::string field_case() {
  testcase::CaseToml c(head());
  c.material({.name = "pool", .law = "hypoplastic",
              .more = "c_R = " + step_table(kLow.c_R, kUp.c_R) + "\nK_m_per_s = [1e-6, 1e-6, 1e-7]\nporosity = 0.2\n"});
  std::string aq = "law = \"elastic\"\n";
  aq += "nu = " + step_table(kLow.nu, kUp.nu) + "\n";
  aq += "biot = " + step_table(kLow.biot, kUp.biot) + "\n";
  aq += "cm_a = " + step_table(kLow.cm_a, kUp.cm_a) + "\n";
  aq += "porosity = " + step_table(kLow.porosity, kUp.porosity) + "\n";
  aq += "K_m_per_s = [" + step_table(kLow.K[0], kUp.K[0]) + ", " + step_table(kLow.K[1], kUp.K[1]) + ", " +
        step_table(kLow.K[2], kUp.K[2]) + "]\n";
  c.material({.name = "aq", .more = aq});
  c.pool({.name = "P", .materials = {"pool"}, .aquifer_materials = {"aq"}, .schedule = "pool.csv"});
  return c.str();
}

void write_case(const fs::path& dir, bool layers) {
  BoxMeshSpec s;
  s.x = linspace(0, 3000, 6);
  s.y = linspace(0, 2000, 4);
  s.z = linspace(-1540, -1500, 4);
  s.material = [layers](const Point3& p) {
    const bool pool = p[0] < 1000 && p[1] < 1000, low = p[2] < -1520;
    if (!layers) return std::string(pool ? "pool" : "aq");
    return std::string(pool ? (low ? "pool_low" : "pool_up") : (low ? "aq_low" : "aq_up"));
  };
  write_msh(make_box_mesh(s), (dir / "mesh.msh").string());
  test::spit(dir / "case.toml", layers ? layers_case() : field_case());
  // Monthly over a year: depletion, then recharge past the start (the pool's c_R in use).
  std::string rows = "date,p_MPa\n";
  for (int m = 0; m <= 12; ++m)
    rows += fmt::format("{}-{:02d}-01,{:.3f}\n", 2000 + m / 12, m % 12 + 1, 15.0 - 3.0 * std::sin(m * 0.5));
  test::spit(dir / "pool.csv", rows);
}

std::string run_chain(const fs::path& dir) {
  const std::string cd = "cd " + dir.string() + " && ";
  const auto f = test::run(cd + test::tool("ugs-flow") + " mesh.msh --case case.toml -o dp.h5 -q");
  if (f.exit_code != 0) return "ugs-flow: " + f.err;
  const auto s = test::run(cd + test::tool("ugs-solve") + " mesh.msh --case case.toml --pressure dp.h5 -o solve.h5 -q");
  if (s.exit_code != 0) return "ugs-solve: " + s.err;
  return "";
}

// The largest difference of a node field over every step of two files, and the largest value.
std::pair<double, double> node_difference(const std::string& a, const std::string& b, const std::string& name) {
  const FieldSeriesReader ra(a), rb(b);
  EXPECT_EQ(ra.steps().size(), rb.steps().size());
  double diff = 0, size = 0;
  for (std::size_t s = 0; s < std::min(ra.steps().size(), rb.steps().size()); ++s) {
    const Field fa = ra.node_field(s, name), fb = rb.node_field(s, name);
    EXPECT_EQ(fa.values.size(), fb.values.size());
    for (std::size_t k = 0; k < std::min(fa.values.size(), fb.values.size()); ++k) {
      diff = std::max(diff, std::abs(fa.values[k] - fb.values[k]));
      size = std::max(size, std::abs(fa.values[k]));
    }
  }
  return {diff, size};
}

}  // namespace

TEST(FieldsCli, LayeredFieldEqualsTheLayersAsMaterials) {
  test::TempDir layers("fields-layers"), field("fields-field");
  write_case(layers.path, true);
  write_case(field.path, false);
  ASSERT_EQ(run_chain(layers.path), "");
  ASSERT_EQ(run_chain(field.path), "");
  // The node order of the two meshes is the same (box meshes differ only in their groups).
  const auto [dp, dp_max] = node_difference(layers / "dp.h5", field / "dp.h5", "dp");
  EXPECT_GT(dp_max, 1e5);                  // the aquifer's pressure did change
  EXPECT_LE(dp, 1e-9 * dp_max) << dp;      // round-off of the conductance sums' order
  const auto [u, u_max] = node_difference(layers / "solve.h5", field / "solve.h5", "u");
  EXPECT_GT(u_max, 1e-4);
  EXPECT_LE(u, 1e-9 * u_max) << u;
  std::printf("layered field against two materials: dp %.3g Pa of %.3g Pa, displacement %.3g m of %.3g m\n", dp, dp_max, u, u_max);
}

TEST(FieldsCli, FieldNotCoveringTheModelIsBadInput) {
  test::TempDir d("fields-bad");
  write_case(d.path, false);
  ASSERT_EQ(run_chain(d.path), "");
  fs::remove(d.path / "solve.h5"), fs::remove(d.path / "solve.xdmf");
  // The c_R table stops at -1530 m: the pool's lowest tetrahedra lie below it.
  std::string text = test::slurp(d / "case.toml");
  const std::string from = "c_R = { elevation_table = [[-1540, 2]";
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << text;
  text.replace(at, from.size(), "c_R = { elevation_table = [[-1530, 2]");
  test::spit(d / "case.toml", text);
  for (const std::string tool : {"ugs-flow", "ugs-solve"}) {
    const auto r = test::run("cd " + d.path.string() + " && " + test::tool(tool) + " mesh.msh --case case.toml" +
                             (tool == "ugs-solve" ? " --pressure dp.h5" : "") + " -o out.h5");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind(tool + ": error: case.toml:", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("material 'pool' c_R: tetrahedron"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("lies outside the field's source table (rows cover -1530 .. -1500 m elevation)"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(d.path / "out.h5"));
  }
}
