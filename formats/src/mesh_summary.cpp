#include "ugs/formats/mesh_summary.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

namespace ugs {

MeshSummary summarize(const Mesh& mesh) {
  MeshSummary s;
  s.nodes = mesh.num_nodes();
  constexpr double inf = std::numeric_limits<double>::infinity();
  s.bbox = {inf, inf, inf, -inf, -inf, -inf};
  for (const auto& x : mesh.nodes)
    for (int k = 0; k < 3; ++k) {
      s.bbox[k] = std::min(s.bbox[k], x[k]);
      s.bbox[k + 3] = std::max(s.bbox[k + 3], x[k]);
    }
  if (mesh.nodes.empty()) s.bbox = {};
  s.min_tet_volume = inf;
  s.max_tet_volume = -inf;
  for (const auto& b : mesh.blocks) {
    s.elements[b.type] += b.size();
    const Entity* e = mesh.find_entity(b.entity_dim, b.entity_tag);
    if (!e || e->physicals.empty()) {
      s.elements_without_group += b.size();
    } else {
      for (int p : e->physicals) {
        auto& g = s.groups[{b.entity_dim, p}];
        g.dim = b.entity_dim;
        if (const PhysicalGroup* pg = mesh.find_physical_tag(b.entity_dim, p)) g.name = pg->name;
        g.elements[b.type] += b.size();
      }
    }
    if (b.type != ElementType::Tetrahedron) continue;
    for (std::size_t i = 0; i < b.size(); ++i) {
      auto n = b.element(i);
      const double v = tet_signed_volume(mesh.nodes[n[0]], mesh.nodes[n[1]], mesh.nodes[n[2]], mesh.nodes[n[3]]);
      s.min_tet_volume = std::min(s.min_tet_volume, v);
      s.max_tet_volume = std::max(s.max_tet_volume, v);
      s.total_tet_volume += v;
      if (v <= 0) ++s.inverted_tets;
    }
  }
  if (s.elements[ElementType::Tetrahedron] == 0) s.min_tet_volume = s.max_tet_volume = 0;
  return s;
}

namespace {
std::string plural(ElementType t) {
  switch (t) {
    case ElementType::Tetrahedron: return "tetrahedra";
    case ElementType::Prism: return "interface prisms";
    default: return std::string(element_name(t)) + "s";
  }
}
}  // namespace

std::string format_summary(const MeshSummary& s) {
  std::string out;
  auto add = [&out]<class... A>(fmt::format_string<A...> f, A&&... a) {
    fmt::format_to(std::back_inserter(out), f, std::forward<A>(a)...);
  };
  add("nodes: {}\n", s.nodes);
  for (const auto& [t, n] : s.elements)
    if (n) add("{}: {}\n", plural(t), n);
  add("bounding box: x [{}, {}] y [{}, {}] z [{}, {}] m\n", s.bbox[0], s.bbox[3], s.bbox[1], s.bbox[4], s.bbox[2], s.bbox[5]);
  auto it = s.elements.find(ElementType::Tetrahedron);
  if (it != s.elements.end() && it->second) {
    add("tetrahedron volume: min {:.6g} max {:.6g} total {:.10g} m3\n", s.min_tet_volume, s.max_tet_volume, s.total_tet_volume);
  }
  add("inverted elements: {}\n", s.inverted_tets);
  add("physical groups: {}\n", s.groups.size());
  for (const auto& [key, g] : s.groups) {
    add("  {}D {:>4} {:<32}", g.dim, key.second, g.name.empty() ? std::string("(unnamed)") : "\"" + g.name + "\"");
    for (const auto& [t, n] : g.elements) add(" {} {}", n, plural(t));
    add("\n");
  }
  if (s.elements_without_group) add("elements without physical group: {}\n", s.elements_without_group);
  return out;
}

}  // namespace ugs
