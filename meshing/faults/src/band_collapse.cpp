// Step 1 of the band improvement (band_improver.hpp; cut_band_improvement.hpp): a node the cut made
// merged into a neighbour across a short edge, where the neighbour lies on all its surfaces and lines,
// the worst tetrahedron touched gets better and the mesh stays conforming.
#include "band_improver.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <iterator>
#include <set>

#include <Eigen/Dense>

#include "ugs/meshing/vec3.hpp"

namespace ugs::cut_band {

using namespace vec3;

namespace {

Face sorted(Face f) {
  std::sort(f.begin(), f.end());
  return f;
}

bool same(const Face& a, const Face& b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }

}  // namespace

// ---- 1. collapse ------------------------------------------------------------------------------
std::size_t BandImprover::collapse_pass() {
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
bool BandImprover::failed_before(std::uint32_t b, std::uint32_t a) const {
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
const Surfaces* BandImprover::cached_surfaces_of(std::uint32_t v) {
  return collapse_surfaces_.get(
      v, changes_, [&](std::uint64_t time) { return changed_at_[v] <= time; },
      [&](SurfaceTopology&, Surfaces& out) { return surfaces_of(v, out); });
}

bool BandImprover::lies_on(const Surfaces& s, std::uint32_t from, std::uint32_t a) const {
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
bool BandImprover::merged_position(const Surfaces& sa, std::uint32_t a, const Surfaces& sb, std::uint32_t b, double reach, Point3& x) const {
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

bool BandImprover::try_collapse(std::uint32_t b, std::uint32_t a) {
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
  auto four_on_one = [&](const Tet& e) {
    std::vector<std::uint32_t> common = fa;
    for (auto w : e) {
      if (w == a) continue;
      std::vector<std::uint32_t> next;
      std::set_intersection(common.begin(), common.end(), node_faults_[w].begin(), node_faults_[w].end(),
                            std::back_inserter(next));
      common = std::move(next);
    }
    return !common.empty();
  };
  for (const auto& [t, e] : changed)
    if (four_on_one(e)) return undo();
  // a's own tetrahedra too when a takes a fault it was not on (on a curved fault, three of their
  // nodes may already lie on it without the tetrahedron being flat).
  if (fa.size() > node_faults_[a].size())
    for (auto t : tets_of_[a])
      if (!has(s_.tets[t], b) && four_on_one(s_.tets[t])) return undo();
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

}  // namespace ugs::cut_band
