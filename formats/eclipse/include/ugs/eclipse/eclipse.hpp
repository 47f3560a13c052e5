// ECLIPSE / OPM Flow binary output (EGRID, UNRST or X0000, X0001, ...) read with opm-common's
// EclIO, and turned into the mechanics' frame and units (docs/eclipse.md):
//   - corner points in map coordinates: COORD/ZCORN are in the deck's local frame, depth positive
//     down; MAPAXES (stored as float32, in MAPUNITS or, without MAPUNITS, the grid's unit) is applied
//     here in double, x' = origin + x e_x + y e_y as opm-common's MapAxes::transform does; z = -depth;
//     then an offset (a local grid origin). Lengths in metres (GRIDUNIT METRES, FEET, CM).
//   - PRESSURE in Pa (INTEHEAD item 3: 1 METRIC bar, 2 FIELD psia, 3 LAB atm, 4 PVT-M atm).
// Every failure of EclIO (missing or truncated file: std::runtime_error) and every inconsistency
// becomes an InputError naming the file.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ugs/formats/corner_point_grid.hpp"
#include "ugs/formats/mesh.hpp"

namespace ugs::eclipse {

// The 8 corners of a cell in ECLIPSE order: top (k) face (i,j) (i+1,j) (i,j+1) (i+1,j+1), then the
// bottom (k+1) face in the same order.
using CellCorners = std::array<Point3, 8>;

// The grid of an EGRID: a corner-point grid (the same cells a GRDECL gives, corner_point_grid.hpp)
// and its non-neighbour connections.
struct Grid : CornerPointGrid {
  std::size_t nnc = 0;                   // non-neighbour connections (faults) in the EGRID
};

// Reads the EGRID's global grid; `offset` (m) is added to every corner after MAPAXES and the flip
// of depth to z.
Grid read_egrid(const std::string& path, const Point3& offset = {0, 0, 0});

struct RestartStep {
  int report = 0;       // SEQNUM
  std::string date;     // ISO 8601 (INTEHEAD day, month, year)
  std::int64_t time = 0; // seconds since 1970
  int units = 0;        // INTEHEAD item 3
};

// The report steps of a unified restart (CASE.UNRST, CASE.FUNRST) or of the non-unified files
// CASE.X0000, CASE.X0001, ... (name any of them: its numbered siblings are all read).
class Restart {
public:
  explicit Restart(const std::string& path);
  ~Restart();
  Restart(const Restart&) = delete;
  Restart& operator=(const Restart&) = delete;

  const std::string& path() const;
  const std::vector<RestartStep>& steps() const;
  // Checks every step's grid dimensions and active cell count against the grid (InputError naming
  // both counts on a mismatch).
  void check_grid(const Grid& grid) const;
  // PRESSURE of step `s` (index into steps()) in Pa, per active cell in natural order.
  std::vector<double> pressure(std::size_t s);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// For the restart next to an EGRID: CASE.UNRST, else CASE.FUNRST, else CASE.X0000; "" if none.
std::string default_restart(const std::string& egrid_path);

// Pa per unit of the restart's pressure for INTEHEAD item 3; InputError for other values.
double pressure_unit_pa(int units, const std::string& where);

}  // namespace ugs::eclipse

namespace ugs::eclipse {

// An array of an INIT file (CASE.INIT, or formatted CASE.FINIT) per active cell of `grid`, as
// written (PORO as a fraction, PERMX in mD, NTG, ...: no unit conversion). Arrays written per grid
// cell (PORV) are reduced to the active ones. InputError naming the file: missing file, no such
// array (naming the arrays there are), a count that is neither the grid's active nor total cells.
std::vector<double> read_init_array(const std::string& init_path, const std::string& keyword, const Grid& grid);

// The EGRID beside an INIT (CASE.EGRID or CASE.FEGRID), "" if none.
std::string default_egrid(const std::string& init_path);

}  // namespace ugs::eclipse
