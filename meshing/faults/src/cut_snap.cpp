// The snap before each cut of the fault cut (cutter.hpp; docs/dipping-faults.md, "Snap"): nodes
// next to a plane moved onto it within their own surfaces, so that the cut makes fewer slivers.
#include "cutter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>

#include "ugs/meshing/mesh_quality.hpp"
#include "ugs/meshing/vec3.hpp"

namespace ugs::fault_cut {

using namespace vec3;

// Snaps nodes onto the plane N . x = C before cutting (docs/dipping-faults.md, "Snap"): where one
// of `edges` crosses the plane within `ratio` of its length from a node, the node is moved onto
// the plane, within the surfaces it lies on (`extra`: more planes it stays on if it lies on them), when its
// tetrahedra stay positive (clear of ugs-solve's flat test: kept_volume) and keep at least half their smallest dihedral angle.
void Cutter::snap_onto(const Point3& N, double C, double ratio, const std::vector<std::array<std::uint32_t, 2>>& edges,
               const std::vector<std::pair<Point3, double>>& extra) {
  if (ratio <= 0 || edges.empty()) return;
  const std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
  auto g = [&](std::uint32_t v) { return dot(N, X_[v]) - C; };
  // Candidates: the end of a crossing edge within ratio of the crossing, nearest first.
  std::unordered_map<std::uint32_t, double> score;
  for (const auto& [a, b] : edges) {
    const double ga = g(a), gb = g(b);
    if (!crosses(ga, gb)) continue;
    const double t = ga / (ga - gb);
    for (auto [v, tv] : {std::pair{a, t}, std::pair{b, 1 - t}}) {
      if (tv >= ratio) continue;
      auto it = score.find(v);
      if (it == score.end() || tv < it->second) score[v] = tv;
    }
  }
  if (score.empty()) return;
  std::vector<std::pair<double, std::uint32_t>> order;
  for (const auto& [v, t] : score) order.push_back({t, v});
  std::sort(order.begin(), order.end());
  std::vector<std::vector<std::uint32_t>> tets_of(order.size());
  std::vector<std::vector<Point3>> normals(order.size());
  for (std::size_t c = 0; c < order.size(); ++c) {
    const std::uint32_t v = order[c].second;
    tets_of[c] = sorted_at(tets_at_, v);
    for (auto i : sorted_at(tris_at_, v)) {
      const auto& f = F_[i];
      normals[c].push_back(unit(cross(sub(X_[f[1]], X_[f[0]]), sub(X_[f[2]], X_[f[0]]))));
    }
  }
  static constexpr int face_of[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (std::size_t c = 0; c < order.size(); ++c) {
    const std::uint32_t v = order[c].second;
    // Faces around v between two materials: shared by two of its tetrahedra of different blocks.
    std::map<std::array<std::uint32_t, 3>, std::uint32_t> face_block;
    for (auto t : tets_of[c])
      for (const auto& f : face_of) {
        std::array<std::uint32_t, 3> key{T_[t][f[0]], T_[t][f[1]], T_[t][f[2]]};
        if (key[0] != v && key[1] != v && key[2] != v) continue;
        std::sort(key.begin(), key.end());
        auto [it, fresh] = face_block.emplace(key, Tb_[t]);
        if (!fresh && it->second != Tb_[t] && it->second != none) {
          normals[c].push_back(unit(cross(sub(X_[key[1]], X_[key[0]]), sub(X_[key[2]], X_[key[0]]))));
          it->second = none;
        }
      }
    // Panels cut so far: their planes, and the outline of those the node lies on.
    for (const CutPanel* q : done_) {
      if (std::abs(dot(q->n, X_[v]) - q->c) > tol_) continue;
      normals[c].push_back(q->n);
      for (const auto& b : q->bounds)
        if (std::abs(dot(b.m, X_[v]) - b.d) <= tol_) normals[c].push_back(b.m);
    }
    for (const auto& [m, d] : extra)
      if (std::abs(dot(m, X_[v]) - d) <= tol_) normals[c].push_back(m);
  }
  // The worst angle of `tets`; kept: each is positive and clear of ugs-solve's flat test (kept_volume).
  auto worst = [&](const std::vector<std::uint32_t>& tets, bool& kept) {
    double a = 180;
    kept = true;
    for (auto t : tets) {
      const auto& e = T_[t];
      kept = kept && kept_volume(X_[e[0]], X_[e[1]], X_[e[2]], X_[e[3]]);
      a = std::min(a, min_dihedral_angle_deg(X_[e[0]], X_[e[1]], X_[e[2]], X_[e[3]]));
    }
    return a;
  };
  for (std::size_t c = 0; c < order.size(); ++c) {
    const std::uint32_t v = order[c].second;
    const double gv = g(v);
    if (std::abs(gv) <= tol_) continue;
    double hmin = std::numeric_limits<double>::infinity();
    for (auto t : tets_of[c])
      for (auto w : T_[t])
        if (w != v) hmin = std::min(hmin, norm(sub(X_[w], X_[v])));
    // The direction of N within the node's surfaces: N minus its part along their normals (a
    // basis of which is built with a loose threshold first, so that a slightly curved layer
    // surface counts as one plane, and then strictly). The move must keep every surface to tol_.
    bool moved = false;
    for (double loose : {0.02, 1e-9}) {
      std::vector<Point3> basis;
      for (const auto& m : normals[c]) {
        Point3 r = m;
        for (const auto& b : basis) r = sub(r, scaled(b, dot(b, r)));
        if (norm(r) > loose) basis.push_back(unit(r));
      }
      if (basis.size() >= 3) break;
      Point3 d = N;
      for (const auto& b : basis) d = sub(d, scaled(b, dot(b, d)));
      const double dd = dot(d, d);
      if (dd < 0.01) break;  // the surfaces run nearly parallel to the plane: the move would be long
      const Point3 delta = scaled(d, -gv / dd);
      if (norm(delta) > 0.5 * hmin) break;
      bool keeps = true;
      for (const auto& m : normals[c]) keeps = keeps && std::abs(dot(m, delta)) <= tol_;
      if (!keeps) continue;
      bool kept0, kept1;
      const double a0 = worst(tets_of[c], kept0);
      const Point3 old = X_[v];
      X_[v] = {old[0] + delta[0], old[1] + delta[1], old[2] + delta[2]};
      const double a1 = worst(tets_of[c], kept1);
      if (kept1 && a1 >= 0.5 * a0) {
        ++snapped_;
        snapped_nodes_.push_back(v);
        moved = true;
        for (auto t : tets_of[c]) raise_reach(T_[t]);
      } else {
        X_[v] = old;
      }
      break;
    }
    (void)moved;
  }
}

}  // namespace ugs::fault_cut
