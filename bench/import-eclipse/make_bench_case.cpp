// Writes a synthetic ECLIPSE case and a mechanics mesh for the import bench (bench/import-eclipse/run.sh):
//   eclipse_make_bench_case DIR NX NY NZ STEPS HEXES_X HEXES_Y HEXES_Z
// DIR/BENCH.EGRID: NX x NY x NZ corner-point cells of 50 x 50 x 2 m, tops dipping and twisted,
// every 50th cell inactive, MAPAXES about (600000, 5000000); DIR/BENCH.UNRST: STEPS + 1 report
// steps of PRESSURE (METRIC), monthly; DIR/mesh.msh: a box mesh of HEXES_X x HEXES_Y x HEXES_Z
// hexahedra (6 tetrahedra each) over the grid, 5 % beyond it in plan and 5 m above and below.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <opm/io/eclipse/EclOutput.hpp>

#include "ugs/formats/msh.hpp"
#include "ugs/meshing/box_mesh.hpp"

int main(int argc, char** argv) {
  if (argc != 9) {
    std::fprintf(stderr, "usage: %s DIR NX NY NZ STEPS HEXES_X HEXES_Y HEXES_Z\n", argv[0]);
    return 2;
  }
  // The first argument is the folder to write: an option there (--help) would become a folder.
  if (argv[1][0] == '-') {
    std::fprintf(stderr, "usage: %s DIR NX NY NZ STEPS HEXES_X HEXES_Y HEXES_Z\n", argv[0]);
    return argv[1] == std::string("--help") || argv[1] == std::string("-h") ? 0 : 2;
  }
  const std::string dir = argv[1];
  const int nx = std::stoi(argv[2]), ny = std::stoi(argv[3]), nz = std::stoi(argv[4]), steps = std::stoi(argv[5]);
  const double dx = 50, dy = 50, dz = 2;
  auto top = [&](int i, int j) { return 1000.0 + 0.02 * i * dx + 0.01 * j * dy + 1e-4 * i * j; };
  {
    Opm::EclIO::EclOutput w(dir + "/BENCH.EGRID", false);
    w.write<std::string>("MAPUNITS", {"METRES"});
    w.write<float>("MAPAXES", {599400.f, 5000800.f, 600000.f, 5000000.f, 600800.f, 5000600.f});
    w.write<std::string>("GRIDUNIT", {"METRES", ""});
    std::vector<int> gh(100, 0);
    gh[0] = 1, gh[1] = nx, gh[2] = ny, gh[3] = nz;
    w.write<int>("GRIDHEAD", gh);
    std::vector<float> coord;
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        const float x = static_cast<float>(i * dx), y = static_cast<float>(j * dy);
        coord.insert(coord.end(), {x, y, 900.f, x, y, 1400.f});
      }
    w.write<float>("COORD", coord);
    std::vector<float> zc;
    zc.reserve(8ull * nx * ny * nz);
    for (int k = 0; k < nz; ++k)
      for (int kk : {k, k + 1})
        for (int j = 0; j < ny; ++j)
          for (int jj : {j, j + 1})
            for (int i = 0; i < nx; ++i)
              for (int ii : {i, i + 1}) zc.push_back(static_cast<float>(top(ii, jj) + kk * dz));
    w.write<float>("ZCORN", zc);
    std::vector<int> act(static_cast<std::size_t>(nx) * ny * nz, 1);
    for (std::size_t g = 0; g < act.size(); g += 50) act[g] = 0;
    w.write<int>("ACTNUM", act);
    w.message("ENDGRID");
  }
  const std::size_t nact = static_cast<std::size_t>(nx) * ny * nz - (static_cast<std::size_t>(nx) * ny * nz + 49) / 50;
  {
    Opm::EclIO::EclOutput w(dir + "/BENCH.UNRST", false);
    std::vector<float> p(nact);
    for (int s = 0; s <= steps; ++s) {
      std::vector<int> ih(411, 0);
      ih[2] = 1, ih[8] = nx, ih[9] = ny, ih[10] = nz, ih[11] = static_cast<int>(nact);
      ih[64] = 1, ih[65] = 1 + s % 12, ih[66] = 2000 + s / 12;
      w.write<int>("SEQNUM", {s});
      w.write<int>("INTEHEAD", ih);
      for (std::size_t a = 0; a < nact; ++a) p[a] = static_cast<float>(150.0 + 20.0 * std::sin(0.5 * s + 1e-4 * a));
      w.write<float>("PRESSURE", p);
    }
  }
  ugs::BoxMeshSpec spec;
  const double X = nx * dx, Y = ny * dy;
  spec.x = ugs::linspace(-0.05 * X, 1.05 * X, std::stoi(argv[6]));
  spec.y = ugs::linspace(-0.05 * Y, 1.05 * Y, std::stoi(argv[7]));
  spec.z = ugs::linspace(-(top(nx, ny) + nz * dz) - 5, -top(0, 0) + 5, std::stoi(argv[8]));
  ugs::Mesh m = ugs::make_box_mesh(spec);
  for (auto& n : m.nodes) n = {600000 + 0.8 * n[0] - 0.6 * n[1], 5000000 + 0.6 * n[0] + 0.8 * n[1], n[2]};
  ugs::write_msh(m, dir + "/mesh.msh", ugs::MshEncoding::Binary);
  std::printf("%zu active cells, %d steps, %zu tetrahedra\n", nact, steps + 1, m.count(ugs::ElementType::Tetrahedron));
  return 0;
}
