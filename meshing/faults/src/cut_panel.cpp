// One panel of the fault cut (cutter.hpp; fault_cut.hpp, steps 1 and 2): the snap onto its plane,
// the edges crossing the plane bisected where its section meets the panel (step 1), the edges along
// each of its bounds (step 2, cut_bound.cpp); then its plane is kept by the later snaps.
#include "cutter.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "ugs/meshing/vec3.hpp"

namespace ugs::fault_cut {

using namespace vec3;

void Cutter::cut_panel(const CutPanel& p, double snap_ratio) {
  snap(p, snap_ratio);
  cut_plane(p);
  for (std::size_t b = 0; b < p.bounds.size(); ++b) cut_bound(p, b, snap_ratio);
  fix_plane(p);
}

// Step 1's snap: nodes of the tetrahedra whose section by P meets Q.
void Cutter::snap(const CutPanel& p, double ratio) { snap_onto(p.n, p.c, ratio, plane_edges(p), {}); }

// The edges crossing P of the tetrahedra whose section by P meets Q.
// Such a tetrahedron of diameter D has an end of a crossing edge within |n| D / 2 of P and,
// for each bound, a node within tol + |m| D of its inside: that end is such a node, and D is at
// most the reach of each of its nodes. So only the tetrahedra around nodes passing that test
// (with a margin for rounding) are examined, in increasing order as a scan of all would meet them.
// The nodes are tested cell by cell of grid_, skipping the cells whose box (widened by their
// largest reach, and by a margin for rounding) cannot hold a node passing the test, and the nodes
// the grid does not place (added or snapped since it was built) one by one: the same nodes pass.
std::vector<std::array<std::uint32_t, 2>> Cutter::plane_edges(const CutPanel& p) const {
  auto g = [&](std::uint32_t i) { return dot(p.n, X_[i]) - p.c; };
  std::vector<std::uint32_t> near;
  const double nn = norm(p.n);
  std::vector<double> mm;
  for (const auto& b : p.bounds) mm.push_back(norm(b.m));
  auto test = [&](std::uint32_t i) {
    const double r = 1.001 * reach_[i] + 2 * tol_;
    bool in = std::abs(g(i)) <= nn * r;
    for (std::size_t k = 0; in && k < p.bounds.size(); ++k) in = dot(p.bounds[k].m, X_[i]) - p.bounds[k].d <= tol_ + mm[k] * r;
    if (in) near.push_back(i);
  };
  const double round = 1e-8 * (nn * grid_.extent() + std::abs(p.c));
  grid_.visit(
      [&](const Point3& lo, const Point3& hi, double reach) {
        const double r = 1.001 * reach + 2 * tol_;
        if (NodeGrid::min_over(p.n, p.c, lo, hi) > nn * r + round || NodeGrid::max_over(p.n, p.c, lo, hi) < -nn * r - round)
          return false;
        for (std::size_t k = 0; k < p.bounds.size(); ++k)
          if (NodeGrid::min_over(p.bounds[k].m, p.bounds[k].d, lo, hi) >
              tol_ + mm[k] * r + 1e-8 * (mm[k] * grid_.extent() + std::abs(p.bounds[k].d)))
            return false;
        return true;
      },
      test);
  for (auto v : snapped_nodes_) test(v);  // moved since the grid was built (tested twice at most: duplicates are harmless)
  for (std::size_t i = grid_.nodes(); i < X_.size(); ++i) test(static_cast<std::uint32_t>(i));
  std::vector<std::array<std::uint32_t, 2>> out;
  std::unordered_set<std::uint64_t> seen;
  std::vector<Point3> section;
  for (auto ti : elements_at(tets_at_, near)) {
    const auto& t = T_[ti];
    const double gt[4] = {g(t[0]), g(t[1]), g(t[2]), g(t[3])};
    double lo = gt[0], hi = lo;
    for (int k = 1; k < 4; ++k) {
      lo = std::min(lo, gt[k]);
      hi = std::max(hi, gt[k]);
    }
    if (!(lo < -tol_ && hi > tol_)) continue;
    section.clear();
    for (int k = 0; k < 4; ++k)
      if (std::abs(gt[k]) <= tol_) section.push_back(X_[t[k]]);
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (crosses(gt[i], gt[j])) section.push_back(crossing(t[i], t[j], gt[i], gt[j]));
    if (separated(section, p.bounds, nullptr)) continue;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (crosses(gt[i], gt[j]) && seen.insert(edge_key(t[i], t[j])).second) out.push_back({t[i], t[j]});
  }
  return out;
}

// Step 1 for one panel.
void Cutter::cut_plane(const CutPanel& p) {
  // Only the crossing edges' ends need their signed distance (no pass over every node).
  auto g = [&](std::uint32_t i) { return dot(p.n, X_[i]) - p.c; };
  EdgeMap marked;
  for (const auto& [a, b] : plane_edges(p)) mark(marked, a, b, g(a), g(b));
  apply(marked);
}

// Is the convex point set outside one of the bounds?
bool Cutter::separated(const std::vector<Point3>& pts, const std::vector<CutHalfSpace>& bounds, const std::size_t* skip) const {
  for (std::size_t k = 0; k < bounds.size(); ++k) {
    if (skip && *skip == k) continue;
    bool all_out = true;
    for (const auto& x : pts)
      if (dot(bounds[k].m, x) <= bounds[k].d + tol_) {
        all_out = false;
        break;
      }
    if (all_out) return true;
  }
  return false;
}

}  // namespace ugs::fault_cut
