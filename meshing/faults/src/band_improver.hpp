// The improvement of the band a fault cut made (cut_band_improvement.hpp): BandImprover::run (in
// cut_band_improvement.cpp) finds the band, collapses short edges (band_collapse.cpp), smooths
// (band_smoothing.cpp) and compacts the arrays; what a node must stay on is band_surfaces.cpp's.
// Internal to ugs_meshing_faults.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "cut_band_improvement.hpp"
#include "ugs/meshing/mesh_quality.hpp"

namespace ugs::cut_band {

using Face = std::array<std::uint32_t, 3>;
using Tet = std::array<std::uint32_t, 4>;

template <class E>
bool has(const E& e, std::uint32_t v) {
  return std::find(e.begin(), e.end(), v) != e.end();
}

constexpr int kFaceOf[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

// What a node must stay on: planes (a point and a unit normal) and feature lines (a direction).
// Fault faces lie on a mathematical plane within the on-plane tolerance: a node may move within it
// and stay within the tolerance. Every other surface (boundary, groups, material interfaces, often
// curved raster horizons) must keep its exact shape, so that material volumes do not change: a
// move must lie in each of its faces' planes to rounding (`exact`).
struct Plane {
  Point3 p, n;
  bool exact;
};
struct Line {
  Point3 d;
  bool exact;
};
struct Surfaces {
  std::vector<Plane> planes;
  std::vector<Line> lines;
};

// Which faces through a node are surfaces and which of their edges at the node may be feature lines
// (surfaces_of's first part: incidences only). at_edge is sorted by (group, w, order).
struct EdgeFace {
  std::uint64_t group;
  std::uint32_t w;      // the edge's other node
  std::uint32_t order;  // position among the edges met
  std::uint32_t face;   // index in faces
  std::uint32_t third;  // the face's third node
};
struct SurfaceTopology {
  bool known = false;
  std::vector<std::pair<std::uint64_t, Face>> faces;  // (group, face)
  std::vector<EdgeFace> at_edge;
};

// A node's surfaces kept between the requests of a pass and across passes: one entry per node
// asked for (a slot per node; a deque, so that entries stay put while it grows), computed again
// when the caller's freshness test says that something it depends on changed after `time`.
class SurfaceCache {
public:
  void reset(std::size_t nodes) {
    slot_.assign(nodes, 0);
    entries_.clear();
  }
  // v's surfaces, nullptr when they cannot be computed (a degenerate face). fresh(time): is the entry
  // computed at `time` still valid; compute(SurfaceTopology&, Surfaces&) -> bool fills them (the
  // topology is the entry's own, kept for a caller whose incidences do not change); `now` stamps it.
  template <class Fresh, class Compute>
  const Surfaces* get(std::uint32_t v, std::uint64_t now, Fresh&& fresh, Compute&& compute) {
    if (slot_[v] == 0) {
      entries_.emplace_back();
      slot_[v] = static_cast<std::uint32_t>(entries_.size());
    } else if (const Entry& c = entries_[slot_[v] - 1]; fresh(c.time)) {
      return c.ok ? &c.s : nullptr;
    }
    Entry& c = entries_[slot_[v] - 1];
    c.s.planes.clear();
    c.s.lines.clear();
    c.ok = compute(c.topology, c.s);
    c.time = now;
    return c.ok ? &c.s : nullptr;
  }

private:
  struct Entry {
    bool ok = false;
    SurfaceTopology topology;
    Surfaces s;
    std::uint64_t time = 0;
  };
  std::vector<std::uint32_t> slot_;  // per node: 1 + its entry, 0 none
  std::deque<Entry> entries_;
};

class BandImprover {
public:
  BandImprover(ElementSoup s, std::size_t first_new, double ratio, double smooth_below, double tol)
      : s_(s), first_new_(first_new), ratio_(ratio), smooth_below_(smooth_below), tol_(tol), round_(1e-3 * tol) {}

  BandImprovement run();  // cut_band_improvement.cpp

private:
  const Point3& X(std::uint32_t v) const { return s_.nodes[v]; }
  double quality(const Tet& t) const { return min_dihedral_angle_deg(X(t[0]), X(t[1]), X(t[2]), X(t[3])); }
  // Positive, and clear of ugs-solve's flat test by a margin (kKeptRatio): a volume "> 0" alone let a
  // collapse make four coplanar points whose rounding left a volume of 1e-10 m3 (issue 43).
  bool positive(const Tet& t) const { return kept_volume(X(t[0]), X(t[1]), X(t[2]), X(t[3])); }
  // The measure every change must raise (its minimum over the tetrahedra it touches): the smallest
  // dihedral angle relative to min(bound, that of the input tetrahedron it comes from), so that a
  // sliver the input already had (a pinch-out, a thin sub-layer) does not stop the repair of its
  // neighbours, and the cut is held to the bound where the input was better.
  double score(std::uint32_t t, const Tet& e) const { return score_of(t, quality(e)); }
  double score_of(std::uint32_t t, double q) const { return q / score_per(t); }
  double score_per(std::uint32_t t) const {
    const double ref = std::min(s_.bound_deg, s_.parent.quality(s_.tet_parent[t]));
    return std::max(ref, 1e-9);
  }
  bool in_band(const Tet& t) const {
    return t[0] >= first_new_ || t[1] >= first_new_ || t[2] >= first_new_ || t[3] >= first_new_;
  }

  // cut_band_improvement.cpp: the band, the incidences of the nodes asked about, the arrays compacted.
  void find_band();
  void build_adjacency(const std::vector<char>& want, bool kept = false);
  void compact();

  // band_surfaces.cpp: what a node must stay on.
  bool surfaces_of(std::uint32_t v, Surfaces& out) const;
  void topology_of(std::uint32_t v, SurfaceTopology& topo) const;
  bool geometry_of(std::uint32_t v, const SurfaceTopology& topo, Surfaces& out) const;

  // band_collapse.cpp: 1. collapse.
  std::size_t collapse_pass();
  bool failed_before(std::uint32_t b, std::uint32_t a) const;
  const Surfaces* cached_surfaces_of(std::uint32_t v);
  bool lies_on(const Surfaces& s, std::uint32_t from, std::uint32_t a) const;
  bool merged_position(const Surfaces& sa, std::uint32_t a, const Surfaces& sb, std::uint32_t b, double reach, Point3& x) const;
  bool try_collapse(std::uint32_t b, std::uint32_t a);

  // band_smoothing.cpp: 2. smoothing.
  std::size_t smoothing_pass();
  bool moved_around(std::uint32_t v, std::uint64_t at) const;
  const Surfaces* smoothing_surfaces_of(std::uint32_t v);
  double smoothing_quality(std::uint32_t t);
  bool smooth(std::uint32_t v);
  const std::vector<std::uint32_t>& neighbours_of(std::uint32_t v);

  struct Around {
    std::uint64_t key;  // the face's two nodes other than v, lower one first: sorts as the sorted faces
    Face tri;
    std::uint32_t block;
    std::uint32_t order;  // position among the faces met, for the pairing in surfaces_of
  };
  struct ConformScratch {
    std::vector<Tet> elems;
    std::vector<Face> faces;
  };
  ConformScratch conform_scratch_;  // try_collapse's arrays
  struct Scratch {
    SurfaceTopology topology;
    std::vector<std::pair<std::uint64_t, Face>> outer;
    std::vector<Around> around;
    std::vector<std::pair<std::uint32_t, std::pair<std::uint64_t, Face>>> between;
    std::vector<Point3> normal;
  };
  mutable Scratch scratch_;  // surfaces_of's arrays
  SurfaceCache smoothing_surfaces_;             // stamped with moves_
  std::vector<std::uint64_t> moved_at_;        // per node: moves_ after its last smoothing move, 0 never
  std::uint64_t moves_ = 0;
  std::vector<std::uint64_t> smooth_failed_;   // per node: moves_ when its last smoothing step failed, kNever none
  std::vector<std::uint32_t> smooth_hint_;      // per node: the index in its tets_of_ list of the tetrahedron that failed its last trial step
  std::vector<std::uint32_t> nb_slot_;                 // per node: 1 + its entry in nb_lists_, 0 none
  std::deque<std::vector<std::uint32_t>> nb_lists_;    // neighbours_of's lists
  static constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();
  // The band's tetrahedra during the smoothing (which changes no incidence), in band_'s order, with
  // what the pass' scan needs in one place (it read five arrays of millions at random per tetrahedron).
  struct SmoothBandTet {
    Tet e;
    std::uint32_t t;
    double per;          // score_of(t, q) = q / per
    double q;            // smoothing_quality(t) when computed
    std::uint64_t time;  // moves_ then, kNever none
  };
  std::vector<SmoothBandTet> smooth_band_;
  struct CachedQuality {
    double q;            // smoothing_quality's value
    std::uint64_t time;  // moves_ when computed, kNever none
  };
  // Tetrahedron t's entry, made when first asked for: only the band's neighbourhood is (a few
  // hundred thousand of 3.2 million), so the entries sit together instead of 51 MB read at random.
  CachedQuality& cached_quality(std::uint32_t t) {
    std::uint32_t& slot = tet_q_slot_[t];
    if (slot == 0) {
      tet_q_.push_back({0.0, kNever});
      slot = static_cast<std::uint32_t>(tet_q_.size());
    }
    return tet_q_[slot - 1];
  }
  std::vector<std::uint32_t> tet_q_slot_;      // per tetrahedron: 1 + its entry in tet_q_, 0 none
  std::vector<CachedQuality> tet_q_;           // one cache line for both
  std::vector<double> trial_scratch_;          // qualities of a node's tetrahedra at a trial position
  SurfaceCache collapse_surfaces_;         // stamped with changes_
  std::vector<std::uint64_t> changed_at_;  // per node: changes_ after the last collapse around it
  std::uint64_t changes_ = 0;              // successful collapses so far
  std::vector<std::uint64_t> quiet_since_;  // per band_ entry: changes_ when it last gave no collapse candidate, kNever else
  std::unordered_map<std::uint64_t, std::uint64_t> failed_at_;  // (b << 32 | a) -> changes_ when its collapse failed
  ElementSoup s_;
  std::size_t first_new_;
  double ratio_, smooth_below_, tol_;
  double round_;  // "to rounding": a thousandth of the on-plane tolerance (1e-10 of the model's size)
  std::vector<char> tet_dead_, tri_dead_, node_dead_;
  std::vector<std::vector<std::uint32_t>> tets_of_, tris_of_;  // of the nodes of the last build_adjacency, else empty
  std::vector<std::uint32_t> listed_;                         // those nodes
  std::vector<char> listed_at_;                               // per node: in listed_
  bool smoothing_lists_ = false;                              // the smoothing has built its first lists
  std::vector<std::uint32_t> band_;                   // the band's tetrahedra at the start, increasing
  std::vector<std::vector<std::uint32_t>> around_;   // per band node: tetrahedra that held it (may be stale)
  std::vector<std::vector<std::uint32_t>> node_faults_;  // fault groups per node (collapse pass)
  std::vector<std::uint32_t> on_fault_;                  // the nodes whose node_faults_ may be filled
};

}  // namespace ugs::cut_band
