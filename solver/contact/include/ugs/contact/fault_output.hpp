// Fault results at a date (thesis 4.3.4): what the contact state means for people — tractions,
// slip, opening, state, the safety factor chi = |tau| / (c - sigma'_n tan(phi)) (eq. 4.2) and the
// Coulomb stress change — per node pair, per fault, and written as
//   <stem>_faults.h5/.xdmf   on the fault surfaces (triangles in groups fault:<name>), node and
//                            cell fields at the output dates (below)
//   <stem>_faults.csv        per fault and date: max chi (and where), max slip, area in slip,
//                            area open, max opening, max Coulomb stress change
//   <prefix><fault>.csv      per fault, one row per node pair and output date (for plotting):
//                            position, along-strike and down-dip coordinates, area, state, tau,
//                            sigma'_n, chi, slip, opening, CFS change in MPa / mm
//
// One definition of every statistic: chi, slip, opening... live at the node pairs (the unknowns of
// the contact problem are there), and "max chi of a fault" is the largest chi over the fault's node
// pairs that act on free degrees of freedom. The statistics CSV, the node fields of the HDF5 (where
// the nodes of tips and of pairs on prescribed boundaries, `interpolated` = 1, hold means of their
// neighbours, never above that maximum) and ugs-report's table, maps and time plot all show that
// number. The cell fields (means of three nodes) are for viewers that colour cells; they are
// smaller than the pair values at peaks and are not what the statistics report.
//
// Fields (SI units; vectors in x, y, z; tension positive; side 1 -> side 2 normal):
//   traction     total traction on side 1 [Pa, 3]       sigma_n, sigma_n_eff  normal, total and
//   tau, tau_abs shear traction vector and magnitude     effective (+ fluid pressure) [Pa]
//   slip, slip_abs  tangential relative displacement u_side2 - u_side1 [m, 3] and its magnitude
//   opening      normal relative displacement [m] (> 0 open)       u_r  relative displacement [m, 3]
//   state        0 stick, 1 slip, 2 open               chi  safety factor (1 in slip or open)
//   cfs_change   Coulomb stress change from the initial state, d|tau| + tan(phi) d sigma'_n [Pa]
//   p_fault      fluid pressure on the fault [Pa]
// Node fields hold the node pairs' values; tip nodes (no multiplier) and pairs on prescribed
// boundaries take the mean of their neighbours on the fault (state: the largest), and the node
// field `interpolated` is 1 there. The node fields `along_strike` and `down_dip` [m] are the
// coordinates in the fault's own plane (fault_plane_coordinates). Cell fields are
// the means over the triangle's nodes (state: the largest). Statistics use the node pairs that act
// on free degrees of freedom only.
#pragma once
#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "ugs/contact/contact.hpp"
#include "ugs/contact/fault_model.hpp"

namespace ugs::contact {

// Per node pair (FaultModel order).
struct FaultFields {
  std::vector<double> traction, tau, slip, u_r;  // 3 per pair
  std::vector<double> sigma_n, sigma_n_eff, tau_abs, slip_abs, opening, state, chi, cfs_change, p_fault;
};
FaultFields derive_fault_fields(const FaultModel& fm, const PairResults& r);

struct FaultDateStats {
  double max_chi = 0;
  Point3 at{};                    // where chi is largest
  double max_slip = 0, slip_area = 0, open_area = 0, max_opening = 0;
  double max_cfs_change = -std::numeric_limits<double>::infinity();
  std::size_t pairs = 0, slipping = 0, open = 0;  // active pairs
};
std::vector<FaultDateStats> fault_date_stats(const FaultModel& fm, const FaultFields& f);

// Coordinates of the fault surface's nodes (FaultSurface order) in their fault's own plane [m]:
//   along_strike  distance along the strike from the fault's end furthest west (south for a fault
//                 striking north-south): (x - x_0) . s, s the horizontal unit vector normal to the
//                 fault's mean normal (area-weighted over its node pairs), pointing east (north);
//   down_dip      distance down the dip from the fault's top edge (its highest node), measured in
//                 the mean plane: (z_top - z) / sin(dip), dip the angle of the mean plane.
// On a planar fault these are exact distances in the plane. A (nearly) horizontal fault (dip below
// 0.06 degrees) has no strike: along_strike is x - x_min and down_dip y_max - y.
struct FaultPlaneCoordinates {
  std::vector<double> along_strike, down_dip;  // per surface node
  std::vector<std::array<double, 3>> strike;   // per fault: the unit strike vector
  std::vector<double> dip_deg;                 // per fault: dip of the mean plane
};
FaultPlaneCoordinates fault_plane_coordinates(const FaultModel& fm);

// A fault name as a file-name part: letters, digits, '-', '_' and '.' kept, anything else '_'.
std::string fault_file_name(const std::string& name);

class FaultOutput {
public:
  // Empty paths disable that output. The files appear on commit() only. `pairs_prefix`: the
  // per-pair CSVs <pairs_prefix><fault_file_name(fault)>.csv, rows at the dates add() is given
  // write_pairs = true (the fields HDF5 at those with write_fields = true).
  FaultOutput(const std::string& h5_path, const std::string& csv_path, const FaultModel& fm,
              const std::vector<std::string>& csv_comments, const std::string& pairs_prefix = "");
  ~FaultOutput();
  void add(const std::string& date, double time, const FaultFields& f, bool write_fields, bool write_pairs);
  void commit();

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ugs::contact
