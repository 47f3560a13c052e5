// The state and the pieces of the mechanics solver (ugs/mechanics/solver.hpp), shared by its source
// files: solver.cpp (public interface, gathers), solver_setup.cpp, assembly.cpp, linear_solve.cpp
// and step.cpp. Newton, the iteration of a (sub-)step, is its own part (newton.hpp, with the
// predictor of its first correction, predictor.hpp), given what it reads and changes. Private to
// ugs_mechanics.
#pragma once

#include "ugs/mechanics/solver.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <Eigen/Dense>
#include <fmt/format.h>
#include <functional>
#include <petscksp.h>
#include "hypre_in_place.hpp"
#include "local_mesh.hpp"
#include "newton.hpp"
#include "ugs/mechanics/reuse_rule.hpp"
#include "petsc_check.hpp"
#include "ugs/fem/tet4.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/mechanics/collective.hpp"
#include "ugs/mechanics/coupling.hpp"

namespace ugs::mech {

using fem::Vec6;
using fem::ZZ;

// PETSc log events of the solver (-log_view).
struct Events {
  PetscLogEvent residual = 0, assembly = 0, gather = 0, predictor = 0;
};

inline const Events& events() {
  static Events ev = [] {
    Events e;
    PetscClassId id = 0;
    PetscClassIdRegister("ugs-solve", &id);
    PetscLogEventRegister("UgsResidual", id, &e.residual);
    PetscLogEventRegister("UgsAssembly", id, &e.assembly);
    PetscLogEventRegister("UgsGather", id, &e.gather);
    PetscLogEventRegister("UgsPredictor", id, &e.predictor);
    return e;
  }();
  return ev;
}

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

inline std::string history_text(const std::vector<double>& h) {
  std::string s;
  for (std::size_t i = 0; i < h.size(); ++i) s += fmt::format("{}{:.2e}", i ? ", " : "", h[i]);
  return s;
}

// The parts of the solver's state, each owned by one concern (the methods of Impl below use them):

// Hypo-plastic state store: per hypo-plastic element h (cells[h] is its local cell), the committed
// state of the last converged (sub-)step, the trial state of the current Newton iterate, and the
// knee holds of the iteration (newton.cpp).
struct HypoStateStore {
  std::vector<std::int32_t> of_cell;   // per local cell: its h, or -1
  std::vector<std::int32_t> cells;     // per h: the local cell
  std::vector<fem::PointState> committed;
  std::vector<fem::LoadingPhase> committed_phase;
  std::vector<double> committed_c;     // 1/MPa
  std::vector<fem::PointUpdate> trial;
  std::vector<Vec6> trial_eps;
  std::vector<std::int8_t> guess;      // direction of the first tangent of the step
  std::vector<std::int8_t> last_ddp;   // sign of the element's last pressure change
  // The knee of the law (hypoplastic.hpp): elements that change branch back and forth are held
  // on one branch for the rest of the (sub-)step; the convergence test checks the held branches.
  std::vector<std::int8_t> piece;      // phase at the last Newton iterate (0: none yet)
  std::vector<std::uint8_t> flips;
  std::vector<fem::Hold> hold;
  std::vector<std::int8_t> hold_dir;   // direction the element was held with (inversion stress)
  long long n_global = 0;              // over all ranks
  bool saturated = false;
  std::size_t size() const { return cells.size(); }
  // Magnitude of the effective vertical stress of element h at the start of the step [MPa]
  // (s0: per local cell, at the initial state).
  double start_sigma(int h, const std::vector<double>& s0) const { return s0[cells[h]] - committed[h].dsig[ZZ] * 1e-6; }
};

// Whether an element's tangent differs between two loading phases (-1: none yet). Under
// sigma-max, unloading and reloading share the stiffness c_M(sigma_max) / c_R.
inline bool tangent_differs(fem::InversionRule rule, int phase_a, int phase_b) {
  if (phase_a == phase_b) return false;
  const auto unload_reload = [](int p) {
    return p == static_cast<int>(fem::LoadingPhase::Unloading) || p == static_cast<int>(fem::LoadingPhase::Reloading);
  };
  return !(unload_reload(phase_a) && unload_reload(phase_b) && rule == fem::InversionRule::SigmaMax);
}

// Assembler: the sparsity pattern of the owned rows, the assembled values, and which tangent each
// hypo-plastic element contributes to them (incremental assembly, assembly.cpp).
struct Assembler {
  std::vector<PetscInt> node_ptr;      // per owned node: range of its neighbour blocks
  std::vector<std::int64_t> node_cols; // neighbour global node numbers, sorted per row
  std::vector<PetscInt> rowptr, cols;  // scalar CSR of the owned rows (global columns)
  // The elastic elements' part of the matrix (with the prescribed rows' diagonal): A's values are
  // kept in A only, the hypo-plastic elements' stiffness (or its change) added into it.
  std::vector<double> vals_lin, diag_scale;
  // After A is created: the elastic part of the only rows a reassembly resets, those of the owned
  // nodes of hypo-plastic elements (compact_reset_rows; the full arrays above are then freed
  // unless CHOLMOD's symmetric P needs them). Empty reset_row: the full arrays are used.
  std::vector<PetscInt> reset_row, reset_ptr, reset_cols;
  std::vector<double> reset_vals;
  std::vector<fem::Mat6> assembled_Dt;
  std::vector<std::int8_t> assembled_phase;  // branch in the matrix
  bool have_lin = false, mat_created = false, mat_changed = false;
  // Incremental assembly: the elements whose tangent changed add the difference; a full
  // assembly every kFullAssemblyEvery updates keeps the sums fresh.
  static constexpr int kFullAssemblyEvery = 100;
  int updates_since_full = 0;
  // Under BoomerAMG, the tangents are added straight into hypre's arrays (hypre_in_place.hpp).
  HypreInPlace in_place;
};

// Preconditioner-reuse policy: what the last setup and solves cost, in iteration counts only
// (never measured time: the decision changes the numbers, reuse_rule.hpp, linear_solve.cpp).
struct PreconditionerReuse {
  bool valid = false;                  // a preconditioner has been set up
  double baseline_ipd = 0, last_ipd = 0, last_decades = 0;
  int setups = 0;
  std::vector<std::int8_t> phase;      // per hypo-plastic element: branch in the matrix of the last setup
  PetscInt user_maxit = -1;
  // Whether the preconditioner of the last setup still converges at a rate worth keeping.
  bool rate_ok(bool factored) const;
  // The iteration budget of a solve with a kept preconditioner (it is rebuilt if that is not enough).
  PetscInt budget(bool factored, double rtol) const;
  // Records a solve's rate (iterations per decade of residual reduction).
  void record(int iterations, double reduction, bool fresh);
};

struct MechanicsSolver::Impl {
  SolverOptions opt;
  LocalMesh lm;

  // ---- elements -------------------------------------------------------------------------------
  std::vector<fem::Tet4> geo;
  std::vector<double> s0;              // initial effective vertical stress magnitude [MPa]
  std::vector<double> inv_c0;          // elastic law: 1 / c_M(s0) [Pa]
  HypoStateStore hyp;
  // Some rank has hypo-plastic elements: the problem is nonlinear and its consistent tangent is not
  // symmetric, so the Krylov method is GMRES and MUMPS factors LU; CHOLMOD (Cholesky only) factors
  // the matrix of the symmetric form of the tangent (material_point.hpp; SPD, unlike the symmetric
  // part of the consistent one at the knee).
  bool has_hyp = false;

  // ---- loads ----------------------------------------------------------------------------------
  std::vector<double> dp_cell;         // pressure change of the current state, per local element
  std::vector<double> fext, fint;      // 3 per owned node
  // The internal forces of the elements that are not hypo-plastic (they depend on u alone), kept
  // from one residual to the next while u keeps its values (its PETSc object state): a step's
  // first residual is taken where the last one of the step before was (residual()).
  std::vector<double> fint_elastic;
  bool fint_elastic_valid = false;
  PetscObjectState fint_elastic_state = 0;

  // ---- linear system --------------------------------------------------------------------------
  Assembler assembler;
  PreconditionerReuse reuse;
  Mat A = nullptr, P = nullptr;
  Vec u = nullptr, u_save = nullptr, u_step = nullptr, r = nullptr, du = nullptr;
  KSP ksp = nullptr;
  // Extra unknowns solved with u (fault contact, coupling.hpp); null for the continuous model.
  Coupling* coupling = nullptr;
  bool released = false;  // release_linear_system() was called: no more steps

  // ---- Newton (newton.cpp, predictor.cpp) -----------------------------------------------------
  Newton newton{Newton::Reads{opt, lm, geo, s0, dp_cell, has_hyp, coupling, reuse, A, r},
                Newton::Changes{hyp, u, u_save, du},
                Newton::Operations{[this](const std::vector<double>& dp) { external_force(dp); },
                                   [this] { return residual(); }, [this] { assemble(); },
                                   [this](double rtol, bool guess) { return solve(rtol, guess); },
                                   [this] { return load_norm(); }}};

  ~Impl() {
    if (ksp) KSPDestroy(&ksp);
    if (A) MatDestroy(&A);
    if (P) MatDestroy(&P);
    for (Vec* v : {&u, &u_save, &u_step, &r, &du})
      if (*v) VecDestroy(v);
  }

  // Every solver runs a Krylov method; with MUMPS or CHOLMOD its preconditioner is a factorization,
  // which is kept across Newton iterations and steps while it still converges fast (a refactor
  // costs tens of solves: docs/mechanics.md).
  bool factored() const { return opt.linear == LinearSolver::Mumps || opt.linear == LinearSolver::Cholmod; }
  bool owned_dof_fixed(int a, int c) const { return (lm.fixed[a] >> c) & 1; }
  // Sets the prescribed components of a vector of owned displacements to zero.
  void zero_fixed(Vec v) const {
    PetscScalar* x = nullptr;
    UGS_PETSC(VecGetArray(v, &x));
    for (int a = 0; a < lm.n_owned; ++a)
      for (int c = 0; c < 3; ++c)
        if (owned_dof_fixed(a, c)) x[3 * a + c] = 0.0;
    UGS_PETSC(VecRestoreArray(v, &x));
  }

  // ---- setup ----------------------------------------------------------------------------------
  void setup_elements();

  void setup_pattern();

  void setup_vectors();

  // PETSc options that ugs-solve sets unless the user gave them (after "--").
  static void set_default_options(std::initializer_list<std::pair<const char*, const char*>> defaults);

  // CG for the SPD operator; right-preconditioned GMRES for the consistent hypo-plastic tangent
  // (both stop on the true residual, so the Newton forcing terms mean the same thing).
  void set_krylov();

  void setup_ksp();

  // ---- element kernels ------------------------------------------------------------------------
  void gather_element(const PetscScalar* ua, int c, double* ue) const {
    const auto& t = lm.cells[c];
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) ue[3 * i + k] = ua[3 * t[i] + k];
  }

  void add_owned(std::vector<double>& f, int c, const double* fe) const {
    const auto& t = lm.cells[c];
    for (int i = 0; i < 4; ++i)
      if (t[i] < lm.n_owned)
        for (int k = 0; k < 3; ++k) f[3 * t[i] + k] += fe[3 * i + k];
  }

  // Effective stress change of a non-hypo-plastic element at strain eps.
  Vec6 elastic_stress(int c, const Vec6& eps) const {
    const fem::Material& m = lm.materials[lm.cell_material[c]];
    if (m.law == fem::Law::Linear) return fem::mat_vec(m.D_linear, eps);
    Vec6 s = fem::mat_vec(m.Dhat, eps);
    for (double& v : s) v *= inv_c0[c];
    return s;
  }

  fem::Mat6 elastic_D(int c) const {
    const fem::Material& m = lm.materials[lm.cell_material[c]];
    if (m.law == fem::Law::Linear) return m.D_linear;
    fem::Mat6 D;
    for (int i = 0; i < 36; ++i) D[i] = m.Dhat[i] * inv_c0[c];
    return D;
  }

  // Magnitude of the effective vertical stress at the start of the step [MPa].
  double start_sigma(int h) const { return hyp.start_sigma(h, s0); }

  void external_force(const std::vector<double>& dp);

  // r = f_ext - f_int(u) (zero on prescribed dofs); evaluates the hypo-plastic trial states.
  double residual();
  double load_norm() const;

  // ---- assembly -------------------------------------------------------------------------------
  void scatter(std::vector<double>& v, int c, const std::array<double, 144>& Ke, bool diag_too);

  void set_constrained_diagonal(std::vector<double>& v) const;

  // Builds (or refreshes) the tangent matrix from the current trial states.
  void assemble();

  const fem::Mat6& tangent(std::size_t h) const { return hyp.trial[h].Dt; }


  // Hypo-plastic elements contribute to the scale of prescribed rows with their initial tangent.
  void scatter_dummy_diag(int c);

  // Preconditioned by hypre (whatever -pc_type chose), A is built as hypre's matrix: PCHYPRE uses it
  // as it is instead of converting a PETSc copy at every setup (one matrix in memory, not two). With
  // hypo-plastic elements A changes in place while a hierarchy is kept: BoomerAMG's fine level is
  // A, so its smoother and residual see the current tangent and only the coarse levels are the
  // kept ones (the Krylov method runs on A either way).
  bool hypre_owns_matrix() const;

  // A from the elastic part: created with it (first call), or its rows reset to it.
  void upload_linear();
  // Frees the pattern and the elastic values once nothing will change A again (no hypo-plastic element).
  void release_pattern();
  void compact_reset_rows();
  // Adds an element's stiffness (or its change) into A as scatter() would into a CSR array:
  // owned rows, no prescribed row or column; the same sums in the same order, so the same bits.
  void add_to_matrix(int c, const std::array<double, 144>& Ke);

  // ---- linear solve ---------------------------------------------------------------------------
  using SolveResult = LinearSolveResult;

  // GAMG's fine-level smoother runs on the preconditioning matrix: when A changes (hypo-plastic
  // branches) and the hierarchy is reused, it must see the matrix the hierarchy was built from, or
  // its Chebyshev bounds no longer hold. So GAMG gets a frozen copy P; hypre copies A itself.
  bool separate_p() const {
    return (opt.linear == LinearSolver::CgGamg && has_hyp) || (opt.linear == LinearSolver::Cholmod && has_hyp);
  }

  // P from the symmetric form of every element's tangent (CHOLMOD's matrix).
  void assemble_symmetric_p();

  void rebuild_pc();

  SolveResult solve_once(double rtol, bool guess, PetscInt maxit);

  SolveResult solve(double rtol, bool guess);

  // True when many hypo-plastic elements changed to a branch of another stiffness since the
  // preconditioner was built: their stiffness jumped by c_R, and a new setup (a few V-cycles) costs
  // less than the iterations a stale hierarchy needs.
  bool branches_moved() const {
    long long mine = 0, all = 0;
    for (std::size_t h = 0; h < assembler.assembled_phase.size(); ++h)
      mine += tangent_differs(h, assembler.assembled_phase[h], reuse.phase[h]);
    MPI_Allreduce(&mine, &all, 1, MPI_LONG_LONG, MPI_SUM, lm.comm);
    return static_cast<double>(all) > 0.05 * static_cast<double>(hyp.n_global);
  }
  bool tangent_differs(std::size_t h, int phase_a, int phase_b) const {
    return mech::tangent_differs(lm.materials[lm.cell_material[hyp.cells[h]]].hypo.rule, phase_a, phase_b);
  }

  // ---- one step (step.cpp): sub-steps, each solved by newton ----------------------------------
  // Adds the increment u - base of a converged (sub-)step to the predictor's basis.
  void remember_increment_from(Vec base);

  void commit(const std::vector<double>& dp_target);

  void restore_u();

  StepReport advance(const std::vector<double>& dp_rank0, const std::string& label);


  // ---- gathers --------------------------------------------------------------------------------
  // Concatenates per-rank arrays on rank 0 (counts in doubles).
  std::vector<double> gatherv(const std::vector<double>& mine) const {
    int n = static_cast<int>(mine.size());
    std::vector<int> counts(lm.size), displs(lm.size, 0);
    MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, lm.comm);
    std::vector<double> all;
    if (lm.rank == 0) {
      long long total = 0;
      for (int p = 0; p < lm.size; ++p) displs[p] = static_cast<int>(total), total += counts[p];
      all.resize(total);
    }
    MPI_Gatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, 0, lm.comm);
    return all;
  }

  // Owned-node values (k per node) to mesh order on rank 0.
  std::vector<double> gather_nodes(const std::vector<double>& owned, int k) const {
    const auto all = gatherv(owned);
    std::vector<double> out;
    if (lm.rank == 0) {
      out.resize(all.size());
      for (std::size_t g = 0; g < lm.orig_of_global.size(); ++g)
        for (int c = 0; c < k; ++c) out[k * lm.orig_of_global[g] + c] = all[k * g + c];
    }
    return out;
  }

  std::vector<double> owned_u() const {
    std::vector<double> v(3 * lm.n_owned);
    const PetscScalar* a = nullptr;
    UGS_PETSC(VecGetArrayRead(u, &a));
    std::copy(a, a + v.size(), v.begin());
    UGS_PETSC(VecRestoreArrayRead(u, &a));
    return v;
  }
};

}  // namespace ugs::mech
