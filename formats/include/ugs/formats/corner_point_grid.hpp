// A corner-point grid (ECLIPSE GRID section: SPECGRID or DIMENS, COORD, ZCORN, ACTNUM, MAPAXES,
// MAPUNITS, GRIDUNIT) as cells with 8 corners in the mesh's frame: map coordinates in metres, z up
// (= -depth), the same transform as ugs-import-eclipse applies to an EGRID (docs/eclipse.md): a
// corner lies on its pillar (COORD: top and bottom point) at its ZCORN depth, linear along the
// pillar; MAPAXES maps the deck's local x, y to the map, x' = origin + x e_x + y e_y; then `offset`.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "ugs/formats/grdecl.hpp"
#include "ugs/formats/mesh.hpp"

namespace ugs {

struct CornerPointGrid {
  std::string path;
  std::array<int, 3> dims{};                  // nx, ny, nz
  std::vector<std::int32_t> active;           // per global cell (i fastest): active index, or -1
  std::vector<std::uint32_t> global;          // per active cell: global index
  std::vector<std::array<Point3, 8>> corners; // per active cell, ECLIPSE corner order (top face
                                              // (i,j) (i+1,j) (i,j+1) (i+1,j+1), then the bottom face)
  std::string length_unit = "METRES";         // GRIDUNIT as written
  bool mapaxes = false;                       // MAPAXES applied

  std::size_t num_active() const { return global.size(); }
  std::size_t num_cells() const { return active.size(); }
  std::array<int, 3> ijk(std::uint32_t global_index) const;  // 0-based
};

// A GRIDUNIT / MAPUNITS item as written ('feet ', 'METRES') in the form grid_length_unit_m reads:
// upper case, without surrounding blanks.
std::string grid_unit_name(std::string item);
// Metres per unit of a GRIDUNIT / MAPUNITS name (METRES, FEET, CM); InputError at `where` else.
double grid_length_unit_m(const std::string& unit, const std::string& where);

// The map frame of MAPAXES (Y-axis point, origin, X-axis point, already in metres): unit axes.
struct MapAxes {
  std::array<double, 2> origin{0, 0}, ex{1, 0}, ey{0, 1};
  // A point of the deck's local frame (x, y, depth in metres) in the mesh's frame, plus `offset`.
  Point3 to_mesh(double x, double y, double depth, const Point3& offset) const {
    return {origin[0] + x * ex[0] + y * ey[0] + offset[0], origin[1] + x * ex[1] + y * ey[1] + offset[1], -depth + offset[2]};
  }
};
// InputError at `where` when the X- or Y-axis point equals the origin or a value is not finite.
MapAxes map_axes(const std::array<double, 6>& points_m, const std::string& where);

// The grid of a GRDECL file (read_grdecl with at least the grid keywords). InputError naming the
// file and keyword for a missing or wrongly sized COORD / ZCORN / ACTNUM, no active cell, a
// non-finite corner.
CornerPointGrid corner_point_grid(const GrdeclFile& f, const Point3& offset = {0, 0, 0});
// The keywords corner_point_grid reads.
const std::set<std::string>& corner_point_keywords();

}  // namespace ugs
