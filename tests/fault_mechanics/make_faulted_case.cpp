// contact_make_case — writes a small faulted ugs-solve case for the tool tests: a box of 50 m
// cells (1000 x 600 x 1000 m) with a fault F dipping 45 degrees (fault_meshes.hpp) inserted by the
// ugs-faultinsert library, a reservoir block crossed by the fault, the case file and the pressure
// change that ugs-flow would write for the reservoir (node field dp on its sub-mesh, which holds the
// fault's twin nodes, with parent node and element tags).
//
//   contact_make_case DIR [--dp MPa] [--friction DEG] [--cohesion MPa] [--cell M] [--extra TOML] [--months N]
//
// --extra is appended to the [solver] table ("\n" separates lines).
// Dates: 2000-01-01 (dp = 0, the reference of the scenario) and 2001-01-01 (dp); with --months N,
// N + 1 monthly dates from 2000-01-01 with dp sin(2 pi k / 12) (a storage cycle: a low in October).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "fault_meshes.hpp"
#include "ugs/formats/msh.hpp"
#include "case_toml.hpp"
#include "dir_argument.hpp"
#include "pressure_files.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

bool in_reservoir(const Point3& c) { return c[0] > 350 && c[0] < 850 && c[1] > 150 && c[1] < 450 && c[2] > -600 && c[2] < -450; }

}  // namespace

int main(int argc, char** argv) {
  if (const auto rc = ugs::testcase::refuse_dir_argument(
          argc, argv, "contact_make_case DIR [--dp MPa] [--friction DEG] [--cohesion MPa] [--cell M] [--extra TOML] [--months N]"))
    return *rc;
  const fs::path dir = argv[1];
  double dp = 5.0, friction = 30, cohesion = 0, cell = 50;
  int months = 0;
  std::string extra;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string k = argv[i];
    if (k == "--dp") dp = std::atof(argv[i + 1]);
    else if (k == "--friction") friction = std::atof(argv[i + 1]);
    else if (k == "--cohesion") cohesion = std::atof(argv[i + 1]);
    else if (k == "--cell") cell = std::atof(argv[i + 1]);
    else if (k == "--months") months = std::atoi(argv[i + 1]);
    else if (k == "--extra") {
      extra = argv[i + 1];
      for (std::size_t p; (p = extra.find("\\n")) != std::string::npos;) extra.replace(p, 2, "\n");
    }
  }
  fs::create_directories(dir);
  BoxMeshSpec spec;
  spec.x = linspace(0, 1000, static_cast<int>(std::lround(1000 / cell)));
  spec.y = linspace(0, 600, static_cast<int>(std::lround(600 / cell)));
  spec.z = linspace(-1000, 0, static_cast<int>(std::lround(1000 / cell)));
  spec.material = [](const Point3& c) { return in_reservoir(c) ? std::string("reservoir") : std::string("rock"); };
  Mesh m = make_box_mesh(spec);
  test::add_planar_fault(
      m, "F", {300, 0, -1000}, {-1, 0, 1}, [](const Point3& c) { return c[1] > 100 && c[1] < 500 && c[2] > -800 && c[2] < -300; },
      1e-6);
  test::insert_all_faults(m);
  m.provenance.push_back("contact_make_case (tests/fault_mechanics)");
  write_msh(m, (dir / "faulted.msh").string());

  namespace tc = ugs::testcase;
  tc::CaseToml c("# Faulted test case (tests/fault_mechanics): linear elastic rock, a reservoir block crossed by fault F.\n");
  c.initial_stress({.surface_elevation_m = 0, .k0 = 0.7});
  c.material(tc::linear("rock", 10000, 0.25)).material(tc::linear("reservoir", 5000, 0.25)).boundary(tc::fixed_sides());
  c.fault({"F", cohesion, friction}).table("solver", "linear_solver = \"mumps\"\n" + extra);
  tc::write_text(dir / "case.toml", c.str());

  const Mesh sub = tc::submesh(m, {"reservoir"});
  tc::Series s;
  if (months > 0) {
    s.dates = tc::monthly(2000, 1, 2000 + months / 12, 1 + months % 12);
    s.dp = [dp](const Point3&, std::size_t k) { return k % 6 == 0 ? 0.0 : dp * 1e6 * std::sin(2 * M_PI * k / 12); };  // exact zeros
  } else {
    s = tc::uniform_series({"2000-01-01", "2001-01-01"}, {0.0, dp * 1e6});
  }
  tc::write_pressure(dir / "flow.h5", sub, s);
  std::fprintf(stderr, "contact_make_case: %zu nodes, %zu tetrahedra, %zu interface elements; reservoir sub-mesh %zu nodes\n",
               m.num_nodes(), m.count(ElementType::Tetrahedron), m.count(ElementType::Prism), sub.num_nodes());
  return 0;
}
