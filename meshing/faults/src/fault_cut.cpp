// Conforming cut of a tetrahedral mesh by fault panels (fault_cut.hpp, docs/dipping-faults.md).
#include "ugs/meshing/fault_cut.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/formats/run_beside.hpp"
#include "ugs/meshing/mesh_quality.hpp"
#include "cut_band_improvement.hpp"
#include "node_grid.hpp"
#include "ugs/meshing/vec3.hpp"

namespace ugs {
namespace {

using namespace vec3;

constexpr double kPi = 3.14159265358979323846;

double cot_deg(double dip_deg) {
  if (dip_deg >= 90) return 0.0;
  const double d = dip_deg * kPi / 180;
  return std::cos(d) / std::sin(d);
}

using P2 = std::array<double, 2>;

// Panels of a trace without `ends_against` handling.
std::vector<CutPanel> plain_panels(const FaultTrace& tr) {
  const double az = tr.dip_dir_deg * kPi / 180;
  const double dx = std::sin(az), dy = std::cos(az);
  std::vector<CutPanel> out;
  const auto pcs = tr.piece_list();
  double above = tr.top;
  for (std::size_t j = 0; j < pcs.size(); ++j) {
    const double below = pcs[j].bottom, cot = cot_deg(pcs[j].dip_deg);
    const double off = tr.offset_at(above);  // offset of the piece's top line from the trace
    const Point3 w{dx * cot, dy * cot, -1.0};
    const Point3 wu = unit(w);
    const double dip = pcs[j].dip_deg * kPi / 180;
    const Point3 ref{-dx * std::sin(dip), -dy * std::sin(dip), -std::cos(dip)};
    std::size_t seg = 0;
    for (const auto& part : tr.parts) {
      const std::size_t nv = part.size();
      // Horizontal direction of the lateral bound at each vertex: the bisector of the segments.
      std::vector<Point3> h(nv);
      for (std::size_t v = 0; v < nv; ++v) {
        Point3 s{0, 0, 0};
        if (v > 0) {
          const Point3 e{part[v][0] - part[v - 1][0], part[v][1] - part[v - 1][1], 0};
          s = unit(e);
        }
        if (v + 1 < nv) {
          const Point3 e = unit(Point3{part[v + 1][0] - part[v][0], part[v + 1][1] - part[v][1], 0});
          s = {s[0] + e[0], s[1] + e[1], 0};
        }
        const Point3 m = sub(s, scaled(wu, dot(s, wu)));  // perpendicular to the down-dip direction
        h[v] = unit(m);
      }
      for (std::size_t i = 0; i + 1 < nv; ++i, ++seg) {
        const Point3 A{part[i][0] + off * dx, part[i][1] + off * dy, above};
        const Point3 B{part[i + 1][0] + off * dx, part[i + 1][1] + off * dy, above};
        CutPanel p;
        p.piece = j;
        p.segment = seg;
        Point3 n = unit(cross(sub(B, A), w));
        if (dot(n, ref) < 0 || (dot(n, ref) == 0 && n[1] + n[0] * 1e-9 > 0)) n = scaled(n, -1);
        p.n = n;
        p.c = dot(n, A);
        p.bounds.push_back({{0, 0, 1}, above});
        p.bounds.push_back({{0, 0, -1}, -below});
        p.bounds.push_back({scaled(h[i], -1), -dot(h[i], A)});
        p.bounds.push_back({h[i + 1], dot(h[i + 1], B)});
        out.push_back(std::move(p));
      }
    }
    above = below;
  }
  return out;
}

// Distance from x to panel p (its polygon, approximately: the plane distance plus how far the
// projection lies outside the bounds).
double panel_distance(const CutPanel& p, const Point3& x) {
  const double h = dot(p.n, x) - p.c;
  double out = 0;
  for (const auto& b : p.bounds) out = std::max(out, dot(b.m, x) - b.d);
  return std::hypot(h, out);
}

}  // namespace

bool panel_contains(const CutPanel& p, const Point3& x, double tol) {
  if (std::abs(dot(p.n, x) - p.c) > tol) return false;
  for (const auto& b : p.bounds)
    if (dot(b.m, x) > b.d + tol) return false;
  return true;
}

std::vector<CutPanel> fault_cut_panels(const FaultTrace& tr, const std::vector<FaultTrace>& all) {
  if (tr.ends_against.empty()) return plain_panels(tr);
  const std::string who = fmt::format("fault '{}'", tr.name);
  const FaultTrace* other = nullptr;
  for (const auto& f : all)
    if (f.name == tr.ends_against) other = &f;
  if (!other) throw InputError(tr.where, fmt::format("{}: ends_against names fault '{}', which is not given", who, tr.ends_against));
  if (other->name == tr.name) throw InputError(tr.where, fmt::format("{}: a fault cannot end against itself", who));
  const auto target = plain_panels(*other);
  const double zmid = 0.5 * (tr.top + tr.bottom);
  // The trace end nearest the other fault (at mid-depth) and the panel of the other fault there.
  std::size_t best_part = 0;
  bool at_last = true;
  std::size_t best_panel = 0;
  double best = std::numeric_limits<double>::infinity();
  const double az = tr.dip_dir_deg * kPi / 180;
  const double dx = std::sin(az), dy = std::cos(az);
  const double off_mid = tr.offset_at(zmid);
  for (std::size_t q = 0; q < tr.parts.size(); ++q)
    for (bool last : {false, true}) {
      const P2& e = last ? tr.parts[q].back() : tr.parts[q].front();
      const Point3 x{e[0] + off_mid * dx, e[1] + off_mid * dy, zmid};
      for (std::size_t k = 0; k < target.size(); ++k)
        if (const double d = panel_distance(target[k], x); d < best) {
          best = d;
          best_part = q;
          at_last = last;
          best_panel = k;
        }
    }
  const CutPanel& A = target[best_panel];
  FaultTrace ext = tr;
  auto& part = ext.parts[best_part];
  const P2 end = at_last ? part.back() : part.front();
  const P2 prev = at_last ? part[part.size() - 2] : part[1];
  const P2 dir2{end[0] - prev[0], end[1] - prev[1]};
  const double len = std::hypot(dir2[0], dir2[1]);
  const Point3 u{dir2[0] / len, dir2[1] / len, 0};
  const double un = dot(A.n, u);
  if (std::abs(un) < 1e-3)
    throw InputError(tr.where, fmt::format("{}: runs parallel to fault '{}' and cannot end against it", who, other->name));
  // How far the end must move along u for the fault to reach the other one at every depth.
  double reach = 0;
  for (double z : {tr.top, tr.bottom, zmid}) {
    const double off = tr.offset_at(z);
    const Point3 x{end[0] + off * dx, end[1] + off * dy, z};
    reach = std::max(reach, (A.c - dot(A.n, x)) / un);
  }
  // A point of the trace away from that end says which side of the other fault it keeps.
  const P2 keep = at_last ? part.front() : part.back();
  const double off_top = tr.offset_at(zmid);
  const Point3 xk{keep[0] + off_top * dx, keep[1] + off_top * dy, zmid};
  double side = dot(A.n, xk) - A.c;
  if (side == 0) side = -reach;  // the other end lies on it: keep the side away from the extension
  if (reach > 0) {
    const double grow = 1.1 * reach + 0.01 * len + 1.0;
    const P2 moved{end[0] + grow * u[0], end[1] + grow * u[1]};
    (at_last ? part.back() : part.front()) = moved;
  }
  auto panels = plain_panels(ext);
  const double s = side > 0 ? 1.0 : -1.0;  // inside: s * (n . x - c) >= 0
  for (auto& p : panels) p.bounds.push_back({scaled(A.n, -s), -s * A.c});
  return panels;
}

namespace {

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

using EdgeMap = std::unordered_map<std::uint64_t, std::uint32_t>;

// Bisects the marked edges of an element in increasing order of their keys (module comment).
template <std::size_t K>
void split_element(const std::array<std::uint32_t, K>& e, const EdgeMap& marked, std::vector<std::array<std::uint32_t, K>>& out) {
  std::uint64_t best = std::numeric_limits<std::uint64_t>::max();
  int ia = -1, ib = -1;
  for (std::size_t i = 0; i < K; ++i)
    for (std::size_t j = i + 1; j < K; ++j) {
      const auto k = edge_key(e[i], e[j]);
      if (k < best && marked.count(k)) {
        best = k;
        ia = static_cast<int>(i);
        ib = static_cast<int>(j);
      }
    }
  if (ia < 0) {
    out.push_back(e);
    return;
  }
  const std::uint32_t m = marked.at(best);
  auto c1 = e, c2 = e;
  c1[ia] = m;
  c2[ib] = m;
  split_element(c1, marked, out);
  split_element(c2, marked, out);
}

class Cutter {
public:
  Cutter(Mesh& mesh, double tol) : mesh_(mesh), X_(mesh.nodes), tol_(tol) {
    std::size_t ntets = 0;
    for (const auto& blk : mesh.blocks)
      if (blk.type == ElementType::Tetrahedron) ntets += blk.size();
    ntets += ntets / 8;  // room for the cut's new tetrahedra (2.4 % at the thesis scale)
    T_.reserve(ntets);
    Tb_.reserve(ntets);
    Tp_.reserve(ntets);
    for (std::size_t b = 0; b < mesh.blocks.size(); ++b) {
      const auto& blk = mesh.blocks[b];
      if (blk.type == ElementType::Tetrahedron) {  // from the node array (element(i) looked up the type per element)
        const std::uint32_t* e = blk.nodes.data();
        for (std::size_t i = 0; i < blk.size(); ++i, e += 4) {
          T_.push_back({e[0], e[1], e[2], e[3]});
          Tp_.push_back(static_cast<std::uint32_t>(Tp_.size()));
        }
        Tb_.insert(Tb_.end(), blk.size(), static_cast<std::uint32_t>(b));
      } else if (blk.type == ElementType::Triangle)
        for (std::size_t i = 0; i < blk.size(); ++i) {
          const auto e = blk.element(i);
          F_.push_back({e[0], e[1], e[2]});
          Fb_.push_back(static_cast<std::uint32_t>(b));
        }
    }
    {  // the input tetrahedra, read from the blocks (unchanged until finish)
      std::vector<std::span<const std::uint32_t>> input;
      for (const auto& blk : mesh.blocks)
        if (blk.type == ElementType::Tetrahedron) input.emplace_back(blk.nodes);
      parent_.emplace(X_, std::move(input));
    }
    // Two threads (two cores): the second builds the incidences and the reaches of the last
    // tetrahedra into an array of its own, this one the reaches of the first; then the larger of
    // the two per node (a maximum: the same whatever the split or the timing) and the node grid.
    reach_.assign(X_.size(), 0.0);
    std::vector<double> reach_last(X_.size(), 0.0);
    const std::size_t split = T_.size() * 5 / 8;
    run_beside(
        [&] {
          tets_at_.build(X_.size(), T_);
          tris_at_.build(X_.size(), F_);
          for (std::size_t i = split; i < T_.size(); ++i) raise_reach(T_[i], reach_last);
        },
        [&] {
          for (std::size_t i = 0; i < split; ++i) raise_reach(T_[i], reach_);
        });
    for (std::size_t v = 0; v < X_.size(); ++v) reach_[v] = std::max(reach_[v], reach_last[v]);
    grid_.build(X_, reach_);
  }

  std::size_t tetrahedra() const { return T_.size(); }
  std::size_t snapped() const { return snapped_; }

  // Nodes that must not move: none any more; nodes move only within the surfaces they lie on
  // (snap_onto). Kept for the call order of cut_faults.
  void init_fixed() {}

  // The planes a node must stay on: its triangles (model boundary, other groups), the faces
  // between two materials around it, and the planes of the panels already cut through it.
  // Returns unit normals (not deduplicated).
  // Snaps nodes onto the plane N . x = C before cutting (docs/dipping-faults.md, "Snap"): where one
  // of `edges` crosses the plane within `ratio` of its length from a node, the node is moved onto
  // the plane, within the surfaces it lies on (`extra`: more planes it stays on if it lies on them), when its
  // tetrahedra stay positive and keep at least half their smallest dihedral angle.
  void snap_onto(const Point3& N, double C, double ratio, const std::vector<std::array<std::uint32_t, 2>>& edges,
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
    auto worst = [&](const std::vector<std::uint32_t>& tets, double& min_vol) {
      double a = 180;
      min_vol = std::numeric_limits<double>::infinity();
      for (auto t : tets) {
        const auto& e = T_[t];
        min_vol = std::min(min_vol, tet_signed_volume(X_[e[0]], X_[e[1]], X_[e[2]], X_[e[3]]));
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
        double vol0, vol1;
        const double a0 = worst(tets_of[c], vol0);
        const Point3 old = X_[v];
        X_[v] = {old[0] + delta[0], old[1] + delta[1], old[2] + delta[2]};
        const double a1 = worst(tets_of[c], vol1);
        if (vol1 > 0 && a1 >= 0.5 * a0) {
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

  // Step 1's snap: nodes of the tetrahedra whose section by P meets Q.
  void snap(const CutPanel& p, double ratio) { snap_onto(p.n, p.c, ratio, plane_edges(p), {}); }

  // After a panel: nodes on its plane stay on it from then on.
  void fix_plane(const CutPanel& p) { done_.push_back(&p); }

  // The edges crossing P of the tetrahedra whose section by P meets Q.
  // Such a tetrahedron of diameter D has an end of a crossing edge within |n| D / 2 of P and,
  // for each bound, a node within tol + |m| D of its inside: that end is such a node, and D is at
  // most the reach of each of its nodes. So only the tetrahedra around nodes passing that test
  // (with a margin for rounding) are examined, in increasing order as a scan of all would meet them.
  // The nodes are tested cell by cell of grid_, skipping the cells whose box (widened by their
  // largest reach, and by a margin for rounding) cannot hold a node passing the test, and the nodes
  // the grid does not place (added or snapped since it was built) one by one: the same nodes pass.
  std::vector<std::array<std::uint32_t, 2>> plane_edges(const CutPanel& p) const {
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
  void cut_plane(const CutPanel& p) {
    // Only the crossing edges' ends need their signed distance (no pass over every node).
    auto g = [&](std::uint32_t i) { return dot(p.n, X_[i]) - p.c; };
    EdgeMap marked;
    for (const auto& [a, b] : plane_edges(p)) mark(marked, a, b, g(a), g(b));
    apply(marked);
  }

  // Step 2 for one bound of one panel: nodes on P next to the bound's plane are snapped onto it
  // (staying on P and their other surfaces), then the edges are bisected.
  void cut_bound(const CutPanel& p, std::size_t bi, double ratio) {
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
  std::vector<std::array<std::uint32_t, 2>> bound_edges(const CutPanel& p, std::size_t bi) {
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

  // Faces lying in panel p with their centroid inside it, sorted node triples -> oriented face.
  void collect(const CutPanel& p, std::map<std::array<std::uint32_t, 3>, std::array<std::uint32_t, 3>>& faces,
               std::map<std::array<std::uint32_t, 3>, int>& uses) const {
    auto on = [&](std::uint32_t i) { return std::abs(dot(p.n, X_[i]) - p.c) <= tol_; };
    static constexpr int face_of[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    for (auto i : elements_at(tets_at_, nodes_on_plane(p.n, p.c))) {
      const auto& t = T_[i];
      if (on(t[0]) + on(t[1]) + on(t[2]) + on(t[3]) < 3) continue;
      for (const auto& f : face_of) {
        std::array<std::uint32_t, 3> tri{t[f[0]], t[f[1]], t[f[2]]};
        if (!on(tri[0]) || !on(tri[1]) || !on(tri[2])) continue;
        Point3 cen{0, 0, 0};
        for (auto v : tri)
          for (int k = 0; k < 3; ++k) cen[k] += X_[v][k] / 3;
        bool inside = true;
        for (const auto& b : p.bounds)
          if (dot(b.m, cen) > b.d) inside = false;
        if (!inside) continue;
        auto key = tri;
        std::sort(key.begin(), key.end());
        ++uses[key];
        const Point3 nrm = cross(sub(X_[tri[1]], X_[tri[0]]), sub(X_[tri[2]], X_[tri[0]]));
        if (dot(nrm, p.n) < 0) std::swap(tri[1], tri[2]);
        faces.emplace(key, tri);
      }
    }
  }

  const std::vector<Point3>& nodes() const { return X_; }

  // Adds the faces of fault f (oriented) as elements of a virtual block after the mesh's blocks,
  // so that later bisections split them too.
  void add_fault_faces(std::size_t f, const std::vector<std::array<std::uint32_t, 3>>& faces) {
    for (const auto& t : faces) {
      link(tris_at_, t, static_cast<std::uint32_t>(F_.size()));
      F_.push_back(t);
      Fb_.push_back(static_cast<std::uint32_t>(mesh_.blocks.size() + f));
    }
  }

  // A tetrahedron with its four nodes on one fault would be torn apart by ugs-faultinsert (it
  // happens where a fault bends, or in slivers between two of its faces): its longest edge that is
  // not an edge of the fault is bisected at its midpoint, until there is none. Returns how many.
  std::size_t untear(std::size_t nfaults) {
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
  BandImprovement improve(std::size_t first_new, double ratio, double smooth_below_deg, double bound_deg) {
    return improve_cut_band({X_, T_, Tb_, Tp_, F_, Fb_, static_cast<std::uint32_t>(mesh_.blocks.size()), *parent_, bound_deg,
                             [this](std::uint32_t v, std::vector<std::uint32_t>& out) { tets_at_.append(v, out); }},
                            first_new, ratio, smooth_below_deg, tol_);
  }

  // The tetrahedra holding a node numbered first_new or above (those the cut made): how many,
  // their smallest dihedral angle, how many are below min(bound, their input tetrahedron's angle)
  // and how many below `fraction` of that.
  struct BandQuality {
    std::size_t tetrahedra = 0, below_reference = 0, below_bound = 0;
    double min_deg = 180;
  };
  BandQuality band_quality(std::size_t first_new, double bound_deg, double fraction) const {
    BandQuality q;
    for (std::size_t i = 0; i < T_.size(); ++i) {
      const auto& t = T_[i];
      if (t[0] < first_new && t[1] < first_new && t[2] < first_new && t[3] < first_new) continue;
      ++q.tetrahedra;
      const double a = min_dihedral_angle_deg(X_[t[0]], X_[t[1]], X_[t[2]], X_[t[3]]);
      const double ref = std::min(bound_deg, parent_->quality(Tp_[i]));
      q.min_deg = std::min(q.min_deg, a);
      q.below_reference += a < ref;
      q.below_bound += a < fraction * ref;
    }
    return q;
  }

  // Writes the elements back into the mesh's blocks, plus the fault groups (the virtual blocks);
  // renumbers element tags.
  void finish(const std::vector<std::string>& names, std::size_t nodes_before) {
    std::uint64_t next_tag = mesh_.max_node_tag();
    for (std::size_t i = nodes_before; i < X_.size(); ++i) mesh_.node_tags.push_back(++next_tag);
    const std::size_t nb = mesh_.blocks.size();
    for (auto& b : mesh_.blocks) {
      if (b.type == ElementType::Tetrahedron || b.type == ElementType::Triangle) {
        b.nodes.clear();
        b.tags.clear();
      }
    }
    int ptag = 0, etag2 = 0;
    for (const auto& p : mesh_.physicals) ptag = std::max(ptag, p.tag);
    for (const auto& e : mesh_.entities)
      if (e.dim == 2) etag2 = std::max(etag2, e.tag);
    for (const auto& name : names) {
      mesh_.physicals.push_back({2, ++ptag, "fault:" + name});
      mesh_.entities.push_back({2, ++etag2, {ptag}, {}});
      ElementBlock b;
      b.entity_dim = 2;
      b.entity_tag = etag2;
      b.type = ElementType::Triangle;
      mesh_.blocks.push_back(std::move(b));
    }
    // Each block's size first, then plain appends (an insert per element was a third of this).
    std::vector<std::size_t> size(mesh_.blocks.size(), 0);
    for (auto b : Tb_) size[b] += 4;
    for (auto b : Fb_) size[b] += 3;
    for (std::size_t b = 0; b < size.size(); ++b) mesh_.blocks[b].nodes.reserve(size[b]);
    for (std::size_t i = 0; i < T_.size(); ++i) {
      auto& nodes = mesh_.blocks[Tb_[i]].nodes;
      for (auto v : T_[i]) nodes.push_back(v);
    }
    for (std::size_t i = 0; i < F_.size(); ++i) {
      auto& nodes = mesh_.blocks[Fb_[i]].nodes;
      for (auto v : F_[i]) nodes.push_back(v);
    }
    (void)nb;
    std::uint64_t tag = 0;
    for (auto& b : mesh_.blocks) {
      b.tags.resize(b.nodes.size() / b.npe());
      for (auto& t : b.tags) t = ++tag;
    }
    mesh_.blocks.erase(std::remove_if(mesh_.blocks.begin(), mesh_.blocks.end(), [](const ElementBlock& b) { return b.tags.empty(); }),
                       mesh_.blocks.end());
    mesh_.update_entity_bboxes();
  }

  // The fault faces after every bisection, for the report.
  std::vector<std::array<std::uint32_t, 3>> fault_faces(std::size_t f) const {
    std::vector<std::array<std::uint32_t, 3>> out;
    const std::size_t id = mesh_.blocks.size() + f;
    for (std::size_t i = 0; i < F_.size(); ++i)
      if (Fb_[i] == id) out.push_back(F_[i]);
    return out;
  }

private:
  bool crosses(double ga, double gb) const { return (ga < -tol_ && gb > tol_) || (ga > tol_ && gb < -tol_); }

  // Crossing point of edge (a, b), computed from the lower index so both directions agree.
  Point3 crossing(std::uint32_t a, std::uint32_t b, double ga, double gb) const {
    if (a > b) {
      std::swap(a, b);
      std::swap(ga, gb);
    }
    const double s = ga / (ga - gb);
    const Point3& A = X_[a];
    const Point3& B = X_[b];
    return {A[0] + s * (B[0] - A[0]), A[1] + s * (B[1] - A[1]), A[2] + s * (B[2] - A[2])};
  }

  // Marks edge (a, b) for bisection at its crossing of the plane whose signed distances at a and b are ga, gb.
  void mark(EdgeMap& marked, std::uint32_t a, std::uint32_t b, double ga, double gb) {
    const auto k = edge_key(a, b);
    if (marked.count(k)) return;
    const Point3 x = crossing(a, b, ga, gb);
    marked.emplace(k, static_cast<std::uint32_t>(X_.size()));
    X_.push_back(x);
  }

  // Is the convex point set outside one of the bounds?
  bool separated(const std::vector<Point3>& pts, const std::vector<CutHalfSpace>& bounds, const std::size_t* skip) const {
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

  // Node -> element incidences (unordered lists), kept up to date by apply, so that the work of a
  // panel visits the elements around the nodes it concerns instead of the whole mesh. The input's
  // lists in one array (each node's at its start size, filled by a counting pass: half a million
  // vectors were allocated and grown one element at a time before), with a vector per node for
  // what no longer fits and for the nodes the cut adds.
  class Incidence {
  public:
    template <std::size_t K>
    void build(std::size_t nodes, const std::vector<std::array<std::uint32_t, K>>& elements) {
      count_.assign(nodes, 0);
      for (const auto& e : elements)
        for (auto v : e) ++count_[v];
      start_.assign(nodes + 1, 0);
      for (std::size_t v = 0; v < nodes; ++v) start_[v + 1] = start_[v] + count_[v];
      data_.resize(start_[nodes]);
      std::fill(count_.begin(), count_.end(), 0);
      for (std::size_t i = 0; i < elements.size(); ++i)
        for (auto v : elements[i]) data_[start_[v] + count_[v]++] = static_cast<std::uint32_t>(i);
    }
    void add(std::uint32_t v, std::uint32_t i) {
      if (v < count_.size() && start_[v] + count_[v] < start_[v + 1]) {
        data_[start_[v] + count_[v]++] = i;
        return;
      }
      if (v >= more_.size()) more_.resize(std::size_t{v} + 1);
      more_[v].push_back(i);
    }
    void remove(std::uint32_t v, std::uint32_t i) {
      if (v < count_.size()) {
        std::uint32_t* b = data_.data() + start_[v];
        std::uint32_t* e = b + count_[v];
        if (std::uint32_t* it = std::find(b, e, i); it != e) {
          *it = e[-1];
          --count_[v];
          return;
        }
      }
      auto& l = more_[v];
      auto it = std::find(l.begin(), l.end(), i);
      *it = l.back();
      l.pop_back();
    }
    // Appends v's elements to out.
    void append(std::uint32_t v, std::vector<std::uint32_t>& out) const {
      if (v < count_.size()) out.insert(out.end(), data_.begin() + start_[v], data_.begin() + start_[v] + count_[v]);
      if (v < more_.size()) out.insert(out.end(), more_[v].begin(), more_[v].end());
    }

  private:
    std::vector<std::size_t> start_;     // per input node: its first slot in data_
    std::vector<std::uint32_t> count_;   // per input node: its slots in use
    std::vector<std::uint32_t> data_;
    std::vector<std::vector<std::uint32_t>> more_;
  };
  template <std::size_t K>
  void link(Incidence& at, const std::array<std::uint32_t, K>& e, std::uint32_t i) {
    for (auto v : e) at.add(v, i);
  }
  // Element i changed from `before` to `after`.
  template <std::size_t K>
  void relink(Incidence& at, const std::array<std::uint32_t, K>& before, const std::array<std::uint32_t, K>& after, std::uint32_t i) {
    for (auto v : before)
      if (std::find(after.begin(), after.end(), v) == after.end()) at.remove(v, i);
    for (auto v : after)
      if (std::find(before.begin(), before.end(), v) == before.end()) at.add(v, i);
  }
  std::vector<std::uint32_t> sorted_at(const Incidence& at, std::uint32_t v) const {
    std::vector<std::uint32_t> l;
    at.append(v, l);
    std::sort(l.begin(), l.end());
    return l;
  }
  // The elements holding a node flagged in `want`, in increasing order.
  static std::vector<std::uint32_t> elements_at(const Incidence& at, const std::vector<char>& want) {
    std::vector<std::uint32_t> out;
    for (std::size_t v = 0; v < want.size(); ++v)
      if (want[v]) at.append(static_cast<std::uint32_t>(v), out);
    return sorted_unique(std::move(out));
  }
  static std::vector<std::uint32_t> sorted_unique(std::vector<std::uint32_t> out) {
    if (out.size() < (std::size_t{1} << 12)) {
      std::sort(out.begin(), out.end());
      out.erase(std::unique(out.begin(), out.end()), out.end());
      return out;
    }
    // Many: a bit per element and one sweep of 64-bit words instead of the sort (the sort of a
    // panel's few ten thousand was ~5 % of the thesis bench).
    const std::uint32_t top = *std::max_element(out.begin(), out.end());
    std::vector<std::uint64_t> hit(top / 64 + 1, 0);
    for (auto i : out) hit[i / 64] |= std::uint64_t{1} << (i % 64);
    out.clear();
    for (std::size_t w = 0; w < hit.size(); ++w)
      for (std::uint64_t bits = hit[w]; bits != 0; bits &= bits - 1)
        out.push_back(static_cast<std::uint32_t>(w * 64 + static_cast<std::size_t>(std::countr_zero(bits))));
    return out;
  }

  // The nodes on panel p's plane (within tol_), in no particular order. One scan of every node per
  // panel; later calls for the same panel test only the nodes added or snapped since, and those
  // found before (a node leaves or joins the plane only by moving: snapped_nodes_).
  const std::vector<std::uint32_t>& on_plane(const CutPanel& p) {
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
  std::vector<std::uint32_t> nodes_on_plane(const Point3& n, double c) const {
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

  // The elements holding one of `nodes`, in increasing order.
  static std::vector<std::uint32_t> elements_at(const Incidence& at, const std::vector<std::uint32_t>& nodes) {
    std::vector<std::uint32_t> out;
    for (auto v : nodes) at.append(v, out);
    return sorted_unique(std::move(out));
  }

  // reach_ of a tetrahedron's nodes: at least its diameter (one square root per tetrahedron).
  void raise_reach(const std::array<std::uint32_t, 4>& t) {
    raise_reach(t, reach_);
    for (auto v : t) grid_.raise(v, reach_[v]);
  }
  // The same into `reach` only (the constructor's threads, before grid_ is built).
  void raise_reach(const std::array<std::uint32_t, 4>& t, std::vector<double>& reach) const {
    double d2 = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const Point3 e = sub(X_[t[i]], X_[t[j]]);
        d2 = std::max(d2, dot(e, e));
      }
    const double d = std::sqrt(d2);
    for (auto v : t) reach[v] = std::max(reach[v], d);
  }

  void apply(const EdgeMap& marked) {
    if (marked.empty()) return;
    // A new node's tetrahedra lie inside those of the edge it splits: the edge's ends' reach holds.
    reach_.resize(X_.size(), 0.0);
    for (const auto& [k, m] : marked) reach_[m] = std::max(reach_[k >> 32], reach_[k & 0xffffffffu]);
    std::vector<char> flag(X_.size(), 0);
    std::vector<std::uint32_t> ends;  // the flagged nodes (no scan of every node's flag below)
    for (const auto& [k, m] : marked)
      for (const auto v : {static_cast<std::uint32_t>(k >> 32), static_cast<std::uint32_t>(k & 0xffffffffu)})
        if (!flag[v]) {
          flag[v] = 1;
          ends.push_back(v);
        }
    // Only elements holding a marked edge's end can split: those around the flagged nodes, in
    // increasing order as a scan of all elements would meet them (children go to the end).
    std::vector<std::array<std::uint32_t, 4>> tets;
    for (auto i : elements_at(tets_at_, ends)) {
      const auto t = T_[i];
      if (flag[t[0]] + flag[t[1]] + flag[t[2]] + flag[t[3]] < 2) continue;
      tets.clear();
      split_element<4>(t, marked, tets);
      T_[i] = tets[0];
      relink(tets_at_, t, tets[0], i);
      for (std::size_t c = 1; c < tets.size(); ++c) {
        link(tets_at_, tets[c], static_cast<std::uint32_t>(T_.size()));
        T_.push_back(tets[c]);
        Tb_.push_back(Tb_[i]);
        Tp_.push_back(Tp_[i]);
      }
    }
    std::vector<std::array<std::uint32_t, 3>> tris;
    for (auto i : elements_at(tris_at_, ends)) {
      const auto f = F_[i];
      if (flag[f[0]] + flag[f[1]] + flag[f[2]] < 2) continue;
      tris.clear();
      split_element<3>(f, marked, tris);
      F_[i] = tris[0];
      relink(tris_at_, f, tris[0], i);
      for (std::size_t c = 1; c < tris.size(); ++c) {
        link(tris_at_, tris[c], static_cast<std::uint32_t>(F_.size()));
        F_.push_back(tris[c]);
        Fb_.push_back(Fb_[i]);
      }
    }
    for (const auto& b : mesh_.blocks) {
      if (b.type == ElementType::Tetrahedron || b.type == ElementType::Triangle) continue;
      for (std::size_t i = 0; i < b.size(); ++i) {
        const auto e = b.element(i);
        for (std::size_t x = 0; x < e.size(); ++x)
          for (std::size_t y = x + 1; y < e.size(); ++y)
            if (e[x] < flag.size() && e[y] < flag.size() && flag[e[x]] && flag[e[y]] && marked.count(edge_key(e[x], e[y])))
              throw InputError("mesh", fmt::format("a {} element uses an edge that a fault cuts; only tetrahedra and "
                                                   "triangles can be cut",
                                                   element_name(b.type)));
      }
    }
  }

  Mesh& mesh_;
  std::vector<Point3>& X_;
  double tol_;
  std::vector<std::array<std::uint32_t, 4>> T_;
  std::vector<std::uint32_t> Tb_;
  std::vector<std::uint32_t> Tp_;         // the input tetrahedron each one comes from
  std::optional<InputTetShape> parent_;   // the input tetrahedra's shape (by Tp_)
  std::vector<std::array<std::uint32_t, 3>> F_;
  std::vector<std::uint32_t> Fb_;
  Incidence tets_at_, tris_at_;        // per node: the tetrahedra / triangles holding it
  std::vector<double> reach_;          // per node: at least the diameter of each tetrahedron holding it
  NodeGrid grid_;                      // the input nodes, for plane_edges (built after reach_)
  std::vector<const CutPanel*> done_;  // the panels cut so far
  std::size_t snapped_ = 0;
  std::vector<std::uint32_t> snapped_nodes_;  // every node snap_onto moved, in order
  struct OnPlane {
    const CutPanel* panel = nullptr;
    std::vector<std::uint32_t> nodes;  // on its plane when last asked
    std::size_t scanned = 0, snapped = 0;  // X_ and snapped_nodes_ sizes then
  } on_plane_;
};

}  // namespace

FaultCutSummary cut_faults(Mesh& mesh, const std::vector<FaultTrace>& traces, const FaultCutOptions& options) {
  FaultCutSummary sum;
  sum.nodes_before = mesh.nodes.size();
  std::array<double, 6> box{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                            std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                            -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const auto& x : mesh.nodes)
    for (int k = 0; k < 3; ++k) {
      box[k] = std::min(box[k], x[k]);
      box[k + 3] = std::max(box[k + 3], x[k]);
    }
  const double diag = mesh.nodes.empty() ? 1.0 : std::hypot(box[3] - box[0], box[4] - box[1], box[5] - box[2]);
  // Not rounding level (fault_cut.hpp): a node a hair off a plane would get all its edges cut that close.
  const double tol = options.tolerance > 0 ? options.tolerance : 1e-7 * diag;
  sum.tolerance = tol;

  std::vector<std::vector<CutPanel>> panels;
  for (const auto& tr : traces) {
    if (mesh.find_physical(2, "fault:" + tr.name))
      throw InputError(tr.where, fmt::format("fault '{}': the mesh already has a group fault:{}", tr.name, tr.name));
    panels.push_back(fault_cut_panels(tr, traces));
  }
  Cutter cut(mesh, tol);
  sum.tetrahedra_before = cut.tetrahedra();
  cut.init_fixed();
  for (const auto& fp : panels)
    for (const auto& p : fp) {
      cut.snap(p, options.snap);
      cut.cut_plane(p);
      for (std::size_t b = 0; b < p.bounds.size(); ++b) cut.cut_bound(p, b, options.snap);
      cut.fix_plane(p);
    }
  sum.snapped = cut.snapped();

  std::vector<std::string> names;
  for (std::size_t f = 0; f < traces.size(); ++f) {
    std::vector<std::array<std::uint32_t, 3>> tris;
    std::set<std::array<std::uint32_t, 3>> taken;
    std::size_t on_boundary = 0;
    for (const auto& p : panels[f]) {
      std::map<std::array<std::uint32_t, 3>, std::array<std::uint32_t, 3>> faces;
      std::map<std::array<std::uint32_t, 3>, int> uses;
      cut.collect(p, faces, uses);
      for (const auto& [key, tri] : faces) {
        if (uses[key] < 2) {
          ++on_boundary;
          continue;
        }
        if (taken.insert(key).second) tris.push_back(tri);
      }
    }
    if (tris.empty())
      throw InputError(traces[f].where,
                       fmt::format("fault '{}': its surface does not cross the mesh (check the trace, top_m, bottom_m, "
                                   "dip_deg and dip_dir_deg)",
                                   traces[f].name));
    cut.add_fault_faces(f, tris);
    names.push_back(traces[f].name);
    FaultCutReport r;
    r.name = traces[f].name;
    r.panels = panels[f].size();
    r.boundary_faces = on_boundary;
    sum.faults.push_back(r);
  }
  sum.untorn = cut.untear(traces.size());
  const BandImprovement better = cut.improve(sum.nodes_before, options.collapse, options.smooth_below_deg, options.bound_deg);
  sum.collapsed = better.collapsed;
  sum.smoothed = better.moved;
  const auto band = cut.band_quality(sum.nodes_before, options.bound_deg, options.bound_fraction);
  sum.band_tetrahedra = band.tetrahedra;
  sum.band_min_dihedral_deg = band.min_deg;
  sum.band_below_reference = band.below_reference;
  sum.band_below_bound = band.below_bound;
  // Report: distance and normal of every face against the panel it lies in.
  const auto& X = cut.nodes();
  for (std::size_t f = 0; f < traces.size(); ++f) {
    FaultCutReport& r = sum.faults[f];
    r.zmin = std::numeric_limits<double>::infinity();
    r.zmax = -r.zmin;
    const auto tris = cut.fault_faces(f);
    r.triangles = tris.size();
    for (const auto& tri : tris) {
      const Point3 nrm = cross(sub(X[tri[1]], X[tri[0]]), sub(X[tri[2]], X[tri[0]]));
      const double a = norm(nrm);
      r.area += 0.5 * a;
      double best_d = std::numeric_limits<double>::infinity(), best_ang = 0;
      for (const auto& p : panels[f]) {
        double d = 0;
        for (auto v : tri) d = std::max(d, std::abs(dot(p.n, X[v]) - p.c));
        if (d < best_d) {
          best_d = d;
          best_ang = std::acos(std::clamp(dot(nrm, p.n) / a, -1.0, 1.0)) * 180 / kPi;
        }
      }
      r.max_distance = std::max(r.max_distance, best_d);
      r.max_angle_deg = std::max(r.max_angle_deg, best_ang);
      for (auto v : tri) {
        r.zmin = std::min(r.zmin, X[v][2]);
        r.zmax = std::max(r.zmax, X[v][2]);
      }
    }
  }
  sum.tetrahedra_after = cut.tetrahedra();
  cut.finish(names, sum.nodes_before);
  sum.nodes_after = mesh.nodes.size();
  return sum;
}

}  // namespace ugs
