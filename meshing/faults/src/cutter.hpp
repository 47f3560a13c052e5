// The mesh a fault cut works on (fault_cut.cpp runs the stages; docs/dipping-faults.md): its
// tetrahedra and triangles as flat arrays with node -> element incidences, the input's shape, and
// the operations of each stage, defined in the file named beside them. Internal to ugs_meshing_faults.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "cut_band_improvement.hpp"
#include "cut_incidence.hpp"
#include "node_grid.hpp"
#include "ugs/formats/mesh.hpp"
#include "ugs/meshing/fault_cut.hpp"

namespace ugs::fault_cut {

inline std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

using EdgeMap = std::unordered_map<std::uint64_t, std::uint32_t>;

class Cutter {
public:
  // cutter.cpp: the mesh's tetrahedra and triangles into the arrays, and back (finish).
  Cutter(Mesh& mesh, double tol);
  void finish(const std::vector<std::string>& names, std::size_t nodes_before);
  std::size_t tetrahedra() const { return T_.size(); }
  std::size_t snapped() const { return snapped_; }
  const std::vector<Point3>& nodes() const { return X_; }

  // cut_panel.cpp: one panel — its snap, step 1 (cut_plane), step 2 for each of its bounds
  // (cut_bound.cpp), then its plane is kept (fix_plane).
  void cut_panel(const CutPanel& p, double snap_ratio);
  void snap(const CutPanel& p, double ratio);
  void cut_plane(const CutPanel& p);
  void fix_plane(const CutPanel& p) { done_.push_back(&p); }
  // cut_bound.cpp
  void cut_bound(const CutPanel& p, std::size_t bi, double ratio);

  // cut_fault_faces.cpp: the faces lying in a panel, the fault groups made of them.
  void collect(const CutPanel& p, std::map<std::array<std::uint32_t, 3>, std::array<std::uint32_t, 3>>& faces,
               std::map<std::array<std::uint32_t, 3>, int>& uses) const;
  void add_fault_faces(std::size_t f, const std::vector<std::array<std::uint32_t, 3>>& faces);
  std::vector<std::array<std::uint32_t, 3>> fault_faces(std::size_t f) const;

  // cut_cleanup.cpp: after the cut.
  std::size_t untear(std::size_t nfaults);
  BandImprovement improve(std::size_t first_new, double ratio, double smooth_below_deg, double bound_deg);

  // cut_report.cpp
  // The tetrahedra holding a node numbered first_new or above (those the cut made): how many,
  // their smallest dihedral angle, how many are below min(bound, their input tetrahedron's angle)
  // and how many below `fraction` of that.
  struct BandQuality {
    std::size_t tetrahedra = 0, below_reference = 0, below_bound = 0;
    double min_deg = 180;
  };
  BandQuality band_quality(std::size_t first_new, double bound_deg, double fraction) const;

private:
  // cut_snap.cpp
  void snap_onto(const Point3& N, double C, double ratio, const std::vector<std::array<std::uint32_t, 2>>& edges,
                 const std::vector<std::pair<Point3, double>>& extra);
  // cut_panel.cpp, cut_bound.cpp
  std::vector<std::array<std::uint32_t, 2>> plane_edges(const CutPanel& p) const;
  std::vector<std::array<std::uint32_t, 2>> bound_edges(const CutPanel& p, std::size_t bi);
  bool separated(const std::vector<Point3>& pts, const std::vector<CutHalfSpace>& bounds, const std::size_t* skip) const;

  // cut_bisect.cpp: the marked edges bisected in every element holding them.
  bool crosses(double ga, double gb) const { return (ga < -tol_ && gb > tol_) || (ga > tol_ && gb < -tol_); }
  Point3 crossing(std::uint32_t a, std::uint32_t b, double ga, double gb) const;
  void mark(EdgeMap& marked, std::uint32_t a, std::uint32_t b, double ga, double gb);
  void apply(const EdgeMap& marked);

  // cut_lookup.cpp: the nodes near a plane, and how far each one's tetrahedra reach.
  const std::vector<std::uint32_t>& on_plane(const CutPanel& p);
  std::vector<std::uint32_t> nodes_on_plane(const Point3& n, double c) const;
  void raise_reach(const std::array<std::uint32_t, 4>& t);
  void raise_reach(const std::array<std::uint32_t, 4>& t, std::vector<double>& reach) const;

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

}  // namespace ugs::fault_cut
