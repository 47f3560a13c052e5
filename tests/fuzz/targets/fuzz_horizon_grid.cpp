// Horizon grids of modelling packages (formats/src/irap_grid.cpp, cps3_grid.cpp, horizon_format.cpp):
// the input is told by its content as ugs-meshgen does, read by the IRAP classic ASCII or CPS-3
// ASCII reader, then sampled bilinearly (meshing/layers/src/horizon_grids.cpp) at points over and around
// the grid; every value sampled must be finite.
#include <cmath>
#include <cstdlib>

#include "fuzz_support.hpp"
#include "ugs/formats/horizon_grid.hpp"
#include "ugs/meshing/horizon_grids.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = ugs::fuzz::write_temp("grid.txt", data, size);
  ugs::fuzz::outcome([&] {
    const ugs::HorizonFormat f = ugs::detect_horizon_format(path);
    ugs::HorizonGrid g;
    if (f == ugs::HorizonFormat::Cps3) g = ugs::read_cps3_grid(path);
    else g = ugs::read_irap_grid(path);  // anything else: the IRAP reader must refuse it cleanly
    if (g.z.size() != g.nx * g.ny || g.nx < 2 || g.ny < 2) std::abort();
    std::vector<ugs::XY> pts;  // nodes, cell middles and points beyond the grid, in its own axes
    const double r = g.rotation_deg * M_PI / 180.0;
    for (int a = -1; a <= 5; ++a)
      for (int b = -1; b <= 5; ++b) {
        const double u = static_cast<double>(g.nx - 1) * a / 4.0 * g.dx, v = static_cast<double>(g.ny - 1) * b / 4.0 * g.dy;
        pts.push_back({g.x0 + std::cos(r) * u - std::sin(r) * v, g.y0 + std::sin(r) * u + std::cos(r) * v});
      }
    const auto s = ugs::geo::sample_grid(g, pts);
    const std::size_t bad = s.outside.size() + s.undefined.size();
    std::size_t defined = 0;
    for (double v : s.values) defined += std::isfinite(v);
    if (defined + bad != pts.size()) std::abort();
  });
  return 0;
}
