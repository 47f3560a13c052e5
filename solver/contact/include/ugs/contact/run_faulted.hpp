// The faulted run of ugs-solve: a mesh with interface elements (ugs-faultinsert) is solved with
// the fault contact of contact.hpp coupled to the continuous solver, and writes, besides the
// volume results of the continuous run (<output>.h5 with the tetrahedra only, <top>.h5 and the
// optional top CSV, docs/mechanics.md):
//   <stem>_faults.h5/.xdmf   fault fields at the output dates (fault_output.hpp)
//   <stem>_faults.csv        per fault and date (every step): max chi, max slip, areas in slip/open
//   <stem>_fault_<name>.csv  per fault, every node pair at the output dates (fault_output.hpp)
//   <stem>_scenario.csv      with --find-safe-scale: every scale tried and its outcome
//
// Initial fault tractions come from the geostatic stress of the case (the thesis' figures
// 4.41-4.42); the fluid pressure on a fault is the hydrostatic pressure plus the pressure change of
// the flow fields at its nodes (mean of the two sides).
//
// Scenario (case [scenario], docs/fault-mechanics.md): after the reference date the pressure change
// is scaled about its value there, dp_s(t) = dp(t_ref) + s (dp(t) - dp(t_ref)), on the rock and on
// the faults. --find-safe-scale searches the smallest s at which a fault patch (a node pair acting
// on free degrees of freedom) reaches chi = 1 — slips, opens or stands on its limit — at any step
// after the reference date: doubling from 1 up to max_scale, then bisection to scale_tolerance,
// each trial rerun from the state saved at the reference date. The answer is the largest safe
// scale and the peak pressure change it allows: the maximum safe storage pressure.
#pragma once
#include <optional>
#include <string>

#include <mpi.h>

#include "ugs/formats/case_file.hpp"
#include "ugs/formats/mesh.hpp"
#include "ugs/mechanics/run.hpp"

namespace ugs::contact {

struct FaultedRunOptions {
  std::string fault_output;            // default <stem>_faults.h5; "none" disables
  std::string fault_csv;               // default <stem>_faults.csv; "none" disables
  std::string fault_pairs_csv;         // prefix of the per-pair CSVs, default <stem>_fault_; "none" disables
  std::string scenario_csv;            // default <stem>_scenario.csv (with find_safe_scale)
  std::string fault_solver;            // overrides the case's [solver] fault_solver
  std::optional<double> scale;         // overrides the case's [scenario] pressure_scale
  bool find_safe_scale = false;
};

struct SafeScale {
  bool searched = false;
  bool critical_before = false;        // chi reached 1 before or at the reference date
  bool found = false;                  // a critical scale below max_scale
  double safe = 0, critical = 0;       // largest safe and smallest critical scale tried
  std::string fault, date;             // first patch to reach chi = 1 at `critical`
  Point3 at{};
  double peak_dp_max = 0, peak_dp_min = 0;  // pressure change extremes after the reference at `safe` [Pa]
};

// Collective; `mesh` and `cs` on rank 0 (null elsewhere), as mech::RunOptions::faulted passes them.
mech::RunSummary run_faulted(MPI_Comm comm, const mech::RunOptions& o, const FaultedRunOptions& fo, Mesh* mesh, CaseFile* cs,
                             SafeScale* safe = nullptr);

}  // namespace ugs::contact
