// Test support for the meshing tests: small random plans and the independent checks a layered
// mesh must pass (face conformity, boundary tagging, volumes).
#pragma once
#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <random>
#include <string>
#include <unordered_map>
#include <vector>

#include "ugs/formats/mesh.hpp"

namespace ugs::test {

// A rectangular plan of (nx+1) x (ny+1) nodes, each cell cut by a random diagonal, interior nodes
// jittered, node tags a random permutation (so the global numbering has no structure).
inline Mesh random_plan_mesh(int nx, int ny, double lx, double ly, unsigned seed, bool shuffle_tags = true) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  Mesh m;
  const int n = (nx + 1) * (ny + 1);
  std::vector<std::uint64_t> tags(n);
  std::iota(tags.begin(), tags.end(), 1);
  if (shuffle_tags) std::shuffle(tags.begin(), tags.end(), rng);
  const double dx = lx / nx, dy = ly / ny;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      double x = i * dx, y = j * dy;
      if (i > 0 && i < nx) x += jitter(rng) * dx;
      if (j > 0 && j < ny) y += jitter(rng) * dy;
      m.add_node({x, y, 0.0}, tags[j * (nx + 1) + i]);
    }
  const int e = m.entity_for_physical(2, "region:domain");
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (nx + 1) + i); };
  std::bernoulli_distribution coin(0.5);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      auto& b = m.block(2, e, ElementType::Triangle);
      const std::uint32_t a = id(i, j), bb = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      // Random diagonal and random orientation of the triangles' node order within each cell.
      std::array<std::uint32_t, 3> t1, t2;
      if (coin(rng)) t1 = {a, bb, c}, t2 = {a, c, d};
      else t1 = {a, bb, d}, t2 = {bb, c, d};
      std::rotate(t1.begin(), t1.begin() + (rng() % 3), t1.end());
      std::rotate(t2.begin(), t2.begin() + (rng() % 3), t2.end());
      m.add_element(b, t1);
      m.add_element(b, t2);
    }
  return m;
}

struct FaceKey {
  std::array<std::uint32_t, 3> n;
  bool operator==(const FaceKey& o) const { return n == o.n; }
};
struct FaceHash {
  std::size_t operator()(const FaceKey& k) const {
    return (static_cast<std::size_t>(k.n[0]) * 73856093u) ^ (static_cast<std::size_t>(k.n[1]) * 19349663u) ^
           (static_cast<std::size_t>(k.n[2]) * 83492791u);
  }
};
inline FaceKey face(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  std::array<std::uint32_t, 3> n{a, b, c};
  std::sort(n.begin(), n.end());
  return {n};
}

// The triangle block of the 2D physical group `name` (nullptr: none).
inline const ElementBlock* triangle_group(const Mesh& m, const std::string& name) {
  const auto* p = m.find_physical(2, name);
  if (!p) return nullptr;
  for (const auto& b : m.blocks)
    if (b.entity_dim == 2 && b.type == ElementType::Triangle)
      for (const auto& e : m.entities)
        if (e.dim == 2 && e.tag == b.entity_tag)
          for (int ph : e.physicals)
            if (ph == p->tag) return &b;
  return nullptr;
}

struct Conformity {
  std::size_t tets = 0, interior_faces = 0, outer_faces = 0;
  std::size_t over_shared = 0;          // faces in more than two tetrahedra
  std::size_t untagged_outer = 0;       // outer faces without a bnd:* triangle
  std::size_t tagged_not_outer = 0;     // bnd:* triangles that are not outer faces
  std::size_t doubly_tagged = 0;        // outer faces tagged twice
  std::size_t fault_not_face = 0;       // fault:* triangles that are no tetrahedron face
  std::size_t nonpositive = 0, repeated_nodes = 0;
  double volume = 0;
  std::map<std::string, double> volume_of;  // per mat:* group
};

inline Conformity check_conformity(const Mesh& m) {
  Conformity c;
  std::unordered_map<FaceKey, int, FaceHash> count;
  for (const auto& b : m.blocks) {
    if (b.type != ElementType::Tetrahedron) continue;
    const std::string name = m.physical_name_of(b.entity_dim, b.entity_tag);
    for (std::size_t i = 0; i < b.size(); ++i) {
      auto n = b.element(i);
      ++c.tets;
      std::array<std::uint32_t, 4> s{n[0], n[1], n[2], n[3]};
      std::sort(s.begin(), s.end());
      if (std::adjacent_find(s.begin(), s.end()) != s.end()) ++c.repeated_nodes;
      const double v = tet_signed_volume(m.nodes[n[0]], m.nodes[n[1]], m.nodes[n[2]], m.nodes[n[3]]);
      if (!(v > 0)) ++c.nonpositive;
      c.volume += v;
      c.volume_of[name] += v;
      ++count[face(n[0], n[1], n[2])];
      ++count[face(n[0], n[1], n[3])];
      ++count[face(n[0], n[2], n[3])];
      ++count[face(n[1], n[2], n[3])];
    }
  }
  std::unordered_map<FaceKey, int, FaceHash> tagged;
  for (const auto& b : m.blocks) {
    if (b.type != ElementType::Triangle) continue;
    const std::string name = m.physical_name_of(b.entity_dim, b.entity_tag);
    const bool bnd = name.rfind("bnd:", 0) == 0, fault = name.rfind("fault:", 0) == 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      auto n = b.element(i);
      const auto f = face(n[0], n[1], n[2]);
      auto it = count.find(f);
      if (bnd) {
        if (it == count.end() || it->second != 1) ++c.tagged_not_outer;
        if (++tagged[f] > 1) ++c.doubly_tagged;
      }
      if (fault && it == count.end()) ++c.fault_not_face;
    }
  }
  for (const auto& [f, k] : count) {
    if (k == 2) ++c.interior_faces;
    else if (k == 1) {
      ++c.outer_faces;
      if (!tagged.count(f)) ++c.untagged_outer;
    } else {
      ++c.over_shared;
    }
  }
  return c;
}

}  // namespace ugs::test
