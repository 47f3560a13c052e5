// Fault insertion: duplicated nodes by connected components of the tetrahedra around each fault
// node, and 6-node interface prisms (see fault_insert.hpp for the rules).
//
// Only the tetrahedra touching a fault node are looked at after one pass over the mesh, so the
// work is proportional to the faults, not to the model. Every check runs before the mesh is
// changed: an error leaves it as it was.
#include "ugs/meshing/fault_insert.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/meshing/vec3.hpp"

namespace ugs {
namespace {

using namespace vec3;

constexpr std::uint32_t kNone = 0xffffffffu;

bool has_fault_prefix(const std::string& n) { return n.rfind("fault:", 0) == 0; }
std::string strip_fault(const std::string& n) { return has_fault_prefix(n) ? n.substr(6) : n; }

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

// Entities (of any dimension) carrying the physical group (dim, tag).
bool entity_has(const Entity& e, int dim, int ptag) {
  return e.dim == dim && std::find(e.physicals.begin(), e.physicals.end(), ptag) != e.physicals.end();
}

// Sign (+1 keep, -1 flip) that makes the mean normal N of a fault part follow the rule of
// fault_insert.hpp: the reference normal if given and not perpendicular, else down, south, west.
int orientation_sign(const Point3& N, const Point3* ref) {
  const double L = norm(N);
  if (ref) {
    const double d = dot(N, *ref);
    if (std::abs(d) > 1e-3 * L * norm(*ref)) return d > 0 ? 1 : -1;
  }
  if (std::abs(N[2]) > 1e-3 * L) return N[2] < 0 ? 1 : -1;
  if (std::abs(N[1]) > 1e-3 * L) return N[1] < 0 ? 1 : -1;
  return N[0] < 0 ? 1 : -1;
}

struct FaultTri {
  std::array<std::uint32_t, 3> n{};         // node indices; oriented side 1 -> side 2 after orient()
  std::uint64_t tag = 0;
  std::uint32_t fault = 0;
  std::array<std::uint32_t, 2> tet{kNone, kNone};  // touched tetrahedra; side 1, side 2 after sides()
};

struct TetRef {
  std::uint32_t block = 0, elem = 0;
};

struct Edit {
  std::uint32_t block = 0;
  std::size_t pos = 0;
  std::uint32_t node = 0;
};

class Inserter {
public:
  Inserter(Mesh& m, const FaultInsertOptions& o) : m_(m), opt_(o) {}

  FaultInsertReport run() {
    choose_faults();
    collect_triangles();
    index_fault_nodes();
    scan_tetrahedra();
    find_triangle_tetrahedra();
    orient();
    check_cells_on_one_fault();
    sides();
    split_nodes();
    build_prisms();
    renumber_other_elements();
    summarize();
    apply();  // nothing below throws InputError: the mesh changes only here
    return std::move(report_);
  }

private:
  // ---- checks and analysis (the mesh is not modified) ----

  InputError error(const std::string& msg) const { return InputError(opt_.source, msg); }
  const std::string& fname(std::uint32_t f) const { return names_[f]; }
  std::string at(std::uint32_t v) const {
    const auto& x = m_.nodes[v];
    return fmt::format("({:.2f}, {:.2f}, {:.2f})", x[0], x[1], x[2]);
  }
  std::string tri_where(const FaultTri& t) const {
    return fmt::format("triangle {} (nodes {} {} {}, at {})", t.tag, m_.node_tags[t.n[0]], m_.node_tags[t.n[1]],
                       m_.node_tags[t.n[2]], at(t.n[0]));
  }

  void choose_faults() {
    const auto tri = fault_triangle_groups(m_);
    const auto ie = fault_interface_groups(m_);
    auto in = [](const std::vector<std::string>& v, const std::string& s) {
      return std::find(v.begin(), v.end(), s) != v.end();
    };
    if (opt_.only.empty()) {
      for (const auto& n : tri) {
        if (in(ie, n)) throw error(fmt::format("fault '{}' already has interface elements: it was inserted before", n));
        names_.push_back(n);
      }
      if (names_.empty()) {
        if (!ie.empty())
          throw error(fmt::format("no fault triangle groups left to insert: fault {} already has interface elements",
                                  join(ie)));
        throw error("no fault triangle groups (physical groups fault:<name> of triangles) to insert");
      }
      return;
    }
    for (const auto& raw : opt_.only) {
      const std::string n = strip_fault(raw);
      if (in(names_, n)) continue;
      if (in(ie, n)) throw error(fmt::format("fault '{}' already has interface elements: it was inserted before", n));
      if (!in(tri, n))
        throw error(fmt::format("unknown fault '{}' ({})", n,
                                tri.empty() ? std::string("the mesh has no fault:<name> triangle groups")
                                            : "fault groups in the mesh: " + join(tri)));
      names_.push_back(n);
    }
  }

  void collect_triangles() {
    // Entity -> fault; an entity carrying two inserted faults would put a triangle on both.
    std::map<int, std::uint32_t> fault_of_entity;
    for (std::uint32_t f = 0; f < names_.size(); ++f) {
      const PhysicalGroup* p = m_.find_physical(2, "fault:" + names_[f]);
      old_ptag_.push_back(p->tag);
      for (const auto& e : m_.entities) {
        if (!entity_has(e, 2, p->tag)) continue;
        auto [it, fresh] = fault_of_entity.emplace(e.tag, f);
        if (!fresh)
          throw error(fmt::format("faults '{}' and '{}' share the surface entity {}: a triangle belongs to one fault",
                                  fname(it->second), names_[f], e.tag));
      }
    }
    for (std::uint32_t b = 0; b < m_.blocks.size(); ++b) {
      const auto& blk = m_.blocks[b];
      if (blk.entity_dim != 2 || blk.type != ElementType::Triangle) continue;
      auto it = fault_of_entity.find(blk.entity_tag);
      if (it == fault_of_entity.end()) continue;
      removed_block_.insert(b);
      for (std::size_t i = 0; i < blk.size(); ++i) {
        FaultTri t;
        const auto el = blk.element(i);
        t.n = {el[0], el[1], el[2]};
        t.tag = blk.tags[i];
        t.fault = it->second;
        if (t.n[0] == t.n[1] || t.n[1] == t.n[2] || t.n[0] == t.n[2])
          throw error(fmt::format("fault '{}': {} has a repeated node", fname(t.fault), tri_where(t)));
        tris_.push_back(t);
      }
    }
    // Keep the fault order for the triangles, then the file order inside each fault.
    std::stable_sort(tris_.begin(), tris_.end(), [](const FaultTri& a, const FaultTri& b) { return a.fault < b.fault; });
    for (std::uint32_t f = 0; f < names_.size(); ++f)
      if (std::none_of(tris_.begin(), tris_.end(), [&](const FaultTri& t) { return t.fault == f; }))
        throw error(fmt::format("fault '{}' has no triangles", names_[f]));
    // Repeated triangles, in one fault or shared by two.
    std::vector<std::pair<std::array<std::uint32_t, 3>, std::uint32_t>> keys(tris_.size());
    for (std::uint32_t i = 0; i < tris_.size(); ++i) {
      auto k = tris_[i].n;
      std::sort(k.begin(), k.end());
      keys[i] = {k, i};
    }
    std::sort(keys.begin(), keys.end());
    for (std::size_t i = 1; i < keys.size(); ++i) {
      if (keys[i].first != keys[i - 1].first) continue;
      const FaultTri& a = tris_[keys[i - 1].second];
      const FaultTri& b = tris_[keys[i].second];
      if (a.fault == b.fault)
        throw error(fmt::format("fault '{}': {} repeats triangle {}", fname(a.fault), tri_where(b), a.tag));
      throw error(fmt::format("faults '{}' and '{}' share {} (triangle {})", fname(a.fault), fname(b.fault),
                              tri_where(a), b.tag));
    }
  }

  void index_fault_nodes() {
    local_.assign(m_.num_nodes(), kNone);
    for (const auto& t : tris_)
      for (auto v : t.n)
        if (local_[v] == kNone) {
          local_[v] = 0;
          fnodes_.push_back(v);
        }
    // Increasing node tag: the order new tags are handed out in.
    std::sort(fnodes_.begin(), fnodes_.end(), [&](std::uint32_t a, std::uint32_t b) { return m_.node_tags[a] < m_.node_tags[b]; });
    for (std::uint32_t i = 0; i < fnodes_.size(); ++i) local_[fnodes_[i]] = i;
    // Fault triangles at each fault node.
    tri_start_.assign(fnodes_.size() + 1, 0);
    for (const auto& t : tris_)
      for (auto v : t.n) ++tri_start_[local_[v] + 1];
    std::partial_sum(tri_start_.begin(), tri_start_.end(), tri_start_.begin());
    node_tris_.resize(tri_start_.back());
    std::vector<std::uint32_t> fill(tri_start_.begin(), tri_start_.end() - 1);
    for (std::uint32_t i = 0; i < tris_.size(); ++i)
      for (auto v : tris_[i].n) node_tris_[fill[local_[v]]++] = i;
  }

  // Is {v, a, b} a triangle of an inserted fault? v is a fault node.
  bool is_fault_face(std::uint32_t v, std::uint32_t a, std::uint32_t b) const {
    const std::uint32_t i = local_[v];
    for (std::uint32_t k = tri_start_[i]; k < tri_start_[i + 1]; ++k) {
      const auto& n = tris_[node_tris_[k]].n;
      const bool ha = n[0] == a || n[1] == a || n[2] == a;
      const bool hb = n[0] == b || n[1] == b || n[2] == b;
      if (ha && hb) return true;
    }
    return false;
  }

  void scan_tetrahedra() {
    // One pass: the tetrahedra touching a fault node, and how many there are per fault node.
    inc_start_.assign(fnodes_.size() + 1, 0);
    for (std::uint32_t b = 0; b < m_.blocks.size(); ++b) {
      const auto& blk = m_.blocks[b];
      if (blk.type != ElementType::Tetrahedron) continue;
      const std::uint32_t* c = blk.nodes.data();
      for (std::uint32_t e = 0; e < blk.size(); ++e, c += 4) {
        bool any = false;
        for (int k = 0; k < 4; ++k)
          if (local_[c[k]] != kNone) {
            any = true;
            ++inc_start_[local_[c[k]] + 1];
          }
        if (any) touched_.push_back({b, e});
      }
    }
    std::partial_sum(inc_start_.begin(), inc_start_.end(), inc_start_.begin());
    inc_.resize(inc_start_.back());
    inc_copy_.assign(inc_.size(), 0);
    std::vector<std::uint32_t> fill(inc_start_.begin(), inc_start_.end() - 1);
    for (std::uint32_t t = 0; t < touched_.size(); ++t) {
      const std::uint32_t* c = tet(t);
      for (int k = 0; k < 4; ++k)
        if (local_[c[k]] != kNone) {
          // A tetrahedron listing a node twice is degenerate: refuse it rather than guess.
          for (int j = 0; j < k; ++j)
            if (c[j] == c[k])
              throw error(fmt::format("tetrahedron {} has node {} twice", tet_tag(t), m_.node_tags[c[k]]));
          inc_[fill[local_[c[k]]]++] = t;
        }
    }
  }

  const std::uint32_t* tet(std::uint32_t t) const {
    return m_.blocks[touched_[t].block].nodes.data() + 4 * static_cast<std::size_t>(touched_[t].elem);
  }
  std::uint64_t tet_tag(std::uint32_t t) const { return m_.blocks[touched_[t].block].tags[touched_[t].elem]; }
  static bool tet_has(const std::uint32_t* c, std::uint32_t v) { return c[0] == v || c[1] == v || c[2] == v || c[3] == v; }

  void find_triangle_tetrahedra() {
    for (auto& t : tris_) {
      const std::uint32_t i = local_[t.n[0]];
      std::uint32_t found = 0;
      for (std::uint32_t k = inc_start_[i]; k < inc_start_[i + 1]; ++k) {
        const std::uint32_t* c = tet(inc_[k]);
        if (!tet_has(c, t.n[1]) || !tet_has(c, t.n[2])) continue;
        if (found < 2) t.tet[found] = inc_[k];
        ++found;
      }
      if (found == 0)
        throw error(fmt::format("fault '{}': {} is not a face of any tetrahedron: the fault does not follow mesh "
                                "faces (build the mesh with the fault as a constraint)",
                                fname(t.fault), tri_where(t)));
      if (found == 1)
        throw error(fmt::format("fault '{}': {} is a face of one tetrahedron only: it lies on the model boundary, "
                                "where there is nothing to split",
                                fname(t.fault), tri_where(t)));
      if (found > 2)
        throw error(fmt::format("fault '{}': {} is a face of {} tetrahedra: the mesh is not conforming there",
                                fname(t.fault), tri_where(t), found));
    }
  }

  // Faults of each fault node (sorted, unique).
  std::vector<std::uint32_t> faults_at(std::uint32_t i) const {
    std::vector<std::uint32_t> f;
    for (std::uint32_t k = tri_start_[i]; k < tri_start_[i + 1]; ++k) f.push_back(tris_[node_tris_[k]].fault);
    std::sort(f.begin(), f.end());
    f.erase(std::unique(f.begin(), f.end()), f.end());
    return f;
  }

  void check_cells_on_one_fault() {
    for (std::uint32_t t = 0; t < touched_.size(); ++t) {
      const std::uint32_t* c = tet(t);
      if (local_[c[0]] == kNone || local_[c[1]] == kNone || local_[c[2]] == kNone || local_[c[3]] == kNone) continue;
      std::vector<std::uint32_t> common = faults_at(local_[c[0]]);
      for (int k = 1; k < 4 && !common.empty(); ++k) {
        const auto f = faults_at(local_[c[k]]);
        std::vector<std::uint32_t> r;
        std::set_intersection(common.begin(), common.end(), f.begin(), f.end(), std::back_inserter(r));
        common = std::move(r);
      }
      if (common.empty()) continue;
      Point3 g{};
      for (int k = 0; k < 4; ++k)
        for (int d = 0; d < 3; ++d) g[d] += 0.25 * m_.nodes[c[k]][d];
      throw error(fmt::format("fault '{}': tetrahedron {} at ({:.2f}, {:.2f}, {:.2f}) has all four nodes on the fault, "
                              "so it would be torn apart; refine the mesh there or smooth the fault surface",
                              fname(common.front()), tet_tag(t), g[0], g[1], g[2]));
    }
  }

  double tri_area2(const FaultTri& t, Point3* n = nullptr) const {
    const Point3 c = cross(sub(m_.nodes[t.n[1]], m_.nodes[t.n[0]]), sub(m_.nodes[t.n[2]], m_.nodes[t.n[0]]));
    if (n) *n = c;
    return norm(c);
  }

  // Consistent orientation over each connected part of each fault; manifold edges checked here.
  void orient() {
    struct EdgeUse {
      std::uint64_t key;
      std::uint32_t fault, tri;
      int dir;  // +1 when the triangle runs from min to max node
    };
    std::vector<EdgeUse> uses;
    uses.reserve(3 * tris_.size());
    for (std::uint32_t i = 0; i < tris_.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = tris_[i].n[k], b = tris_[i].n[(k + 1) % 3];
        uses.push_back({pair_key(a, b), tris_[i].fault, i, a < b ? 1 : -1});
      }
    std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
      return std::tie(x.fault, x.key, x.tri) < std::tie(y.fault, y.key, y.tri);
    });
    // Neighbours across manifold edges: (tri, other tri, dir product).
    std::vector<std::vector<std::pair<std::uint32_t, int>>> nb(tris_.size());
    for (std::size_t i = 0; i < uses.size();) {
      std::size_t j = i;
      while (j < uses.size() && uses[j].fault == uses[i].fault && uses[j].key == uses[i].key) ++j;
      if (j - i > 2) {
        const auto a = static_cast<std::uint32_t>(uses[i].key >> 32), b = static_cast<std::uint32_t>(uses[i].key);
        throw error(fmt::format("fault '{}' has a non-manifold edge: nodes {}-{} at {} are shared by {} of its "
                                "triangles (e.g. {} and {})",
                                fname(uses[i].fault), m_.node_tags[a], m_.node_tags[b], at(a), j - i,
                                tris_[uses[i].tri].tag, tris_[uses[i + 1].tri].tag));
      }
      if (j - i == 2) {
        nb[uses[i].tri].push_back({uses[i + 1].tri, uses[i].dir * uses[i + 1].dir});
        nb[uses[i + 1].tri].push_back({uses[i].tri, uses[i].dir * uses[i + 1].dir});
      }
      i = j;
    }
    // Breadth-first: neighbours must run along the shared edge in opposite directions.
    std::vector<int> sign(tris_.size(), 0);
    part_of_.assign(tris_.size(), kNone);
    std::vector<std::uint32_t> queue;
    for (std::uint32_t s = 0; s < tris_.size(); ++s) {
      if (sign[s] != 0) continue;
      const std::uint32_t part = static_cast<std::uint32_t>(part_fault_.size());
      part_fault_.push_back(tris_[s].fault);
      sign[s] = 1;
      part_of_[s] = part;
      queue.assign(1, s);
      for (std::size_t q = 0; q < queue.size(); ++q) {
        const std::uint32_t t = queue[q];
        for (auto [u, dd] : nb[t]) {
          const int want = -sign[t] * dd;
          if (sign[u] == 0) {
            sign[u] = want;
            part_of_[u] = part;
            queue.push_back(u);
          } else if (sign[u] != want) {
            throw error(fmt::format("fault '{}' is not orientable (its two faces join up, as on a Moebius strip) "
                                    "near {}",
                                    fname(tris_[u].fault), tri_where(tris_[u])));
          }
        }
      }
    }
    // One sign per part from its area-weighted mean normal.
    std::vector<Point3> mean(part_fault_.size(), Point3{});
    std::vector<double> area(part_fault_.size(), 0.0);
    std::vector<std::uint32_t> first(part_fault_.size(), kNone);
    for (std::uint32_t i = 0; i < tris_.size(); ++i) {
      Point3 n;
      const double a2 = tri_area2(tris_[i], &n);
      const std::uint32_t p = part_of_[i];
      for (int d = 0; d < 3; ++d) mean[p][d] += sign[i] * n[d];
      area[p] += a2;
      if (first[p] == kNone || tris_[i].tag < tris_[first[p]].tag) first[p] = i;
      if (!(a2 > 0))
        throw error(fmt::format("fault '{}': {} has zero area", fname(tris_[i].fault), tri_where(tris_[i])));
    }
    std::vector<int> part_sign(part_fault_.size());
    for (std::uint32_t p = 0; p < part_fault_.size(); ++p) {
      Point3 N = mean[p];
      if (norm(N) <= 1e-9 * area[p]) {  // a closed surface: the lowest-tag triangle decides
        tri_area2(tris_[first[p]], &N);
        for (auto& x : N) x *= sign[first[p]];
      }
      auto it = opt_.reference_normals.find(fname(part_fault_[p]));
      part_sign[p] = orientation_sign(N, it == opt_.reference_normals.end() ? nullptr : &it->second);
    }
    for (std::uint32_t i = 0; i < tris_.size(); ++i)
      if (sign[i] * part_sign[part_of_[i]] < 0) std::swap(tris_[i].n[1], tris_[i].n[2]);
  }

  // Side 1 is the tetrahedron behind the oriented triangle's normal, side 2 the one in front.
  void sides() {
    for (auto& t : tris_) {
      Point3 n;
      tri_area2(t, &n);
      double h[2];
      for (int s = 0; s < 2; ++s) {
        const std::uint32_t* c = tet(t.tet[s]);
        std::uint32_t d = c[0];
        for (int k = 0; k < 4; ++k)
          if (c[k] != t.n[0] && c[k] != t.n[1] && c[k] != t.n[2]) d = c[k];
        h[s] = dot(sub(m_.nodes[d], m_.nodes[t.n[0]]), n);
      }
      if (!((h[0] < 0 && h[1] > 0) || (h[0] > 0 && h[1] < 0)))
        throw error(fmt::format("fault '{}': the two tetrahedra at {} ({} and {}) are not on opposite sides of it "
                                "(flat or inverted elements)",
                                fname(t.fault), tri_where(t), tet_tag(t.tet[0]), tet_tag(t.tet[1])));
      if (h[0] > 0) std::swap(t.tet[0], t.tet[1]);
    }
  }

  // Components of the tetrahedra around each fault node, joined through non-fault faces.
  void split_nodes() {
    ncopies_.assign(fnodes_.size(), 1);
    struct FaceUse {
      std::uint64_t key;
      std::uint32_t j;
    };
    std::vector<FaceUse> faces;
    std::vector<std::uint32_t> parent;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> comps;  // (min tag, root)
    auto find = [&](std::uint32_t x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    for (std::uint32_t i = 0; i < fnodes_.size(); ++i) {
      const std::uint32_t v = fnodes_[i], b = inc_start_[i], k = inc_start_[i + 1] - b;
      faces.clear();
      for (std::uint32_t j = 0; j < k; ++j) {
        const std::uint32_t* c = tet(inc_[b + j]);
        std::uint32_t o[3], n = 0;
        for (int q = 0; q < 4; ++q)
          if (c[q] != v) o[n++] = c[q];
        faces.push_back({pair_key(o[0], o[1]), j});
        faces.push_back({pair_key(o[0], o[2]), j});
        faces.push_back({pair_key(o[1], o[2]), j});
      }
      std::sort(faces.begin(), faces.end(), [](const FaceUse& x, const FaceUse& y) {
        return x.key < y.key || (x.key == y.key && x.j < y.j);
      });
      parent.resize(k);
      std::iota(parent.begin(), parent.end(), 0u);
      for (std::size_t a = 0; a < faces.size();) {
        std::size_t z = a;
        while (z < faces.size() && faces[z].key == faces[a].key) ++z;
        if (z - a > 2) {
          const auto p = static_cast<std::uint32_t>(faces[a].key >> 32), q = static_cast<std::uint32_t>(faces[a].key);
          throw error(fmt::format("the face of nodes {} {} {} at {} belongs to {} tetrahedra: the mesh is not conforming",
                                  m_.node_tags[v], m_.node_tags[p], m_.node_tags[q], at(v), z - a));
        }
        if (z - a == 2 &&
            !is_fault_face(v, static_cast<std::uint32_t>(faces[a].key >> 32), static_cast<std::uint32_t>(faces[a].key))) {
          const std::uint32_t r1 = find(faces[a].j), r2 = find(faces[a + 1].j);
          if (r1 != r2) parent[std::max(r1, r2)] = std::min(r1, r2);
        }
        a = z;
      }
      // Sets ordered by their lowest element tag; the first keeps the node.
      comps.clear();
      std::vector<std::uint64_t> min_tag(k, ~std::uint64_t{0});
      for (std::uint32_t j = 0; j < k; ++j) {
        const std::uint32_t r = find(j);
        min_tag[r] = std::min(min_tag[r], tet_tag(inc_[b + j]));
      }
      for (std::uint32_t j = 0; j < k; ++j)
        if (find(j) == j) comps.push_back({min_tag[j], j});
      std::sort(comps.begin(), comps.end());
      ncopies_[i] = static_cast<std::uint32_t>(comps.size());
      for (std::uint32_t j = 0; j < k; ++j) {
        const std::uint32_t r = find(j);
        for (std::uint32_t c = 0; c < comps.size(); ++c)
          if (comps[c].second == r) inc_copy_[b + j] = c;
      }
    }
    // New node indices and tags, in increasing (original tag, set) order.
    first_new_.assign(fnodes_.size(), kNone);
    std::uint32_t next = static_cast<std::uint32_t>(m_.num_nodes());
    for (std::uint32_t i = 0; i < fnodes_.size(); ++i)
      if (ncopies_[i] > 1) {
        first_new_[i] = next;
        next += ncopies_[i] - 1;
      }
    report_.new_nodes = next - m_.num_nodes();
  }

  // The copy of fault node v used by touched tetrahedron t (v itself for unsplit nodes).
  std::uint32_t copy(std::uint32_t v, std::uint32_t t) const {
    const std::uint32_t i = local_[v];
    if (i == kNone || ncopies_[i] == 1) return v;
    const auto b = inc_.begin() + inc_start_[i], e = inc_.begin() + inc_start_[i + 1];
    const auto it = std::lower_bound(b, e, t);
    const std::uint32_t c = inc_copy_[static_cast<std::size_t>(it - inc_.begin())];
    return c == 0 ? v : first_new_[i] + c - 1;
  }

  void build_prisms() {
    prisms_.resize(6 * tris_.size());
    for (std::size_t i = 0; i < tris_.size(); ++i) {
      const auto& t = tris_[i];
      for (int k = 0; k < 3; ++k) {
        prisms_[6 * i + k] = copy(t.n[k], t.tet[0]);
        prisms_[6 * i + 3 + k] = copy(t.n[k], t.tet[1]);
      }
    }
  }

  // Elements other than tetrahedra: each group of nodes (a prism's two sides separately) takes
  // the copies of the lowest-tag tetrahedron holding all of them.
  void renumber_other_elements() {
    for (std::uint32_t b = 0; b < m_.blocks.size(); ++b) {
      const auto& blk = m_.blocks[b];
      if (blk.type == ElementType::Tetrahedron || removed_block_.count(b)) continue;
      const int npe = blk.npe();
      const int group = blk.type == ElementType::Prism ? 3 : npe;
      for (std::size_t e = 0; e < blk.size(); ++e) {
        bool moved = false, unattached = false;
        for (int g0 = 0; g0 < npe; g0 += group) {
          const std::uint32_t* n = blk.nodes.data() + e * npe + g0;
          std::uint32_t split = kNone;
          for (int q = 0; q < group && split == kNone; ++q)
            if (local_[n[q]] != kNone && ncopies_[local_[n[q]]] > 1) split = n[q];
          if (split == kNone) continue;
          const std::uint32_t i = local_[split];
          std::uint32_t best = kNone;
          std::uint64_t best_tag = 0;
          for (std::uint32_t k = inc_start_[i]; k < inc_start_[i + 1]; ++k) {
            const std::uint32_t* c = tet(inc_[k]);
            bool all = true;
            for (int q = 0; q < group && all; ++q) all = tet_has(c, n[q]);
            if (all && (best == kNone || tet_tag(inc_[k]) < best_tag)) {
              best = inc_[k];
              best_tag = tet_tag(best);
            }
          }
          if (best == kNone) {
            unattached = true;
            continue;
          }
          for (int q = 0; q < group; ++q) {
            const std::uint32_t c = copy(n[q], best);
            if (c != n[q]) {
              edits_.push_back({b, e * npe + g0 + q, c});
              moved = true;
            }
          }
        }
        report_.renumbered_elements += moved;
        report_.unattached_elements += unattached;
      }
    }
  }

  void summarize() {
    report_.faults.resize(names_.size());
    for (std::uint32_t f = 0; f < names_.size(); ++f) report_.faults[f].name = names_[f];
    std::vector<Point3> mean(names_.size(), Point3{});
    for (std::size_t i = 0; i < tris_.size(); ++i) {
      auto& s = report_.faults[tris_[i].fault];
      Point3 n;
      const double a2 = tri_area2(tris_[i], &n);
      ++s.triangles;
      s.area += 0.5 * a2;
      for (int d = 0; d < 3; ++d) mean[tris_[i].fault][d] += n[d];
      bool any = false;
      for (int k = 0; k < 3; ++k) any = any || prisms_[6 * i + k] != prisms_[6 * i + 3 + k];
      s.unsplit_triangles += !any;
    }
    for (std::uint32_t f = 0; f < names_.size(); ++f) {
      const double L = norm(mean[f]);
      if (L > 0) report_.faults[f].normal = {mean[f][0] / L, mean[f][1] / L, mean[f][2] / L};
    }
    for (auto p : part_fault_) ++report_.faults[p].parts;
    // Per fault node and fault: split when any of the fault's triangles there separates it.
    for (std::uint32_t i = 0; i < fnodes_.size(); ++i) {
      const std::uint32_t v = fnodes_[i];
      const auto fs = faults_at(i);
      for (auto f : fs) {
        auto& s = report_.faults[f];
        ++s.nodes;
        bool split = false;
        for (std::uint32_t k = tri_start_[i]; k < tri_start_[i + 1] && !split; ++k) {
          const std::uint32_t t = node_tris_[k];
          if (tris_[t].fault != f) continue;
          for (int q = 0; q < 3; ++q)
            if (tris_[t].n[q] == v) split = prisms_[6 * t + q] != prisms_[6 * t + 3 + q];
        }
        (split ? s.duplicated_nodes : s.tip_nodes)++;
        if (fs.size() > 1) {
          ++s.junction_nodes;
          for (auto g : fs)
            if (g != f) ++s.meets[names_[g]];
        }
      }
    }
  }

  // ---- the only place the mesh changes ----
  void apply() {
    // Tetrahedra: the copies of their component.
    for (std::uint32_t i = 0; i < fnodes_.size(); ++i) {
      if (ncopies_[i] == 1) continue;
      const std::uint32_t v = fnodes_[i];
      for (std::uint32_t k = inc_start_[i]; k < inc_start_[i + 1]; ++k) {
        if (inc_copy_[k] == 0) continue;
        auto& blk = m_.blocks[touched_[inc_[k]].block];
        std::uint32_t* c = blk.nodes.data() + 4 * static_cast<std::size_t>(touched_[inc_[k]].elem);
        for (int q = 0; q < 4; ++q)
          if (c[q] == v) c[q] = first_new_[i] + inc_copy_[k] - 1;
      }
    }
    for (const auto& e : edits_) m_.blocks[e.block].nodes[e.pos] = e.node;
    // New nodes: same coordinates, tags above the largest.
    const std::uint64_t base = m_.max_node_tag();
    std::uint64_t next_tag = base + 1;
    m_.node_tags.reserve(m_.num_nodes() + report_.new_nodes);
    m_.nodes.reserve(m_.num_nodes() + report_.new_nodes);
    for (std::uint32_t i = 0; i < fnodes_.size(); ++i)
      for (std::uint32_t c = 1; c < ncopies_[i]; ++c) {
        const Point3 x = m_.nodes[fnodes_[i]];
        m_.add_node(x, next_tag++);
      }
    // Fault triangles out, their groups and entities with them.
    std::vector<ElementBlock> kept;
    kept.reserve(m_.blocks.size());
    for (std::uint32_t b = 0; b < m_.blocks.size(); ++b)
      if (!removed_block_.count(b)) kept.push_back(std::move(m_.blocks[b]));
    m_.blocks = std::move(kept);
    for (int ptag : old_ptag_) {
      for (auto& e : m_.entities)
        if (e.dim == 2) std::erase(e.physicals, ptag);
      std::erase_if(m_.physicals, [&](const PhysicalGroup& p) { return p.dim == 2 && p.tag == ptag; });
    }
    std::erase_if(m_.entities, [&](const Entity& e) {
      if (e.dim != 2 || !e.physicals.empty()) return false;
      for (const auto& b : m_.blocks)
        if (b.entity_dim == 2 && b.entity_tag == e.tag) return false;
      return true;
    });
    // Interface prisms: one dim-3 group and entity per fault; element tags of the triangles.
    int max_ptag = 0, max_etag3 = 0;
    for (const auto& p : m_.physicals) max_ptag = std::max(max_ptag, p.tag);
    for (const auto& e : m_.entities)
      if (e.dim == 3) max_etag3 = std::max(max_etag3, e.tag);
    for (std::uint32_t f = 0; f < names_.size(); ++f) {
      int ptag = old_ptag_[f];
      if (m_.find_physical_tag(3, ptag)) ptag = ++max_ptag;
      m_.physicals.push_back({3, ptag, "fault:" + names_[f]});
      constexpr double inf = std::numeric_limits<double>::infinity();
      Entity ent{3, ++max_etag3, {ptag}, {inf, inf, inf, -inf, -inf, -inf}};
      ElementBlock blk;
      blk.entity_dim = 3;
      blk.entity_tag = ent.tag;
      blk.type = ElementType::Prism;
      for (std::size_t i = 0; i < tris_.size(); ++i) {
        if (tris_[i].fault != f) continue;
        blk.tags.push_back(tris_[i].tag);
        for (int k = 0; k < 6; ++k) {
          const std::uint32_t v = prisms_[6 * i + k];
          blk.nodes.push_back(v);
          for (int d = 0; d < 3; ++d) {
            ent.bbox[d] = std::min(ent.bbox[d], m_.nodes[v][d]);
            ent.bbox[d + 3] = std::max(ent.bbox[d + 3], m_.nodes[v][d]);
          }
        }
      }
      m_.entities.push_back(ent);
      m_.blocks.push_back(std::move(blk));
    }
  }

  Mesh& m_;
  const FaultInsertOptions& opt_;
  FaultInsertReport report_;
  std::vector<std::string> names_;          // faults to insert, without "fault:"
  std::vector<int> old_ptag_;               // their dim-2 physical tags
  std::set<std::uint32_t> removed_block_;   // fault triangle blocks
  std::vector<FaultTri> tris_;
  std::vector<std::uint32_t> local_;        // node -> fault node index (kNone if not on a fault)
  std::vector<std::uint32_t> fnodes_;       // fault nodes by increasing tag
  std::vector<std::uint32_t> tri_start_, node_tris_;  // fault node -> fault triangles
  std::vector<TetRef> touched_;             // tetrahedra with a fault node, in mesh order
  std::vector<std::uint32_t> inc_start_, inc_, inc_copy_;  // fault node -> touched tets (ascending), copy rank
  std::vector<std::uint32_t> part_of_, part_fault_;
  std::vector<std::uint32_t> ncopies_, first_new_;
  std::vector<std::uint32_t> prisms_;
  std::vector<Edit> edits_;
};

std::vector<std::string> groups_with(const Mesh& m, bool prisms) {
  std::vector<std::string> out;
  for (const auto& p : m.physicals) {
    if (!has_fault_prefix(p.name)) continue;
    bool found = false;
    for (const auto& b : m.blocks) {
      if ((b.type == ElementType::Prism) != prisms || (!prisms && b.type != ElementType::Triangle)) continue;
      const Entity* e = m.find_entity(b.entity_dim, b.entity_tag);
      if (e && entity_has(*e, p.dim, p.tag) && b.size() > 0) found = true;
    }
    const std::string n = p.name.substr(6);
    if (found && std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
  }
  return out;
}

}  // namespace

std::vector<std::string> fault_triangle_groups(const Mesh& mesh) { return groups_with(mesh, false); }
std::vector<std::string> fault_interface_groups(const Mesh& mesh) { return groups_with(mesh, true); }

FaultInsertReport insert_faults(Mesh& mesh, const FaultInsertOptions& options) {
  return Inserter(mesh, options).run();
}

}  // namespace ugs
