// The fault options of ugs-solve (docs/fault-mechanics.md), kept beside the fault mechanics so
// the tool adds them with one call, and the hook that hands faulted meshes to run_faulted.
// Header-only: it needs CLI11, which the tools have and the library does not.
#pragma once
#include <CLI/CLI.hpp>

#include "ugs/contact/run_faulted.hpp"
#include "ugs/mechanics/run.hpp"

namespace ugs::contact {

inline void add_fault_options(CLI::App& app, FaultedRunOptions& f) {
  auto* g = app.add_option_group("Faults", "Meshes with interface elements (ugs-faultinsert): fault mechanics");
  g->add_option("--fault-output", f.fault_output,
                "Fault fields at the output dates (HDF5 + XDMF; default <output>_faults.h5; 'none')");
  g->add_option("--fault-csv", f.fault_csv, "Per fault and date: max chi, max slip, areas in slip and open (default "
                                            "<output>_faults.csv; 'none')");
  g->add_option("--fault-pairs-csv", f.fault_pairs_csv,
                "Per fault, every node pair at the output dates (position, along strike, down dip, state, tau, sigma'_n, chi, "
                "slip, opening, CFS change): PREFIX<fault>.csv (default <output>_fault_<fault>.csv; 'none')");
  g->add_option("--fault-solver", f.fault_solver, "Saddle-point solver: auto, mumps, fieldsplit (overrides the case)")
      ->check(CLI::IsMember({"auto", "mumps", "fieldsplit"}));
  g->add_option("--scale", f.scale, "Scale of the pressure swing after the scenario's reference date (overrides the case)")
      ->check(CLI::NonNegativeNumber);
  g->add_flag("--find-safe-scale", f.find_safe_scale,
              "Search the smallest scale of the swing at which a fault patch reaches chi = 1 (maximum safe storage pressure)");
  g->add_option("--scenario-csv", f.scenario_csv, "Scales tried by --find-safe-scale (default <output>_scenario.csv)");
}

// Faulted meshes go to run_faulted with these options.
inline void use_fault_mechanics(mech::RunOptions& o, const FaultedRunOptions& f) {
  o.faulted = [f](MPI_Comm comm, const mech::RunOptions& ro, Mesh* mesh, CaseFile* cs) {
    return run_faulted(comm, ro, f, mesh, cs);
  };
}

}  // namespace ugs::contact
