// Horizon grids as geological modelling packages export them (docs/meshing.md, "Horizons from
// Petrel, RMS, SKUA-GOCAD, Move"): a regular grid of nodes, possibly rotated, with undefined nodes.
// IRAP classic ASCII and CPS-3 ASCII are read here (GDAL 3.6 reads neither); ZMAP+ is read by
// GDAL's ZMap driver (meshing/layers/src/horizon_grids.cpp). The format is told by the file's content.
#pragma once
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace ugs {

// Node (i, j) lies at origin + R(rotation) * (i * dx, j * dy): i counts columns along the grid's
// own x axis, j rows along its y axis, R turns counter-clockwise by rotation_deg about the origin.
// dx and dy are signed (a grid whose rows go south has dy < 0).
struct HorizonGrid {
  std::string path, format;          // format: "IRAP classic ASCII", "CPS-3 ASCII", "ZMAP+"
  std::size_t nx = 0, ny = 0;        // columns, rows (both >= 2)
  double x0 = 0, y0 = 0;             // node (0, 0)
  double dx = 0, dy = 0;             // increments (m in the grid's CRS), non-zero and finite
  double rotation_deg = 0;           // counter-clockwise
  std::vector<double> z;             // elevation of node (i, j) at [j * nx + i]; NaN = undefined
  std::size_t undefined = 0;         // how many nodes are undefined

  double at(std::size_t i, std::size_t j) const { return z[j * nx + i]; }
  std::array<double, 2> node(std::size_t i, std::size_t j) const {
    const double a = rotation_deg * (M_PI / 180.0), u = static_cast<double>(i) * dx, v = static_cast<double>(j) * dy;
    return {x0 + std::cos(a) * u - std::sin(a) * v, y0 + std::sin(a) * u + std::cos(a) * v};
  }
};

// The grid's value at the map point (x, y): bilinear in the cell holding it (1e-9 of a node
// spacing of slack at the edges). Value: `value` set; Outside: beyond the grid's nodes; Undefined:
// a node with a non-zero weight is undefined. ugs-meshgen's horizons and the maps of material
// fields (meshing/properties) are sampled by this one function.
enum class GridPoint { Value, Outside, Undefined };
GridPoint horizon_grid_value(const HorizonGrid& g, double x, double y, double& value);

// The horizon file formats ugs-meshgen reads beside GDAL rasters, told by their first lines:
// IRAP classic ASCII starts with the number -996, CPS-3 ASCII with FSASCI, ZMAP+ with "@name, GRID,"
// (after '!' comment lines), GOCAD TSurf with "GOCAD TSurf".
enum class HorizonFormat { Irap, Cps3, Zmap, Tsurf, Unknown };
HorizonFormat detect_horizon_format(const std::string& path);
const char* horizon_format_name(HorizonFormat f);

// IRAP classic ASCII (RMS, Petrel "IRAP classic grid"):
//   -996 NY XINC YINC / XORI XMAX YORI YMAX / NX ROTATION XROT YROT / 0 0 0 0 0 0 0 / NX * NY values,
// x fastest from the origin's row; 9999900 (and anything above 9999000) is undefined. The rotation
// is in degrees counter-clockwise about the origin (XROT, YROT must then be the origin).
// Throws InputError "file:line: ..." for a header that disagrees with itself or with its values.
HorizonGrid read_irap_grid(const std::string& path);

// CPS-3 ASCII (Petrel "CPS-3 grid", Landmark): FSASCI (last number: the undefined value), FSATTR,
// FSLIMI xmin xmax ymin ymax zmin zmax, FSNROW nrow ncol, FSXINC xinc yinc, "->" comment lines, then
// nrow * ncol values column by column from the west, each column from the north (ymax) down.
// Unrotated. Throws InputError as read_irap_grid.
HorizonGrid read_cps3_grid(const std::string& path);

}  // namespace ugs
