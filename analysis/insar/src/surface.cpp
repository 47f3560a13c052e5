#include "ugs/insar/surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs::insar {

std::array<double, 4> TopSurface::extent() const {
  std::array<double, 4> e{std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
                          std::numeric_limits<double>::max(), -std::numeric_limits<double>::max()};
  for (const auto& t : triangles)
    for (auto n : t) {
      e[0] = std::min(e[0], points[n][0]);
      e[1] = std::max(e[1], points[n][0]);
      e[2] = std::min(e[2], points[n][1]);
      e[3] = std::max(e[3], points[n][1]);
    }
  return e;
}

namespace {

// Keeps only the nodes the triangles use, renumbered in first-use order.
TopSurface compact(std::span<const Point3> x, std::span<const std::uint64_t> tags,
                   const std::vector<std::array<std::uint32_t, 3>>& tris, std::string source) {
  TopSurface s;
  s.source = std::move(source);
  std::unordered_map<std::uint32_t, std::uint32_t> local;
  for (const auto& t : tris) {
    std::array<std::uint32_t, 3> lt{};
    for (int k = 0; k < 3; ++k) {
      auto [it, fresh] = local.emplace(t[k], static_cast<std::uint32_t>(s.points.size()));
      if (fresh) {
        s.points.push_back(x[t[k]]);
        s.node_tags.push_back(tags[t[k]]);
      }
      lt[k] = it->second;
    }
    s.triangles.push_back(lt);
  }
  return s;
}

}  // namespace

TopSurface surface_from_mesh(const Mesh& mesh, const std::string& group, const std::string& where) {
  const PhysicalGroup* g = mesh.find_physical(2, group);
  if (!g) throw InputError(where, fmt::format("mesh has no surface group '{}'", group));
  std::vector<std::array<std::uint32_t, 3>> tris;
  for (const auto& b : mesh.blocks) {
    if (b.type != ElementType::Triangle || b.entity_dim != 2) continue;
    const Entity* e = mesh.find_entity(2, b.entity_tag);
    if (!e || std::find(e->physicals.begin(), e->physicals.end(), g->tag) == e->physicals.end()) continue;
    for (std::size_t i = 0; i < b.size(); ++i) {
      const auto n = b.element(i);
      tris.push_back({n[0], n[1], n[2]});
    }
  }
  if (tris.empty()) throw InputError(where, fmt::format("surface group '{}' has no triangles", group));
  return compact(mesh.nodes, mesh.node_tags, tris, fmt::format("{}: {}", where, group));
}

TopSurface upward_boundary(std::span<const Point3> x, std::span<const std::uint64_t> tags,
                           std::span<const std::array<std::uint32_t, 4>> tets, double min_nz,
                           std::vector<std::uint32_t>* face_codes) {
  // A face is on the boundary of the set when exactly one of its tetrahedra has it.
  struct Key {
    std::array<std::uint32_t, 3> n;
    bool operator==(const Key& o) const { return n == o.n; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = 1469598103934665603ull;
      for (auto v : k.n) h = (h ^ v) * 1099511628211ull;
      return static_cast<std::size_t>(h);
    }
  };
  std::unordered_map<Key, std::pair<std::uint32_t, int>, Hash> faces;  // -> (tet index * 4 + face, count)
  faces.reserve(tets.size() * 2);
  if (face_codes) face_codes->clear();
  static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (std::size_t e = 0; e < tets.size(); ++e)
    for (int f = 0; f < 4; ++f) {
      Key k{{tets[e][kFace[f][0]], tets[e][kFace[f][1]], tets[e][kFace[f][2]]}};
      std::sort(k.n.begin(), k.n.end());
      auto [it, fresh] = faces.emplace(k, std::make_pair(static_cast<std::uint32_t>(e * 4 + f), 1));
      if (!fresh) ++it->second.second;
    }
  std::vector<std::uint32_t> chosen;
  for (const auto& [k, v] : faces)
    if (v.second == 1) chosen.push_back(v.first);
  std::sort(chosen.begin(), chosen.end());  // deterministic order
  std::vector<std::array<std::uint32_t, 3>> tris;
  for (std::uint32_t code : chosen) {
    const auto& t = tets[code / 4];
    const int f = static_cast<int>(code % 4);
    // Outward normal: the face's orientation seen from outside, whatever the tet's orientation.
    std::array<std::uint32_t, 3> n{t[kFace[f][0]], t[kFace[f][1]], t[kFace[f][2]]};
    const Point3 &a = x[n[0]], &b = x[n[1]], &c = x[n[2]], &d = x[t[f]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double nrm[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double into = nrm[0] * (d[0] - a[0]) + nrm[1] * (d[1] - a[1]) + nrm[2] * (d[2] - a[2]);
    if (into > 0)
      for (double& v : nrm) v = -v;
    const double len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    if (len > 0 && nrm[2] / len > min_nz) {
      tris.push_back(n);
      if (face_codes) face_codes->push_back(code);
    }
  }
  return compact(x, tags, tris, "upward boundary faces");
}

TopSurface surface_from_results(const FieldSeriesReader& r) {
  const auto x = r.coordinates();
  const auto tags = r.node_tags();
  const auto tri = r.cells(ElementType::Triangle);
  if (!tri.empty()) {
    std::vector<std::array<std::uint32_t, 3>> tris(tri.size() / 3);
    for (std::size_t i = 0; i < tris.size(); ++i) tris[i] = {tri[3 * i], tri[3 * i + 1], tri[3 * i + 2]};
    return compact(x, tags, tris, r.path() + ": triangles");
  }
  const auto tet = r.cells(ElementType::Tetrahedron);
  if (tet.empty()) throw InputError(r.path(), "has neither triangles nor tetrahedra: give the mesh of the top surface");
  std::vector<std::array<std::uint32_t, 4>> tets(tet.size() / 4);
  for (std::size_t i = 0; i < tets.size(); ++i) tets[i] = {tet[4 * i], tet[4 * i + 1], tet[4 * i + 2], tet[4 * i + 3]};
  TopSurface s = upward_boundary(x, tags, tets);
  s.source = r.path() + ": upward boundary faces";
  return s;
}

}  // namespace ugs::insar
