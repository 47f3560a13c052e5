// ZMAP+ grids (meshing/layers/src/horizon_grids.cpp: the line layout checked against the header, then
// GDAL's ZMap driver reads the values), then bilinear sampling at points over the grid.
#include <cmath>
#include <cstdlib>

#include "fuzz_support.hpp"
#include "ugs/meshing/gdal_util.hpp"
#include "ugs/meshing/horizon_grids.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ugs::geo::gdal_init();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = ugs::fuzz::write_temp("grid.zmap", data, size);
  ugs::fuzz::outcome([&] {
    const ugs::HorizonGrid g = ugs::geo::read_zmap_grid(path);
    if (g.z.size() != g.nx * g.ny || g.nx < 2 || g.ny < 2) std::abort();
    std::vector<ugs::XY> pts;
    for (int a = -1; a <= 5; ++a)
      for (int b = -1; b <= 5; ++b) pts.push_back({g.x0 + (g.nx - 1) * g.dx * a / 4.0, g.y0 + (g.ny - 1) * g.dy * b / 4.0});
    const auto s = ugs::geo::sample_grid(g, pts);
    for (double v : s.values)
      if (!std::isnan(v) && !std::isfinite(v)) std::abort();
  });
  return 0;
}
