// Lookups of the fault cut (cutter.hpp): the nodes on a plane (through the node grid, so that a panel
// visits the nodes near it, not every node), and each node's reach (at least the diameter of its
// tetrahedra), which bounds how far from a node its tetrahedra can hold a crossing.
#include "cutter.hpp"

#include <algorithm>
#include <cmath>

#include "ugs/meshing/vec3.hpp"

namespace ugs::fault_cut {

using namespace vec3;

// The nodes on panel p's plane (within tol_), in no particular order. One scan of every node per
// panel; later calls for the same panel test only the nodes added or snapped since, and those
// found before (a node leaves or joins the plane only by moving: snapped_nodes_).
const std::vector<std::uint32_t>& Cutter::on_plane(const CutPanel& p) {
  auto on = [&](std::uint32_t i) { return std::abs(dot(p.n, X_[i]) - p.c) <= tol_; };
  auto& o = on_plane_;
  if (o.panel != &p) {
    o.panel = &p;
    o.nodes = nodes_on_plane(p.n, p.c);
  } else {
    std::vector<std::uint32_t> test = std::move(o.nodes);
    test.insert(test.end(), snapped_nodes_.begin() + static_cast<std::ptrdiff_t>(o.snapped), snapped_nodes_.end());
    for (std::size_t i = o.scanned; i < X_.size(); ++i) test.push_back(static_cast<std::uint32_t>(i));
    std::sort(test.begin(), test.end());
    test.erase(std::unique(test.begin(), test.end()), test.end());
    o.nodes.clear();
    for (auto i : test)
      if (on(i)) o.nodes.push_back(i);
  }
  o.scanned = X_.size();
  o.snapped = snapped_nodes_.size();
  return o.nodes;
}

// The nodes within tol_ of the plane n . x = c, in increasing order: grid_'s cells whose box
// (widened by a margin for rounding) reaches within tol_ of it, and the nodes added or snapped
// since it was built one by one (the same nodes as a scan of all).
std::vector<std::uint32_t> Cutter::nodes_on_plane(const Point3& n, double c) const {
  auto on = [&](std::uint32_t i) { return std::abs(dot(n, X_[i]) - c) <= tol_; };
  const double round = 1e-8 * (norm(n) * grid_.extent() + std::abs(c));
  std::vector<std::uint32_t> out;
  grid_.visit(
      [&](const Point3& lo, const Point3& hi, double) {
        return !(NodeGrid::min_over(n, c, lo, hi) > tol_ + round || NodeGrid::max_over(n, c, lo, hi) < -tol_ - round);
      },
      [&](std::uint32_t i) {
        if (on(i)) out.push_back(i);
      });
  for (auto v : snapped_nodes_)
    if (v < grid_.nodes() && on(v)) out.push_back(v);
  for (std::size_t i = grid_.nodes(); i < X_.size(); ++i)
    if (on(static_cast<std::uint32_t>(i))) out.push_back(static_cast<std::uint32_t>(i));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// reach_ of a tetrahedron's nodes: at least its diameter (one square root per tetrahedron).
void Cutter::raise_reach(const std::array<std::uint32_t, 4>& t) {
  raise_reach(t, reach_);
  for (auto v : t) grid_.raise(v, reach_[v]);
}

// The same into `reach` only (the constructor's threads, before grid_ is built).
void Cutter::raise_reach(const std::array<std::uint32_t, 4>& t, std::vector<double>& reach) const {
  double d2 = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      const Point3 e = sub(X_[t[i]], X_[t[j]]);
      d2 = std::max(d2, dot(e, e));
    }
  const double d = std::sqrt(d2);
  for (auto v : t) reach[v] = std::max(reach[v], d);
}

}  // namespace ugs::fault_cut
