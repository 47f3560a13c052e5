#include "ugs/meshing/layered_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <stdexcept>
#include <unordered_map>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs {

std::vector<double> sublayer_fractions(int layers, double bias) {
  if (layers < 1) throw std::invalid_argument("sublayer_fractions: layers must be >= 1");
  if (!(bias > 0) || !std::isfinite(bias)) throw std::invalid_argument("sublayer_fractions: bias must be > 0");
  std::vector<double> f(layers + 1, 0.0);
  double w = 1.0, sum = 0.0;
  for (int k = 0; k < layers; ++k, w *= bias) {
    sum += w;
    f[k + 1] = sum;
  }
  for (auto& v : f) v /= sum;
  f[layers] = 1.0;
  return f;
}

namespace {

enum Side { East, West, North, South };
const char* side_name(Side s) {
  static const char* names[] = {"bnd:east", "bnd:west", "bnd:north", "bnd:south"};
  return names[s];
}

Side side_of_normal(double nx, double ny) {
  if (std::abs(nx) > std::abs(ny)) return nx > 0 ? East : West;
  return ny > 0 ? North : South;
}

class Builder {
public:
  Builder(const LayeredMeshInput& in) : in_(in), plan_(*in.plan) { check(); }

  Mesh build(LayeredMeshStats* stats) {
    make_levels();
    make_nodes();
    make_tetrahedra();
    make_boundary();
    make_faults();
    finish();
    if (stats) *stats = stats_;
    return std::move(mesh_);
  }

private:
  void check() const {
    const std::size_t ns = in_.surfaces.size(), nc = plan_.num_columns(), nt = plan_.triangles.size();
    if (ns < 2) throw std::invalid_argument("layered mesh: need at least two surfaces");
    if (in_.units.size() != ns - 1) throw std::invalid_argument("layered mesh: need one unit between two surfaces");
    if (in_.material_of.size() != ns - 1) throw std::invalid_argument("layered mesh: material_of needs one row per unit");
    for (std::size_t s = 0; s < ns; ++s)
      if (in_.surfaces[s].size() != nc) throw std::invalid_argument("layered mesh: one elevation per column");
    for (std::size_t u = 0; u + 1 < ns; ++u) {
      if (in_.units[u].layers < 1) throw std::invalid_argument("layered mesh: sub-layers must be >= 1");
      if (in_.material_of[u].size() != nt) throw std::invalid_argument("layered mesh: one material per triangle");
      for (auto m : in_.material_of[u])
        if (m >= in_.materials.size()) throw std::invalid_argument("layered mesh: material index out of range");
      for (std::size_t c = 0; c < nc; ++c)
        if (!(in_.surfaces[u + 1][c] <= in_.surfaces[u][c]))
          throw std::invalid_argument(fmt::format("layered mesh: surface {} above surface {} at column {}", u + 1, u, c));
    }
  }

  // Level l > 0 of a column lies in unit unit_of_sublayer_[l - 1], at fraction level_frac_[l] of its
  // thickness from its top.
  void make_levels() {
    unit_of_sublayer_.clear();
    level_frac_.assign(1, 0.0);
    for (std::size_t u = 0; u < in_.units.size(); ++u) {
      const auto f = sublayer_fractions(in_.units[u].layers, in_.units[u].bias);
      for (int k = 1; k <= in_.units[u].layers; ++k) {
        unit_of_sublayer_.push_back(static_cast<std::uint32_t>(u));
        level_frac_.push_back(f[k]);
      }
    }
    nlev_ = level_frac_.size();
  }

  double thickness(std::size_t u, std::size_t c) const { return in_.surfaces[u][c] - in_.surfaces[u + 1][c]; }

  void make_nodes() {
    const std::size_t nc = plan_.num_columns();
    node_of_.resize(nc * nlev_);
    stats_.columns = nc;
    stats_.levels = nlev_;
    stats_.pinched_columns.assign(in_.units.size(), 0);
    for (std::size_t u = 0; u < in_.units.size(); ++u)
      for (std::size_t c = 0; c < nc; ++c) stats_.pinched_columns[u] += thickness(u, c) == 0.0;
    mesh_.nodes.reserve(nc * nlev_);
    mesh_.node_tags.reserve(nc * nlev_);
    for (std::size_t c = 0; c < nc; ++c) {
      const auto& xy = plan_.xy[c];
      for (std::size_t l = 0; l < nlev_; ++l) {
        // A level inside (or at the base of) a unit of zero thickness is the node above it.
        if (l > 0 && thickness(unit_of_sublayer_[l - 1], c) == 0.0) {
          node_of_[c * nlev_ + l] = node_of_[c * nlev_ + l - 1];
          continue;
        }
        double z;
        if (l == 0) {
          z = in_.surfaces[0][c];
        } else {
          const std::size_t u = unit_of_sublayer_[l - 1];
          const double f = level_frac_[l];
          z = f == 1.0 ? in_.surfaces[u + 1][c] : in_.surfaces[u][c] - f * thickness(u, c);
        }
        node_of_[c * nlev_ + l] = static_cast<std::uint32_t>(mesh_.nodes.size());
        mesh_.nodes.push_back({xy[0], xy[1], z});
        mesh_.node_tags.push_back(mesh_.nodes.size());
      }
    }
    stats_.nodes = mesh_.nodes.size();
    stats_.merged_nodes = nc * nlev_ - stats_.nodes;
  }

  std::uint32_t node(std::uint32_t column, std::size_t level) const { return node_of_[column * nlev_ + level]; }

  void make_tetrahedra() {
    const auto& tris = plan_.triangles;
    const std::size_t nm = in_.materials.size();
    tets_.assign(nm, {});
    // Sorted columns and orientation of each triangle, computed once.
    std::vector<std::array<std::uint32_t, 3>> sorted(tris.size());
    std::vector<char> ccw(tris.size());
    for (std::size_t t = 0; t < tris.size(); ++t) {
      auto s = tris[t];
      std::sort(s.begin(), s.end());
      sorted[t] = s;
      // The triangle is counter-clockwise in its own order; sorting is an even or odd permutation.
      int inversions = (tris[t][0] > tris[t][1]) + (tris[t][0] > tris[t][2]) + (tris[t][1] > tris[t][2]);
      ccw[t] = inversions % 2 == 0;
    }
    std::vector<std::size_t> estimate(nm, 0);
    for (std::size_t l = 0; l + 1 < nlev_; ++l) {
      const auto& mat = in_.material_of[unit_of_sublayer_[l]];
      for (std::size_t t = 0; t < tris.size(); ++t) estimate[mat[t]] += 12;
    }
    for (std::size_t m = 0; m < nm; ++m) tets_[m].reserve(estimate[m]);
    for (std::size_t l = 0; l + 1 < nlev_; ++l) {
      const auto& mat = in_.material_of[unit_of_sublayer_[l]];
      for (std::size_t t = 0; t < tris.size(); ++t) {
        const auto [v0, v1, v2] = sorted[t];
        const std::uint32_t T0 = node(v0, l), T1 = node(v1, l), T2 = node(v2, l);
        const std::uint32_t B0 = node(v0, l + 1), B1 = node(v1, l + 1), B2 = node(v2, l + 1);
        auto& out = tets_[mat[t]];
        const bool pos = ccw[t];
        // Volumes: +h2, -h1, +h0 times area/3 for a counter-clockwise (v0, v1, v2); swap to make positive.
        if (T2 != B2) pos ? push(out, B0, B1, B2, T2) : push(out, B1, B0, B2, T2);
        else ++stats_.dropped_tetrahedra;
        if (T1 != B1) pos ? push(out, B1, B0, T1, T2) : push(out, B0, B1, T1, T2);
        else ++stats_.dropped_tetrahedra;
        if (T0 != B0) pos ? push(out, B0, T0, T1, T2) : push(out, T0, B0, T1, T2);
        else ++stats_.dropped_tetrahedra;
      }
    }
    for (const auto& v : tets_) stats_.tetrahedra += v.size() / 4;
  }

  static void push(std::vector<std::uint32_t>& v, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    v.insert(v.end(), {a, b, c, d});
  }

  // The two triangles of the vertical face above plan edge a -> b in sub-layer l, split by the
  // prism rule, normal to the right of a -> b; triangles with repeated nodes are skipped.
  void face_triangles(std::uint32_t a, std::uint32_t b, std::size_t l, std::vector<std::uint32_t>& out) const {
    const std::uint32_t Ta = node(a, l), Tb = node(b, l), Ba = node(a, l + 1), Bb = node(b, l + 1);
    auto add = [&](std::uint32_t p, std::uint32_t q, std::uint32_t r) {
      if (p != q && q != r && p != r) out.insert(out.end(), {p, q, r});
    };
    if (a < b) {  // diagonal Ba - Tb
      add(Ba, Bb, Tb);
      add(Ba, Tb, Ta);
    } else {      // diagonal Bb - Ta
      add(Ba, Bb, Ta);
      add(Bb, Tb, Ta);
    }
  }

  void make_boundary() {
    const auto& tris = plan_.triangles;
    auto& top = surface_group("bnd:top");
    auto& bottom = surface_group("bnd:bottom");
    top.reserve(3 * tris.size());
    bottom.reserve(3 * tris.size());
    for (const auto& t : tris) {
      top.insert(top.end(), {node(t[0], 0), node(t[1], 0), node(t[2], 0)});
      bottom.insert(bottom.end(), {node(t[0], nlev_ - 1), node(t[2], nlev_ - 1), node(t[1], nlev_ - 1)});
    }
    // Outer edges: used by one triangle; a -> b in its counter-clockwise order has the outside on the right.
    std::unordered_map<std::uint64_t, int> uses;
    uses.reserve(3 * tris.size());
    auto key = [](std::uint32_t a, std::uint32_t b) {
      return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
    };
    for (const auto& t : tris)
      for (int k = 0; k < 3; ++k) ++uses[key(t[k], t[(k + 1) % 3])];
    std::array<std::vector<std::array<std::uint32_t, 2>>, 4> edges;
    for (const auto& t : tris)
      for (int k = 0; k < 3; ++k) {
        const auto a = t[k], b = t[(k + 1) % 3];
        if (uses[key(a, b)] != 1) continue;
        const double dx = plan_.xy[b][0] - plan_.xy[a][0], dy = plan_.xy[b][1] - plan_.xy[a][1];
        edges[side_of_normal(dy, -dx)].push_back({a, b});
      }
    for (int s : {West, East, South, North}) {
      if (edges[s].empty()) continue;
      auto& out = surface_group(side_name(static_cast<Side>(s)));
      for (std::size_t l = 0; l + 1 < nlev_; ++l)
        for (const auto& [a, b] : edges[s]) face_triangles(a, b, l, out);
    }
    edge_uses_ = std::move(uses);
  }

  void make_faults() {
    auto key = [](std::uint32_t a, std::uint32_t b) {
      return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
    };
    for (const auto& f : in_.faults) {
      if (!(f.top >= f.bottom)) throw std::invalid_argument("layered mesh: fault '" + f.name + "' top below bottom");
      std::vector<std::uint32_t> tri;
      for (const auto& [a, b] : f.edges) {
        if (!edge_uses_.count(key(a, b)))
          throw InputError(plan_.source,
                           fmt::format("fault '{}': segment from node {} ({:.2f}, {:.2f}) to node {} ({:.2f}, {:.2f}) is "
                                       "not an edge of the plan triangles",
                                       f.name, plan_.node_tags[a], plan_.xy[a][0], plan_.xy[a][1], plan_.node_tags[b],
                                       plan_.xy[b][0], plan_.xy[b][1]));
        for (std::size_t l = 0; l + 1 < nlev_; ++l) {
          const double zmid = 0.25 * (mesh_.nodes[node(a, l)][2] + mesh_.nodes[node(b, l)][2] +
                                      mesh_.nodes[node(a, l + 1)][2] + mesh_.nodes[node(b, l + 1)][2]);
          if (zmid <= f.top && zmid >= f.bottom) face_triangles(a, b, l, tri);
        }
      }
      if (tri.empty()) continue;
      auto& out = surface_group("fault:" + f.name);
      out.insert(out.end(), tri.begin(), tri.end());
    }
  }

  std::vector<std::uint32_t>& surface_group(const std::string& name) {
    for (auto& [n, v] : surfaces_)
      if (n == name) return v;
    return surfaces_.emplace_back(name, std::vector<std::uint32_t>{}).second;
  }

  // Physical groups, entities and blocks with tags: tetrahedra first, then triangles.
  void finish() {
    int ptag = 0, etag3 = 0, etag2 = 0;
    std::uint64_t next = 1;
    mesh_.blocks.reserve(in_.materials.size() + surfaces_.size());
    auto add_block = [&](int dim, const std::string& name, ElementType type, std::vector<std::uint32_t>&& nodes) {
      const int p = ++ptag, e = dim == 3 ? ++etag3 : ++etag2;
      mesh_.physicals.push_back({dim, p, name});
      mesh_.entities.push_back({dim, e, {p}, {}});
      ElementBlock b;
      b.entity_dim = dim;
      b.entity_tag = e;
      b.type = type;
      b.nodes = std::move(nodes);
      b.tags.resize(b.nodes.size() / b.npe());
      for (auto& t : b.tags) t = next++;
      mesh_.blocks.push_back(std::move(b));
    };
    for (std::size_t m = 0; m < in_.materials.size(); ++m)
      if (!tets_[m].empty()) add_block(3, "mat:" + in_.materials[m], ElementType::Tetrahedron, std::move(tets_[m]));
    for (auto& [name, tri] : surfaces_)
      if (!tri.empty()) add_block(2, name, ElementType::Triangle, std::move(tri));
    mesh_.update_entity_bboxes();
  }

  const LayeredMeshInput& in_;
  const Plan& plan_;
  std::size_t nlev_ = 0;
  std::vector<std::uint32_t> unit_of_sublayer_;
  std::vector<double> level_frac_;
  std::vector<std::uint32_t> node_of_;
  std::vector<std::vector<std::uint32_t>> tets_;
  std::deque<std::pair<std::string, std::vector<std::uint32_t>>> surfaces_;  // references stay valid
  std::unordered_map<std::uint64_t, int> edge_uses_;
  LayeredMeshStats stats_;
  Mesh mesh_;
};

}  // namespace

Mesh build_layered_mesh(const LayeredMeshInput& in, LayeredMeshStats* stats) {
  if (!in.plan) throw std::invalid_argument("layered mesh: no plan");
  return Builder(in).build(stats);
}

}  // namespace ugs
