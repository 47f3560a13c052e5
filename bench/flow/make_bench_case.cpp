// The ugs-flow benchmark case at the thesis' scale when no real Pool C sub-mesh is at hand: a
// structured box mesh of the Pool C flow layers — a plan of N x N nodes (114 x 114 ~ the 13,301
// nodes of the thesis' plan mesh) times (8 + 2) layers (Pool C's 8 sub-layers and the 2 below it,
// Table 4.1), ~143,000 nodes — with Pool C as an ellipse in the upper 8 layers and its aquifer
// around and below it. Writes mesh.msh, case.toml and (unless given) a monthly 1950-2033
// schedule pressure_pool_c.csv into DIR, and the same mesh as raw arrays for the SciPy peer
// (nodes.f64: x y z per node; tets.u32: 4 node indices per tetrahedron; pool.u8: 1 for Pool C).
//
//   make_bench_case DIR [N] [SCHEDULE.csv]
//   make_bench_case --raw MESH POOL_MATERIAL DIR     (only the raw arrays of an existing flow mesh)
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/box_mesh.hpp"
#include "case_toml.hpp"
#include "dir_argument.hpp"

namespace {

void write_raw(const ugs::Mesh& mesh, const std::filesystem::path& dir, const std::string& pool_material) {
  std::ofstream nodes(dir / "nodes.f64", std::ios::binary), tets(dir / "tets.u32", std::ios::binary),
      pool(dir / "pool.u8", std::ios::binary);
  nodes.write(reinterpret_cast<const char*>(mesh.nodes.data()), static_cast<std::streamsize>(mesh.nodes.size() * 24));
  for (const auto& b : mesh.blocks) {
    if (b.type != ugs::ElementType::Tetrahedron) continue;
    const char flag = mesh.physical_name_of(3, b.entity_tag) == "mat:" + pool_material ? 1 : 0;
    tets.write(reinterpret_cast<const char*>(b.nodes.data()), static_cast<std::streamsize>(b.nodes.size() * 4));
    for (std::size_t i = 0; i < b.size(); ++i) pool.put(flag);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 5 && std::string(argv[1]) == "--raw") {
    std::filesystem::create_directories(argv[4]);
    write_raw(ugs::read_msh(argv[2]), argv[4], argv[3]);
    return 0;
  }
  if (const auto rc = ugs::testcase::refuse_dir_argument(argc, argv, "make_bench_case DIR [N] [SCHEDULE.csv]")) return *rc;
  const std::filesystem::path dir = argv[1];
  const int n = argc > 2 ? std::stoi(argv[2]) : 114;
  std::filesystem::create_directories(dir);

  // Plan 12 x 10 km around the pool; Pool C top -1,498 m, base -1,515 m (8 layers), then 2 layers to -1,543 m.
  ugs::BoxMeshSpec s;
  s.x = ugs::linspace(-6000, 6000, n - 1);
  s.y = ugs::linspace(-5000, 5000, n - 1);
  s.z = ugs::linspace(-1543, -1515, 2);
  const auto upper = ugs::linspace(-1515, -1498, 8);
  s.z.insert(s.z.end(), upper.begin() + 1, upper.end());
  s.material = [](const ugs::Point3& c) {
    const double ex = c[0] / 2500, ey = c[1] / 1200;
    return (c[2] > -1515 && ex * ex + ey * ey < 1) ? std::string("pool_c") : std::string("aquifer_pool_c");
  };
  ugs::Mesh mesh = ugs::make_box_mesh(s);
  mesh.provenance.push_back("make_bench_case (bench/flow)");
  ugs::write_msh(mesh, (dir / "mesh.msh").string());
  write_raw(mesh, dir, "pool_c");

  std::string schedule = "pressure_pool_c.csv";
  if (argc > 3) {
    schedule = std::filesystem::absolute(argv[3]).string();
  } else {
    // Primary production to 52 % of the initial pressure by 1964 (thesis 4.2.1), then yearly cycles.
    ugs::CsvWriter w((dir / schedule).string(), {"date", "p_norm", "p_MPa"});
    const double p0 = 15.2055;
    for (int y = 1950; y <= 2033; ++y)
      for (int m = 1; m <= 12; ++m) {
        const double t = (y - 1950) + (m - 1) / 12.0;
        double p = t <= 14.25 ? 1 - 0.35 * std::pow(t / 10, std::log(0.52 / 0.35) / std::log(1.4))
                              : 0.70 + 0.12 * std::cos(2 * M_PI * (t - 14.25 - 7.0 / 12));
        if (t > 14.25 && t < 15.25) p = std::min(p, 0.48 + 0.2 * (t - 14.25));
        w.date(ugs::days_from_civil(y, m, 1) * 86400).number(p, 5).number(p * p0, 4).end_row();
      }
    w.commit();
  }
  namespace tc = ugs::testcase;
  tc::CaseToml c("# ugs-flow benchmark: Pool C flow layers at the thesis' scale (Table 4.2 conductivities)\n",
                 tc::Numbers::Decimal);
  c.table("model", "start = \"1950-01-01\"\nend = \"2033-12-01\"\n");
  c.initial_stress({.surface_elevation_m = 50, .hydrostatic_gradient_MPa_per_m = 0.00981});
  for (const char* name : {"pool_c", "aquifer_pool_c"})
    c.material({.name = name, .law = "hypoplastic", .c_R = 3, .more = "K_m_per_s = [2.04e-7, 2.04e-7, 2.04e-8]\nporosity = 0.20\n"});
  c.pool({.name = "Pool C", .materials = {"pool_c"}, .schedule = schedule, .column = "p_norm", .more = "reference_pressure_MPa = 15.2055\n"});
  tc::write_text(dir / "case.toml", c.str());
  std::printf("%s: %zu nodes, %zu tetrahedra\n", (dir / "mesh.msh").c_str(), mesh.num_nodes(),
              mesh.count(ugs::ElementType::Tetrahedron));
  return 0;
}
