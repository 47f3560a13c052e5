#include "ugs/meshing/plan.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <unordered_map>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs {

double Plan::area(std::size_t t) const {
  const auto& [a, b, c] = triangles[t];
  return 0.5 * ((xy[b][0] - xy[a][0]) * (xy[c][1] - xy[a][1]) - (xy[b][1] - xy[a][1]) * (xy[c][0] - xy[a][0]));
}

XY Plan::centroid(std::size_t t) const {
  const auto& [a, b, c] = triangles[t];
  return {(xy[a][0] + xy[b][0] + xy[c][0]) / 3.0, (xy[a][1] + xy[b][1] + xy[c][1]) / 3.0};
}

const PlanLineGroup* Plan::find_line_group(const std::string& name) const {
  for (const auto& g : lines)
    if (g.name == name) return &g;
  return nullptr;
}

namespace {

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

}  // namespace

Plan plan_from_mesh(const Mesh& mesh, const std::string& source) {
  Plan p;
  p.source = source;
  p.provenance = mesh.provenance;

  // Triangles of every 2D block, in file order.
  std::vector<std::array<std::uint32_t, 3>> tri_nodes;
  for (const auto& b : mesh.blocks) {
    if (b.type == ElementType::Tetrahedron)
      throw InputError(source, "is a 3D mesh (it has tetrahedra); expected a 2D plan of triangles");
    if (b.type != ElementType::Triangle) continue;
    for (std::size_t i = 0; i < b.size(); ++i) {
      auto e = b.element(i);
      tri_nodes.push_back({e[0], e[1], e[2]});
      p.triangle_tags.push_back(b.tags[i]);
    }
  }
  if (tri_nodes.empty()) throw InputError(source, "has no triangles; expected a 2D plan (e.g. from ugs-mesh2d)");

  // Columns: nodes used by triangles, ordered by tag.
  std::vector<std::uint32_t> used;
  {
    std::vector<char> is_used(mesh.num_nodes(), 0);
    for (const auto& t : tri_nodes)
      for (auto n : t) is_used[n] = 1;
    for (std::uint32_t n = 0; n < is_used.size(); ++n)
      if (is_used[n]) used.push_back(n);
  }
  std::sort(used.begin(), used.end(), [&](auto a, auto b) { return mesh.node_tags[a] < mesh.node_tags[b]; });
  std::vector<std::uint32_t> column_of(mesh.num_nodes(), UINT32_MAX);
  p.node_tags.reserve(used.size());
  p.xy.reserve(used.size());
  for (std::uint32_t c = 0; c < used.size(); ++c) {
    column_of[used[c]] = c;
    if (c > 0 && mesh.node_tags[used[c]] == mesh.node_tags[used[c - 1]])
      throw InputError(source, fmt::format("node tag {} appears twice", mesh.node_tags[used[c]]));
    p.node_tags.push_back(mesh.node_tags[used[c]]);
    p.xy.push_back({mesh.nodes[used[c]][0], mesh.nodes[used[c]][1]});
  }
  auto at = [&](const XY& x) { return fmt::format("x={:.2f}, y={:.2f}", x[0], x[1]); };

  // No two columns at the same place.
  {
    std::vector<std::uint32_t> order(p.xy.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return p.xy[a] < p.xy[b]; });
    for (std::size_t i = 1; i < order.size(); ++i)
      if (p.xy[order[i]] == p.xy[order[i - 1]])
        throw InputError(source, fmt::format("nodes {} and {} are at the same place ({}): their columns would coincide",
                                             p.node_tags[std::min(order[i], order[i - 1])],
                                             p.node_tags[std::max(order[i], order[i - 1])], at(p.xy[order[i]])));
  }

  p.triangles.reserve(tri_nodes.size());
  for (const auto& t : tri_nodes) p.triangles.push_back({column_of[t[0]], column_of[t[1]], column_of[t[2]]});
  auto describe = [&](std::size_t t) {
    const auto& n = p.triangles[t];
    return fmt::format("triangle {} (nodes {}, {}, {}) at {}", p.triangle_tags[t], p.node_tags[n[0]], p.node_tags[n[1]],
                       p.node_tags[n[2]], at(p.centroid(t)));
  };

  // Degenerate triangles, then orientation: the majority sets it, the others are inverted.
  std::size_t positive = 0;
  for (std::size_t t = 0; t < p.triangles.size(); ++t) {
    const auto& [a, b, c] = p.triangles[t];
    double longest = 0;
    for (auto [u, v] : {std::pair{a, b}, {b, c}, {c, a}})
      longest = std::max(longest, std::hypot(p.xy[u][0] - p.xy[v][0], p.xy[u][1] - p.xy[v][1]));
    const double A = p.area(t);
    if (a == b || b == c || a == c || std::abs(A) <= 1e-10 * longest * longest)
      throw InputError(source, "degenerate " + describe(t) + " (zero area)");
    positive += A > 0;
  }
  const bool flip = positive * 2 < p.triangles.size();
  for (std::size_t t = 0; t < p.triangles.size(); ++t) {
    if ((p.area(t) > 0) == flip)
      throw InputError(source, fmt::format("inverted {}: its orientation is opposite to the other {} triangles",
                                           describe(t), flip ? p.triangles.size() - positive : positive));
    if (flip) std::swap(p.triangles[t][1], p.triangles[t][2]);
  }

  // Duplicates, and edges: at most two triangles each, traversed in opposite directions.
  {
    std::map<std::array<std::uint32_t, 3>, std::size_t> exact;
    for (std::size_t t = 0; t < p.triangles.size(); ++t) {
      auto s = p.triangles[t];
      std::sort(s.begin(), s.end());
      auto [it, fresh] = exact.emplace(s, t);
      if (!fresh)
        throw InputError(source, fmt::format("duplicate triangles {} and {} (nodes {}, {}, {}) at {}",
                                             p.triangle_tags[it->second], p.triangle_tags[t], p.node_tags[s[0]],
                                             p.node_tags[s[1]], p.node_tags[s[2]], at(p.centroid(t))));
    }
    struct EdgeUse {
      std::size_t first;  // triangle
      int direction, uses;
    };
    std::unordered_map<std::uint64_t, EdgeUse> edges;
    edges.reserve(p.triangles.size() * 2);
    for (std::size_t t = 0; t < p.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const auto a = p.triangles[t][k], b = p.triangles[t][(k + 1) % 3];
        const auto key = edge_key(a, b);
        const int dir = a < b ? 1 : -1;
        auto [it, fresh] = edges.emplace(key, EdgeUse{t, dir, 1});
        if (fresh) continue;
        if (++it->second.uses > 2)
          throw InputError(source, fmt::format("edge between nodes {} and {} is shared by more than two triangles ({})",
                                               p.node_tags[a], p.node_tags[b], describe(t)));
        if (it->second.direction == dir)
          throw InputError(source, fmt::format("triangles {} and {} overlap: they lie on the same side of their common "
                                               "edge (nodes {} and {}) near {}",
                                               p.triangle_tags[it->second.first], p.triangle_tags[t], p.node_tags[a],
                                               p.node_tags[b], at(p.centroid(t))));
      }
  }

  // Named line groups (line elements), kept when their nodes are plan columns.
  for (const auto& b : mesh.blocks) {
    if (b.type != ElementType::Line) continue;
    const Entity* e = mesh.find_entity(b.entity_dim, b.entity_tag);
    if (!e) continue;
    for (int ptag : e->physicals) {
      const PhysicalGroup* pg = mesh.find_physical_tag(b.entity_dim, ptag);
      if (!pg || pg->name.empty()) continue;
      PlanLineGroup* g = nullptr;
      for (auto& l : p.lines)
        if (l.name == pg->name) g = &l;
      if (!g) g = &p.lines.emplace_back(PlanLineGroup{pg->name, {}});
      for (std::size_t i = 0; i < b.size(); ++i) {
        auto n = b.element(i);
        const auto a = column_of[n[0]], c = column_of[n[1]];
        if (a == UINT32_MAX || c == UINT32_MAX)
          throw InputError(source, fmt::format("line element {} of group '{}' uses node {} which no triangle uses",
                                               b.tags[i], pg->name, mesh.node_tags[a == UINT32_MAX ? n[0] : n[1]]));
        if (a != c) g->edges.push_back({a, c});
      }
    }
  }
  // Line groups in the order of their physical tags (the file's order of definition).
  std::stable_sort(p.lines.begin(), p.lines.end(), [&](const PlanLineGroup& a, const PlanLineGroup& b) {
    const PhysicalGroup* pa = mesh.find_physical(1, a.name);
    const PhysicalGroup* pb = mesh.find_physical(1, b.name);
    return (pa ? pa->tag : 0) < (pb ? pb->tag : 0);
  });
  return p;
}

}  // namespace ugs
