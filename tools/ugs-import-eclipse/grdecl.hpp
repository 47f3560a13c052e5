// The way back to the simulator (docs/eclipse.md): the mechanics' volumetric strain change and
// mean effective stress change per active grid cell, as GRDECL keywords ResInsight and OPM read.
#pragma once
#include <string>
#include <vector>

#include "ugs/eclipse/eclipse.hpp"

namespace ugs::eclipse {

struct GrdeclReport {
  std::size_t tetrahedra = 0;       // of the results' mesh
  std::size_t outside = 0;          // tetrahedra outside every active cell
  std::size_t empty_cells = 0;      // active cells holding no tetrahedron centroid (written as 0)
  std::vector<std::string> keywords;
};

// Reads ugs-solve's `strain` and `stress_change` cell fields at `dates` (every step when empty) from
// `results`, averages them over the tetrahedra whose centroid lies in each active cell (weighted by
// volume), and writes per date d (1-based) UGSEV<d> = eps_xx + eps_yy + eps_zz and UGSDSM<d> = the
// mean of the three normal effective stress changes, in bar (METRES grid), psi (FEET) or atm (CM),
// one value per grid cell in natural order, 0 in inactive and empty cells.
GrdeclReport export_grdecl(const Grid& grid, const std::string& results, std::vector<std::string> dates,
                           const std::string& out, const std::string& command_line);

}  // namespace ugs::eclipse
