// GOCAD TSurf horizons (formats/src/gocad_tsurf.cpp), then what ugs-meshgen does with one
// (meshing/layers/src/horizon_grids.cpp): the surface checks (non-manifold edges and vertices,
// orientation, folds, CGAL's self-intersection test) and linear sampling at points over the surface.
#include <cmath>
#include <cstdlib>

#include "fuzz_support.hpp"
#include "ugs/formats/gocad_tsurf.hpp"
#include "ugs/meshing/horizon_grids.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = ugs::fuzz::write_temp("surface.ts", data, size);
  ugs::fuzz::outcome([&] {
    const ugs::TriangulatedSurface s = ugs::read_gocad_tsurf(path);
    for (const auto& t : s.triangles)
      for (auto v : t)
        if (v >= s.vertices.size()) std::abort();
    if (s.triangles.size() > 20000) return;  // CGAL's test on a huge soup is time, not coverage
    ugs::geo::check_horizon_surface(s);
    double x0 = s.vertices[0][0], x1 = x0, y0 = s.vertices[0][1], y1 = y0;
    for (const auto& p : s.vertices)
      x0 = std::min(x0, p[0]), x1 = std::max(x1, p[0]), y0 = std::min(y0, p[1]), y1 = std::max(y1, p[1]);
    std::vector<ugs::XY> pts;
    for (int a = 0; a <= 6; ++a)
      for (int b = 0; b <= 6; ++b) pts.push_back({x0 + (x1 - x0) * a / 6.0, y0 + (y1 - y0) * b / 6.0});
    pts.push_back({s.vertices[0][0], s.vertices[0][1]});
    const auto r = ugs::geo::sample_tsurf(s, pts);
    std::size_t defined = 0;
    for (double v : r.values) {
      if (!std::isnan(v) && !std::isfinite(v)) std::abort();
      defined += std::isfinite(v);
    }
    if (defined + r.outside.size() != pts.size()) std::abort();
  });
  return 0;
}
