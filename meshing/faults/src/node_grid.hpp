// Nodes binned in a uniform 3-D grid (internal to ugs_meshing), so that a query for the nodes that
// may lie near a plane and inside a few half-spaces visits only the cells whose box can hold one
// instead of every node: fault_cut.cpp's plane_edges scanned the 545,000 nodes of the thesis
// bench twice per panel.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "ugs/formats/mesh.hpp"

namespace ugs {

class NodeGrid {
public:
  // Bins the nodes X[0 .. X.size()) by position, with a per-node distance (`reach`, as many entries)
  // that the queries widen their tests by. About 32 nodes per cell.
  void build(const std::vector<Point3>& X, const std::vector<double>& reach) {
    const std::size_t n = X.size();
    constexpr double inf = std::numeric_limits<double>::infinity();
    Point3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
    for (const auto& x : X)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], x[k]);
        hi[k] = std::max(hi[k], x[k]);
      }
    const int per_axis = std::max(1, static_cast<int>(std::cbrt(static_cast<double>(n) / 32.0)));
    Point3 scale{0, 0, 0};  // cells per unit length (which cell a node goes to only matters for speed)
    for (int k = 0; k < 3; ++k) scale[k] = hi[k] > lo[k] ? per_axis / (hi[k] - lo[k]) : 0.0;
    cell_of_.resize(n);
    std::vector<std::uint32_t> count(static_cast<std::size_t>(per_axis) * per_axis * per_axis, 0);
    for (std::size_t i = 0; i < n; ++i) {
      std::size_t c = 0;
      for (int k = 0; k < 3; ++k) {
        const int b = std::min(per_axis - 1, static_cast<int>((X[i][k] - lo[k]) * scale[k]));
        c = c * static_cast<std::size_t>(per_axis) + static_cast<std::size_t>(std::max(0, b));
      }
      cell_of_[i] = static_cast<std::uint32_t>(c);
      ++count[c];
    }
    start_.assign(count.size() + 1, 0);
    for (std::size_t c = 0; c < count.size(); ++c) start_[c + 1] = start_[c] + count[c];
    nodes_.resize(n);
    std::fill(count.begin(), count.end(), 0);
    for (std::size_t i = 0; i < n; ++i) nodes_[start_[cell_of_[i]] + count[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
    lo_.assign(count.size(), Point3{inf, inf, inf});
    hi_.assign(count.size(), Point3{-inf, -inf, -inf});
    reach_.assign(count.size(), 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t c = cell_of_[i];
      for (int k = 0; k < 3; ++k) {
        lo_[c][k] = std::min(lo_[c][k], X[i][k]);
        hi_[c][k] = std::max(hi_[c][k], X[i][k]);
      }
      reach_[c] = std::max(reach_[c], reach[i]);
    }
    extent_ = 0;
    for (int k = 0; k < 3; ++k)
      if (n > 0) extent_ = std::max({extent_, std::abs(lo[k]), std::abs(hi[k])});
  }

  // The nodes binned (those numbered below); a node added later is not in any cell.
  std::size_t nodes() const { return cell_of_.size(); }
  // The largest absolute coordinate of the binned nodes (for rounding margins).
  double extent() const { return extent_; }

  // Binned node v's reach is now r (reaches only grow).
  void raise(std::uint32_t v, double r) {
    if (v < cell_of_.size()) reach_[cell_of_[v]] = std::max(reach_[cell_of_[v]], r);
  }

  // Calls f(v) for each node of every cell for which may(lo, hi, reach) is true: lo, hi the box of
  // its nodes' positions when built (a node that moved since must be tested by the caller), reach
  // their largest reach.
  template <class May, class F>
  void visit(May&& may, F&& f) const {
    for (std::size_t c = 0; c + 1 < start_.size(); ++c) {
      if (start_[c] == start_[c + 1] || !may(lo_[c], hi_[c], reach_[c])) continue;
      for (std::uint32_t j = start_[c]; j < start_[c + 1]; ++j) f(nodes_[j]);
    }
  }

  // Smallest and largest of a . x - b over the box [lo, hi] (at a corner), in exact arithmetic.
  static double min_over(const Point3& a, double b, const Point3& lo, const Point3& hi) {
    double s = -b;
    for (int k = 0; k < 3; ++k) s += a[k] * (a[k] > 0 ? lo[k] : hi[k]);
    return s;
  }
  static double max_over(const Point3& a, double b, const Point3& lo, const Point3& hi) {
    double s = -b;
    for (int k = 0; k < 3; ++k) s += a[k] * (a[k] > 0 ? hi[k] : lo[k]);
    return s;
  }

private:
  std::vector<std::uint32_t> cell_of_;  // per binned node
  std::vector<std::uint32_t> start_;    // per cell: its first entry in nodes_
  std::vector<std::uint32_t> nodes_;
  std::vector<Point3> lo_, hi_;         // per cell: the box of its nodes
  std::vector<double> reach_;           // per cell: the largest reach of its nodes
  double extent_ = 0;
};

}  // namespace ugs
