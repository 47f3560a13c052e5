// The fault cut's clean-up (cutter.hpp; docs/dipping-faults.md, steps 4-6): no tetrahedron left with
// its four nodes on one fault (untear), then the band the cut made improved by collapse and smoothing
// (cut_band_improvement.hpp).
#include "cut_stages.hpp"

#include <algorithm>
#include <unordered_set>

#include "cutter.hpp"
#include "ugs/meshing/vec3.hpp"

namespace ugs::fault_cut {

using namespace vec3;

// A tetrahedron with its four nodes on one fault would be torn apart by ugs-faultinsert (it
// happens where a fault bends, or in slivers between two of its faces): its longest edge that is
// not an edge of the fault is bisected at its midpoint, until there is none. Returns how many.
std::size_t Cutter::untear(std::size_t nfaults) {
  const std::uint32_t nb = static_cast<std::uint32_t>(mesh_.blocks.size());
  std::size_t total = 0;
  for (int iter = 0; iter < 20; ++iter) {
    std::vector<std::vector<char>> on(nfaults, std::vector<char>(X_.size(), 0));
    std::vector<std::unordered_set<std::uint64_t>> edges(nfaults);
    for (std::size_t i = 0; i < F_.size(); ++i) {
      if (Fb_[i] < nb) continue;
      const auto f = Fb_[i] - nb;
      const auto& t = F_[i];
      for (int k = 0; k < 3; ++k) {
        on[f][t[k]] = 1;
        edges[f].insert(edge_key(t[k], t[(k + 1) % 3]));
      }
    }
    EdgeMap marked;
    std::vector<char> on_any(X_.size(), 0);
    for (const auto& o : on)
      for (std::size_t v = 0; v < X_.size(); ++v) on_any[v] |= o[v];
    for (auto ti : elements_at(tets_at_, on_any))
      for (std::size_t f = 0; f < nfaults; ++f) {
        const auto& t = T_[ti];
        if (!(on[f][t[0]] && on[f][t[1]] && on[f][t[2]] && on[f][t[3]])) continue;
        double best = -1;
        std::uint32_t ba = 0, bb = 0;
        for (int i = 0; i < 4; ++i)
          for (int j = i + 1; j < 4; ++j) {
            if (edges[f].count(edge_key(t[i], t[j]))) continue;
            const double l = norm(sub(X_[t[i]], X_[t[j]]));
            if (l > best) {
              best = l;
              ba = t[i];
              bb = t[j];
            }
          }
        if (best < 0) continue;  // every edge on the fault: left to ugs-faultinsert to report
        const auto k = edge_key(ba, bb);
        if (marked.count(k)) continue;
        const Point3& A = X_[std::min(ba, bb)];
        const Point3& B = X_[std::max(ba, bb)];
        marked.emplace(k, static_cast<std::uint32_t>(X_.size()));
        X_.push_back({0.5 * (A[0] + B[0]), 0.5 * (A[1] + B[1]), 0.5 * (A[2] + B[2])});
      }
    if (marked.empty()) break;
    total += marked.size();
    apply(marked);
  }
  return total;
}

// Steps 5 and 6: collapse of short edges and smoothing in the band the cut made
// (cut_band_improvement.hpp).
BandImprovement Cutter::improve(std::size_t first_new, double ratio, double smooth_below_deg, double bound_deg) {
  return improve_cut_band({X_, T_, Tb_, Tp_, F_, Fb_, static_cast<std::uint32_t>(mesh_.blocks.size()), *parent_, bound_deg,
                           [this](std::uint32_t v, std::vector<std::uint32_t>& out) { tets_at_.append(v, out); }},
                          first_new, ratio, smooth_below_deg, tol_);
}

void improve_band(Cutter& cut, const FaultCutOptions& options, FaultCutSummary& sum) {
  const BandImprovement better = cut.improve(sum.nodes_before, options.collapse, options.smooth_below_deg, options.bound_deg);
  sum.collapsed = better.collapsed;
  sum.smoothed = better.moved;
}

}  // namespace ugs::fault_cut
