// One ugs-solve run: read the mesh, the case file and the pressure fields (rank 0), build and
// distribute the model, march over the steps (the union of the pressure files' dates, plus the
// case's output dates), and write on rank 0:
//   <output>.h5/.xdmf        fields at the output dates: node u [m]; cell strain, stress,
//                            stress_change [Pa, 6 components xx yy zz xy yz xz], cM [1/Pa],
//                            state (0 elastic, 1 virgin, 2 unloading, 3 reloading), sigma_z_max [Pa];
//                            node dp [Pa] on request
//   <top>.h5/.xdmf           top surface (bnd:top) at every step: node u_mm [mm, 3 components]
//   <top_csv>                the same as a CSV table (optional)
//   <state>.h5/.xdmf         restart state: at the output dates, every checkpoint_every steps, at
//                            the end, and — the last good one — when a step fails
// Every rank calls run_solve; errors surface on every rank alike (collective.hpp).
#pragma once
#include <functional>
#include <string>
#include <vector>

#include <mpi.h>

namespace ugs {
class Mesh;
struct CaseFile;
}  // namespace ugs

namespace ugs::mech {

struct RunSummary;

struct RunOptions {
  std::string mesh = "-";
  std::string case_file;
  std::vector<std::string> pressure;
  std::string output = "solve.h5";
  std::string top;       // default: <output stem>_top.h5; "none" disables
  std::string top_csv;   // optional
  std::string state;     // default: <output stem>_state.h5; "none" writes no restart state
  std::string restart;   // a state file to resume from
  std::string until;     // stop after this date (ISO 8601): a long history can run in pieces
  std::string solver;    // overrides the case's linear_solver
  std::string partition = "ptscotch";
  int checkpoint_every = -1;  // overrides the case's checkpoint_every when >= 0
  std::string command_line;
  // Messages (level 0 info, 1 detail, -1 warning) and progress; called on rank 0 only.
  std::function<void(int, const std::string&)> log;
  std::function<void(std::size_t done, std::size_t total)> progress;
  // A mesh with interface elements (faults) is handed, with the case file, to this runner (the
  // fault mechanics of ugs_contact) on every rank (mesh and case on rank 0, null elsewhere);
  // without it such meshes are refused.
  std::function<RunSummary(MPI_Comm, const RunOptions&, Mesh*, CaseFile*)> faulted;
};

struct RunSummary {
  std::size_t steps = 0, newton_iterations = 0, linear_iterations = 0, substeps = 0, preconditioner_setups = 0;
  double seconds_read = 0, seconds_setup = 0, seconds_solve = 0, seconds_output = 0;
};

RunSummary run_solve(MPI_Comm comm, const RunOptions& options);

// "<stem>" of a results path: "out/solve.h5" -> "out/solve".
std::string output_stem(const std::string& h5_path);

}  // namespace ugs::mech
