#include "ugs/formats/mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>

#include "ugs/formats/run_beside.hpp"

namespace ugs {

int nodes_per_element(ElementType t) {
  switch (t) {
    case ElementType::Point: return 1;
    case ElementType::Line: return 2;
    case ElementType::Triangle: return 3;
    case ElementType::Tetrahedron: return 4;
    case ElementType::Prism: return 6;
  }
  return 0;
}

int element_dimension(ElementType t) {
  switch (t) {
    case ElementType::Point: return 0;
    case ElementType::Line: return 1;
    case ElementType::Triangle: return 2;
    case ElementType::Tetrahedron: return 3;
    case ElementType::Prism: return 3;
  }
  return 0;
}

std::string_view element_name(ElementType t) {
  switch (t) {
    case ElementType::Point: return "point";
    case ElementType::Line: return "line";
    case ElementType::Triangle: return "triangle";
    case ElementType::Tetrahedron: return "tetrahedron";
    case ElementType::Prism: return "interface prism";
  }
  return "?";
}

std::optional<ElementType> element_type_from_gmsh(int gmsh_type) {
  switch (gmsh_type) {
    case 15: return ElementType::Point;
    case 1: return ElementType::Line;
    case 2: return ElementType::Triangle;
    case 4: return ElementType::Tetrahedron;
    case 6: return ElementType::Prism;
    default: return std::nullopt;
  }
}

std::size_t Mesh::count(ElementType t) const {
  std::size_t n = 0;
  for (const auto& b : blocks)
    if (b.type == t) n += b.size();
  return n;
}

std::uint64_t Mesh::max_node_tag() const {
  std::uint64_t m = 0;
  for (auto t : node_tags) m = std::max(m, t);
  return m;
}

std::uint64_t Mesh::max_element_tag() const {
  std::uint64_t m = 0;
  for (const auto& b : blocks)
    for (auto t : b.tags) m = std::max(m, t);
  return m;
}

std::uint32_t Mesh::add_node(const Point3& x, std::uint64_t tag) {
  if (tag == 0) {
    if (next_node_tag_ == 0) next_node_tag_ = max_node_tag() + 1;
    tag = next_node_tag_++;
  } else if (tag >= next_node_tag_ && next_node_tag_ != 0) {
    next_node_tag_ = tag + 1;
  }
  if (nodes.size() >= std::numeric_limits<std::uint32_t>::max())
    throw std::length_error("mesh: more than 4 billion nodes");
  node_tags.push_back(tag);
  nodes.push_back(x);
  return static_cast<std::uint32_t>(nodes.size() - 1);
}

const PhysicalGroup* Mesh::find_physical(int dim, std::string_view name) const {
  for (const auto& p : physicals)
    if (p.dim == dim && p.name == name) return &p;
  return nullptr;
}

const PhysicalGroup* Mesh::find_physical_tag(int dim, int tag) const {
  for (const auto& p : physicals)
    if (p.dim == dim && p.tag == tag) return &p;
  return nullptr;
}

const Entity* Mesh::find_entity(int dim, int tag) const {
  for (const auto& e : entities)
    if (e.dim == dim && e.tag == tag) return &e;
  return nullptr;
}

std::string Mesh::physical_name_of(int entity_dim, int entity_tag) const {
  const Entity* e = find_entity(entity_dim, entity_tag);
  if (!e || e->physicals.empty()) return {};
  const PhysicalGroup* p = find_physical_tag(entity_dim, e->physicals.front());
  return p ? p->name : std::string{};
}

int Mesh::entity_for_physical(int dim, const std::string& name) {
  const PhysicalGroup* p = find_physical(dim, name);
  int ptag;
  if (p) {
    ptag = p->tag;
    for (const auto& e : entities)
      if (e.dim == dim && e.physicals.size() == 1 && e.physicals[0] == ptag) return e.tag;
  } else {
    ptag = 1;
    for (const auto& q : physicals) ptag = std::max(ptag, q.tag + 1);
    physicals.push_back({dim, ptag, name});
  }
  int etag = 1;
  for (const auto& e : entities)
    if (e.dim == dim) etag = std::max(etag, e.tag + 1);
  entities.push_back({dim, etag, {ptag}, {}});
  return etag;
}

ElementBlock& Mesh::block(int entity_dim, int entity_tag, ElementType type) {
  for (auto& b : blocks)
    if (b.entity_dim == entity_dim && b.entity_tag == entity_tag && b.type == type) return b;
  if (!find_entity(entity_dim, entity_tag)) entities.push_back({entity_dim, entity_tag, {}, {}});
  ElementBlock b;
  b.entity_dim = entity_dim;
  b.entity_tag = entity_tag;
  b.type = type;
  blocks.push_back(std::move(b));
  return blocks.back();
}

void Mesh::add_element(ElementBlock& b, std::span<const std::uint32_t> node_indices, std::uint64_t tag) {
  if (static_cast<int>(node_indices.size()) != b.npe())
    throw std::invalid_argument("mesh: wrong number of nodes for element");
  if (tag == 0) {
    if (next_element_tag_ == 0) next_element_tag_ = max_element_tag() + 1;
    tag = next_element_tag_++;
  } else if (next_element_tag_ != 0 && tag >= next_element_tag_) {
    next_element_tag_ = tag + 1;
  }
  b.tags.push_back(tag);
  b.nodes.insert(b.nodes.end(), node_indices.begin(), node_indices.end());
}

std::unordered_map<std::uint64_t, std::uint32_t> Mesh::node_index_by_tag() const {
  std::unordered_map<std::uint64_t, std::uint32_t> m;
  m.reserve(node_tags.size());
  for (std::uint32_t i = 0; i < node_tags.size(); ++i) m.emplace(node_tags[i], i);
  return m;
}

namespace {

// Widens `box` (lo xyz, hi xyz) by the nodes of block b. `used`: scratch, one flag per node.
void widen_box(const std::vector<Point3>& nodes, const ElementBlock& b, std::array<double, 6>& box, std::vector<char>& used) {
  // In locals (written through the entity, every step was a load and a store: the box could alias
  // the nodes). A large block is swept in node order (its elements' order visited the nodes at
  // random, 3 % of ugs-meshgen's thesis bench in cache misses): the same minimum and maximum,
  // unless one is a zero that may come as +0 or -0, where the first met wins: then again in
  // element order.
  const double lo0[3] = {box[0], box[1], box[2]}, hi0[3] = {box[3], box[4], box[5]};
  double lo[3] = {lo0[0], lo0[1], lo0[2]}, hi[3] = {hi0[0], hi0[1], hi0[2]};
  auto add = [&](const Point3& x) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], x[k]);
      hi[k] = std::max(hi[k], x[k]);
    }
  };
  const auto [first, last] = std::minmax_element(b.nodes.begin(), b.nodes.end());
  bool swept = false;
  if (8 * b.nodes.size() >= *last - *first + 1 && *last < nodes.size()) {
    used.assign(nodes.size(), 0);
    for (auto n : b.nodes) used[n] = 1;
    for (std::size_t n = *first; n <= *last; ++n)
      if (used[n]) add(nodes[n]);
    swept = true;
    for (int k = 0; k < 3; ++k) swept = swept && lo[k] != 0 && hi[k] != 0;
  }
  if (!swept) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = lo0[k];
      hi[k] = hi0[k];
    }
    for (auto n : b.nodes) add(nodes[n]);
  }
  for (int k = 0; k < 3; ++k) {
    box[k] = lo[k];
    box[k + 3] = hi[k];
  }
}

}  // namespace

void Mesh::update_entity_bboxes() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (auto& e : entities) e.bbox = {inf, inf, inf, -inf, -inf, -inf};
  // Each entity's box from its blocks in block order (the entity is the last one of the block's
  // dimension and tag); the entities are independent of each other, so a large mesh's are shared
  // between two threads (a fixed split by size: the boxes do not depend on timing).
  std::vector<std::vector<const ElementBlock*>> of(entities.size());
  std::vector<std::size_t> refs(entities.size(), 0);
  std::size_t total = 0;
  for (const auto& b : blocks) {
    std::size_t ei = entities.size();
    for (std::size_t f = 0; f < entities.size(); ++f)
      if (entities[f].dim == b.entity_dim && entities[f].tag == b.entity_tag) ei = f;
    if (ei == entities.size() || b.nodes.empty()) continue;
    of[ei].push_back(&b);
    refs[ei] += b.nodes.size();
    total += b.nodes.size();
  }
  auto run = [&](const std::vector<std::size_t>& mine) {
    std::vector<char> used;  // per node, for the blocks swept in node order
    for (auto ei : mine)
      for (const ElementBlock* b : of[ei]) widen_box(nodes, *b, entities[ei].bbox, used);
  };
  std::vector<std::size_t> order(entities.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  if (total < (std::size_t{1} << 22) || std::thread::hardware_concurrency() < 2) {
    run(order);
  } else {
    std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return refs[x] > refs[y]; });
    std::vector<std::size_t> part[2];
    std::size_t load[2] = {0, 0};
    for (auto ei : order) {
      const int t = load[1] < load[0] ? 1 : 0;
      part[t].push_back(ei);
      load[t] += refs[ei];
    }
    run_beside([&] { run(part[1]); }, [&] { run(part[0]); });
  }
  for (auto& e : entities)
    if (e.bbox[0] > e.bbox[3]) e.bbox = {};
}

double tet_signed_volume(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const double wx = d[0] - a[0], wy = d[1] - a[1], wz = d[2] - a[2];
  return (ux * (vy * wz - vz * wy) - uy * (vx * wz - vz * wx) + uz * (vx * wy - vy * wx)) / 6.0;
}

// The Jacobian's determinant as solver/fem/src/tet4.cpp forms it (edges from p0, a . (b x c)).
double tet_volume_ratio(const Point3& p0, const Point3& p1, const Point3& p2, const Point3& p3) {
  const double a[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  const double b[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
  const double c[3] = {p3[0] - p0[0], p3[1] - p0[1], p3[2] - p0[2]};
  const double bxc[3] = {b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]};
  const double det = a[0] * bxc[0] + a[1] * bxc[1] + a[2] * bxc[2];
  const double scale = std::abs(a[0]) + std::abs(a[1]) + std::abs(a[2]) + std::abs(b[0]) + std::abs(b[1]) +
                       std::abs(b[2]) + std::abs(c[0]) + std::abs(c[1]) + std::abs(c[2]);
  const double ratio = std::abs(det) / (scale * scale * scale);
  return std::isfinite(ratio) ? ratio : 0.0;  // four equal points: 0 / 0
}

}  // namespace ugs
