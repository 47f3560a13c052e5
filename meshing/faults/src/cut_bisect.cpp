// Bisection in the fault cut (cutter.hpp; fault_cut.hpp): a marked edge is split at its crossing of
// a plane in every element holding it, several in increasing order of their node pair, so that two
// elements sharing a face split it the same way and the mesh stays conforming.
#include "cutter.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/meshing/vec3.hpp"

namespace ugs::fault_cut {

using namespace vec3;

namespace {

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

}  // namespace

// Crossing point of edge (a, b), computed from the lower index so both directions agree.
Point3 Cutter::crossing(std::uint32_t a, std::uint32_t b, double ga, double gb) const {
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
void Cutter::mark(EdgeMap& marked, std::uint32_t a, std::uint32_t b, double ga, double gb) {
  const auto k = edge_key(a, b);
  if (marked.count(k)) return;
  const Point3 x = crossing(a, b, ga, gb);
  marked.emplace(k, static_cast<std::uint32_t>(X_.size()));
  X_.push_back(x);
}

void Cutter::apply(const EdgeMap& marked) {
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

}  // namespace ugs::fault_cut
