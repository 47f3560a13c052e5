// The ugs-faultinsert benchmark case at the thesis' scale (chapter 4: 496,136 nodes, 2,891,095
// tetrahedra, 26,598 interface elements) when the real faulted mesh is not at hand: a box of
// 84 x 84 x 68 cells of 100 m (498,525 nodes, 2,878,848 tetrahedra, Kuhn-split) with the sample
// twin's kinds of faults, all following mesh faces:
//   two regional faults dipping 45 deg (to the west and to the south) from -500 to -6,600 m across
//   the whole model, crossing each other (an X-junction along a dipping line), and four buried local
//   faults, two on grid planes and two oblique (x - y = const), crossing the regional ones and
//   each other: 26,496 fault triangles in all.
// Writes into DIR: faults.geojson (the traces), plain.msh (no fault groups: the trace path) and
// groups.msh (the same mesh with fault:<name> triangle groups selected from the traces).
//
//   make_faultinsert_bench DIR
#include <cstdio>
#include <string>
#include <filesystem>
#include <fstream>

#include "ugs/formats/msh.hpp"
#include "ugs/meshing/box_mesh.hpp"
#include "ugs/meshing/fault_select.hpp"
#include "ugs/meshing/fault_traces.hpp"
#include "dir_argument.hpp"
#include "six_faults.hpp"

int main(int argc, char** argv) {
  if (argc > 2) {
    std::fprintf(stderr, "usage: make_faultinsert_bench DIR\n");
    return 2;
  }
  if (const auto rc = ugs::testcase::refuse_dir_argument(argc, argv, "make_faultinsert_bench DIR")) return *rc;
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  try {
    ugs::BoxMeshSpec s;
    s.x = ugs::linspace(0, 8400, 84);
    s.y = ugs::linspace(0, 8400, 84);
    s.z = ugs::linspace(-6800, 0, 68);
    ugs::Mesh mesh = ugs::make_box_mesh(s);
    mesh.provenance.push_back("make_faultinsert_bench (bench/faultinsert)");
    ugs::write_msh(mesh, (dir / "plain.msh").string());

    std::ofstream g(dir / "faults.geojson");
    g << "{\"type\":\"FeatureCollection\",\"name\":\"faults\",\"features\":[\n";
    std::vector<ugs::FaultTrace> traces;
    for (std::size_t i = 0; i < std::size(ugs::testcase::kSixFaults); ++i) {
      const auto& t = ugs::testcase::kSixFaults[i];
      char line[512];
      std::snprintf(line, sizeof line,
                    "{\"type\":\"Feature\",\"properties\":{\"name\":\"%s\",\"top_m\":%g,\"bottom_m\":%g,\"dip_deg\":%g,"
                    "\"dip_dir_deg\":%g},\"geometry\":{\"type\":\"LineString\",\"coordinates\":[[%g,%g],[%g,%g]]}}%s\n",
                    t.name, t.top, t.bottom, t.dip, t.dip_dir, t.x0, t.y0, t.x1, t.y1,
                    i + 1 < std::size(ugs::testcase::kSixFaults) ? "," : "");
      g << line;
      ugs::FaultTrace ft;
      ft.name = t.name;
      ft.where = "bench";
      ft.parts = {{{t.x0, t.y0}, {t.x1, t.y1}}};
      ft.top = ft.trace_z = t.top;
      ft.bottom = t.bottom;
      ft.dip_deg = t.dip;
      ft.dip_dir_deg = t.dip_dir;
      ugs::check_fault_trace(ft);
      traces.push_back(ft);
    }
    g << "]}\n";
    g.close();

    std::size_t triangles = 0;
    for (const auto& sel : ugs::select_fault_faces(mesh, traces)) triangles += sel.triangles;
    ugs::write_msh(mesh, (dir / "groups.msh").string());
    std::printf("%zu nodes, %zu tetrahedra, %zu fault triangles in %zu faults\n", mesh.num_nodes(),
                mesh.count(ugs::ElementType::Tetrahedron), triangles, traces.size());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_faultinsert_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
