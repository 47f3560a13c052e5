// The fault cut (fault_cut.hpp, docs/dipping-faults.md): cut_faults runs its stages in order, each in
// a file of its own. The mesh is held as arrays by the Cutter (cutter.hpp) from stage 2 to stage 9.
#include "ugs/meshing/fault_cut.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "cut_stages.hpp"
#include "cutter.hpp"

namespace ugs {
namespace {

// The on-plane tolerance: the option, or 1e-7 of the model's diagonal.
double on_plane_tolerance(const Mesh& mesh, const FaultCutOptions& options) {
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
  return tol;
}

}  // namespace

FaultCutSummary cut_faults(Mesh& mesh, const std::vector<FaultTrace>& traces, const FaultCutOptions& options) {
  using namespace fault_cut;
  FaultCutSummary sum;
  sum.nodes_before = mesh.nodes.size();
  sum.tolerance = on_plane_tolerance(mesh, options);
  const auto panels = panels_of(mesh, traces);                                // 1. each fault's panels (cut_panels.cpp)
  Cutter cut(mesh, sum.tolerance);                                            // 2. the mesh as arrays (cutter.cpp)
  sum.tetrahedra_before = cut.tetrahedra();
  for (const auto& fault : panels)                                            // 3. panel by panel: snap, plane, bounds
    for (const auto& p : fault) cut.cut_panel(p, options.snap);               //    (cut_panel.cpp, cut_bound.cpp)
  sum.snapped = cut.snapped();
  const auto names = add_fault_groups(cut, traces, panels, sum.faults);      // 4. faces in the panels -> fault:<name>
  sum.untorn = cut.untear(traces.size());                                     // 5. untear (cut_cleanup.cpp)
  improve_band(cut, options, sum);                                            // 6. collapse, smoothing (cut_cleanup.cpp)
  measure_band(cut, options, sum);                                            // 7. the band's quality (cut_report.cpp)
  measure_faults(cut, traces, panels, sum);                                   // 8. each fault's faces (cut_report.cpp)
  sum.tetrahedra_after = cut.tetrahedra();
  cut.finish(names, sum.nodes_before);                                        // 9. back into the mesh (cutter.cpp)
  sum.nodes_after = mesh.nodes.size();
  return sum;
}

}  // namespace ugs
