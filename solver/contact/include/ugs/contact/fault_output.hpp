// Fault results at a date (thesis 4.3.4): what the contact state means for people — tractions,
// slip, opening, state, the safety factor chi = |tau| / (c - sigma'_n tan(phi)) (eq. 4.2) and the
// Coulomb stress change — per node pair, per fault, and written as
//   <stem>_faults.h5/.xdmf   on the fault surfaces (triangles in groups fault:<name>), node and
//                            cell fields at the output dates (below)
//   <stem>_faults.csv        per fault and date: max chi (and where), max slip, area in slip,
//                            area open, max opening, max Coulomb stress change
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
// field `interpolated` is 1 there. Cell fields are
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

class FaultOutput {
public:
  // Empty paths disable that output. The files appear on commit() only.
  FaultOutput(const std::string& h5_path, const std::string& csv_path, const FaultModel& fm,
              const std::vector<std::string>& csv_comments);
  ~FaultOutput();
  void add(const std::string& date, double time, const FaultFields& f, bool write_fields);
  void commit();

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ugs::contact
