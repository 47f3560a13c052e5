// What the fault cut reports (fault_cut.hpp, FaultCutSummary): the quality of the band of
// tetrahedra it made, and per fault its faces' area, extent and how far they lie from their panels.
#include "cut_stages.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cutter.hpp"
#include "ugs/meshing/mesh_quality.hpp"
#include "ugs/meshing/vec3.hpp"

namespace ugs::fault_cut {

using namespace vec3;

namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

Cutter::BandQuality Cutter::band_quality(std::size_t first_new, double bound_deg, double fraction) const {
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

void measure_band(const Cutter& cut, const FaultCutOptions& options, FaultCutSummary& sum) {
  const auto band = cut.band_quality(sum.nodes_before, options.bound_deg, options.bound_fraction);
  sum.band_tetrahedra = band.tetrahedra;
  sum.band_min_dihedral_deg = band.min_deg;
  sum.band_below_reference = band.below_reference;
  sum.band_below_bound = band.below_bound;
}

void measure_faults(const Cutter& cut, const std::vector<FaultTrace>& traces, const std::vector<std::vector<CutPanel>>& panels,
                    FaultCutSummary& sum) {
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
      // Against the panels whose bounds hold the face's centroid (where it was collected: of a
      // surface's many triangles, another one's plane may pass nearer); all of them if none does.
      Point3 cen{0, 0, 0};
      for (auto v : tri) cen = add(cen, scaled(X[v], 1.0 / 3));
      bool any_holds = false;
      auto holds = [&](const CutPanel& p) {
        for (const auto& b : p.bounds)
          if (dot(b.m, cen) > b.d + sum.tolerance) return false;
        return true;
      };
      for (const auto& p : panels[f]) any_holds = any_holds || holds(p);
      for (const auto& p : panels[f]) {
        if (any_holds && !holds(p)) continue;
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
}

}  // namespace ugs::fault_cut
