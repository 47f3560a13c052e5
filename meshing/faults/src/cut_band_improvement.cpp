// Quality of the tetrahedra a fault cut made (cut_band_improvement.hpp): run() names the steps — the
// band, the collapse passes (band_collapse.cpp), the smoothing passes (band_smoothing.cpp), the
// arrays compacted.
#include "cut_band_improvement.hpp"

#include <algorithm>

#include "band_improver.hpp"

namespace ugs {
namespace cut_band {

BandImprovement BandImprover::run() {
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

// The band's tetrahedra, and the tetrahedra around the band's nodes (from the caller's
// incidences: the passes then visit only these). A tetrahedron never enters the band (a collapse
// replaces a cut node by a neighbour), and the nodes the passes ask about are the band's.
void BandImprover::find_band() {
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
void BandImprover::build_adjacency(const std::vector<char>& want, bool kept) {
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

void BandImprover::compact() {
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

}  // namespace cut_band

BandImprovement improve_cut_band(ElementSoup soup, std::size_t first_new, double ratio, double smooth_below_deg, double tol) {
  if (first_new >= soup.nodes.size()) return {};
  return cut_band::BandImprover(soup, first_new, ratio, smooth_below_deg, tol).run();
}

}  // namespace ugs
