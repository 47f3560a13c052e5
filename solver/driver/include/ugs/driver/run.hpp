// One ugs-solve run, continuous or faulted: read the mesh, the case file and the pressure fields
// (rank 0), build and distribute the model, march over the step plan and write the output set on
// rank 0 (docs/mechanics.md "Outputs", docs/fault-mechanics.md "Outputs"):
//   <output>.h5/.xdmf        fields at the output dates (node u; cell strain, stress, stress_change,
//                            cM, state, sigma_z_max; node dp on request) — tetrahedra only
//   <top>.h5/.xdmf, <top_csv> top surface (bnd:top) at every step
//   <state>.h5/.xdmf         restart state: at the output dates, every checkpoint_every steps, at
//                            the end, and — the last good one — when a step fails; a faulted run
//                            adds <state stem>_faults.h5 (fault_state_file.hpp)
//   faulted meshes also:     the fault outputs (contact/fault_output.hpp) and, with the safe-scale
//                            search, the table of the scales tried (safe_scale.hpp)
// A mesh with interface elements (ugs-faultinsert) is solved with the fault contact coupled to the
// continuous solver; everything else (settings, steps, outputs, restart) is shared. Every rank
// calls run(); errors surface on every rank alike (mech/collective.hpp).
#pragma once
#include <cstddef>

#include <mpi.h>

#include "ugs/driver/safe_scale.hpp"
#include "ugs/driver/settings.hpp"

namespace ugs::driver {

struct RunSummary {
  std::size_t steps = 0, newton_iterations = 0, linear_iterations = 0, substeps = 0, preconditioner_setups = 0;
  double seconds_read = 0, seconds_setup = 0, seconds_solve = 0, seconds_output = 0;
  bool searched = false;       // the safe-scale search ran
  bool critical_before = false;  // chi reached 1 before or at the reference date
  SafeScale safe;
};

RunSummary run(MPI_Comm comm, const RunSettings& settings);

}  // namespace ugs::driver
