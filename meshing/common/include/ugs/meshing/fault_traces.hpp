// Faults given as traces (thesis 2.1, 4.3.4; data-samples/po-plain/faults.geojson): a line in plan
// at elevation trace_z (default top), a dip and a dip direction, a depth range. The fault surface is
// the trace translated down-dip: at elevation z the trace moves by (trace_z - z) / tan(dip) along the
// dip direction (azimuth, degrees clockwise from north), from top down to bottom. Each segment of
// the trace sweeps a planar panel; the panels form the surface.
//
// Listric faults (docs/dipping-faults.md): a list of pieces down-dip, each with its own dip, from
// top to its bottom; the trace moves down-dip by the integral of cot(dip) over depth, so each
// (segment, piece) pair is a planar panel and successive pieces meet along horizontal lines.
#pragma once
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ugs/formats/mesh.hpp"
#include "ugs/meshing/fault_surface_input.hpp"

namespace ugs {

struct FaultTrace {
  std::string name;                                  // group fault:<name>
  std::string where;                                 // for messages, e.g. "faults.geojson: feature 3"
  std::vector<std::vector<std::array<double, 2>>> parts;  // polylines (x, y) at trace_z
  double top = 0, bottom = 0;                        // elevations, m (negative below sea level)
  double dip_deg = 90, dip_dir_deg = 0;
  double trace_z = 0;                                // elevation of the trace line
  // Listric: pieces top to bottom (bottom elevations strictly decreasing, the last == bottom); empty
  // = one planar piece of dip_deg. When set, dip_deg is the dip of the first piece.
  struct Piece {
    double bottom = 0;
    double dip_deg = 90;
  };
  std::vector<Piece> pieces;
  std::string ends_against;                          // another fault this one ends against ("" = none)
  // A fault given as a surface (docs/faults.md, "Faults as surfaces"): its triangles are the cut's
  // panels; top and bottom are its elevation range, parts the feature's line (ugs-mesh2d's only),
  // the dip fields unused.
  std::shared_ptr<const FaultSurfaceInput> surface;

  bool planar() const { return pieces.size() <= 1; }
  bool vertical() const;                             // every piece has dip 90
  // Horizontal offset along the dip direction of the surface at elevation z from the trace (m; the
  // pieces extended above top and below bottom by their first and last dip).
  double offset_at(double z) const;
  // The pieces, also for a planar fault (one piece).
  std::vector<Piece> piece_list() const;
};

// Checks a trace and drops repeated consecutive points: InputError(where, "fault '<name>': ...")
// for an empty name, top not above bottom, dip outside (0, 90], parts with fewer than two distinct
// points, and traces that cross or touch themselves (the surface would intersect itself).
void check_fault_trace(FaultTrace& trace);

// Reads traces from any OGR vector file: (multi)line features with fields name, top_m, bottom_m,
// dip_deg, dip_dir_deg and optionally trace_z_m (default top_m), reprojected to `model_wkt` when
// both have a CRS. Every trace is checked; a name used twice is an error. Optional fields:
// listric_bottom_m and listric_dip_deg (lists of the same length, as JSON arrays or text "a, b, c":
// the listric pieces; then dip_deg may be left out) and ends_against (name of another fault).
std::vector<FaultTrace> read_fault_traces(const std::string& path, const std::string& model_wkt = "");

// One faults file, one schema, read the same way by ugs-mesh2d, ugs-meshgen and ugs-faultinsert
// (docs/faults.md says which fields each tool uses): every feature is a (multi)line with a `name`
// ("fault:" prefix dropped, unique in the file); the other fields are optional, and each one given
// is checked the same way for every tool: top_m, bottom_m (top_m >= bottom_m), dip_deg in (0, 90],
// dip_dir_deg, trace_z_m, listric_bottom_m and listric_dip_deg (lists of one length, together),
// size_m > 0, ends_against (text), surface (a GOCAD TSurf or fault sticks file, relative to the faults
// file's folder; then top_m, bottom_m, the dip fields and ends_against must be absent: the surface
// is the fault). Numbers may be stored as text ("35"); all must be finite.
struct FaultRecord {
  std::string name;
  std::string where;                                  // "faults.geojson: feature 3"
  std::vector<std::vector<std::array<double, 2>>> lines;  // in the model CRS
  std::optional<double> top, bottom, dip_deg, dip_dir_deg, trace_z, size;
  std::vector<double> listric_bottom, listric_dip;
  std::string ends_against;
  std::string surface;                                // path of its TSurf or sticks file ("" = none)
  bool has_dip() const { return dip_deg.has_value() || !listric_dip.empty(); }
  bool has_depth_range() const { return top.has_value() && bottom.has_value(); }
};
std::vector<FaultRecord> read_fault_file(const std::string& path, const std::string& model_wkt = "",
                                         const std::string& name_field = "name");
// The trace of a record, for a tool that builds the surface from the file: needs top_m, bottom_m,
// dip_deg (or the listric fields) and dip_dir_deg; `why` says what it is needed for in the message.
// A record with `surface`: the surface read and checked (read_fault_surface), top and bottom its
// elevation range.
FaultTrace fault_trace_from_record(const FaultRecord& record, const std::string& why = "a trace needs");
// Side 1 -> side 2 reference normal of a record for a fault whose surface comes from the mesh:
// from dip_deg (90 when absent: ugs-meshgen builds faults without a dip vertical) and dip_dir_deg;
// nullopt without dip_dir_deg (the mesh's own orientation rule applies).
std::optional<Point3> record_reference_normal(const FaultRecord& record);

// The trace surface as planar panels.
class FaultSurface {
public:
  struct Panel {
    Point3 a{};                 // trace point at s = 0, t = 0
    Point3 e{}, w{}, n{};       // along the segment (s: 0..1), down-dip per metre of depth (t), unit normal
    double ee = 0, ew = 0, ww = 0, det = 0;
    double length = 0;          // of the segment, m
    double area_scale = 0;      // |e x w|: area per unit of s * t
    bool first = false, last = false;  // ends of their part: the surface ends there
    std::array<double, 6> bbox{};      // of the panel within the depth range
    double t0 = 0, t1 = 0;             // depth range of the panel below the trace elevation (its piece)
    std::size_t piece = 0;             // listric piece (0 for a planar fault)
  };
  struct Local {
    double s = 0, t = 0, h = 0; // along the segment, depth below the trace, signed distance from the plane
  };

  explicit FaultSurface(const FaultTrace& trace);
  const std::vector<Panel>& panels() const { return panels_; }
  Local local(std::size_t panel, const Point3& p) const;
  // Depth range below the trace: t0 = trace_z - top, t1 = trace_z - bottom (a panel covers its
  // piece's part of it: Panel::t0, t1).
  double t0() const { return t0_; }
  double t1() const { return t1_; }
  // Side 1 -> side 2 normal: down and against the dip direction (side 1 = hanging wall); of the
  // first piece for a listric fault.
  const Point3& reference_normal() const { return normal_; }
  // Distance from p to the surface (to the nearest panel, within its ends (not at the ends of a
  // fault that ends against another: ugs-meshgen extends it there) and, when
  // `within_depth`, between top and bottom; otherwise the panels extend up and down without end).
  double distance(const Point3& p, bool within_depth = true) const;
  std::array<double, 6> bbox() const;

private:
  std::vector<Panel> panels_;
  double t0_ = 0, t1_ = 0;
  Point3 normal_{};
  bool open_ends_ = false;
};

}  // namespace ugs
