// make_faulted_bench — the thesis-scale faulted ugs-solve case (chapter 4: 508,495 nodes, 26,598
// interface elements) for bench/faulted/run.sh, when the real faulted model is not at hand:
//   - the box of bench/faultinsert (84 x 84 x 68 cells of 100 m, Kuhn-split: 498,525 nodes,
//     2,878,848 tetrahedra) with its six crossing faults (two regional faults dipping 45 degrees
//     from -500 to -6,600 m, four buried local ones), inserted as interface elements: 26,496 of them
//     and about 511,600 nodes;
//   - a storage pool (hypo-plastic, c_R = 3) in the layer -1,500 to -1,400 m, an ellipse of
//     2,000 x 1,400 m about the centre, inside a hypo-plastic aquifer ring to 3,000 m, in elastic rock
//     with c_M from eq. 4.1; regional_west crosses the pool's edge;
//   - one storage half-cycle: the pool's pressure change -6 MPa on 2015-05-01 (the production
//     before it, reached in the first step) rising monthly to -1 MPa on 2015-11-01; the aquifer
//     follows with exp(-d / 1 km) of the distance to the pool's edge;
//   - the same case without faults (plain.msh, case_plain.toml) for the continuous peer run.
// Writes DIR/faulted.msh, plain.msh, case.toml, case_plain.toml, flow.h5, flow_plain.h5, and for
// the whole history (bench/faulted/run.sh FAULTED_HISTORY=1) case_history.toml and flow_history.h5:
// monthly 1950-01-01 .. 2034-01-01 (1,008 steps), primary production 1950-1964 to -8 MPa in the pool,
// then seasonal storage between -8 and -2 MPa (withdrawal November-March, injection April-October);
// the aquifer follows the pool two months late (a second spatial mode, so that a step is not simply
// a multiple of the previous one).
//
//   make_faulted_bench DIR [--coarsen K] [--history]
// --coarsen K (1, 2 or 4) makes the cells K times larger in each direction (about 1/K^3 of the
// nodes: 2 gives ~66,000) and moves the faults' traces, tops and bottoms to the nearest grid line
// (the mesh must follow them): the same kind of case, for measurements on a busy machine.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/box_mesh.hpp"
#include "ugs/meshing/fault_insert.hpp"
#include "ugs/meshing/fault_select.hpp"
#include "ugs/meshing/fault_traces.hpp"
#include "case_toml.hpp"
#include "dir_argument.hpp"
#include "pressure_files.hpp"
#include "six_faults.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

constexpr double kCx = 4200, kCy = 4200, kRx = 2000, kRy = 1400, kAq = 3000, kTop = -1400, kBot = -1500;

// Elliptic distance (m along x) from the pool's centre.
double radius(const Point3& c) { return std::hypot(c[0] - kCx, (c[1] - kCy) * kRx / kRy); }

std::string material(const Point3& c) {
  if (c[2] > kTop || c[2] < kBot) return "rock";
  const double r = radius(c);
  return r < kRx ? "pool" : r < kAq ? "aquifer" : "rock";
}

void write_flow(const Mesh& m, const fs::path& path) {
  testcase::Series s;
  for (int k = 0; k <= 6; ++k) s.dates.push_back(fmt::format("2015-{:02d}-01", 5 + k));
  s.dp = [](const Point3& x, std::size_t k) {
    const double pool = (-6.0 + 5.0 * static_cast<double>(k) / 6.0) * 1e6;
    return pool * std::exp(-std::max(0.0, radius(x) - kRx) / 1000.0);
  };
  testcase::write_pressure(path, testcase::submesh(m, {"pool", "aquifer"}), s);
}

// The pool's pressure change [Pa] at month k after 1950-01 (history).
double pool_history(long k) {
  if (k <= 0) return 0.0;
  if (k <= 168) return -8e6 * static_cast<double>(k) / 168.0;  // production to 1964-01
  const double phase = 2.0 * M_PI * static_cast<double>((k - 168) % 12) / 12.0;  // 0 in January
  return -5e6 - 3e6 * std::cos(phase - M_PI / 6.0);  // deepest in late February, highest in August
}

void write_flow_history(const Mesh& m, const fs::path& path) {
  testcase::Series s;
  s.dates = testcase::monthly(1950, 1, 2034, 1);
  s.dp = [](const Point3& x, std::size_t k) {
    const double d = std::max(0.0, radius(x) - kRx);
    const double lag = pool_history(static_cast<long>(k) - 2);
    return d == 0 ? pool_history(static_cast<long>(k)) : lag * std::exp(-d / 1000.0);
  };
  testcase::write_pressure(path, testcase::submesh(m, {"pool", "aquifer"}), s);
}

std::string case_text(bool faults) {
  testcase::CaseToml c(
      "# Thesis-scale faulted benchmark (bench/faulted): elastic rock with c_M from eq. 4.1, a hypo-plastic\n"
      "# pool and aquifer (Table 4.3), six faults (cohesion 0, friction 30 degrees), one storage half-cycle.\n");
  c.initial_stress({.surface_elevation_m = 0, .k0 = 0.9}).material(testcase::elastic("rock", 0.3));
  c.material(testcase::hypoplastic("pool", 3)).material(testcase::hypoplastic("aquifer", 3));
  c.table("output", "dates = [\"2015-05-01\", \"2015-11-01\"]\nfields = [\"displacement\", \"stress_change\"]\n");
  if (faults)
    for (const auto& t : testcase::kSixFaults) c.fault({t.name, 0, 30});
  return c.str();
}

}  // namespace

int main(int argc, char** argv) {
  int coarsen = 1;
  const bool history = argc >= 3 && std::string(argv[argc - 1]) == "--history";
  if (history) --argc;
  if (argc == 4 && std::string(argv[2]) == "--coarsen") {
    const std::string k = argv[3];
    if (k != "1" && k != "2" && k != "4") {
      std::fprintf(stderr, "make_faulted_bench: error: --coarsen: '%s' is not 1, 2 or 4 (the cell counts must stay whole)\n", argv[3]);
      return 2;
    }
    coarsen = std::stoi(k);
  } else if (argc != 2) {
    std::fprintf(stderr, "usage: make_faulted_bench DIR [--coarsen K] [--history]\n");
    return 2;
  }
  if (const auto rc = testcase::refuse_dir_argument(argc, argv, "make_faulted_bench DIR [--coarsen K] [--history]")) return *rc;
  const fs::path dir = argv[1];
  const double h = 100.0 * coarsen;
  // Snaps a coordinate to the grid line nearest to it (origin o).
  const auto snap = [h](double v, double o) { return o + h * std::round((v - o) / h); };
  fs::create_directories(dir);
  try {
    BoxMeshSpec s;
    s.x = linspace(0, 8400, 84 / coarsen);
    s.y = linspace(0, 8400, 84 / coarsen);
    s.z = linspace(-6800, 0, 68 / coarsen);
    s.material = [](const Point3& c) { return material(c); };
    Mesh mesh = make_box_mesh(s);
    mesh.provenance.push_back("make_faulted_bench (bench/faulted)");
    write_msh(mesh, (dir / "plain.msh").string());
    write_flow(mesh, dir / "flow_plain.h5");
    std::ofstream(dir / "case_plain.toml") << case_text(false);

    std::vector<FaultTrace> traces;
    for (const auto& t : testcase::kSixFaults) {
      FaultTrace ft;
      ft.name = t.name;
      ft.where = "bench";
      ft.parts = {{{snap(t.x0, 0), snap(t.y0, 0)}, {snap(t.x1, 0), snap(t.y1, 0)}}};
      ft.top = ft.trace_z = snap(t.top, -6800);
      ft.bottom = snap(t.bottom, -6800);
      ft.dip_deg = t.dip;
      ft.dip_dir_deg = t.dip_dir;
      check_fault_trace(ft);
      traces.push_back(ft);
    }
    select_fault_faces(mesh, traces);
    FaultInsertOptions fo;
    fo.source = "make_faulted_bench";
    const FaultInsertReport rep = insert_faults(mesh, fo);
    std::size_t ie = 0;
    for (const auto& f : rep.faults) ie += f.triangles;
    write_msh(mesh, (dir / "faulted.msh").string());
    write_flow(mesh, dir / "flow.h5");
    std::ofstream(dir / "case.toml") << case_text(true);
    if (history) {
      write_flow_history(mesh, dir / "flow_history.h5");
      std::string h = case_text(true);
      const std::string out = "dates = [\"2015-05-01\", \"2015-11-01\"]";
      h.replace(h.find(out), out.size(), "dates = [\"1964-01-01\", \"2000-03-01\", \"2033-09-01\", \"2034-01-01\"]\ncheckpoint_every = 60");
      std::ofstream(dir / "case_history.toml") << h;
    }
    std::printf("make_faulted_bench: %zu nodes, %zu tetrahedra, %zu interface elements in %zu faults (plain: %zu nodes)\n",
                mesh.num_nodes(), mesh.count(ElementType::Tetrahedron), ie, rep.faults.size(),
                mesh.num_nodes() - rep.new_nodes);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_faulted_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
