// Test meshes with faults and the checks every faulted mesh must pass (tests/fault_insertion).
//
// Faults are marked as the issue describes: all tetrahedron faces whose three nodes satisfy a
// predicate (e.g. on the plane x = 3 inside a rectangle) become a `fault:<name>` triangle group.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <vector>

#include "ugs/formats/mesh.hpp"
#include "ugs/meshing/box_mesh.hpp"

namespace ugs::test {

using NodePredicate = std::function<bool(const Point3&)>;
using FacePredicate = std::function<bool(const Point3&, const Point3&, const Point3&)>;

// Unit-spaced box [0,n]^3 (n cells per axis), Kuhn-split.
inline Mesh unit_box(int n) {
  BoxMeshSpec s;
  s.x = s.y = s.z = linspace(0, n, n);
  return make_box_mesh(s);
}

inline bool near(double a, double b) { return std::abs(a - b) < 1e-9; }

// Every distinct tetrahedron face accepted by `on`, as a triangle group fault:<name>.
inline std::size_t add_fault_faces(Mesh& m, const std::string& name, const FacePredicate& on) {
  std::set<std::array<std::uint32_t, 3>> faces;
  for (const auto& b : m.blocks) {
    if (b.type != ElementType::Tetrahedron) continue;
    for (std::size_t e = 0; e < b.size(); ++e) {
      const auto c = b.element(e);
      for (int skip = 0; skip < 4; ++skip) {
        std::array<std::uint32_t, 3> f{};
        int k = 0;
        for (int q = 0; q < 4; ++q)
          if (q != skip) f[k++] = c[q];
        if (!on(m.nodes[f[0]], m.nodes[f[1]], m.nodes[f[2]])) continue;
        std::sort(f.begin(), f.end());
        faces.insert(f);
      }
    }
  }
  const int ent = m.entity_for_physical(2, "fault:" + name);
  for (const auto& f : faces) {
    ElementBlock& blk = m.block(2, ent, ElementType::Triangle);
    m.add_element(blk, f);
  }
  m.update_entity_bboxes();
  return faces.size();
}

// Every distinct tetrahedron face whose three nodes satisfy `on`.
inline std::size_t add_fault_group(Mesh& m, const std::string& name, const NodePredicate& on) {
  return add_fault_faces(m, name, [&](const Point3& a, const Point3& b, const Point3& c) { return on(a) && on(b) && on(c); });
}

inline const ElementBlock* find_block(const Mesh& m, int dim, const std::string& name, ElementType type) {
  const PhysicalGroup* p = m.find_physical(dim, name);
  if (!p) return nullptr;
  for (const auto& b : m.blocks) {
    const Entity* e = m.find_entity(b.entity_dim, b.entity_tag);
    if (b.type == type && e && std::find(e->physicals.begin(), e->physicals.end(), p->tag) != e->physicals.end())
      return &b;
  }
  return nullptr;
}

// Number of nodes at each location (keyed by rounded coordinates).
inline std::map<std::array<long long, 3>, int> copies_by_location(const Mesh& m) {
  std::map<std::array<long long, 3>, int> c;
  for (const auto& x : m.nodes) ++c[{std::llround(x[0] * 1e6), std::llround(x[1] * 1e6), std::llround(x[2] * 1e6)}];
  return c;
}
inline int copies_at(const Mesh& m, const Point3& x) {
  const auto c = copies_by_location(m);
  auto it = c.find({std::llround(x[0] * 1e6), std::llround(x[1] * 1e6), std::llround(x[2] * 1e6)});
  return it == c.end() ? 0 : it->second;
}

// Glues every twin back: each node maps to the node with the smallest tag among those joined by
// interface prisms; prisms become their side-1 triangles in dim-2 groups of the same name.
inline Mesh glue(const Mesh& m) {
  std::vector<std::uint32_t> parent(m.num_nodes());
  std::iota(parent.begin(), parent.end(), 0u);
  std::function<std::uint32_t(std::uint32_t)> find = [&](std::uint32_t x) {
    return parent[x] == x ? x : parent[x] = find(parent[x]);
  };
  for (const auto& b : m.blocks) {
    if (b.type != ElementType::Prism) continue;
    for (std::size_t e = 0; e < b.size(); ++e) {
      const auto c = b.element(e);
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t r1 = find(c[k]), r2 = find(c[k + 3]);
        if (r1 == r2) continue;
        if (m.node_tags[r1] < m.node_tags[r2])
          parent[r2] = r1;
        else
          parent[r1] = r2;
      }
    }
  }
  Mesh g;
  std::vector<std::uint32_t> new_index(m.num_nodes(), 0xffffffffu);
  // Originals keep their relative order (they come first in a faulted mesh).
  for (std::uint32_t v = 0; v < m.num_nodes(); ++v)
    if (find(v) == v) {
      new_index[v] = static_cast<std::uint32_t>(g.nodes.size());
      g.nodes.push_back(m.nodes[v]);
      g.node_tags.push_back(m.node_tags[v]);
    }
  for (std::uint32_t v = 0; v < m.num_nodes(); ++v) new_index[v] = new_index[find(v)];
  g.physicals = m.physicals;
  g.entities = m.entities;
  for (auto& p : g.physicals)
    if (p.dim == 3 && p.name.rfind("fault:", 0) == 0) p.dim = 2;
  for (const auto& b : m.blocks) {
    ElementBlock nb;
    nb.entity_dim = b.entity_dim;
    nb.entity_tag = b.entity_tag;
    nb.type = b.type;
    nb.tags = b.tags;
    if (b.type == ElementType::Prism) {
      nb.type = ElementType::Triangle;
      nb.entity_dim = 2;
      for (std::size_t e = 0; e < b.size(); ++e)
        for (int k = 0; k < 3; ++k) nb.nodes.push_back(new_index[b.element(e)[k]]);
    } else {
      for (auto v : b.nodes) nb.nodes.push_back(new_index[v]);
    }
    g.blocks.push_back(std::move(nb));
  }
  for (auto& e : g.entities)
    for (const auto& b : m.blocks)
      if (b.type == ElementType::Prism && b.entity_dim == e.dim && b.entity_tag == e.tag) e.dim = 2;
  return g;
}

// Elements by tag with their node tags, per type (triangles compared as sets when `tri_as_set`).
inline std::map<std::pair<int, std::uint64_t>, std::vector<std::uint64_t>> elements_by_tag(const Mesh& m, bool tri_as_set) {
  std::map<std::pair<int, std::uint64_t>, std::vector<std::uint64_t>> r;
  for (const auto& b : m.blocks)
    for (std::size_t e = 0; e < b.size(); ++e) {
      std::vector<std::uint64_t> t;
      for (auto v : b.element(e)) t.push_back(m.node_tags[v]);
      if (tri_as_set && b.type == ElementType::Triangle) std::sort(t.begin(), t.end());
      r[{static_cast<int>(b.type), b.tags[e]}] = t;
    }
  return r;
}

inline std::map<std::uint64_t, Point3> nodes_by_tag(const Mesh& m) {
  std::map<std::uint64_t, Point3> r;
  for (std::size_t i = 0; i < m.num_nodes(); ++i) r[m.node_tags[i]] = m.nodes[i];
  return r;
}

// The structural checks of a faulted mesh (issue 5):
// - twins have the same coordinates; the prism normal agrees over each fault with `normals`;
// - each side's triangle is a face of exactly one tetrahedron, on its side (side 1 behind the normal);
// - no tetrahedron holds a node and its distinct twin of the same prism;
// - all tetrahedra positive; boundary triangles are faces of exactly one tetrahedron.
inline void check_faulted(const Mesh& m) {
  std::vector<std::vector<std::uint32_t>> tets_of(m.num_nodes());
  std::vector<std::array<std::uint32_t, 4>> tets;
  for (const auto& b : m.blocks)
    if (b.type == ElementType::Tetrahedron)
      for (std::size_t e = 0; e < b.size(); ++e) {
        const auto c = b.element(e);
        std::array<std::uint32_t, 4> t{c[0], c[1], c[2], c[3]};
        EXPECT_GT(tet_signed_volume(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]], m.nodes[t[3]]), 0);
        for (auto v : t) tets_of[v].push_back(static_cast<std::uint32_t>(tets.size()));
        tets.push_back(t);
      }
  auto has = [](const std::array<std::uint32_t, 4>& t, std::uint32_t v) {
    return std::find(t.begin(), t.end(), v) != t.end();
  };
  auto face_tets = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    std::vector<std::uint32_t> r;
    for (auto t : tets_of[a])
      if (has(tets[t], b) && has(tets[t], c)) r.push_back(t);
    return r;
  };
  auto fourth = [&](std::uint32_t t, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    for (auto v : tets[t])
      if (v != a && v != b && v != c) return v;
    return a;
  };
  for (const auto& b : m.blocks) {
    if (b.type == ElementType::Triangle) {
      // Boundary triangles border one tetrahedron; other groups (faults not inserted) one or two.
      const bool boundary = m.physical_name_of(b.entity_dim, b.entity_tag).rfind("bnd:", 0) == 0;
      for (std::size_t e = 0; e < b.size(); ++e) {
        const auto c = b.element(e);
        const auto n = face_tets(c[0], c[1], c[2]).size();
        if (boundary)
          EXPECT_EQ(n, 1u) << "boundary triangle " << b.tags[e];
        else
          EXPECT_TRUE(n == 1 || n == 2) << "triangle " << b.tags[e];
      }
    }
    if (b.type != ElementType::Prism) continue;
    for (std::size_t e = 0; e < b.size(); ++e) {
      const auto c = b.element(e);
      for (int k = 0; k < 3; ++k)
        for (int d = 0; d < 3; ++d) EXPECT_EQ(m.nodes[c[k]][d], m.nodes[c[k + 3]][d]);
      const bool any_split = c[0] != c[3] || c[1] != c[4] || c[2] != c[5];
      if (!any_split) continue;
      const Point3& a = m.nodes[c[0]];
      const Point3 u{m.nodes[c[1]][0] - a[0], m.nodes[c[1]][1] - a[1], m.nodes[c[1]][2] - a[2]};
      const Point3 w{m.nodes[c[2]][0] - a[0], m.nodes[c[2]][1] - a[1], m.nodes[c[2]][2] - a[2]};
      const Point3 n{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
      for (int side = 0; side < 2; ++side) {
        const auto ft = face_tets(c[3 * side], c[3 * side + 1], c[3 * side + 2]);
        ASSERT_EQ(ft.size(), 1u) << "prism " << b.tags[e] << " side " << side + 1;
        const Point3& d = m.nodes[fourth(ft[0], c[3 * side], c[3 * side + 1], c[3 * side + 2])];
        const double h = (d[0] - a[0]) * n[0] + (d[1] - a[1]) * n[1] + (d[2] - a[2]) * n[2];
        EXPECT_TRUE(side == 0 ? h < 0 : h > 0) << "prism " << b.tags[e] << " side " << side + 1;
      }
      for (int k = 0; k < 3; ++k) {
        if (c[k] == c[k + 3]) continue;
        for (auto t : tets_of[c[k]])
          for (int j = 0; j < 3; ++j) {
            if (c[j] != c[j + 3]) {
              EXPECT_FALSE(has(tets[t], c[j + 3])) << "tet holds both sides of prism " << b.tags[e];
            }
          }
      }
    }
  }
}

// Glued mesh equals the input: nodes by tag, every element by tag with its node order; the fault
// triangles (now prisms) as node sets, since insertion orients them side 1 -> side 2.
inline void expect_glues_back(const Mesh& faulted, const Mesh& input) {
  std::set<std::uint64_t> fault_tags;
  for (const auto& b : faulted.blocks)
    if (b.type == ElementType::Prism) fault_tags.insert(b.tags.begin(), b.tags.end());
  const Mesh g = glue(faulted);
  EXPECT_EQ(g.num_nodes(), input.num_nodes());
  EXPECT_EQ(nodes_by_tag(g), nodes_by_tag(input));
  EXPECT_EQ(elements_by_tag(g, true), elements_by_tag(input, true));
  const auto exact_g = elements_by_tag(g, false), exact_in = elements_by_tag(input, false);
  ASSERT_EQ(exact_g.size(), exact_in.size());
  std::size_t differ = 0;
  for (const auto& [k, v] : exact_in)
    if (!fault_tags.count(k.second) && exact_g.at(k) != v) ++differ;
  EXPECT_EQ(differ, 0u);
}

}  // namespace ugs::test
