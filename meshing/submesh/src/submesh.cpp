#include "ugs/meshing/submesh.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <set>
#include <unordered_map>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/formats/face_key.hpp"

namespace ugs {
namespace {

// The four faces of a tetrahedron, as local node positions.
constexpr int kTetFaces[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};

std::string strip(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0 ? s.substr(prefix.size()) : s; }

std::string list_groups(const Mesh& m, const std::string& prefix, std::initializer_list<int> dims) {
  std::string s;
  for (const auto& p : m.physicals)
    if (p.name.rfind(prefix, 0) == 0 && std::find(dims.begin(), dims.end(), p.dim) != dims.end())
      s += fmt::format("{}{} ({})", s.empty() ? "" : ", ", p.name.substr(prefix.size()), p.tag);
  return s.empty() ? "none" : s;
}

bool has_physical_in(const Entity* e, const std::set<int>& tags) {
  if (!e) return false;
  for (int p : e->physicals)
    if (tags.count(p)) return true;
  return false;
}

}  // namespace

bool inside_rings(const std::vector<std::vector<std::array<double, 2>>>& rings, double x, double y) {
  bool in = false;
  for (const auto& r : rings) {
    const std::size_t n = r.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const double xi = r[i][0], yi = r[i][1], xj = r[j][0], yj = r[j][1];
      if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) in = !in;
    }
  }
  return in;
}

Mesh extract_submesh(const Mesh& parent, const SubmeshSpec& spec, SubmeshReport* report) {
  SubmeshReport rep;
  // 1. Materials: volume groups mat:<name>, chosen by name or physical tag.
  std::set<int> material_tags;
  for (const auto& want : spec.materials) {
    const std::string name = strip(want, "mat:");
    const PhysicalGroup* hit = nullptr;
    for (const auto& p : parent.physicals)
      if (p.dim == 3 && p.name.rfind("mat:", 0) == 0 && (p.name.substr(4) == name || std::to_string(p.tag) == name)) hit = &p;
    if (!hit)
      throw InputError("", fmt::format("no material '{}' in the mesh (materials: {})", want, list_groups(parent, "mat:", {3})));
    material_tags.insert(hit->tag);
  }
  if (spec.materials.empty())
    for (const auto& p : parent.physicals)
      if (p.dim == 3 && p.name.rfind("mat:", 0) == 0) material_tags.insert(p.tag);

  // 2. Fault groups: which are barriers, as triangles or as interface prisms.
  std::map<std::pair<int, int>, std::string> fault_of_entity;  // (dim, entity tag) -> fault name
  std::set<std::string> barrier_names;
  for (const auto& want : spec.barriers) {
    const std::string name = strip(want, "fault:");
    if (!parent.find_physical(2, "fault:" + name) && !parent.find_physical(3, "fault:" + name))
      throw InputError("", fmt::format("no fault 'fault:{}' to use as a barrier (faults: {})", name,
                                       list_groups(parent, "fault:", {2, 3})));
    barrier_names.insert(name);
  }
  for (const auto& e : parent.entities)
    for (int p : e.physicals)
      if (const PhysicalGroup* g = parent.find_physical_tag(e.dim, p); g && g->name.rfind("fault:", 0) == 0)
        fault_of_entity.emplace(std::make_pair(e.dim, e.tag), g->name.substr(6));
  auto fault_name = [&](const ElementBlock& b) -> const std::string* {
    auto it = fault_of_entity.find({b.entity_dim, b.entity_tag});
    return it == fault_of_entity.end() ? nullptr : &it->second;
  };

  // 3. Tetrahedra kept: of the materials, centroid inside the polygon.
  struct KeptTet {
    std::size_t block, index;
  };
  std::vector<KeptTet> kept;
  std::set<std::string> kept_materials;
  for (std::size_t bi = 0; bi < parent.blocks.size(); ++bi) {
    const ElementBlock& b = parent.blocks[bi];
    if (b.type != ElementType::Tetrahedron) continue;
    const Entity* e = parent.find_entity(b.entity_dim, b.entity_tag);
    if (!has_physical_in(e, material_tags)) continue;
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (!spec.rings.empty()) {
        double cx = 0, cy = 0;
        for (auto n : b.element(i)) cx += parent.nodes[n][0], cy += parent.nodes[n][1];
        if (!inside_rings(spec.rings, 0.25 * cx, 0.25 * cy)) {
          ++rep.clipped_tetrahedra;
          continue;
        }
      }
      kept.push_back({bi, i});
    }
  }
  if (kept.empty())
    throw InputError("", spec.rings.empty() ? "the chosen materials have no tetrahedra"
                                            : "no tetrahedron of the chosen materials has its centroid inside the polygon");

  // 4. Sub-mesh nodes: the parent nodes of kept tetrahedra, in parent order, with parent tags.
  std::vector<std::uint32_t> sub_of_parent(parent.num_nodes(), UINT32_MAX);
  for (const auto& k : kept)
    for (auto n : parent.blocks[k.block].element(k.index)) sub_of_parent[n] = 0;
  Mesh sub;
  for (std::uint32_t n = 0; n < parent.num_nodes(); ++n)
    if (sub_of_parent[n] == 0) sub_of_parent[n] = sub.add_node(parent.nodes[n], parent.node_tags[n]);
  std::vector<std::array<std::uint32_t, 4>> tet_nodes(kept.size());
  for (std::size_t t = 0; t < kept.size(); ++t) {
    const auto el = parent.blocks[kept[t].block].element(kept[t].index);
    for (int j = 0; j < 4; ++j) tet_nodes[t][j] = sub_of_parent[el[j]];
  }

  // 5. Barrier faces given as triangles, and the interface prisms (dropped; ties for non-barriers).
  std::unordered_map<FaceKey, std::string, FaceKeyHash> barrier_faces;
  std::map<std::string, std::vector<std::pair<std::uint32_t, std::uint32_t>>> ties;
  std::set<std::pair<std::uint32_t, std::uint32_t>> tie_seen;
  for (const ElementBlock& b : parent.blocks) {
    const std::string* fault = fault_name(b);
    const bool barrier = fault && barrier_names.count(*fault);
    if (b.type == ElementType::Triangle && barrier) {
      for (std::size_t i = 0; i < b.size(); ++i) {
        const auto el = b.element(i);
        barrier_faces.emplace(face_key(el[0], el[1], el[2]), *fault);
      }
    } else if (b.type == ElementType::Prism) {
      rep.dropped_interface_elements += b.size();
      if (barrier) continue;
      const std::string group = fault ? *fault : "interface";
      for (std::size_t i = 0; i < b.size(); ++i) {
        const auto el = b.element(i);
        for (int j = 0; j < 3; ++j) {
          const std::uint32_t a = sub_of_parent[el[j]], c = sub_of_parent[el[j + 3]];
          if (a == UINT32_MAX || c == UINT32_MAX || a == c) continue;
          if (tie_seen.insert({std::min(a, c), std::max(a, c)}).second) ties[group].push_back({a, c});
        }
      }
    }
  }

  // 6. Cut along barrier triangles: split the tetrahedra around each barrier node into groups
  //    joined across non-barrier faces; the first group keeps the node, each other one gets a twin.
  std::map<std::string, std::vector<std::pair<std::uint32_t, std::uint32_t>>> twins;
  if (!barrier_faces.empty()) {
    std::vector<char> on_barrier(parent.num_nodes(), 0);
    for (const auto& [f, name] : barrier_faces)
      for (auto n : f) on_barrier[n] = 1;
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> tets_at;  // parent node -> kept tets
    for (std::uint32_t t = 0; t < kept.size(); ++t)
      for (auto n : parent.blocks[kept[t].block].element(kept[t].index))
        if (on_barrier[n]) tets_at[n].push_back(t);
    std::vector<std::uint32_t> nodes_on_barrier;
    for (const auto& [n, ts] : tets_at) nodes_on_barrier.push_back(n);
    // As ugs-faultinsert numbers its twins: by original tag, then by group.
    std::sort(nodes_on_barrier.begin(), nodes_on_barrier.end(),
              [&](std::uint32_t x, std::uint32_t y) { return parent.node_tags[x] < parent.node_tags[y]; });
    std::uint64_t next_tag = parent.max_node_tag() + 1;
    for (std::uint32_t v : nodes_on_barrier) {
      const auto& ts = tets_at[v];
      std::vector<std::size_t> root(ts.size());
      std::iota(root.begin(), root.end(), 0);
      auto find = [&](std::size_t a) {
        while (root[a] != a) a = root[a] = root[root[a]];
        return a;
      };
      std::string fault;
      for (std::size_t i = 0; i < ts.size(); ++i) {
        const auto ei = parent.blocks[kept[ts[i]].block].element(kept[ts[i]].index);
        for (std::size_t j = i + 1; j < ts.size(); ++j) {
          const auto ej = parent.blocks[kept[ts[j]].block].element(kept[ts[j]].index);
          std::array<std::uint32_t, 4> shared{};
          int ns = 0;
          for (auto a : ei)
            if (std::find(ej.begin(), ej.end(), a) != ej.end()) shared[ns++] = a;
          if (ns != 3) continue;  // they share no face (v is in both, so a shared face contains v)
          const auto it = barrier_faces.find(face_key(shared[0], shared[1], shared[2]));
          if (it != barrier_faces.end()) {
            if (fault.empty()) fault = it->second;
            continue;
          }
          const std::size_t a = find(i), b = find(j);
          if (a != b) root[std::max(a, b)] = std::min(a, b);
        }
      }
      // Groups ordered by their lowest element tag (as ugs-faultinsert): the first keeps the node.
      auto tag_of = [&](std::uint32_t t) { return parent.blocks[kept[t].block].tags[kept[t].index]; };
      std::map<std::size_t, std::uint64_t> lowest;  // group root -> lowest element tag
      for (std::size_t i = 0; i < ts.size(); ++i) {
        auto [it, fresh] = lowest.emplace(find(i), tag_of(ts[i]));
        if (!fresh) it->second = std::min(it->second, tag_of(ts[i]));
      }
      if (lowest.size() < 2) continue;
      std::vector<std::pair<std::uint64_t, std::size_t>> order;
      for (const auto& [g, t] : lowest) order.push_back({t, g});
      std::sort(order.begin(), order.end());
      std::map<std::size_t, std::uint32_t> node_of_group;
      node_of_group[order[0].second] = sub_of_parent[v];
      for (std::size_t k = 1; k < order.size(); ++k) {
        const std::uint32_t twin = sub.add_node(parent.nodes[v], next_tag++);
        node_of_group[order[k].second] = twin;
        twins[fault.empty() ? "barrier" : fault].push_back({sub_of_parent[v], twin});
        ++rep.duplicated_nodes;
      }
      for (std::size_t i = 0; i < ts.size(); ++i)
        for (auto& n : tet_nodes[ts[i]])
          if (n == sub_of_parent[v]) n = node_of_group.at(find(i));
    }
  }

  // 7. Entities and groups used, with their parent tags; then the elements.
  std::set<std::pair<int, int>> used_entities;
  for (const auto& k : kept) used_entities.insert({3, parent.blocks[k.block].entity_tag});
  // Parent triangles that are faces of kept tetrahedra (nodes as that tetrahedron has them).
  std::unordered_map<FaceKey, std::pair<std::size_t, std::size_t>, FaceKeyHash> triangle_at;
  for (std::size_t bi = 0; bi < parent.blocks.size(); ++bi) {
    const ElementBlock& b = parent.blocks[bi];
    if (b.type != ElementType::Triangle) continue;
    for (std::size_t i = 0; i < b.size(); ++i) {
      const auto el = b.element(i);
      triangle_at.emplace(face_key(el[0], el[1], el[2]), std::make_pair(bi, i));
    }
  }
  struct KeptTriangle {
    std::size_t block, index;
    std::array<std::uint32_t, 3> nodes;
  };
  std::vector<KeptTriangle> kept_triangles;
  if (!triangle_at.empty()) {
    std::set<std::pair<std::size_t, std::size_t>> done;
    for (std::size_t t = 0; t < kept.size(); ++t) {
      const auto el = parent.blocks[kept[t].block].element(kept[t].index);
      for (const auto& lf : kTetFaces) {
        const auto it = triangle_at.find(face_key(el[lf[0]], el[lf[1]], el[lf[2]]));
        if (it == triangle_at.end() || !done.insert(it->second).second) continue;
        const auto tri = parent.blocks[it->second.first].element(it->second.second);
        KeptTriangle k{it->second.first, it->second.second, {}};
        for (int j = 0; j < 3; ++j)
          for (int q = 0; q < 4; ++q)
            if (el[q] == tri[j]) k.nodes[j] = tet_nodes[t][q];
        kept_triangles.push_back(k);
        used_entities.insert({2, parent.blocks[it->second.first].entity_tag});
      }
    }
    std::sort(kept_triangles.begin(), kept_triangles.end(),
              [](const KeptTriangle& a, const KeptTriangle& b) { return std::tie(a.block, a.index) < std::tie(b.block, b.index); });
  }
  std::set<std::pair<int, int>> used_physicals;
  for (const auto& e : parent.entities)
    if (used_entities.count({e.dim, e.tag})) {
      sub.entities.push_back({e.dim, e.tag, e.physicals, {}});
      for (int p : e.physicals) used_physicals.insert({e.dim, p});
    }
  for (const auto& p : parent.physicals)
    if (used_physicals.count({p.dim, p.tag})) sub.physicals.push_back(p);
  for (const auto& k : kept) {
    const ElementBlock& pb = parent.blocks[k.block];
    ElementBlock& b = sub.block(3, pb.entity_tag, ElementType::Tetrahedron);
    const std::size_t t = static_cast<std::size_t>(&k - kept.data());
    sub.add_element(b, tet_nodes[t], pb.tags[k.index]);
  }
  for (const auto& k : kept_triangles) {
    const ElementBlock& pb = parent.blocks[k.block];
    ElementBlock& b = sub.block(2, pb.entity_tag, ElementType::Triangle);
    sub.add_element(b, k.nodes, pb.tags[k.index]);
  }
  // 8. Line groups twin:<fault> and tie:<fault>, tags after the parent's.
  int next_physical = 1, next_line_entity = 1;
  for (const auto& p : parent.physicals) next_physical = std::max(next_physical, p.tag + 1);
  for (const auto& e : parent.entities)
    if (e.dim == 1) next_line_entity = std::max(next_line_entity, e.tag + 1);
  std::uint64_t next_element = parent.max_element_tag() + 1;
  auto add_lines = [&](const std::string& prefix, const auto& groups) {
    for (const auto& [name, pairs] : groups) {
      sub.physicals.push_back({1, next_physical, prefix + name});
      sub.entities.push_back({1, next_line_entity, {next_physical}, {}});
      ElementBlock& b = sub.block(1, next_line_entity, ElementType::Line);
      for (const auto& [a, c] : pairs) {
        const std::uint32_t n[2] = {a, c};
        sub.add_element(b, n, next_element++);
      }
      ++next_physical, ++next_line_entity;
    }
  };
  add_lines("twin:", twins);
  add_lines("tie:", ties);
  for (const auto& [name, pairs] : ties) rep.tied_pairs += pairs.size();
  sub.provenance = parent.provenance;
  sub.update_entity_bboxes();

  for (const auto& p : sub.physicals)
    if (p.dim == 3 && p.name.rfind("mat:", 0) == 0) rep.materials.push_back(p.name.substr(4));
  rep.tetrahedra = kept.size();
  rep.nodes = sub.num_nodes();
  rep.triangles = kept_triangles.size();
  if (report) *report = rep;
  return sub;
}

}  // namespace ugs
