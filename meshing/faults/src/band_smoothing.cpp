// Step 2 of the band improvement (band_improver.hpp; cut_band_improvement.hpp): a node of a poor
// band tetrahedron moved toward the mean of its neighbours, within its surfaces, by the largest of
// 1, 1/2, 1/4, 1/8 of the way that raises the smallest dihedral angle of its tetrahedra.
#include "band_improver.hpp"

#include <algorithm>
#include <cmath>

#include "ugs/meshing/vec3.hpp"

namespace ugs::cut_band {

using namespace vec3;

namespace {

// Unit normals or directions this close (|cross|, radians) are one plane or line when choosing
// the directions a node may move in; the move must then keep the node within the tolerance of
// every plane (checked). A raster surface's curvature (1e-2) restricts or fixes its nodes.
constexpr double kParallel = 1e-4;

}  // namespace

// ---- 2. smoothing ---------------------------------------------------------------------------
std::size_t BandImprover::smoothing_pass() {
  std::vector<char> want(s_.nodes.size(), 0);
  std::vector<std::pair<double, std::uint32_t>> order;  // (worst score, node)
  std::vector<double> worst(s_.nodes.size(), 180);
  if (smooth_band_.empty())
    for (auto t : band_)
      if (!tet_dead_[t] && in_band(s_.tets[t])) smooth_band_.push_back({s_.tets[t], t, score_per(t), 0.0, kNever});
  for (auto& b : smooth_band_) {
    const auto& e = b.e;
    if (b.time == kNever || moved_at_[e[0]] > b.time || moved_at_[e[1]] > b.time || moved_at_[e[2]] > b.time || moved_at_[e[3]] > b.time) {
      b.q = smoothing_quality(b.t);
      b.time = moves_;
    }
    const double qa = b.q;
    const double q = qa / b.per;  // score_of(b.t, qa)
    if (!(q < 1) && !(qa < smooth_below_)) continue;
    for (auto v : e)
      if (!node_dead_[v]) {
        want[v] = 1;
        worst[v] = std::min(worst[v], q);
      }
  }
  for (std::size_t v = 0; v < want.size(); ++v)
    if (want[v]) order.push_back({worst[v], static_cast<std::uint32_t>(v)});
  if (order.empty()) return 0;
  std::sort(order.begin(), order.end());
  build_adjacency(want, smoothing_lists_);
  smoothing_lists_ = true;
  std::size_t moved = 0;
  for (const auto& [q, v] : order) {
    if (smooth_failed_[v] != kNever && !moved_around(v, smooth_failed_[v])) continue;
    if (smooth(v)) ++moved;
    else smooth_failed_[v] = moves_;
  }
  return moved;
}

// Has a node of v's tetrahedra or triangles moved after moves_ was `at`? A smoothing step of v
// depends on nothing else (its surfaces, its neighbours' mean, its tetrahedra's angles), so one
// that failed fails again until then (most candidates of the later passes on the thesis bench).
bool BandImprover::moved_around(std::uint32_t v, std::uint64_t at) const {
  for (auto t : tets_of_[v])
    for (auto w : s_.tets[t])
      if (moved_at_[w] > at) return true;
  for (auto i : tris_of_[v])
    for (auto w : s_.tris[i])
      if (moved_at_[w] > at) return true;
  return false;
}

// surfaces_of for the smoothing, kept across its passes: they change no incidence, so v's
// surfaces stay as computed until v or a node of its tetrahedra or triangles moves, and then only
// their planes and creases are computed again (the faces and edges, sorted once per node).
const Surfaces* BandImprover::smoothing_surfaces_of(std::uint32_t v) {
  return smoothing_surfaces_.get(
      v, moves_, [&](std::uint64_t time) { return !moved_around(v, time); }, [&](SurfaceTopology& topo, Surfaces& out) {
        if (!topo.known) topology_of(v, topo);
        return geometry_of(v, topo, out);
      });
}

// A tetrahedron's smallest dihedral angle during the smoothing, kept until one of its nodes
// moves (the smoothing changes no incidence).
double BandImprover::smoothing_quality(std::uint32_t t) {
  const auto& e = s_.tets[t];
  auto& c = cached_quality(t);
  const std::uint64_t at = c.time;
  if (at != kNever && moved_at_[e[0]] <= at && moved_at_[e[1]] <= at && moved_at_[e[2]] <= at && moved_at_[e[3]] <= at)
    return c.q;
  c = {quality(e), moves_};
  return c.q;
}

bool BandImprover::smooth(std::uint32_t v) {
  const Surfaces* sp = smoothing_surfaces_of(v);
  if (!sp) return false;
  const Surfaces& s = *sp;
  // The directions v may move in: within every plane and along its feature line, if any (exact
  // surfaces to rounding, faults to kParallel).
  std::vector<Point3> normals;
  for (const auto& pl : s.planes) {
    Point3 r = pl.n;
    for (const auto& b : normals) r = sub(r, scaled(b, dot(b, r)));
    if (norm(r) > (pl.exact ? 1e-9 : kParallel)) normals.push_back(scaled(r, 1 / norm(r)));
    if (normals.size() == 3) return false;
  }
  const Line* line = nullptr;
  for (const auto& l : s.lines) {
    if (!line) line = &l;
    else if (norm(cross(line->d, l.d)) > (l.exact || line->exact ? 1e-9 : kParallel)) return false;  // a corner
  }
  Point3 mean{0, 0, 0};
  const auto& nb = neighbours_of(v);  // sorted, unique: the mean adds them in increasing order
  for (auto w : nb) mean = add(mean, scaled(X(w), 1.0 / static_cast<double>(nb.size())));
  Point3 d = sub(mean, X(v));
  if (!line) {
    for (const auto& n : normals) d = sub(d, scaled(n, dot(n, d)));
  } else {
    // Along the feature line, if it lies in every plane (else it crosses one there: a corner).
    for (const auto& pl : s.planes)
      if (std::abs(dot(pl.n, line->d)) > (pl.exact || line->exact ? 1e-9 : kParallel)) return false;
    d = scaled(line->d, dot(d, line->d));
  }
  if (!(norm(d) > 0)) return false;
  double before = std::numeric_limits<double>::infinity();
  for (auto t : tets_of_[v]) before = std::min(before, score_of(t, smoothing_quality(t)));
  const Point3 x0 = X(v);
  auto& trial = trial_scratch_;
  for (double step : {1.0, 0.5, 0.25, 0.125}) {
    s_.nodes[v] = add(x0, scaled(d, step));
    // Exact surfaces keep the node to rounding, faults within the tolerance.
    bool ok = true;
    for (const auto& pl : s.planes) ok = ok && std::abs(dot(pl.n, sub(X(v), pl.p))) <= (pl.exact ? round_ : tol_);
    // The step is taken when every tetrahedron stays positive and scores above `before`: the
    // first that does not ends the trial (the rest cannot change the answer, and neither can the
    // order they are tested in). So the tetrahedron that failed last for v goes first (it
    // usually fails again: ~2 million angles were computed for trials that failed, thesis
    // bench), then the cheap volumes of the others, then their angles.
    const auto& tets = tets_of_[v];
    const std::size_t n = tets.size();
    std::uint32_t& hint = smooth_hint_[v];
    if (hint >= n) hint = 0;
    trial.assign(n, 0.0);
    auto scores_above = [&](std::size_t i) {
      trial[i] = quality(s_.tets[tets[i]]);
      return !(score_of(tets[i], trial[i]) <= before);  // as min(after, NaN) kept `after`
    };
    if (ok && n > 0) ok = positive(s_.tets[tets[hint]]) && scores_above(hint);
    for (std::size_t i = 0; ok && i < n; ++i)
      if (i != hint && !positive(s_.tets[tets[i]])) {
        ok = false;
        hint = static_cast<std::uint32_t>(i);
      }
    for (std::size_t i = 0; ok && i < n; ++i)
      if (i != hint && !scores_above(i)) {
        ok = false;
        hint = static_cast<std::uint32_t>(i);
      }
    if (ok) {
      moved_at_[v] = ++moves_;
      for (std::size_t i = 0; i < trial.size(); ++i) {
        cached_quality(tets_of_[v][i]) = {trial[i], moves_};
      }
      return true;
    }
  }
  s_.nodes[v] = x0;
  return false;
}

// v's neighbours (the other nodes of its tetrahedra), sorted: the smoothing changes no incidence,
// so they are listed once per node over its passes.
const std::vector<std::uint32_t>& BandImprover::neighbours_of(std::uint32_t v) {
  std::uint32_t& slot = nb_slot_[v];
  if (slot == 0) {
    auto& nb = nb_lists_.emplace_back();
    for (auto t : tets_of_[v])
      for (auto w : s_.tets[t])
        if (w != v) nb.push_back(w);
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
    slot = static_cast<std::uint32_t>(nb_lists_.size());
  }
  return nb_lists_[slot - 1];
}

}  // namespace ugs::cut_band
