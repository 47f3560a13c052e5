// What a node of the cut's band must stay on (band_improver.hpp): the planes of its surfaces (its
// triangles, the faces between two materials, the model's outer faces) and its feature lines.
#include "band_improver.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "ugs/meshing/vec3.hpp"

namespace ugs::cut_band {

using namespace vec3;

// The surfaces through v: its triangles, the faces between two materials and the outer faces
// around it (a face holding v belongs to tetrahedra holding v, so the counts are exact); its
// feature lines: edges of a surface group used by other than two faces, or by two faces that are
// not coplanar. nullopt-like: returns false when a face is degenerate (v stays).
// In two parts: which faces and edges (incidences only: the smoothing computes them once per
// node) and their planes and creases (node positions).
bool BandImprover::surfaces_of(std::uint32_t v, Surfaces& out) const {
  topology_of(v, scratch_.topology);
  return geometry_of(v, scratch_.topology, out);
}

void BandImprover::topology_of(std::uint32_t v, SurfaceTopology& topo) const {
  // Flat sorted vectors rather than maps: this runs for every node the collapse and the smoothing
  // look at (millions of calls at the thesis scale), and the sets are a few dozen entries.
  // Scratch arrays kept between calls (malloc and free were about 7 % of the samples).
  auto& faces = topo.faces;
  auto& at_edge = topo.at_edge;
  auto& around = scratch_.around;
  auto& between = scratch_.between;
  auto& outer = scratch_.outer;
  faces.clear();
  at_edge.clear();
  around.clear();
  between.clear();
  outer.clear();
  topo.known = true;
  for (auto i : tris_of_[v]) faces.push_back({s_.tri_group[i], s_.tris[i]});
  for (auto t : tets_of_[v])
    for (const auto& f : kFaceOf) {
      const Face tri{s_.tets[t][f[0]], s_.tets[t][f[1]], s_.tets[t][f[2]]};
      if (!has(tri, v)) continue;
      // Sets of three holding v compare as their two other nodes do (the smallest node in one and
      // not the other decides, and v is in both): one 64-bit key instead of three fields.
      const std::uint32_t p = tri[0] == v ? tri[1] : tri[0], q = tri[2] == v ? tri[1] : tri[2];
      const std::uint64_t key = (std::uint64_t{std::min(p, q)} << 32) | std::max(p, q);
      around.push_back({key, tri, s_.tet_block[t], static_cast<std::uint32_t>(around.size())});
    }
  std::sort(around.begin(), around.end(),
            [](const Around& a, const Around& b) { return a.key < b.key || (a.key == b.key && a.order < b.order); });
  // Faces between two materials in the order they were met (the second use of a key), then the
  // outer faces (one use) in key order: as the maps this replaces gave them.
  for (std::size_t i = 0; i < around.size();) {
    std::size_t j = i + 1;
    while (j < around.size() && around[j].key == around[i].key) ++j;
    if (j - i == 1) outer.push_back({std::uint64_t{1} << 63, around[i].tri});
    for (std::size_t k = i + 1; k < j; ++k)
      if (around[i].block != around[k].block) {
        const std::uint64_t lo = std::min(around[i].block, around[k].block), hi = std::max(around[i].block, around[k].block);
        between.push_back({around[k].order, {(std::uint64_t{1} << 62) | (lo << 24) | hi, around[k].tri}});
      }
    i = j;
  }
  std::sort(between.begin(), between.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& b : between) faces.push_back(b.second);
  faces.insert(faces.end(), outer.begin(), outer.end());
  // Per (group, edge v-w): the faces and their third nodes.
  for (std::size_t fi = 0; fi < faces.size(); ++fi) {
    const auto& [g, f] = faces[fi];
    for (int k = 0; k < 3; ++k)
      if (f[k] != v)
        at_edge.push_back({g, f[k], static_cast<std::uint32_t>(at_edge.size()), static_cast<std::uint32_t>(fi),
                           f[3 - k - (f[0] == v ? 0 : f[1] == v ? 1 : 2)]});
  }
  std::sort(at_edge.begin(), at_edge.end(), [](const EdgeFace& a, const EdgeFace& b) {
    return std::tie(a.group, a.w, a.order) < std::tie(b.group, b.w, b.order);
  });
}

bool BandImprover::geometry_of(std::uint32_t v, const SurfaceTopology& topo, Surfaces& out) const {
  auto exact = [&](std::uint64_t g) { return !(g >= s_.first_fault_group && g < (std::uint64_t{1} << 62)); };
  auto& normal = scratch_.normal;  // of each face
  normal.clear();
  for (const auto& [g, f] : topo.faces) {
    const Point3 n = cross(sub(X(f[1]), X(f[0])), sub(X(f[2]), X(f[0])));
    const double nn = norm(n);
    if (!(nn > 0)) return false;
    const Point3 u = scaled(n, 1 / nn);
    out.planes.push_back({X(f[0]), u, exact(g)});
    normal.push_back(u);
  }
  // A crease: the two faces' third nodes off each other's plane (by more than the tolerance on a
  // fault, by more than rounding elsewhere).
  const auto& at_edge = topo.at_edge;
  for (std::size_t i = 0; i < at_edge.size();) {
    std::size_t j = i + 1;
    while (j < at_edge.size() && at_edge[j].group == at_edge[i].group && at_edge[j].w == at_edge[i].w) ++j;
    const double t = exact(at_edge[i].group) ? round_ : tol_;
    if (j - i != 2 || std::abs(dot(normal[at_edge[i].face], sub(X(at_edge[i + 1].third), X(v)))) > t ||
        std::abs(dot(normal[at_edge[i + 1].face], sub(X(at_edge[i].third), X(v)))) > t) {
      const Point3 d = sub(X(at_edge[i].w), X(v));
      out.lines.push_back({scaled(d, 1 / norm(d)), exact(at_edge[i].group)});
    }
    i = j;
  }
  return true;
}

}  // namespace ugs::cut_band
