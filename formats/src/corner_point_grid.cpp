#include "ugs/formats/corner_point_grid.hpp"

#include <cctype>
#include <cmath>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs {
namespace {

const GrdeclKeyword& required(const GrdeclFile& f, const std::string& name, std::size_t count, const std::string& what) {
  const GrdeclKeyword* k = f.find(name);
  if (!k) throw InputError(f.path, fmt::format("no {} keyword (expected {}; keywords: {})", name, what, f.names()));
  if (k->values.size() != count)
    throw InputError(k->where, fmt::format("{} has {} values, expected {} ({})", name, k->values.size(), count, what));
  return *k;
}

}  // namespace

std::array<int, 3> CornerPointGrid::ijk(std::uint32_t g) const {
  const auto nx = static_cast<std::uint32_t>(dims[0]), ny = static_cast<std::uint32_t>(dims[1]);
  return {static_cast<int>(g % nx), static_cast<int>((g / nx) % ny), static_cast<int>(g / (nx * ny))};
}

std::string grid_unit_name(std::string s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  std::size_t b = 0;
  while (b < s.size() && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  s.erase(0, b);
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

double grid_length_unit_m(const std::string& unit, const std::string& where) {
  if (unit == "METRES" || unit == "METERS" || unit == "M") return 1.0;
  if (unit == "FEET" || unit == "FT") return 0.3048;
  if (unit == "CM") return 0.01;
  throw InputError(where, fmt::format("unknown length unit '{}' (expected METRES, FEET or CM)", unit));
}

MapAxes map_axes(const std::array<double, 6>& p, const std::string& where) {
  for (int q = 0; q < 6; ++q)
    if (!std::isfinite(p[q])) throw InputError(where, fmt::format("MAPAXES value {} is not finite", q + 1));
  MapAxes m;
  m.origin = {p[2], p[3]};
  std::array<double, 2> ex{p[4] - p[2], p[5] - p[3]}, ey{p[0] - p[2], p[1] - p[3]};
  const double lx = std::hypot(ex[0], ex[1]), ly = std::hypot(ey[0], ey[1]);
  if (!(lx > 0) || !(ly > 0)) throw InputError(where, "MAPAXES: the X- or Y-axis point equals the origin (expected three distinct points)");
  m.ex = {ex[0] / lx, ex[1] / lx};
  m.ey = {ey[0] / ly, ey[1] / ly};
  return m;
}

const std::set<std::string>& corner_point_keywords() {
  static const std::set<std::string> k = {"SPECGRID", "DIMENS", "COORD", "ZCORN", "ACTNUM", "MAPAXES", "MAPUNITS", "GRIDUNIT", "COORDSYS"};
  return k;
}

CornerPointGrid corner_point_grid(const GrdeclFile& f, const Point3& offset) {
  CornerPointGrid g;
  g.path = f.path;
  const GrdeclKeyword* spec = f.find("SPECGRID");
  if (!spec) spec = f.find("DIMENS");
  if (!spec) throw InputError(f.path, fmt::format("no SPECGRID or DIMENS keyword (expected a corner-point grid; keywords: {})", f.names()));
  if (spec->values.size() < 3) throw InputError(spec->where, fmt::format("{} needs NX NY NZ", spec->name));
  for (int d = 0; d < 3; ++d) {
    const double v = spec->values[static_cast<std::size_t>(d)];
    if (!(v >= 1 && v <= 1e6) || v != std::floor(v))
      throw InputError(spec->where, fmt::format("{} item {} is {} (expected a positive integer count of cells)", spec->name, d + 1, v));
    g.dims[d] = static_cast<int>(v);
  }
  if (f.find("COORDSYS")) throw InputError(f.find("COORDSYS")->where, "COORDSYS (several reservoirs in one grid) is not supported");
  const std::size_t nx = static_cast<std::size_t>(g.dims[0]), ny = static_cast<std::size_t>(g.dims[1]), nz = static_cast<std::size_t>(g.dims[2]);
  const std::size_t total = nx * ny * nz;
  if (total > 2000000000) throw InputError(spec->where, "more than 2e9 cells");
  const auto& coord = required(f, "COORD", 6 * (nx + 1) * (ny + 1), "6 numbers per pillar, (NX+1)(NY+1) pillars").values;
  const auto& zcorn = required(f, "ZCORN", 8 * total, "8 depths per cell").values;
  std::vector<double> act(total, 1.0);
  if (f.find("ACTNUM")) act = required(f, "ACTNUM", total, "one 0 or 1 per cell").values;

  if (const GrdeclKeyword* gu = f.find("GRIDUNIT"); gu && !gu->words.empty()) g.length_unit = grid_unit_name(gu->words[0]);
  const double L = grid_length_unit_m(g.length_unit, f.find("GRIDUNIT") ? f.find("GRIDUNIT")->where : f.path);
  MapAxes axes;
  if (const GrdeclKeyword* ma = f.find("MAPAXES")) {
    if (ma->values.size() != 6) throw InputError(ma->where, fmt::format("MAPAXES has {} values (expected 6)", ma->values.size()));
    double M = L;
    if (const GrdeclKeyword* mu = f.find("MAPUNITS"); mu && !mu->words.empty()) M = grid_length_unit_m(grid_unit_name(mu->words[0]), mu->where);
    std::array<double, 6> p;
    for (int q = 0; q < 6; ++q) p[q] = ma->values[static_cast<std::size_t>(q)] * M;
    axes = map_axes(p, ma->where);
    g.mapaxes = true;
  }

  g.active.assign(total, -1);
  for (std::size_t c = 0; c < total; ++c)
    if (act[c] != 0) {
      g.active[c] = static_cast<std::int32_t>(g.global.size());
      g.global.push_back(static_cast<std::uint32_t>(c));
    }
  if (g.global.empty()) throw InputError(f.find("ACTNUM")->where, "no active cell (ACTNUM is all 0)");
  g.corners.resize(g.global.size());
  for (std::size_t a = 0; a < g.global.size(); ++a) {
    const auto [i, j, k] = g.ijk(g.global[a]);
    for (int c = 0; c < 8; ++c) {
      const std::size_t di = c & 1, dj = (c >> 1) & 1, dk = c >> 2;
      const std::size_t pillar = (static_cast<std::size_t>(i) + di) + (nx + 1) * (static_cast<std::size_t>(j) + dj);
      const double* p = &coord[6 * pillar];
      const double depth = zcorn[((2 * static_cast<std::size_t>(k) + dk) * 2 * ny + 2 * static_cast<std::size_t>(j) + dj) * 2 * nx +
                                 2 * static_cast<std::size_t>(i) + di];
      // On the pillar at that depth (a vertical pillar of zero length: its top point).
      const double t = p[5] != p[2] ? (depth - p[2]) / (p[5] - p[2]) : 0.0;
      const double x = (p[0] + t * (p[3] - p[0])) * L, y = (p[1] + t * (p[4] - p[1])) * L;
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(depth * L))
        throw InputError(f.path, fmt::format("cell ({},{},{}): corner {} is not finite", i + 1, j + 1, k + 1, c + 1));
      g.corners[a][static_cast<std::size_t>(c)] = axes.to_mesh(x, y, depth * L, offset);
    }
  }
  return g;
}

}  // namespace ugs
