// Quality of the tetrahedra a fault cut made (cut_band_improvement.hpp).
#include "cut_band_improvement.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <deque>
#include <limits>
#include <set>
#include <iterator>
#include <tuple>
#include <unordered_map>

#include <Eigen/Dense>

#include "ugs/meshing/mesh_quality.hpp"
#include "ugs/meshing/vec3.hpp"

namespace ugs {
namespace {

using namespace vec3;

using Face = std::array<std::uint32_t, 3>;
using Tet = std::array<std::uint32_t, 4>;

Face sorted(Face f) {
  std::sort(f.begin(), f.end());
  return f;
}

bool same(const Face& a, const Face& b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }

template <class E>
bool has(const E& e, std::uint32_t v) {
  return std::find(e.begin(), e.end(), v) != e.end();
}

constexpr int kFaceOf[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
// Unit normals or directions this close (|cross|, radians) are one plane or line when choosing
// the directions a node may move in; the move must then keep the node within the tolerance of
// every plane (checked). A raster surface's curvature (1e-2) restricts or fixes its nodes.
constexpr double kParallel = 1e-4;

// What a node must stay on: planes (a point and a unit normal) and feature lines (a direction).
// Fault faces lie on a mathematical plane within the on-plane tolerance: a node may move within it
// and stay within the tolerance. Every other surface (boundary, groups, material interfaces, often
// curved raster horizons) must keep its exact shape, so that material volumes do not change: a
// move must lie in each of its faces' planes to rounding (`exact`).
struct Plane {
  Point3 p, n;
  bool exact;
};
struct Line {
  Point3 d;
  bool exact;
};
struct Surfaces {
  std::vector<Plane> planes;
  std::vector<Line> lines;
};

// Which faces through a node are surfaces and which of their edges at the node may be feature lines
// (surfaces_of's first part: incidences only). at_edge is sorted by (group, w, order).
struct EdgeFace {
  std::uint64_t group;
  std::uint32_t w;      // the edge's other node
  std::uint32_t order;  // position among the edges met
  std::uint32_t face;   // index in faces
  std::uint32_t third;  // the face's third node
};
struct SurfaceTopology {
  bool known = false;
  std::vector<std::pair<std::uint64_t, Face>> faces;  // (group, face)
  std::vector<EdgeFace> at_edge;
};

// A node's surfaces kept between the requests of a pass and across passes: one entry per node
// asked for (a slot per node; a deque, so that entries stay put while it grows), computed again
// when the caller's freshness test says that something it depends on changed after `time`.
class SurfaceCache {
public:
  void reset(std::size_t nodes) {
    slot_.assign(nodes, 0);
    entries_.clear();
  }
  // v's surfaces, nullptr when they cannot be computed (a degenerate face). fresh(time): is the entry
  // computed at `time` still valid; compute(SurfaceTopology&, Surfaces&) -> bool fills them (the
  // topology is the entry's own, kept for a caller whose incidences do not change); `now` stamps it.
  template <class Fresh, class Compute>
  const Surfaces* get(std::uint32_t v, std::uint64_t now, Fresh&& fresh, Compute&& compute) {
    if (slot_[v] == 0) {
      entries_.emplace_back();
      slot_[v] = static_cast<std::uint32_t>(entries_.size());
    } else if (const Entry& c = entries_[slot_[v] - 1]; fresh(c.time)) {
      return c.ok ? &c.s : nullptr;
    }
    Entry& c = entries_[slot_[v] - 1];
    c.s.planes.clear();
    c.s.lines.clear();
    c.ok = compute(c.topology, c.s);
    c.time = now;
    return c.ok ? &c.s : nullptr;
  }

private:
  struct Entry {
    bool ok = false;
    SurfaceTopology topology;
    Surfaces s;
    std::uint64_t time = 0;
  };
  std::vector<std::uint32_t> slot_;  // per node: 1 + its entry, 0 none
  std::deque<Entry> entries_;
};

class BandImprover {
public:
  BandImprover(ElementSoup s, std::size_t first_new, double ratio, double smooth_below, double tol)
      : s_(s), first_new_(first_new), ratio_(ratio), smooth_below_(smooth_below), tol_(tol), round_(1e-3 * tol) {}

  BandImprovement run() {
    BandImprovement r;
    tet_dead_.assign(s_.tets.size(), 0);
    find_band();
    tri_dead_.assign(s_.tris.size(), 0);
    node_dead_.assign(s_.nodes.size(), 0);
    collapse_surfaces_.reset(s_.nodes.size());
    changed_at_.assign(s_.nodes.size(), 0);
    if (ratio_ > 0)
      for (int pass = 0; pass < 10; ++pass) {
        const std::size_t n = collapse_pass();
        r.collapsed += n;
        if (n == 0) break;
      }
    smoothing_surfaces_.reset(s_.nodes.size());
    moved_at_.assign(s_.nodes.size(), 0);
    smooth_failed_.assign(s_.nodes.size(), kNever);
    smooth_hint_.assign(s_.nodes.size(), 0);
    nb_slot_.assign(s_.nodes.size(), 0);
    tet_q_slot_.assign(s_.tets.size(), 0);
    tet_q_.clear();
    if (smooth_below_ > 0)
      for (int pass = 0; pass < 6; ++pass) {
        const std::size_t n = smoothing_pass();
        r.moved += n;
        if (n == 0) break;
      }
    compact();
    return r;
  }

private:
  const Point3& X(std::uint32_t v) const { return s_.nodes[v]; }
  double quality(const Tet& t) const { return min_dihedral_angle_deg(X(t[0]), X(t[1]), X(t[2]), X(t[3])); }
  bool positive(const Tet& t) const { return tet_signed_volume(X(t[0]), X(t[1]), X(t[2]), X(t[3])) > 0; }
  // The measure every change must raise (its minimum over the tetrahedra it touches): the smallest
  // dihedral angle relative to min(bound, that of the input tetrahedron it comes from), so that a
  // sliver the input already had (a pinch-out, a thin sub-layer) does not stop the repair of its
  // neighbours, and the cut is held to the bound where the input was better.
  double score(std::uint32_t t, const Tet& e) const { return score_of(t, quality(e)); }
  double score_of(std::uint32_t t, double q) const { return q / score_per(t); }
  double score_per(std::uint32_t t) const {
    const double ref = std::min(s_.bound_deg, s_.parent.quality(s_.tet_parent[t]));
    return std::max(ref, 1e-9);
  }
  bool in_band(const Tet& t) const {
    return t[0] >= first_new_ || t[1] >= first_new_ || t[2] >= first_new_ || t[3] >= first_new_;
  }

  // The band's tetrahedra, and the tetrahedra around the band's nodes (from the caller's
  // incidences: the passes then visit only these). A tetrahedron never enters the band (a collapse
  // replaces a cut node by a neighbour), and the nodes the passes ask about are the band's.
  void find_band() {
    for (std::size_t v = first_new_; v < s_.nodes.size(); ++v) s_.tets_at(static_cast<std::uint32_t>(v), band_);
    std::sort(band_.begin(), band_.end());
    band_.erase(std::unique(band_.begin(), band_.end()), band_.end());
    around_.assign(s_.nodes.size(), {});
    std::vector<char> listed(s_.nodes.size(), 0);
    for (auto t : band_)
      for (auto v : s_.tets[t])
        if (!listed[v]) {
          listed[v] = 1;
          s_.tets_at(v, around_[v]);
        }
  }

  // Incidences of the nodes flagged in `want` (alive elements only), in increasing order.
  // Only the lists of the previous call's nodes are emptied (not half a million per pass: freeing
  // and zeroing them cost more than the lists themselves). `kept`: no incidence changed since the
  // previous call (the smoothing's passes), so the lists made then are still right and only the
  // nodes without one get theirs (the others' lists are not read: every caller asks about `want`).
  void build_adjacency(const std::vector<char>& want, bool kept = false) {
    tets_of_.resize(s_.nodes.size());
    tris_of_.resize(s_.nodes.size());
    listed_at_.resize(s_.nodes.size(), 0);
    if (!kept) {
      for (auto v : listed_) {
        tets_of_[v].clear();
        tris_of_[v].clear();
        listed_at_[v] = 0;
      }
      listed_.clear();
    }
    const std::size_t first = listed_.size();
    for (std::size_t v = 0; v < want.size(); ++v) {
      if (!want[v] || listed_at_[v]) continue;
      listed_.push_back(static_cast<std::uint32_t>(v));
      listed_at_[v] = 1;
      auto& l = tets_of_[v];
      for (auto t : around_[v])
        if (!tet_dead_[t] && has(s_.tets[t], static_cast<std::uint32_t>(v))) l.push_back(t);
      std::sort(l.begin(), l.end());
      l.erase(std::unique(l.begin(), l.end()), l.end());
    }
    if (first == listed_.size()) return;
    std::vector<char> now(want.size(), 0);  // the nodes listed by this call
    for (std::size_t k = first; k < listed_.size(); ++k) now[listed_[k]] = 1;
    for (std::size_t i = 0; i < s_.tris.size(); ++i)
      if (!tri_dead_[i])
        for (auto v : s_.tris[i])
          if (now[v]) tris_of_[v].push_back(static_cast<std::uint32_t>(i));
  }

  // The surfaces through v: its triangles, the faces between two materials and the outer faces
  // around it (a face holding v belongs to tetrahedra holding v, so the counts are exact); its
  // feature lines: edges of a surface group used by other than two faces, or by two faces that are
  // not coplanar. nullopt-like: returns false when a face is degenerate (v stays).
  // In two parts: which faces and edges (incidences only: the smoothing computes them once per
  // node) and their planes and creases (node positions).
  bool surfaces_of(std::uint32_t v, Surfaces& out) const {
    topology_of(v, scratch_.topology);
    return geometry_of(v, scratch_.topology, out);
  }

  void topology_of(std::uint32_t v, SurfaceTopology& topo) const {
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

  bool geometry_of(std::uint32_t v, const SurfaceTopology& topo, Surfaces& out) const {
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

  // ---- 1. collapse ------------------------------------------------------------------------------
  std::size_t collapse_pass() {
    // (length, removed, kept) in that order of priority: a length is a norm (+0 or more, never NaN
    // here), whose bits order as its value, so the three compare as two 64-bit words (sorting
    // tuples of a double and two integers was 4 % of the thesis bench).
    struct Cand {
      std::uint64_t len;   // the bits of the edge's length
      std::uint64_t ends;  // removed << 32 | kept
      bool operator<(const Cand& o) const { return len < o.len || (len == o.len && ends < o.ends); }
      bool operator==(const Cand& o) const { return len == o.len && ends == o.ends; }
    };
    std::vector<Cand> cands;
    std::vector<char> want(s_.nodes.size(), 0);
    node_faults_.resize(s_.nodes.size());  // emptied where filled (not reallocated per pass)
    for (auto v : on_fault_) node_faults_[v].clear();
    on_fault_.clear();
    for (std::size_t i = 0; i < s_.tris.size(); ++i)
      if (!tri_dead_[i] && s_.tri_group[i] >= s_.first_fault_group)
        for (auto v : s_.tris[i]) {
          if (node_faults_[v].empty()) on_fault_.push_back(v);
          if (!has(node_faults_[v], s_.tri_group[i])) node_faults_[v].push_back(s_.tri_group[i]);
        }
    for (auto v : on_fault_) std::sort(node_faults_[v].begin(), node_faults_[v].end());  // the others are empty
    quiet_since_.resize(band_.size(), kNever);
    for (std::size_t k = 0; k < band_.size(); ++k) {
      const auto t = band_[k];
      if (tet_dead_[t] || !in_band(s_.tets[t])) continue;
      const auto& e = s_.tets[t];
      // A tetrahedron that gave no candidate gives none again until a collapse changes one of its
      // nodes (its lengths, its nodes' faults and the tetrahedron itself depend on nothing else).
      const std::uint64_t quiet = quiet_since_[k];
      if (quiet != kNever && changed_at_[e[0]] <= quiet && changed_at_[e[1]] <= quiet && changed_at_[e[2]] <= quiet &&
          changed_at_[e[3]] <= quiet)
        continue;
      const std::size_t before = cands.size();
      // Short: against the longest edge of the tetrahedron, except between two nodes of a fault,
      // where it is against the input tetrahedron's shortest edge: the cut points of successive
      // thin sub-layers are as far apart as the sub-layers and stay, so the fault's interface
      // elements keep the layering's resolution.
      double len[4][4] = {}, longest = 0;
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) longest = std::max(longest, len[i][j] = norm(sub(X(e[i]), X(e[j]))));
      const double shortest = s_.parent.min_edge(s_.tet_parent[t]);
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          const double ref = !node_faults_[e[i]].empty() && !node_faults_[e[j]].empty() ? shortest : longest;
          if (!(len[i][j] < ratio_ * ref)) continue;
          for (auto [b, a] : {std::pair{e[i], e[j]}, std::pair{e[j], e[i]}})
            if (b >= first_new_) {
              cands.push_back({std::bit_cast<std::uint64_t>(len[i][j]), (std::uint64_t{b} << 32) | a});
              want[a] = want[b] = 1;
            }
        }
      quiet_since_[k] = cands.size() == before ? changes_ : kNever;
    }
    if (cands.empty()) return 0;
    std::sort(cands.begin(), cands.end());
    cands.erase(std::unique(cands.begin(), cands.end()), cands.end());
    build_adjacency(want);
    std::vector<char> touched(s_.nodes.size(), 0);
    std::size_t merged = 0;
    for (const auto& c : cands) {
      const auto b = static_cast<std::uint32_t>(c.ends >> 32), a = static_cast<std::uint32_t>(c.ends);
      if (node_dead_[b] || node_dead_[a] || touched[b] || touched[a]) continue;
      if (failed_before(b, a)) continue;
      if (!try_collapse(b, a)) {
        failed_at_[(std::uint64_t{b} << 32) | a] = changes_;
        continue;
      }
      ++merged;
      // Incidences around b changed: its neighbourhood waits for the next pass. The surfaces of
      // b's and a's neighbours changed with them (incidences, a's position): computed again when asked.
      ++changes_;
      for (auto t : tets_of_[b])
        for (auto v : s_.tets[t]) {
          touched[v] = 1;
          changed_at_[v] = changes_;
        }
      for (auto t : tets_of_[a])
        for (auto v : s_.tets[t]) changed_at_[v] = changes_;
    }
    return merged;
  }

  // A collapse of b into a that failed fails again while no collapse has changed a tetrahedron
  // around b or a, moved one of their nodes or changed one of their nodes' faults (each of these
  // marks the nodes of every tetrahedron it touched: changed_at_): the trial depends on nothing
  // else. The later passes meet the same ten thousand failing candidates again (thesis bench).
  bool failed_before(std::uint32_t b, std::uint32_t a) const {
    const auto it = failed_at_.find((std::uint64_t{b} << 32) | a);
    if (it == failed_at_.end()) return false;
    const std::uint64_t at = it->second;
    for (auto v : {b, a})
      for (auto t : tets_of_[v])
        for (auto w : s_.tets[t])
          if (changed_at_[w] > at) return false;
    return true;
  }

  // surfaces_of once per node over the collapse passes (a node is the end of several candidate
  // edges, and is asked again in later passes); nullptr when surfaces_of fails. Computed again
  // after a collapse changed the node's tetrahedra or moved one of their nodes: they depend on
  // nothing else (tets_of_ lists are sorted, so a rebuilt list of the same tetrahedra is the same).
  const Surfaces* cached_surfaces_of(std::uint32_t v) {
    return collapse_surfaces_.get(
        v, changes_, [&](std::uint64_t time) { return changed_at_[v] <= time; },
        [&](SurfaceTopology&, Surfaces& out) { return surfaces_of(v, out); });
  }

  bool lies_on(const Surfaces& s, std::uint32_t from, std::uint32_t a) const {
    for (const auto& pl : s.planes)
      if (std::abs(dot(pl.n, sub(X(a), pl.p))) > (pl.exact ? round_ : tol_)) return false;
    const Point3 d = sub(X(a), X(from));
    for (const auto& l : s.lines)
      if (norm(cross(d, l.d)) > (l.exact ? round_ : tol_)) return false;
    return true;
  }

  // The point nearest to a on every surface and line of a and of b (two cuts that met at a small
  // angle leave nodes a few tolerances apart on different constraints: the merged node must keep
  // both). A line through q along l counts as two planes. False when they do not meet near a.
  bool merged_position(const Surfaces& sa, std::uint32_t a, const Surfaces& sb, std::uint32_t b, double reach, Point3& x) const {
    struct Con {
      Point3 n;
      double c;
      bool exact;
    };
    std::vector<Con> cons;
    for (const Surfaces* s : {&sa, &sb})
      for (const auto& pl : s->planes) cons.push_back({pl.n, dot(pl.n, pl.p), pl.exact});
    for (auto [s, q] : {std::pair{&sa, a}, std::pair{&sb, b}})
      for (const auto& l : s->lines) {
        const Point3 t = std::abs(l.d[0]) < 0.9 ? Point3{1, 0, 0} : Point3{0, 1, 0};
        const Point3 u1 = scaled(cross(l.d, t), 1 / norm(cross(l.d, t)));
        const Point3 u2 = cross(l.d, u1);
        cons.push_back({u1, dot(u1, X(q)), l.exact});
        cons.push_back({u2, dot(u2, X(q)), l.exact});
      }
    Eigen::MatrixXd A(cons.size(), 3);
    Eigen::VectorXd r(cons.size());
    for (std::size_t i = 0; i < cons.size(); ++i) {
      for (int k = 0; k < 3; ++k) A(static_cast<Eigen::Index>(i), k) = cons[i].n[k];
      r(static_cast<Eigen::Index>(i)) = cons[i].c - dot(cons[i].n, X(a));
    }
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(A);
    const bool z_built = cod.rank() < A.cols();  // Z exists only when the default threshold found A rank deficient
    cod.setThreshold(1e-6);
    Eigen::Vector3d dx;
    if (z_built || cod.rank() == A.cols()) {
      dx = cod.solve(r);
    } else {
      // Rank deficient at 1e-6 only: solve() would apply a Z factor that was never computed (Eigen
      // builds it for the rank found at compute(); its coefficients are then uninitialised memory,
      // which made the mesh depend on what the heap held). The basic solution instead: what solve()
      // gives with Z = identity, the outcome the meshes so far had.
      const Eigen::Index rank = cod.rank();
      dx.setZero();
      if (rank > 0) {
        Eigen::VectorXd c = r;
        c.applyOnTheLeft(cod.householderQ().setLength(rank).adjoint());
        dx.topRows(rank) = cod.matrixT().topLeftCorner(rank, rank).template triangularView<Eigen::Upper>().solve(c.topRows(rank));
        dx = cod.colsPermutation() * dx;
      }
    }
    x = {X(a)[0] + dx(0), X(a)[1] + dx(1), X(a)[2] + dx(2)};
    if (!(dx.norm() <= reach)) return false;
    for (const auto& k : cons)
      if (std::abs(dot(k.n, x) - k.c) > (k.exact ? round_ : tol_)) return false;
    return true;
  }

  bool try_collapse(std::uint32_t b, std::uint32_t a) {
    // The kept node must lie on b's surfaces and lines (a node on a fault's outline stays on that
    // line: the fault keeps its extent), moved there if needed (within half the edge, staying on
    // its own).
    const Surfaces* sbp = cached_surfaces_of(b);
    if (!sbp) return false;
    const Surfaces& sb = *sbp;
    const Point3 xa = X(a);
    Point3 x = xa;
    if (!lies_on(sb, b, a)) {
      const Surfaces* sa = cached_surfaces_of(a);
      if (!sa || !merged_position(*sa, a, sb, b, 0.5 * norm(sub(X(b), xa)), x)) return false;
    }
    const bool moves = x[0] != xa[0] || x[1] != xa[1] || x[2] != xa[2];
    double before = std::numeric_limits<double>::infinity();
    if (moves)
      for (auto t : tets_of_[a]) before = std::min(before, score(t, s_.tets[t]));
    std::vector<std::pair<std::uint32_t, Tet>> changed;
    for (auto t : tets_of_[b]) {
      before = std::min(before, score(t, s_.tets[t]));
      if (has(s_.tets[t], a)) continue;
      auto e = s_.tets[t];
      std::replace(e.begin(), e.end(), b, a);
      changed.push_back({t, e});
    }
    s_.nodes[a] = x;
    auto undo = [&] {
      s_.nodes[a] = xa;
      return false;
    };
    double after = std::numeric_limits<double>::infinity();
    for (const auto& [t, e] : changed) {
      if (!positive(e)) return undo();
      after = std::min(after, score(t, e));
    }
    for (auto t : tets_of_[a]) {  // a's own tetrahedra, when it moved
      if (!moves || has(s_.tets[t], b)) continue;
      const auto& e = s_.tets[t];
      if (!positive(e)) return undo();
      after = std::min(after, score(t, e));
    }
    if (!(after > before)) return undo();
    // Conforming around a: no face of three tetrahedra, no element twice (sorted keys in flat
    // arrays: the maps they replace allocated a node per face).
    auto& elems = conform_scratch_.elems;
    auto& uses = conform_scratch_.faces;
    elems.clear();
    uses.clear();
    auto add_tet = [&](const Tet& e) {
      Tet k = e;
      std::sort(k.begin(), k.end());
      elems.push_back(k);
      for (const auto& f : kFaceOf) uses.push_back(sorted({e[f[0]], e[f[1]], e[f[2]]}));
    };
    for (auto t : tets_of_[a])
      if (!has(s_.tets[t], b)) add_tet(s_.tets[t]);
    for (const auto& [t, e] : changed) add_tet(e);
    std::sort(elems.begin(), elems.end());
    if (std::adjacent_find(elems.begin(), elems.end()) != elems.end()) return undo();
    std::sort(uses.begin(), uses.end());
    for (std::size_t i = 0; i + 2 < uses.size(); ++i)
      if (same(uses[i], uses[i + 2])) return undo();
    std::set<Face> tris;
    for (auto i : tris_of_[a])
      if (!has(s_.tris[i], b)) tris.insert(sorted(s_.tris[i]));
    std::vector<std::pair<std::uint32_t, Face>> changed_tris;
    for (auto i : tris_of_[b]) {
      if (has(s_.tris[i], a)) continue;
      Face f = s_.tris[i];
      std::replace(f.begin(), f.end(), b, a);
      if (!tris.insert(sorted(f)).second) return undo();
      const Face& o = s_.tris[i];  // same orientation (a fault's faces face its hanging wall)
      if (!(dot(cross(sub(X(o[1]), X(o[0])), sub(X(o[2]), X(o[0]))), cross(sub(X(f[1]), X(f[0])), sub(X(f[2]), X(f[0])))) > 0))
        return undo();
      changed_tris.push_back({i, f});
    }
    // No tetrahedron with its four nodes on one fault (a takes b's faults along).
    std::vector<std::uint32_t> fa = node_faults_[a];
    for (auto g : node_faults_[b])
      if (!has(fa, g)) fa.push_back(g);
    std::sort(fa.begin(), fa.end());
    for (const auto& [t, e] : changed) {
      std::vector<std::uint32_t> common = fa;
      for (auto w : e) {
        if (w == a) continue;
        std::vector<std::uint32_t> next;
        std::set_intersection(common.begin(), common.end(), node_faults_[w].begin(), node_faults_[w].end(),
                              std::back_inserter(next));
        common = std::move(next);
      }
      if (!common.empty()) return undo();
    }
    for (auto t : tets_of_[b])
      if (has(s_.tets[t], a)) tet_dead_[t] = 1;
    for (auto i : tris_of_[b])
      if (has(s_.tris[i], a)) tri_dead_[i] = 1;
    for (const auto& [t, e] : changed) {
      s_.tets[t] = e;
      around_[a].push_back(t);
    }
    for (const auto& [i, f] : changed_tris) s_.tris[i] = f;
    if (node_faults_[a].empty() && !fa.empty()) on_fault_.push_back(a);
    node_faults_[a] = std::move(fa);
    node_dead_[b] = 1;
    return true;
  }

  // ---- 2. smoothing ---------------------------------------------------------------------------
  std::size_t smoothing_pass() {
    std::vector<char> want(s_.nodes.size(), 0);
    std::vector<std::pair<double, std::uint32_t>> order;  // (worst score, node)
    std::vector<double> worst(s_.nodes.size(), 180);
    if (smooth_band_.empty())
      for (auto t : band_)
        if (!tet_dead_[t] && in_band(s_.tets[t])) smooth_band_.push_back({s_.tets[t], t, score_per(t), 0.0, kNever});
    for (auto& b : smooth_band_) {
      const auto& e = b.e;
      if (b.time == kNever || moved_at_[e[0]] > b.time || moved_at_[e[1]] > b.time || moved_at_[e[2]] > b.time || moved_at_[e[3]] > b.time) {
        b.q = smoothing_quality(b.t);
        b.time = moves_;
      }
      const double qa = b.q;
      const double q = qa / b.per;  // score_of(b.t, qa)
      if (!(q < 1) && !(qa < smooth_below_)) continue;
      for (auto v : e)
        if (!node_dead_[v]) {
          want[v] = 1;
          worst[v] = std::min(worst[v], q);
        }
    }
    for (std::size_t v = 0; v < want.size(); ++v)
      if (want[v]) order.push_back({worst[v], static_cast<std::uint32_t>(v)});
    if (order.empty()) return 0;
    std::sort(order.begin(), order.end());
    build_adjacency(want, smoothing_lists_);
    smoothing_lists_ = true;
    std::size_t moved = 0;
    for (const auto& [q, v] : order) {
      if (smooth_failed_[v] != kNever && !moved_around(v, smooth_failed_[v])) continue;
      if (smooth(v)) ++moved;
      else smooth_failed_[v] = moves_;
    }
    return moved;
  }

  // Has a node of v's tetrahedra or triangles moved after moves_ was `at`? A smoothing step of v
  // depends on nothing else (its surfaces, its neighbours' mean, its tetrahedra's angles), so one
  // that failed fails again until then (most candidates of the later passes on the thesis bench).
  bool moved_around(std::uint32_t v, std::uint64_t at) const {
    for (auto t : tets_of_[v])
      for (auto w : s_.tets[t])
        if (moved_at_[w] > at) return true;
    for (auto i : tris_of_[v])
      for (auto w : s_.tris[i])
        if (moved_at_[w] > at) return true;
    return false;
  }

  // surfaces_of for the smoothing, kept across its passes: they change no incidence, so v's
  // surfaces stay as computed until v or a node of its tetrahedra or triangles moves, and then only
  // their planes and creases are computed again (the faces and edges, sorted once per node).
  const Surfaces* smoothing_surfaces_of(std::uint32_t v) {
    return smoothing_surfaces_.get(
        v, moves_, [&](std::uint64_t time) { return !moved_around(v, time); }, [&](SurfaceTopology& topo, Surfaces& out) {
          if (!topo.known) topology_of(v, topo);
          return geometry_of(v, topo, out);
        });
  }

  // A tetrahedron's smallest dihedral angle during the smoothing, kept until one of its nodes
  // moves (the smoothing changes no incidence).
  double smoothing_quality(std::uint32_t t) {
    const auto& e = s_.tets[t];
    auto& c = cached_quality(t);
    const std::uint64_t at = c.time;
    if (at != kNever && moved_at_[e[0]] <= at && moved_at_[e[1]] <= at && moved_at_[e[2]] <= at && moved_at_[e[3]] <= at)
      return c.q;
    c = {quality(e), moves_};
    return c.q;
  }

  bool smooth(std::uint32_t v) {
    const Surfaces* sp = smoothing_surfaces_of(v);
    if (!sp) return false;
    const Surfaces& s = *sp;
    // The directions v may move in: within every plane and along its feature line, if any (exact
    // surfaces to rounding, faults to kParallel).
    std::vector<Point3> normals;
    for (const auto& pl : s.planes) {
      Point3 r = pl.n;
      for (const auto& b : normals) r = sub(r, scaled(b, dot(b, r)));
      if (norm(r) > (pl.exact ? 1e-9 : kParallel)) normals.push_back(scaled(r, 1 / norm(r)));
      if (normals.size() == 3) return false;
    }
    const Line* line = nullptr;
    for (const auto& l : s.lines) {
      if (!line) line = &l;
      else if (norm(cross(line->d, l.d)) > (l.exact || line->exact ? 1e-9 : kParallel)) return false;  // a corner
    }
    Point3 mean{0, 0, 0};
    const auto& nb = neighbours_of(v);  // sorted, unique: the mean adds them in increasing order
    for (auto w : nb) mean = add(mean, scaled(X(w), 1.0 / static_cast<double>(nb.size())));
    Point3 d = sub(mean, X(v));
    if (!line) {
      for (const auto& n : normals) d = sub(d, scaled(n, dot(n, d)));
    } else {
      // Along the feature line, if it lies in every plane (else it crosses one there: a corner).
      for (const auto& pl : s.planes)
        if (std::abs(dot(pl.n, line->d)) > (pl.exact || line->exact ? 1e-9 : kParallel)) return false;
      d = scaled(line->d, dot(d, line->d));
    }
    if (!(norm(d) > 0)) return false;
    double before = std::numeric_limits<double>::infinity();
    for (auto t : tets_of_[v]) before = std::min(before, score_of(t, smoothing_quality(t)));
    const Point3 x0 = X(v);
    auto& trial = trial_scratch_;
    for (double step : {1.0, 0.5, 0.25, 0.125}) {
      s_.nodes[v] = add(x0, scaled(d, step));
      // Exact surfaces keep the node to rounding, faults within the tolerance.
      bool ok = true;
      for (const auto& pl : s.planes) ok = ok && std::abs(dot(pl.n, sub(X(v), pl.p))) <= (pl.exact ? round_ : tol_);
      // The step is taken when every tetrahedron stays positive and scores above `before`: the
      // first that does not ends the trial (the rest cannot change the answer, and neither can the
      // order they are tested in). So the tetrahedron that failed last for v goes first (it
      // usually fails again: ~2 million angles were computed for trials that failed, thesis
      // bench), then the cheap volumes of the others, then their angles.
      const auto& tets = tets_of_[v];
      const std::size_t n = tets.size();
      std::uint32_t& hint = smooth_hint_[v];
      if (hint >= n) hint = 0;
      trial.assign(n, 0.0);
      auto scores_above = [&](std::size_t i) {
        trial[i] = quality(s_.tets[tets[i]]);
        return !(score_of(tets[i], trial[i]) <= before);  // as min(after, NaN) kept `after`
      };
      if (ok && n > 0) ok = positive(s_.tets[tets[hint]]) && scores_above(hint);
      for (std::size_t i = 0; ok && i < n; ++i)
        if (i != hint && !positive(s_.tets[tets[i]])) {
          ok = false;
          hint = static_cast<std::uint32_t>(i);
        }
      for (std::size_t i = 0; ok && i < n; ++i)
        if (i != hint && !scores_above(i)) {
          ok = false;
          hint = static_cast<std::uint32_t>(i);
        }
      if (ok) {
        moved_at_[v] = ++moves_;
        for (std::size_t i = 0; i < trial.size(); ++i) {
          cached_quality(tets_of_[v][i]) = {trial[i], moves_};
        }
        return true;
      }
    }
    s_.nodes[v] = x0;
    return false;
  }

  // v's neighbours (the other nodes of its tetrahedra), sorted: the smoothing changes no incidence,
  // so they are listed once per node over its passes.
  const std::vector<std::uint32_t>& neighbours_of(std::uint32_t v) {
    std::uint32_t& slot = nb_slot_[v];
    if (slot == 0) {
      auto& nb = nb_lists_.emplace_back();
      for (auto t : tets_of_[v])
        for (auto w : s_.tets[t])
          if (w != v) nb.push_back(w);
      std::sort(nb.begin(), nb.end());
      nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
      slot = static_cast<std::uint32_t>(nb_lists_.size());
    }
    return nb_lists_[slot - 1];
  }

  void compact() {
    std::vector<std::uint32_t> to(s_.nodes.size());
    std::size_t n = 0;
    for (std::size_t v = 0; v < s_.nodes.size(); ++v) {
      if (v >= first_new_ && node_dead_[v]) continue;
      to[v] = static_cast<std::uint32_t>(n);
      s_.nodes[n++] = s_.nodes[v];
    }
    s_.nodes.resize(n);
    std::size_t k = 0;
    for (std::size_t t = 0; t < s_.tets.size(); ++t) {
      if (tet_dead_[t]) continue;
      for (auto& v : s_.tets[t]) v = to[v];
      s_.tets[k] = s_.tets[t];
      s_.tet_parent[k] = s_.tet_parent[t];
      s_.tet_block[k++] = s_.tet_block[t];
    }
    s_.tets.resize(k);
    s_.tet_block.resize(k);
    s_.tet_parent.resize(k);
    k = 0;
    for (std::size_t i = 0; i < s_.tris.size(); ++i) {
      if (tri_dead_[i]) continue;
      for (auto& v : s_.tris[i]) v = to[v];
      s_.tris[k] = s_.tris[i];
      s_.tri_group[k++] = s_.tri_group[i];
    }
    s_.tris.resize(k);
    s_.tri_group.resize(k);
  }

  struct Around {
    std::uint64_t key;  // the face's two nodes other than v, lower one first: sorts as the sorted faces
    Face tri;
    std::uint32_t block;
    std::uint32_t order;  // position among the faces met, for the pairing in surfaces_of
  };
  struct ConformScratch {
    std::vector<Tet> elems;
    std::vector<Face> faces;
  };
  ConformScratch conform_scratch_;  // try_collapse's arrays
  struct Scratch {
    SurfaceTopology topology;
    std::vector<std::pair<std::uint64_t, Face>> outer;
    std::vector<Around> around;
    std::vector<std::pair<std::uint32_t, std::pair<std::uint64_t, Face>>> between;
    std::vector<Point3> normal;
  };
  mutable Scratch scratch_;  // surfaces_of's arrays
  SurfaceCache smoothing_surfaces_;             // stamped with moves_
  std::vector<std::uint64_t> moved_at_;        // per node: moves_ after its last smoothing move, 0 never
  std::uint64_t moves_ = 0;
  std::vector<std::uint64_t> smooth_failed_;   // per node: moves_ when its last smoothing step failed, kNever none
  std::vector<std::uint32_t> smooth_hint_;      // per node: the index in its tets_of_ list of the tetrahedron that failed its last trial step
  std::vector<std::uint32_t> nb_slot_;                 // per node: 1 + its entry in nb_lists_, 0 none
  std::deque<std::vector<std::uint32_t>> nb_lists_;    // neighbours_of's lists
  static constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();
  // The band's tetrahedra during the smoothing (which changes no incidence), in band_'s order, with
  // what the pass' scan needs in one place (it read five arrays of millions at random per tetrahedron).
  struct SmoothBandTet {
    Tet e;
    std::uint32_t t;
    double per;          // score_of(t, q) = q / per
    double q;            // smoothing_quality(t) when computed
    std::uint64_t time;  // moves_ then, kNever none
  };
  std::vector<SmoothBandTet> smooth_band_;
  struct CachedQuality {
    double q;            // smoothing_quality's value
    std::uint64_t time;  // moves_ when computed, kNever none
  };
  // Tetrahedron t's entry, made when first asked for: only the band's neighbourhood is (a few
  // hundred thousand of 3.2 million), so the entries sit together instead of 51 MB read at random.
  CachedQuality& cached_quality(std::uint32_t t) {
    std::uint32_t& slot = tet_q_slot_[t];
    if (slot == 0) {
      tet_q_.push_back({0.0, kNever});
      slot = static_cast<std::uint32_t>(tet_q_.size());
    }
    return tet_q_[slot - 1];
  }
  std::vector<std::uint32_t> tet_q_slot_;      // per tetrahedron: 1 + its entry in tet_q_, 0 none
  std::vector<CachedQuality> tet_q_;           // one cache line for both
  std::vector<double> trial_scratch_;          // qualities of a node's tetrahedra at a trial position
  SurfaceCache collapse_surfaces_;         // stamped with changes_
  std::vector<std::uint64_t> changed_at_;  // per node: changes_ after the last collapse around it
  std::uint64_t changes_ = 0;              // successful collapses so far
  std::vector<std::uint64_t> quiet_since_;  // per band_ entry: changes_ when it last gave no collapse candidate, kNever else
  std::unordered_map<std::uint64_t, std::uint64_t> failed_at_;  // (b << 32 | a) -> changes_ when its collapse failed
  ElementSoup s_;
  std::size_t first_new_;
  double ratio_, smooth_below_, tol_;
  double round_;  // "to rounding": a thousandth of the on-plane tolerance (1e-10 of the model's size)
  std::vector<char> tet_dead_, tri_dead_, node_dead_;
  std::vector<std::vector<std::uint32_t>> tets_of_, tris_of_;  // of the nodes of the last build_adjacency, else empty
  std::vector<std::uint32_t> listed_;                         // those nodes
  std::vector<char> listed_at_;                               // per node: in listed_
  bool smoothing_lists_ = false;                              // the smoothing has built its first lists
  std::vector<std::uint32_t> band_;                   // the band's tetrahedra at the start, increasing
  std::vector<std::vector<std::uint32_t>> around_;   // per band node: tetrahedra that held it (may be stale)
  std::vector<std::vector<std::uint32_t>> node_faults_;  // fault groups per node (collapse pass)
  std::vector<std::uint32_t> on_fault_;                  // the nodes whose node_faults_ may be filled
};

}  // namespace

InputTetShape::InputTetShape(std::vector<Point3> nodes, std::vector<std::span<const std::uint32_t>> tet_arrays)
    : nodes_(std::move(nodes)), arrays_(std::move(tet_arrays)) {
  std::size_t n = 0;
  for (const auto& a : arrays_) {
    first_.push_back(static_cast<std::uint32_t>(n));
    n += a.size() / 4;
  }
  quality_.assign(n, kUnknown);
  min_edge_.assign(n, kUnknown);
}

std::array<std::uint32_t, 4> InputTetShape::tet(std::uint32_t p) const {
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(first_.begin(), first_.end(), p) - first_.begin()) - 1;
  const std::uint32_t* e = arrays_[k].data() + std::size_t{4} * (p - first_[k]);
  return {e[0], e[1], e[2], e[3]};
}

double InputTetShape::quality(std::uint32_t p) const {
  if (quality_[p] == kUnknown) {
    const auto e = tet(p);
    quality_[p] = min_dihedral_angle_deg(nodes_[e[0]], nodes_[e[1]], nodes_[e[2]], nodes_[e[3]]);
  }
  return quality_[p];
}

double InputTetShape::min_edge(std::uint32_t p) const {
  if (min_edge_[p] == kUnknown) {
    const auto e = tet(p);
    double shortest = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) shortest = std::min(shortest, vec3::norm(vec3::sub(nodes_[e[i]], nodes_[e[j]])));
    min_edge_[p] = shortest;
  }
  return min_edge_[p];
}

BandImprovement improve_cut_band(ElementSoup soup, std::size_t first_new, double ratio, double smooth_below_deg, double tol) {
  if (first_new >= soup.nodes.size()) return {};
  return BandImprover(soup, first_new, ratio, smooth_below_deg, tol).run();
}

}  // namespace ugs
