// Step 2 of the fault cut for one bound of a panel (cutter.hpp; fault_cut.hpp): the edges lying in
// the panel's plane that cross the bound's plane along the panel's edge are bisected there, so that
// the panel's outline is made of mesh edges.
#include "cutter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

#include "ugs/meshing/vec3.hpp"

namespace ugs::fault_cut {

using namespace vec3;

// Step 2 for one bound of one panel: nodes on P next to the bound's plane are snapped onto it
// (staying on P and their other surfaces), then the edges are bisected.
void Cutter::cut_bound(const CutPanel& p, std::size_t bi, double ratio) {
  std::vector<std::pair<Point3, double>> keep{{p.n, p.c}};  // P, and its other bounds
  for (std::size_t k = 0; k < p.bounds.size(); ++k)
    if (k != bi) keep.push_back({p.bounds[k].m, p.bounds[k].d});
  snap_onto(p.bounds[bi].m, p.bounds[bi].d, ratio, bound_edges(p, bi), keep);
  EdgeMap marked;
  const CutHalfSpace& B = p.bounds[bi];
  for (const auto& [a, b] : bound_edges(p, bi)) mark(marked, a, b, dot(B.m, X_[a]) - B.d, dot(B.m, X_[b]) - B.d);
  apply(marked);
}

// The edges lying in P that cross bound bi's plane along Q's edge.
std::vector<std::array<std::uint32_t, 2>> Cutter::bound_edges(const CutPanel& p, std::size_t bi) {
  const CutHalfSpace& B = p.bounds[bi];
  auto on = [&](std::uint32_t i) { return std::abs(dot(p.n, X_[i]) - p.c) <= tol_; };
  auto h = [&](std::uint32_t i) { return dot(B.m, X_[i]) - B.d; };
  // A crossing edge's ends are within |m| times their reach of the bound's plane: only the
  // tetrahedra around such nodes of P can hold one (the others were visited for nothing, one
  // fault plane's worth per bound). The nodes of P come from on_plane (no scan of every node per bound).
  const double mm = norm(B.m);
  std::vector<std::uint32_t> near;
  for (auto i : on_plane(p)) {
    const double reach = i < reach_.size() ? reach_[i] : std::numeric_limits<double>::infinity();
    if (std::abs(h(i)) <= mm * (1.001 * reach + 2 * tol_)) near.push_back(i);
  }
  struct Cand {
    std::uint32_t a, b;
    Point3 x;
    double len;
  };
  std::vector<Cand> cands;
  std::unordered_set<std::uint64_t> seen;
  for (auto i : elements_at(tets_at_, near)) {
    const auto& t = T_[i];
    const bool o[4] = {on(t[0]), on(t[1]), on(t[2]), on(t[3])};
    if (o[0] + o[1] + o[2] + o[3] < 2) continue;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const auto a = t[i], b = t[j];
        if (!o[i] || !o[j]) continue;
        const double ha = h(a), hb = h(b);
        if (!crosses(ha, hb)) continue;
        if (!seen.insert(edge_key(a, b)).second) continue;
        cands.push_back({std::min(a, b), std::max(a, b), crossing(a, b, ha, hb), norm(sub(X_[a], X_[b]))});
      }
  }
  // Edges whose crossing lies along Q's edge, widened by twice the longest such edge: every face
  // of P meeting Q's edge has both its crossing edges cut.
  auto outside_by = [&](const Point3& x) {
    double o = 0;
    for (std::size_t k = 0; k < p.bounds.size(); ++k)
      if (k != bi) o = std::max(o, dot(p.bounds[k].m, x) - p.bounds[k].d);
    return o;
  };
  double margin = 0;
  for (const auto& c : cands)
    if (outside_by(c.x) <= 2 * c.len) margin = std::max(margin, 2 * c.len);
  std::vector<std::array<std::uint32_t, 2>> out;
  for (const auto& c : cands)
    if (outside_by(c.x) <= margin + tol_) out.push_back({c.a, c.b});
  return out;
}

}  // namespace ugs::fault_cut
