#include "ugs/insar/sections.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "ugs/formats/error.hpp"

namespace ugs::insar {

SectionSlice slice_tets(std::span<const Point3> x, std::span<const Tet> tets, const std::string& name,
                        const std::vector<std::array<double, 2>>& line, double zmin, double zmax) {
  SectionSlice s;
  s.name = name;
  s.offsets.push_back(0);
  double s0 = 0;
  static constexpr int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    const double ax = line[k][0], ay = line[k][1];
    const double dx = line[k + 1][0] - ax, dy = line[k + 1][1] - ay, len = std::hypot(dx, dy);
    if (len <= 0) continue;
    const double tx = dx / len, ty = dy / len;  // along the segment
    const double nx = -ty, ny = tx;             // normal of the vertical plane
    for (std::uint32_t e = 0; e < tets.size(); ++e) {
      const auto& t = tets[e];
      double d[4], zlo = x[t[0]][2], zhi = zlo;
      bool pos = false, neg = false;
      for (int i = 0; i < 4; ++i) {
        const Point3& p = x[t[i]];
        d[i] = nx * (p[0] - ax) + ny * (p[1] - ay);
        // A node on the plane counts on the positive side (sections often run along mesh lines): the
        // tetrahedra on the negative side then contribute their faces on the plane, once.
        pos = pos || d[i] >= 0;
        neg = neg || d[i] < 0;
        zlo = std::min(zlo, p[2]);
        zhi = std::max(zhi, p[2]);
      }
      if (!pos || !neg || zhi < zmin || zlo > zmax) continue;
      // Edge crossings, in section coordinates.
      std::array<std::array<double, 2>, 6> pts;
      int np = 0;
      for (const auto& ed : kEdge) {
        const double da = d[ed[0]], db = d[ed[1]];
        if ((da >= 0) == (db >= 0)) continue;
        const double w = da / (da - db);
        const Point3 &a = x[t[ed[0]]], &b = x[t[ed[1]]];
        const double px = a[0] + w * (b[0] - a[0]), py = a[1] + w * (b[1] - a[1]), pz = a[2] + w * (b[2] - a[2]);
        pts[np++] = {s0 + tx * (px - ax) + ty * (py - ay), pz};
      }
      if (np < 3) continue;
      double cs = 0, cz = 0;
      for (int i = 0; i < np; ++i) cs += pts[i][0], cz += pts[i][1];
      cs /= np, cz /= np;
      std::sort(pts.begin(), pts.begin() + np, [&](const auto& p, const auto& q) {
        return std::atan2(p[1] - cz, p[0] - cs) < std::atan2(q[1] - cz, q[0] - cs);
      });
      // Clip to this segment's stretch of the section, s0 <= s <= s0 + len, and to the depth window
      // zmin <= z <= zmax: the polygons tile the window's rectangle, with no ragged edges of the
      // tetrahedra that reach out of it (blank wedges in the pictures).
      std::vector<std::array<double, 2>> poly(pts.begin(), pts.begin() + np);
      struct Bound {
        int axis;  // 0: s, 1: z
        double at;
        bool keep_below;
      };
      for (const Bound& b : {Bound{0, s0, false}, Bound{0, s0 + len, true}, Bound{1, zmin, false}, Bound{1, zmax, true}}) {
        std::vector<std::array<double, 2>> next;
        const auto inside = [&](const std::array<double, 2>& p) { return b.keep_below ? p[b.axis] <= b.at : p[b.axis] >= b.at; };
        for (std::size_t i = 0; i < poly.size(); ++i) {
          const auto& p = poly[i];
          const auto& q = poly[(i + 1) % poly.size()];
          if (inside(p)) next.push_back(p);
          if (inside(p) != inside(q)) {
            const double w = (b.at - p[b.axis]) / (q[b.axis] - p[b.axis]);
            std::array<double, 2> r{p[0] + w * (q[0] - p[0]), p[1] + w * (q[1] - p[1])};
            r[b.axis] = b.at;
            next.push_back(r);
          }
        }
        poly.swap(next);
        if (poly.size() < 3) break;
      }
      if (poly.size() < 3) continue;
      double area = 0;
      for (std::size_t i = 0; i < poly.size(); ++i) {
        const auto& p = poly[i];
        const auto& q = poly[(i + 1) % poly.size()];
        area += p[0] * q[1] - q[0] * p[1];
      }
      if (std::abs(area) <= 1e-12 * len * len) continue;  // only an edge or a node on the plane
      for (const auto& p : poly) {
        s.sz.push_back(p[0]);
        s.sz.push_back(p[1]);
      }
      s.offsets.push_back(static_cast<std::int32_t>(s.sz.size() / 2));
      s.cell.push_back(e);
    }
    s0 += len;
  }
  s.length = s0;
  return s;
}

namespace {
struct FaceKey {
  std::array<std::uint32_t, 3> n;
  bool operator==(const FaceKey& o) const { return n == o.n; }
};
struct FaceHash {
  std::size_t operator()(const FaceKey& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (auto v : k.n) h = (h ^ v) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};
constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
FaceKey face_key(const Tet& t, int f) {
  FaceKey k{{t[kFace[f][0]], t[kFace[f][1]], t[kFace[f][2]]}};
  std::sort(k.n.begin(), k.n.end());
  return k;
}
}  // namespace

LayerTop layer_top(std::span<const Point3> x, std::span<const std::uint64_t> tags, std::span<const Tet> tets,
                   const std::vector<char>& in_layer) {
  std::vector<Tet> sub;
  std::vector<std::uint32_t> sub_to_cell;
  for (std::uint32_t e = 0; e < tets.size(); ++e)
    if (in_layer[e]) {
      sub.push_back(tets[e]);
      sub_to_cell.push_back(e);
    }
  if (sub.empty()) throw InputError("", "the layer has no cells");
  LayerTop lt;
  std::vector<std::uint32_t> codes;
  lt.surface = upward_boundary(x, tags, sub, 1e-6, &codes);
  lt.below.resize(codes.size());
  lt.above.assign(codes.size(), -1);
  std::unordered_map<FaceKey, std::size_t, FaceHash> wanted;
  for (std::size_t i = 0; i < codes.size(); ++i) {
    const std::uint32_t cell = sub_to_cell[codes[i] / 4];
    lt.below[i] = cell;
    wanted.emplace(face_key(tets[cell], static_cast<int>(codes[i] % 4)), i);
  }
  for (std::uint32_t e = 0; e < tets.size(); ++e) {
    if (in_layer[e]) continue;
    for (int f = 0; f < 4; ++f) {
      const auto it = wanted.find(face_key(tets[e], f));
      if (it != wanted.end()) lt.above[it->second] = e;
    }
  }
  return lt;
}

ConfinementHeight confinement_height(std::span<const Point3> x, std::span<const Tet> tets, const std::vector<double>& v,
                                     const std::vector<char>& in_layer, const SurfaceLocator& top, double fraction,
                                     const std::vector<char>& own_load) {
  if (!own_load.empty() && own_load.size() != tets.size())
    throw std::logic_error("confinement_height: own_load needs one flag per cell");
  ConfinementHeight r;
  for (std::size_t e = 0; e < tets.size(); ++e)
    if (in_layer[e] && std::isfinite(v[e])) r.peak = std::max(r.peak, std::abs(v[e]));
  if (r.peak <= 0) return r;
  const double limit = fraction * r.peak;
  // Footprint test on the plan bounding box first: most cells are far from the layer.
  const auto ext = top.surface().extent();
  for (std::size_t e = 0; e < tets.size(); ++e) {
    if (in_layer[e] || (!own_load.empty() && own_load[e])) continue;
    Point3 c{0, 0, 0};
    for (auto n : tets[e])
      for (int j = 0; j < 3; ++j) c[j] += 0.25 * x[n][j];
    if (c[0] < ext[0] || c[0] > ext[1] || c[1] < ext[2] || c[1] > ext[3]) continue;
    const auto h = top.locate(c[0], c[1]);
    if (!h.inside || c[2] <= h.point[2]) continue;
    ++r.cells_above;
    if (std::abs(v[e]) >= limit) {
      ++r.cells_over;
      r.height = std::max(r.height, c[2] - h.point[2]);
    }
  }
  return r;
}

}  // namespace ugs::insar
