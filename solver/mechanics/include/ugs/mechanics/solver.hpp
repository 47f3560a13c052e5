// The quasi-static equilibrium of the continuous model (thesis 3.4-3.5.1) on linear tetrahedra,
// distributed over MPI ranks with PETSc:
//
//   r(u) = f_ext(t) - f_int(u) = 0,  f_int = sum_e V B^T (sigma' - sigma'_0),  f_ext = sum_e V B^T i alpha dp_e
//
// u is the displacement from the geostatic state (in equilibrium, the reference), dp_e the pore
// pressure change of element e from the flow model (Biot forcing, eq. 3.57; pressure.hpp). Each load step is solved by Newton's method with the tangent of material_point.hpp to
// ||r|| <= tol ||r_0|| (r_0: the unbalanced force at the start of the step); a step that fails is
// split in halves (sub-steps) down to 1/max_substeps before the run is declared failed.
//
// Layout: rank 0 holds the Model and partitions the nodes; each rank owns a contiguous block of
// global node numbers (3 rows each), keeps every element touching an owned node (elements on a
// partition boundary are computed by both ranks, identically) and assembles its own rows without
// communication. Linear algebra: MPIAIJ matrix with block size 3, CG + GAMG with the rigid-body
// near-null space (default), CG + BoomerAMG, MUMPS or CHOLMOD; PETSc options override everything.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <mpi.h>

#include "ugs/mechanics/model.hpp"
#include "ugs/mechanics/partition.hpp"

namespace ugs::mech {

enum class LinearSolver { CgGamg, CgHypre, Mumps, Cholmod };
// "cg-gamg" | "cg-hypre" | "mumps" | "cholmod"; InputError otherwise.
LinearSolver parse_linear_solver(const std::string& s);
const char* linear_solver_name(LinearSolver s);

// How accurately the linear solve of each Newton correction is done on models with hypo-plastic
// elements, where the elements held at their knee, and so the answer, are decided on the iterates
// (docs/mechanics.md "Newton corrections of hypo-plastic models"). Other models use Eisenstat-Walker.
enum class Corrections {
  Bounded,          // Eisenstat-Walker, never leaving more than 50 x tolerance x r_0 (the default; exact with faults)
  Exact,            // to 0.5 x tolerance x r_0 every time (sessions 9-12; `-ugs_exact_newton`)
  EisenstatWalker,  // Eisenstat-Walker alone (`-ugs_inexact_newton`): faster, the answer moves with the solver
};

struct SolverOptions {
  LinearSolver linear = LinearSolver::CgHypre;
  PartitionMethod partition = PartitionMethod::PtScotch;
  double tolerance = 1e-8;   // Newton: ||r|| <= tolerance ||r_0||
  // ||r|| <= tolerance max(||r_0||, ||f_ext||) instead: relative to the whole load at the step's
  // date, not to the step's increment ([solver] tolerance_of = "total-load", docs/mechanics.md).
  bool tolerance_of_total_load = false;
  int max_newton = 25;
  int max_substeps = 64;
  bool reuse_preconditioner = true;
  Corrections corrections = Corrections::Bounded;  // PETSc's -ugs_exact_newton / -ugs_inexact_newton override it
};

struct StepReport {
  bool converged = false;
  int newton_iterations = 0;   // summed over sub-steps
  int linear_iterations = 0;
  int substeps = 1;
  int preconditioner_setups = 0;
  std::vector<double> residuals;  // ||r_k|| / ||r_0|| of the last (sub-)step tried
  std::string failure;            // why the step failed
  // Why the step was split into sub-steps (the first failure and its residuals; empty if it was not).
  std::string substep_reason;
  // Elements held on a branch (docs/mechanics.md "Newton iteration") that ended on the other side
  // of their knee: bound on the residual of the nearest state obeying the law, relative to r_0.
  double off_branch = 0;
  double seconds = 0;
};

// Element results gathered on rank 0, in output order (one tuple per tetrahedron).
struct CellResults {
  std::vector<double> strain;        // 6 per cell, output order xx yy zz xy yz xz (tensor components)
  std::vector<double> stress;        // effective stress, initial + change [Pa], output order
  std::vector<double> stress_change; // [Pa], output order
  std::vector<double> cm;            // c_M in use [1/Pa]
  std::vector<double> state;         // 0 elastic/linear, 1 virgin, 2 unloading, 3 reloading
  std::vector<double> sigma_max;     // preconsolidation sigma_z [Pa] (hypo-plastic; 0 elsewhere)
};

// One element result of CellResults, gathered on its own (an output date gathers and writes one
// at a time, so rank 0 never holds them all: 21 values per cell, 460 MB on the 1.49M-dof box).
enum class CellField { Strain, Stress, StressChange, Cm, State, SigmaMax };

// The history variables, gathered on rank 0 (restart files).
struct SavedState {
  std::vector<double> u;          // 3 per mesh node
  std::vector<double> eps;        // 6 per cell, thesis order (hypo-plastic cells; zeros elsewhere)
  std::vector<double> dsig;       // 6 per cell, thesis order
  std::vector<double> hypo;       // 4 per cell: sigma_max, sigma_inv [MPa], direction, sign of the last dp change
  std::vector<double> dp;         // the pressure change the state is in equilibrium with (per cell)
};

// One cell member of SavedState, gathered on its own: a restart file is written one field at a time,
// so rank 0 never holds them all (17 values per cell, 390 MB on the 1.49M-dof box, rank 0's peak).
enum class StateField { Dp, Eps, Dsig, Hypo };

class Coupling;

class MechanicsSolver {
public:
  // Collective. `model` is used on rank 0 only (other ranks may pass nullptr).
  MechanicsSolver(MPI_Comm comm, const Model* model, const SolverOptions& options);
  ~MechanicsSolver();
  MechanicsSolver(const MechanicsSolver&) = delete;
  MechanicsSolver& operator=(const MechanicsSolver&) = delete;

  // Collective: solve `coupling`'s unknowns (e.g. the fault contact, coupling.hpp) with the
  // displacement from now on. It must outlive the solver's use of it.
  void set_coupling(Coupling& coupling);

  // Collective: advances from the current state to equilibrium with the pressure change `dp`
  // (Pa, one value per tetrahedron in output order, read on rank 0). On failure the state is left
  // as it was before the call.
  StepReport advance(const std::vector<double>& dp, const std::string& label);
  // Collective: frees the linear system (matrix, preconditioner, predictor basis) when no step
  // follows: the gathers and writes of the last output date then run without it (on the
  // 1.49M-dof box it was a third of the process at that point). advance() is refused afterwards
  // (std::logic_error); the gathers work as before.
  void release_linear_system();

  // Collective gathers to rank 0 (empty elsewhere).
  std::vector<double> gather_displacement();  // 3 per mesh node [m]
  CellResults gather_cells();
  std::vector<double> gather_cell_field(CellField field);  // the same values as gather_cells()'s member
  SavedState gather_state();
  std::vector<double> gather_state_field(StateField field);  // the same values as gather_state()'s member
  // Collective: sets the state from rank 0's `state` (restart). InputError if sizes do not match.
  void restore_state(const SavedState& state);

  // Sizes and the partition, for messages.
  std::size_t global_nodes() const;
  std::size_t global_cells() const;
  std::size_t local_nodes() const;    // owned by this rank
  std::size_t local_cells() const;    // kept by this rank (with shared ones)
  std::string solver_description() const;
  // PETSc's type of the tangent matrix ("hypre" when BoomerAMG preconditions it: built as hypre's own
  // matrix, unless `-ugs_aij_matrix` keeps a PETSc matrix that PCHYPRE converts); "" before the first step.
  std::string matrix_type() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ugs::mech
