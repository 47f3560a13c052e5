// mech_make_case — writes ugs-solve test cases: a box mesh (MSH), a case file and the
// pressure-change field series that ugs-flow would write for each pool (node field dp on the
// pool's sub-mesh, parent node and element tags). Used by tests/mechanics; the thesis-scale
// benchmark case has its own writer (bench/solve/make_thesis_case.cpp).
//
//   mech_make_case column DIR [--rule sigma-max]   V1 oedometer column, path 20-26-23-28-25 MPa
//   mech_make_case geertsma DIR [--refine F]       V2 disk reservoir (quarter domain, symmetry rollers)
//   mech_make_case small DIR [--refine F]           layered model, two pools, monthly across an inversion
//   mech_make_case caprock DIR --dp MPa --cohesion MPa --friction DEG --tensile MPa
//                                                   a box of seal rock under a uniform pressure change
//                                                   (oedometric: lateral rollers, bottom fixed), docs/caprock.md
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "ugs/formats/msh.hpp"
#include "ugs/meshing/box_mesh.hpp"
#include "case_toml.hpp"
#include "layered_model.hpp"
#include "pressure_files.hpp"

using namespace ugs;
using namespace ugs::testcase;
namespace fs = std::filesystem;

namespace {

// ---- V1 column --------------------------------------------------------------------------------
void make_column(const fs::path& dir, const std::string& rule) {
  const double d20 = 20.0 / 0.0126, H = 1.0;
  BoxMeshSpec spec;
  spec.x = {0, 1};
  spec.y = {0, 1};
  spec.z = linspace(-d20 - H / 2, -d20 + H / 2, 4);
  const Mesh m = make_box_mesh(spec);
  write_msh(m, (dir / "mesh.msh").string());
  CaseToml c("# V1: oedometer column, sigma'_v0 = 20 MPa at its centre (VERIFICATION.md)\n", Numbers::Decimal);
  c.initial_stress({}).material(hypoplastic("rock", 3));
  c.boundary({.fixed = {"bottom"}, .rollers = {"west", "east", "south", "north"}, .free = {"top"}});
  write_text(dir / "case.toml", c.table("solver", fmt::format("inversion_rule = \"{}\"\n", rule)).str());
  write_pressure(dir / "flow.h5", m,
                 uniform_series({"2000-01-01", "2001-01-01", "2002-01-01", "2003-01-01", "2004-01-01"},
                                {0, -6e6, -3e6, -8e6, -5e6}));
}

// ---- V2 Geertsma ------------------------------------------------------------------------------
void make_geertsma(const fs::path& dir, double refine) {
  // eta = D / R = 1: the reference values of VERIFICATION.md V2 are tabulated for it.
  const double D = 1500, R = 1500, h = 50, L = 10 * R, depth = 10 * D;
  // Plan: uniform inside 1.6 R, graded to 10 R. Vertical: the reservoir in 4 layers, graded away.
  const double hx = 100 / refine;
  std::vector<double> x = linspace(0, 1.6 * R, static_cast<int>(std::lround(1.6 * R / hx)));
  for (double v : graded(1.6 * R, L, hx * 1.3, 1.3)) if (v > x.back()) x.push_back(v);
  std::vector<double> z;
  const double top = -D + h / 2, bot = -D - h / 2, hz = h / std::max(2.0, std::round(4 * refine));
  for (double v : graded(0, depth - (-bot), hz * 1.25, 1.25)) z.push_back(bot - v);  // below, downwards
  std::reverse(z.begin(), z.end());
  z.pop_back();
  for (double v : linspace(bot, top, static_cast<int>(std::lround(h / hz)))) z.push_back(v);
  for (double v : graded(0, -top, hz * 1.25, 1.25)) if (v > 0) z.push_back(top + v);
  z.back() = 0.0;
  BoxMeshSpec spec;
  spec.x = x;
  spec.y = x;
  spec.z = z;
  spec.material = [&](const Point3& c) {
    return (std::hypot(c[0], c[1]) < R && c[2] < top && c[2] > bot) ? std::string("reservoir") : std::string("rock");
  };
  const Mesh m = make_box_mesh(spec);
  write_msh(m, (dir / "mesh.msh").string());
  CaseToml c(
      "# V2: Geertsma disk (D = R = 1500 m, h = 50 m, dp = -10 MPa, E = 10 GPa, nu = 0.25).\n"
      "# Quarter domain: rollers on the symmetry planes x = 0 (west) and y = 0 (south).\n");
  c.material(linear("rock", 10000, 0.25)).material(linear("reservoir", 10000, 0.25));
  c.boundary({.fixed = {"bottom", "east", "north"}, .rollers = {"west", "south"}, .free = {"top"}});
  write_text(dir / "case.toml", c.str());
  write_pressure(dir / "flow.h5", submesh(m, {"reservoir"}), uniform_series({"2000-01-01", "2001-01-01"}, {0.0, -10e6}));
  std::fprintf(stderr, "geertsma: %zu nodes, %zu tetrahedra\n", m.num_nodes(), m.count(ElementType::Tetrahedron));
}

// ---- a small layered model with two pools -----------------------------------------------------
void make_small(const fs::path& dir, double refine) {
  Layered L{3000, 2000, -1400, -1440, -1460, -1490, 700, 600, 1100};
  BoxMeshSpec spec;
  spec.x = linspace(0, L.lx, static_cast<int>(std::lround(12 * refine)));
  spec.y = linspace(0, L.ly, static_cast<int>(std::lround(8 * refine)));
  spec.z = {-2500, -2000, -1700, -1550, -1490, -1475, -1460, -1450, -1440, -1420, -1400, -1300, -1000, -500, 0};
  spec.material = [&](const Point3& c) { return material_of(L, c); };
  const Mesh m = make_box_mesh(spec);
  write_msh(m, (dir / "mesh.msh").string());
  CaseToml c = layered_case();
  c.pool({.name = "Pool A", .materials = {"pool_a"}, .aquifer_materials = {"aquifer_a"}, .schedule = "unused.csv"});
  write_text(dir / "case.toml", c.table("output", "dates = [\"1960-03-01\", \"1960-09-01\"]\n").str());
  // Monthly through the end of production and into the first cycle: load inversions.
  write_pools(dir, m, L, monthly(1959, 10, 1960, 9), 1950, 15e6);
  std::fprintf(stderr, "small: %zu nodes, %zu tetrahedra\n", m.num_nodes(), m.count(ElementType::Tetrahedron));
}

}  // namespace

// ---- Caprock: the closed form of tests/mechanics/test_caprock.cpp ---------------------------------
// A 200 m x 200 m x 100 m box of one linear-elastic seal (E 10 GPa, nu 0.25, Biot 1) at 900-1000 m
// depth, k0 0.7, every element under the same pressure change dp on 2001-01-01 (0 on 2000-01-01).
void make_caprock(const fs::path& dir, double dp_MPa, double cohesion, double friction, double tensile) {
  BoxMeshSpec spec;
  spec.x = linspace(0, 200, 2);
  spec.y = linspace(0, 200, 2);
  spec.z = linspace(-1000, -900, 4);
  spec.material = [](const Point3&) { return std::string("seal"); };
  const Mesh m = make_box_mesh(spec);
  write_msh(m, (dir / "mesh.msh").string());
  CaseToml c("# Caprock integrity: a box of seal rock, oedometric, uniform pressure change (docs/caprock.md)\n");
  c.initial_stress({.surface_elevation_m = 0, .k0 = 0.7}).material(linear("seal", 10000, 0.25));
  c.boundary({.fixed = {"bottom"}, .rollers = {"west", "east", "south", "north"}, .free = {"top"}});
  c.seal({.material = "seal", .cohesion_MPa = cohesion, .friction_deg = friction, .tensile_strength_MPa = tensile});
  c.table("scenario", "max_scale = 10\nscale_tolerance = 0.002\n");
  write_text(dir / "case.toml", c.str());
  write_pressure(dir / "flow.h5", m, uniform_series({"2000-01-01", "2001-01-01"}, {0.0, dp_MPa * 1e6}));
}

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: mech_make_case column|geertsma|small|caprock DIR [options]\n");
    return 2;
  }
  const std::string kind = argv[1];
  const fs::path dir = argv[2];
  fs::create_directories(dir);
  std::map<std::string, std::string> opt;
  for (int i = 3; i < argc; ++i) {
    std::string a = argv[i];
    if (i + 1 < argc) opt[a] = argv[++i];
  }
  try {
    if (kind == "column") make_column(dir, opt.count("--rule") ? opt["--rule"] : "sigma-max");
    else if (kind == "geertsma") make_geertsma(dir, opt.count("--refine") ? std::stod(opt["--refine"]) : 1.0);
    else if (kind == "small") make_small(dir, opt.count("--refine") ? std::stod(opt["--refine"]) : 1.0);
    else if (kind == "caprock")
      make_caprock(dir, std::stod(opt.at("--dp")), std::stod(opt.at("--cohesion")), std::stod(opt.at("--friction")),
                   std::stod(opt.at("--tensile")));
    else {
      std::fprintf(stderr, "mech_make_case: unknown kind '%s'\n", kind.c_str());
      return 2;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mech_make_case: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
