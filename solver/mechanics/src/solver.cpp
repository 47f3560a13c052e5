#include "ugs/mechanics/solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include <Eigen/Dense>
#include <fmt/format.h>
#include <petscksp.h>

#include "local_mesh.hpp"
#include "petsc_check.hpp"
#include "ugs/fem/tet4.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/mechanics/collective.hpp"
#include "ugs/mechanics/coupling.hpp"

namespace ugs::mech {
namespace {

using fem::Vec6;
using fem::ZZ;

struct Events {
  PetscLogEvent residual = 0, assembly = 0, gather = 0, predictor = 0;
};

const Events& events() {
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

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string history_text(const std::vector<double>& h) {
  std::string s;
  for (std::size_t i = 0; i < h.size(); ++i) s += fmt::format("{}{:.2e}", i ? ", " : "", h[i]);
  return s;
}

}  // namespace

LinearSolver parse_linear_solver(const std::string& s) {
  if (s == "cg-gamg") return LinearSolver::CgGamg;
  if (s == "cg-hypre") return LinearSolver::CgHypre;
  if (s == "mumps") return LinearSolver::Mumps;
  if (s == "cholmod") return LinearSolver::Cholmod;
  throw InputError("--solver", "'" + s + "' is not one of cg-gamg, cg-hypre, mumps, cholmod");
}

const char* linear_solver_name(LinearSolver s) {
  switch (s) {
    case LinearSolver::CgGamg: return "cg-gamg";
    case LinearSolver::CgHypre: return "cg-hypre";
    case LinearSolver::Mumps: return "mumps";
    case LinearSolver::Cholmod: return "cholmod";
  }
  return "?";
}

struct MechanicsSolver::Impl {
  SolverOptions opt;
  LocalMesh lm;

  // ---- elements -------------------------------------------------------------------------------
  std::vector<fem::Tet4> geo;
  std::vector<double> s0;              // initial effective vertical stress magnitude [MPa]
  std::vector<double> inv_c0;          // elastic law: 1 / c_M(s0) [Pa]
  std::vector<std::int32_t> hyp_of_cell;
  std::vector<std::int32_t> hyp_cells;
  std::vector<fem::PointState> committed;
  std::vector<fem::LoadingPhase> committed_phase;
  std::vector<double> committed_c;     // 1/MPa
  std::vector<fem::PointUpdate> trial;
  std::vector<Vec6> trial_eps;
  std::vector<std::int8_t> guess;
  std::vector<std::int8_t> last_ddp;   // sign of the element's last pressure change
  // The knee of the law (hypoplastic.hpp): elements that change branch back and forth are held
  // on one branch for the rest of the (sub-)step; the convergence test checks the held branches.
  std::vector<std::int8_t> piece;      // phase at the last Newton iterate (0: none yet)
  std::vector<std::uint8_t> flips;
  std::vector<fem::Hold> hold;
  std::vector<std::int8_t> hold_dir;   // direction the element was held with (inversion stress)
  std::vector<fem::Mat6> assembled_Dt;
  std::vector<std::int8_t> assembled_phase, pc_phase;  // branch in the matrix / in the matrix of the last PC setup
  long long n_hyp_global = 0;
  bool saturated = false;
  // Some rank has hypo-plastic elements: the problem is nonlinear and its consistent tangent is not
  // symmetric, so the Krylov method is GMRES and MUMPS factors LU; CHOLMOD (Cholesky only) factors
  // the matrix of the symmetric form of the tangent (material_point.hpp; SPD, unlike the symmetric
  // part of the consistent one at the knee).
  bool has_hyp = false;

  // ---- loads ----------------------------------------------------------------------------------
  std::vector<double> dp_cell;         // pressure change of the current state, per local element
  std::vector<double> fext, fint;      // 3 per owned node

  // ---- linear system --------------------------------------------------------------------------
  std::vector<PetscInt> node_ptr;      // per owned node: range of its neighbour blocks
  std::vector<std::int64_t> node_cols; // neighbour global node numbers, sorted per row
  std::vector<PetscInt> rowptr, cols;  // scalar CSR of the owned rows (global columns)
  std::vector<double> vals_lin, vals, diag_scale;
  bool have_lin = false, mat_created = false, mat_changed = false;
  // Incremental assembly: an element's stiffness is updated when its tangent
  // moved by more than kTangentChange (relative, largest entry); a full assembly every
  // kFullAssemblyEvery updates.
  static constexpr double kTangentChange = 5e-3;
  static constexpr int kFullAssemblyEvery = 100;
  static constexpr double kFactorIpd = 5.0;      // iterations per decade a kept factorization gets
  static constexpr double kFactorHorizon = 3.0;  // solves over which a refactor must pay off
  int updates_since_full = 0;
  Mat A = nullptr, P = nullptr;
  PetscInt user_maxit_ = -1;
  Vec u = nullptr, u_save = nullptr, u_step = nullptr, r = nullptr, du = nullptr;
  KSP ksp = nullptr;
  bool pc_valid = false;
  double baseline_ipd = 0, last_ipd = 0, last_decades = 0;
  double setup_seconds = 0, seconds_per_iteration = 0;  // measured: last PC setup, last solve
  int pc_setups = 0;
  // Predictor: the span of the last step increments (orthonormal), Galerkin-projected.
  static constexpr int kRecycle = 48;
  std::vector<Vec> basis, abasis;  // W (A-orthonormal) and A W
  Vec aw = nullptr;
  // Extra unknowns solved with u (fault contact, coupling.hpp); null for the continuous model.
  Coupling* coupling = nullptr;

  ~Impl() {
    if (ksp) KSPDestroy(&ksp);
    if (A) MatDestroy(&A);
    if (P) MatDestroy(&P);
    for (Vec* v : {&u, &u_save, &u_step, &r, &du, &aw})
      if (*v) VecDestroy(v);
    for (Vec& v : basis) VecDestroy(&v);
    for (Vec& v : abasis) VecDestroy(&v);
  }

  // Every solver runs a Krylov method; with MUMPS or CHOLMOD its preconditioner is a factorization,
  // which is kept across Newton iterations and steps while it still converges fast (a refactor
  // costs tens of solves: docs/mechanics.md).
  bool factored() const { return opt.linear == LinearSolver::Mumps || opt.linear == LinearSolver::Cholmod; }
  bool owned_dof_fixed(int a, int c) const { return (lm.fixed[a] >> c) & 1; }

  // ---- setup ----------------------------------------------------------------------------------
  void setup_elements() {
    const std::size_t nc = lm.n_cells();
    geo.resize(nc);
    s0.resize(nc);
    inv_c0.assign(nc, 0.0);
    hyp_of_cell.assign(nc, -1);
    collective(lm.comm, [&] {
      for (std::size_t c = 0; c < nc; ++c) {
        const auto& t = lm.cells[c];
        try {
          geo[c] = fem::tet4({lm.x[t[0]], lm.x[t[1]], lm.x[t[2]], lm.x[t[3]]});
        } catch (const std::domain_error&) {
          throw InputError("mesh", fmt::format("tetrahedron {} (output index) is degenerate", lm.cell_index[c]));
        }
        const fem::Material& m = lm.materials[lm.cell_material[c]];
        const double zc = 0.25 * (lm.x[t[0]][2] + lm.x[t[1]][2] + lm.x[t[2]][2] + lm.x[t[3]][2]);
        s0[c] = -lm.initial.effective_stress(zc, m.biot)[ZZ] * 1e-6;
        if (m.law == fem::Law::Elastic) inv_c0[c] = 1e6 / m.hypo.cm(s0[c]);
        if (m.law == fem::Law::Hypoplastic) {
          hyp_of_cell[c] = static_cast<std::int32_t>(hyp_cells.size());
          hyp_cells.push_back(static_cast<std::int32_t>(c));
        }
      }
    });
    const std::size_t nh = hyp_cells.size();
    int mine = nh ? 1 : 0, any = 0;
    MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, lm.comm);
    has_hyp = any != 0;
    committed.resize(nh);
    committed_phase.assign(nh, fem::LoadingPhase::Virgin);
    committed_c.resize(nh);
    trial.resize(nh);
    trial_eps.resize(nh);
    guess.assign(nh, +1);
    last_ddp.assign(nh, -1);  // the geostatic state ends a virgin compression
    piece.assign(nh, 0);
    flips.assign(nh, 0);
    hold.assign(nh, fem::Hold::None);
    hold_dir.assign(nh, +1);
    assembled_Dt.resize(nh);
    assembled_phase.assign(nh, -1);
    pc_phase.assign(nh, -1);
    {
      long long mine_h = static_cast<long long>(nh);
      MPI_Allreduce(&mine_h, &n_hyp_global, 1, MPI_LONG_LONG, MPI_SUM, lm.comm);
    }
    for (std::size_t h = 0; h < nh; ++h) {
      const int c = hyp_cells[h];
      committed[h].hypo = fem::HypoState::virgin(s0[c]);
      committed_c[h] = lm.materials[lm.cell_material[c]].hypo.cm(s0[c]);
    }
    dp_cell.assign(lm.n_cells(), 0.0);
    fext.assign(3 * lm.n_owned, 0.0);
    fint.assign(3 * lm.n_owned, 0.0);
  }

  void setup_pattern() {
    const int n = lm.n_owned;
    std::vector<std::vector<std::int32_t>> cells_of(n);
    for (std::size_t c = 0; c < lm.n_cells(); ++c)
      for (auto v : lm.cells[c])
        if (v < n) cells_of[v].push_back(static_cast<std::int32_t>(c));
    node_ptr.assign(n + 1, 0);
    node_cols.clear();
    std::vector<std::int64_t> row;
    for (int a = 0; a < n; ++a) {
      row.clear();
      for (auto c : cells_of[a])
        for (auto v : lm.cells[c]) row.push_back(lm.global[v]);
      std::sort(row.begin(), row.end());
      row.erase(std::unique(row.begin(), row.end()), row.end());
      node_cols.insert(node_cols.end(), row.begin(), row.end());
      node_ptr[a + 1] = static_cast<PetscInt>(node_cols.size());
    }
    rowptr.assign(3 * n + 1, 0);
    cols.resize(9 * node_cols.size());
    for (int a = 0; a < n; ++a) {
      const PetscInt nb = node_ptr[a], d = node_ptr[a + 1] - nb;
      for (int ci = 0; ci < 3; ++ci) {
        rowptr[3 * a + ci] = 9 * nb + ci * 3 * d;
        for (PetscInt k = 0; k < d; ++k)
          for (int e = 0; e < 3; ++e) cols[9 * nb + ci * 3 * d + 3 * k + e] = static_cast<PetscInt>(3 * node_cols[nb + k] + e);
      }
    }
    rowptr[3 * n] = static_cast<PetscInt>(cols.size());
  }

  void setup_vectors() {
    std::vector<PetscInt> ghosts;
    for (int k = lm.n_owned; k < lm.n_local(); ++k) ghosts.push_back(static_cast<PetscInt>(lm.global[k]));
    UGS_PETSC(VecCreateGhostBlock(lm.comm, 3, 3 * lm.n_owned, 3 * lm.n_global_nodes, static_cast<PetscInt>(ghosts.size()),
                                  ghosts.data(), &u));
    UGS_PETSC(VecDuplicate(u, &u_save));
    UGS_PETSC(VecDuplicate(u, &u_step));
    UGS_PETSC(VecDuplicate(u, &aw));
    UGS_PETSC(VecDuplicate(u, &r));
    UGS_PETSC(VecDuplicate(u, &du));
    // Prescribed boundary values (zero unless a test sets them) on owned and ghost entries.
    Vec ul;
    PetscScalar* a = nullptr;
    UGS_PETSC(VecGhostGetLocalForm(u, &ul));
    UGS_PETSC(VecGetArray(ul, &a));
    for (int k = 0; k < lm.n_local(); ++k)
      for (int c = 0; c < 3; ++c) a[3 * k + c] = ((lm.fixed[k] >> c) & 1) ? lm.prescribed[k][c] : 0.0;
    UGS_PETSC(VecRestoreArray(ul, &a));
    UGS_PETSC(VecGhostRestoreLocalForm(u, &ul));
  }

  // PETSc options that ugs-solve sets unless the user gave them (after "--").
  static void set_default_options(std::initializer_list<std::pair<const char*, const char*>> defaults) {
    for (const auto& [k, v] : defaults) {
      PetscBool has = PETSC_FALSE;
      UGS_PETSC(PetscOptionsHasName(nullptr, nullptr, k, &has));
      if (!has) UGS_PETSC(PetscOptionsSetValue(nullptr, k, v));
    }
  }

  // CG for the SPD operator; right-preconditioned GMRES for the consistent hypo-plastic tangent
  // (both stop on the true residual, so the Newton forcing terms mean the same thing).
  void set_krylov() {
    if (has_hyp) {
      UGS_PETSC(KSPSetType(ksp, KSPGMRES));
      UGS_PETSC(KSPGMRESSetRestart(ksp, 100));
      UGS_PETSC(KSPGMRESSetOrthogonalization(ksp, KSPGMRESModifiedGramSchmidtOrthogonalization));
      UGS_PETSC(KSPSetPCSide(ksp, PC_RIGHT));
    } else {
      UGS_PETSC(KSPSetType(ksp, KSPCG));
    }
    UGS_PETSC(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED));
  }

  void setup_ksp() {
    UGS_PETSC(KSPCreate(lm.comm, &ksp));
    PC pc;
    UGS_PETSC(KSPGetPC(ksp, &pc));
    switch (opt.linear) {
      case LinearSolver::CgGamg:
        set_krylov();
        UGS_PETSC(PCSetType(pc, PCGAMG));
        UGS_PETSC(PCGAMGSetReuseInterpolation(pc, PETSC_TRUE));
        // Smoothed aggregation with the rigid-body near-null space (set on the matrix); CG
        // eigenvalue estimates for the Chebyshev smoothers when the operator is SPD.
        set_default_options({{"-mg_levels_esteig_ksp_type", has_hyp ? "gmres" : "cg"}});
        break;
      case LinearSolver::CgHypre: {
        set_krylov();
        UGS_PETSC(PCSetType(pc, PCHYPRE));
        UGS_PETSC(PCHYPRESetType(pc, "boomeramg"));
        // BoomerAMG for 3D elasticity on layered meshes (docs/mechanics.md, measured on the
        // thesis-like box): nodal coarsening of the 3 x 3 blocks, HMIS with extended+i
        // interpolation capped at 4 entries, aggressive coarsening on the first level. (Vector
        // interpolation with the rigid-body modes tripled the operator complexity there.)
        set_default_options({{"-pc_hypre_boomeramg_nodal_coarsen", "6"},
                             {"-pc_hypre_boomeramg_coarsen_type", "HMIS"},
                             {"-pc_hypre_boomeramg_interp_type", "ext+i"},
                             {"-pc_hypre_boomeramg_P_max", "4"},
                             {"-pc_hypre_boomeramg_agg_nl", "1"},
                             {"-pc_hypre_boomeramg_strong_threshold", "0.5"},
                             // One forward Gauss-Seidel sweep down, one backward up: the cycle stays
                             // symmetric (CG) at half the smoothing work of symmetric sweeps both ways.
                             {"-pc_hypre_boomeramg_relax_type_down", "SOR/Jacobi"},
                             {"-pc_hypre_boomeramg_relax_type_up", "backward-SOR/Jacobi"}});
        break;
      }
      case LinearSolver::Mumps:
        set_krylov();
        UGS_PETSC(PCSetType(pc, has_hyp ? PCLU : PCCHOLESKY));
        UGS_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
        break;
      case LinearSolver::Cholmod:
        if (lm.size > 1) throw InputError("--solver", "cholmod runs on one process; use mumps under mpirun");
        set_krylov();
        UGS_PETSC(PCSetType(pc, PCCHOLESKY));
        UGS_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERCHOLMOD));
        break;
    }
    UGS_PETSC(KSPSetTolerances(ksp, 1e-9, 1e-300, PETSC_DEFAULT, 5000));
    UGS_PETSC(KSPSetFromOptions(ksp));
  }

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

  double start_sigma(int h) const {
    // Magnitude of the effective vertical stress at the start of the step [MPa].
    return s0[hyp_cells[h]] - committed[h].dsig[ZZ] * 1e-6;
  }

  void external_force(const std::vector<double>& dp) {
    std::fill(fext.begin(), fext.end(), 0.0);
    for (std::size_t c = 0; c < lm.n_cells(); ++c) {
      const double dpe = lm.materials[lm.cell_material[c]].biot * dp[c];
      if (dpe == 0) continue;
      const double w = std::abs(geo[c].volume) * dpe;
      double fe[12];
      for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) fe[3 * i + k] = w * geo[c].grad[i][k];
      add_owned(fext, static_cast<int>(c), fe);
    }
  }

  // r = f_ext - f_int(u) (zero on prescribed dofs); evaluates the hypo-plastic trial states.
  double residual() {
    PetscLogEventBegin(events().residual, 0, 0, 0, 0);
    UGS_PETSC(VecGhostUpdateBegin(u, INSERT_VALUES, SCATTER_FORWARD));
    UGS_PETSC(VecGhostUpdateEnd(u, INSERT_VALUES, SCATTER_FORWARD));
    Vec ul;
    const PetscScalar* ua = nullptr;
    UGS_PETSC(VecGhostGetLocalForm(u, &ul));
    UGS_PETSC(VecGetArrayRead(ul, &ua));
    std::fill(fint.begin(), fint.end(), 0.0);
    bool sat = false;
    for (std::size_t ci = 0; ci < lm.n_cells(); ++ci) {
      const int c = static_cast<int>(ci);
      double ue[12];
      gather_element(ua, c, ue);
      const Vec6 eps = fem::tet4_strain(geo[c], ue);
      Vec6 ds;
      const int h = hyp_of_cell[c];
      if (h < 0) {
        ds = elastic_stress(c, eps);
      } else {
        trial[h] = fem::hypo_update(lm.materials[lm.cell_material[c]], committed[h], start_sigma(h), eps,
                                    hold[h] == fem::Hold::None ? guess[h] : hold_dir[h], hold[h],
                                    fem::TangentForm::Consistent);
        trial_eps[h] = eps;
        ds = trial[h].dsig;
        sat = sat || trial[h].saturated;
      }
      double fe[12] = {};
      fem::tet4_add_internal_force(geo[c], ds, fe);
      add_owned(fint, c, fe);
    }
    saturated = sat;
    UGS_PETSC(VecRestoreArrayRead(ul, &ua));
    UGS_PETSC(VecGhostRestoreLocalForm(u, &ul));
    PetscScalar* ra = nullptr;
    UGS_PETSC(VecGetArray(r, &ra));
    for (int a = 0; a < lm.n_owned; ++a)
      for (int k = 0; k < 3; ++k) ra[3 * a + k] = owned_dof_fixed(a, k) ? 0.0 : fext[3 * a + k] - fint[3 * a + k];
    UGS_PETSC(VecRestoreArray(r, &ra));
    const double extra = coupling ? coupling->residual(u, r) : 0.0;
    PetscReal norm = 0;
    UGS_PETSC(VecNorm(r, NORM_2, &norm));
    PetscLogEventEnd(events().residual, 0, 0, 0, 0);
    return coupling ? std::sqrt(norm * norm + extra) : norm;
  }

  // ---- assembly -------------------------------------------------------------------------------
  void scatter(std::vector<double>& v, int c, const std::array<double, 144>& Ke, bool diag_too) {
    const auto& t = lm.cells[c];
    for (int i = 0; i < 4; ++i) {
      const int a = t[i];
      if (a >= lm.n_owned) continue;
      const PetscInt nb = node_ptr[a], d = node_ptr[a + 1] - nb;
      const std::int64_t* row = node_cols.data() + nb;
      for (int j = 0; j < 4; ++j) {
        const int b = t[j];
        const PetscInt k = static_cast<PetscInt>(std::lower_bound(row, row + d, lm.global[b]) - row);
        for (int ci = 0; ci < 3; ++ci) {
          if (diag_too && i == j) diag_scale[3 * a + ci] += Ke[(3 * i + ci) * 12 + 3 * j + ci];
          if ((lm.fixed[a] >> ci) & 1) continue;
          double* dst = v.data() + 9 * nb + ci * 3 * d + 3 * k;
          for (int e = 0; e < 3; ++e)
            if (!((lm.fixed[b] >> e) & 1)) dst[e] += Ke[(3 * i + ci) * 12 + 3 * j + e];
        }
      }
    }
  }

  void set_constrained_diagonal(std::vector<double>& v) const {
    for (int a = 0; a < lm.n_owned; ++a) {
      if (!lm.fixed[a]) continue;
      const PetscInt nb = node_ptr[a], d = node_ptr[a + 1] - nb;
      const std::int64_t* row = node_cols.data() + nb;
      const PetscInt k = static_cast<PetscInt>(std::lower_bound(row, row + d, lm.global[a]) - row);
      for (int ci = 0; ci < 3; ++ci)
        if ((lm.fixed[a] >> ci) & 1) {
          const double s = diag_scale[3 * a + ci];
          v[9 * nb + ci * 3 * d + 3 * k + ci] = s > 0 ? s : 1.0;
        }
    }
  }

  // Builds (or refreshes) the tangent matrix from the current trial states.
  void assemble() {
    bool changed = !mat_created;
    if (!have_lin) {
      vals_lin.assign(cols.size(), 0.0);
      diag_scale.assign(3 * lm.n_owned, 0.0);
      for (std::size_t ci = 0; ci < lm.n_cells(); ++ci) {
        const int c = static_cast<int>(ci);
        if (hyp_of_cell[c] >= 0) {
          scatter_dummy_diag(c);
          continue;
        }
        scatter(vals_lin, c, fem::tet4_stiffness(geo[c], elastic_D(c)), true);
      }
      have_lin = true;
    }
    // Only the elements whose tangent changed materially are updated (their stiffness difference
    // is added): the matrix is a quasi-Newton tangent anyway, and most elements change by little
    // between iterations. A full assembly every kFullAssemblyEvery updates keeps the sums fresh.
    const bool full = changed || updates_since_full >= kFullAssemblyEvery;
    std::vector<std::int32_t> stale;
    for (std::size_t h = 0; h < hyp_cells.size(); ++h) {
      if (std::memcmp(tangent(h).data(), assembled_Dt[h].data(), sizeof(fem::Mat6)) == 0) continue;
      if (full) {
        changed = true;
        break;
      }
      if (relative_change(tangent(h), assembled_Dt[h]) > kTangentChange) stale.push_back(static_cast<std::int32_t>(h));
    }
    int mine = changed || !stale.empty() ? 1 : 0, any = 0;
    MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, lm.comm);
    if (!any) return;
    PetscLogEventBegin(events().assembly, 0, 0, 0, 0);
    if (full) {
      vals = vals_lin;
      for (std::size_t h = 0; h < hyp_cells.size(); ++h) {
        scatter(vals, hyp_cells[h], fem::tet4_stiffness(geo[hyp_cells[h]], tangent(h)), false);
        assembled_Dt[h] = tangent(h);
        assembled_phase[h] = static_cast<std::int8_t>(trial[h].phase);
      }
      set_constrained_diagonal(vals);  // (scatter never touches prescribed rows or columns)
      updates_since_full = 0;
    } else {
      for (const auto h : stale) {
        fem::Mat6 dD;
        for (int i = 0; i < 36; ++i) dD[i] = tangent(h)[i] - assembled_Dt[h][i];
        scatter(vals, hyp_cells[h], fem::tet4_stiffness(geo[hyp_cells[h]], dD), false);
        assembled_Dt[h] = tangent(h);
        assembled_phase[h] = static_cast<std::int8_t>(trial[h].phase);
      }
      ++updates_since_full;
    }
    upload();
    if (!has_hyp) {
      // The matrix can never change: the assembly arrays are not needed again.
      std::vector<double>().swap(vals);
      std::vector<double>().swap(vals_lin);
      std::vector<PetscInt>().swap(cols);
    }
    PetscLogEventEnd(events().assembly, 0, 0, 0, 0);
  }

  const fem::Mat6& tangent(std::size_t h) const { return trial[h].Dt; }

  static double relative_change(const fem::Mat6& a, const fem::Mat6& b) {
    double d = 0, n = 0;
    for (int i = 0; i < 36; ++i) d = std::max(d, std::abs(a[i] - b[i])), n = std::max(n, std::abs(b[i]));
    return n > 0 ? d / n : (d > 0 ? 1.0 : 0.0);
  }

  // Hypo-plastic elements contribute to the scale of prescribed rows with their initial tangent.
  void scatter_dummy_diag(int c) {
    const fem::Material& m = lm.materials[lm.cell_material[c]];
    fem::Mat6 D;
    const double ic = 1e6 / m.hypo.cm(s0[c]);
    for (int i = 0; i < 36; ++i) D[i] = m.Dhat[i] * ic;
    const auto Ke = fem::tet4_stiffness(geo[c], D);
    const auto& t = lm.cells[c];
    for (int i = 0; i < 4; ++i)
      if (t[i] < lm.n_owned)
        for (int ci = 0; ci < 3; ++ci) diag_scale[3 * t[i] + ci] += Ke[(3 * i + ci) * 12 + 3 * i + ci];
  }

  void upload() {
    const PetscInt m = 3 * lm.n_owned;
    if (!mat_created) {
      UGS_PETSC(MatCreate(lm.comm, &A));
      UGS_PETSC(MatSetSizes(A, m, m, PETSC_DETERMINE, PETSC_DETERMINE));
      UGS_PETSC(MatSetBlockSize(A, 3));
      UGS_PETSC(MatSetType(A, MATAIJ));
      if (lm.size == 1) {
        UGS_PETSC(MatSeqAIJSetPreallocationCSR(A, rowptr.data(), cols.data(), vals.data()));
      } else {
        UGS_PETSC(MatMPIAIJSetPreallocationCSR(A, rowptr.data(), cols.data(), vals.data()));
      }
      UGS_PETSC(MatSetOption(A, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
      UGS_PETSC(MatSetOption(A, MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE));
      if (!has_hyp) {
        UGS_PETSC(MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE));
        UGS_PETSC(MatSetOption(A, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
        UGS_PETSC(MatSetOption(A, MAT_SPD, PETSC_TRUE));
      }
      // Rigid-body modes from the owned node coordinates: the near-null space of elasticity.
      Vec xyz;
      UGS_PETSC(VecCreateMPI(lm.comm, m, PETSC_DETERMINE, &xyz));
      UGS_PETSC(VecSetBlockSize(xyz, 3));
      PetscScalar* a = nullptr;
      UGS_PETSC(VecGetArray(xyz, &a));
      for (int k = 0; k < lm.n_owned; ++k)
        for (int c = 0; c < 3; ++c) a[3 * k + c] = lm.x[k][c];
      UGS_PETSC(VecRestoreArray(xyz, &a));
      MatNullSpace nsp;
      UGS_PETSC(MatNullSpaceCreateRigidBody(xyz, &nsp));
      UGS_PETSC(MatSetNearNullSpace(A, nsp));
      UGS_PETSC(MatNullSpaceDestroy(&nsp));
      UGS_PETSC(VecDestroy(&xyz));
      UGS_PETSC(KSPSetOperators(ksp, A, A));
      mat_created = true;
    } else {
      for (PetscInt i = 0; i < m; ++i) {
        const PetscInt row = static_cast<PetscInt>(3 * lm.node_begin) + i;
        UGS_PETSC(MatSetValues(A, 1, &row, rowptr[i + 1] - rowptr[i], cols.data() + rowptr[i], vals.data() + rowptr[i],
                               INSERT_VALUES));
      }
      UGS_PETSC(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
      UGS_PETSC(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
    }
    mat_changed = true;
  }

  // ---- linear solve ---------------------------------------------------------------------------
  struct SolveResult {
    int iterations = 0;
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    double reduction = 0;
  };

  // GAMG's fine-level smoother runs on the preconditioning matrix: when A changes (hypo-plastic
  // branches) and the hierarchy is reused, it must see the matrix the hierarchy was built from, or
  // its Chebyshev bounds no longer hold. So GAMG gets a frozen copy P; hypre copies A itself.
  bool separate_p() const {
    return (opt.linear == LinearSolver::CgGamg && has_hyp) || (opt.linear == LinearSolver::Cholmod && has_hyp);
  }

  // P from the symmetric form of every element's tangent (CHOLMOD's matrix).
  void assemble_symmetric_p() {
    std::vector<double> pv = vals_lin;
    for (std::size_t h = 0; h < hyp_cells.size(); ++h)
      scatter(pv, hyp_cells[h], fem::tet4_stiffness(geo[hyp_cells[h]], fem::symmetric_tangent(lm.materials[lm.cell_material[hyp_cells[h]]], trial[h])), false);
    set_constrained_diagonal(pv);
    if (!P) {
      UGS_PETSC(MatCreate(lm.comm, &P));
      const PetscInt m = 3 * lm.n_owned;
      UGS_PETSC(MatSetSizes(P, m, m, PETSC_DETERMINE, PETSC_DETERMINE));
      UGS_PETSC(MatSetType(P, MATSEQAIJ));
      UGS_PETSC(MatSeqAIJSetPreallocationCSR(P, rowptr.data(), cols.data(), pv.data()));
      UGS_PETSC(MatSetOption(P, MAT_SYMMETRIC, PETSC_TRUE));
      UGS_PETSC(MatSetOption(P, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
      UGS_PETSC(MatSetOption(P, MAT_SPD, PETSC_TRUE));
    } else {
      for (PetscInt i = 0; i < 3 * lm.n_owned; ++i)
        UGS_PETSC(MatSetValues(P, 1, &i, rowptr[i + 1] - rowptr[i], cols.data() + rowptr[i], pv.data() + rowptr[i],
                               INSERT_VALUES));
      UGS_PETSC(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
      UGS_PETSC(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
    }
  }

  void rebuild_pc() {
    if (pc_valid) refresh_basis();
    pc_phase = assembled_phase;
    if (separate_p()) {
      if (opt.linear == LinearSolver::Cholmod) assemble_symmetric_p();
      else if (!P) UGS_PETSC(MatDuplicate(A, MAT_COPY_VALUES, &P));
      else UGS_PETSC(MatCopy(A, P, SAME_NONZERO_PATTERN));
      UGS_PETSC(KSPSetOperators(ksp, A, P));
    }
    UGS_PETSC(KSPSetReusePreconditioner(ksp, PETSC_FALSE));
  }

  SolveResult solve_once(double rtol, bool guess, PetscInt maxit) {
    PetscReal old_rtol, abstol, dtol;
    PetscInt user_maxit;
    UGS_PETSC(KSPGetTolerances(ksp, &old_rtol, &abstol, &dtol, &user_maxit));
    UGS_PETSC(KSPSetTolerances(ksp, rtol, abstol, dtol, maxit > 0 ? std::min(maxit, user_maxit_) : user_maxit_));
    PetscReal bnorm = 0;
    UGS_PETSC(VecNorm(r, NORM_2, &bnorm));
    UGS_PETSC(KSPSetInitialGuessNonzero(ksp, guess ? PETSC_TRUE : PETSC_FALSE));
    UGS_PETSC(KSPSolve(ksp, r, du));
    SolveResult s;
    PetscInt its = 0;
    UGS_PETSC(KSPGetIterationNumber(ksp, &its));
    UGS_PETSC(KSPGetConvergedReason(ksp, &s.reason));
    s.iterations = static_cast<int>(its);
    PetscReal rnorm = 0;
    UGS_PETSC(KSPGetResidualNorm(ksp, &rnorm));
    s.reduction = bnorm > 0 ? rnorm / bnorm : 0;
    return s;
  }

  // solve_once, timing the preconditioner setup (when fresh) and the iterations apart.
  SolveResult timed_solve(double rtol, bool guess, PetscInt maxit, bool fresh) {
    using clock = std::chrono::steady_clock;
    auto t0 = clock::now();
    if (fresh) {
      UGS_PETSC(KSPSetUp(ksp));
      setup_seconds = std::chrono::duration<double>(clock::now() - t0).count();
      t0 = clock::now();
    }
    const SolveResult s = solve_once(rtol, guess, maxit);
    seconds_per_iteration = std::chrono::duration<double>(clock::now() - t0).count() / std::max(s.iterations, 1);
    // Every rank must take the same keep-or-refactor decision (the setup is collective): the
    // slowest rank's times decide.
    double t[2] = {setup_seconds, seconds_per_iteration}, tmax[2];
    MPI_Allreduce(t, tmax, 2, MPI_DOUBLE, MPI_MAX, lm.comm);
    setup_seconds = tmax[0];
    seconds_per_iteration = tmax[1];
    return s;
  }

  SolveResult solve(double rtol, bool guess) {
    if (user_maxit_ < 0) {
      PetscReal a, b, c;
      UGS_PETSC(KSPGetTolerances(ksp, &a, &b, &c, &user_maxit_));
    }
    bool fresh = !pc_valid;
    if (!pc_valid) rebuild_pc();
    if (mat_changed) {
      // A factorization is kept while the iterations it costs beyond a fresh one, over the next
      // kFactorHorizon solves, take less time than refactoring (both measured: a refactor costs
      // tens of solves); a multigrid hierarchy while it stays near its first rate and few
      // elements changed branch (a setup costs a few cycles).
      const double excess = (last_ipd - baseline_ipd) * last_decades * seconds_per_iteration * kFactorHorizon;
      const bool keep = factored() ? excess <= setup_seconds
                                   : last_ipd <= std::max(1.5 * baseline_ipd, baseline_ipd + 3.0) && !branches_moved();
      const bool reuse = pc_valid && opt.reuse_preconditioner && keep;
      if (reuse) UGS_PETSC(KSPSetReusePreconditioner(ksp, PETSC_TRUE));
      else rebuild_pc();
      fresh = !reuse;
      mat_changed = false;
    }
    // A reused preconditioner gets a budget; if it cannot make it, rebuild and solve again.
    const double decades = std::log10(1.0 / std::max(rtol, 1e-16));
    const PetscInt budget = fresh ? -1
                            : factored() ? static_cast<PetscInt>(std::ceil(2 * kFactorIpd * decades))
                                         : static_cast<PetscInt>(std::max(100.0, 4 * baseline_ipd * decades));
    SolveResult s = timed_solve(rtol, guess, budget, fresh);
    int its_total = s.iterations;
    if (!fresh && s.reason < 0) {
      rebuild_pc();
      fresh = true;
      s = timed_solve(rtol, false, -1, fresh);
      its_total += s.iterations;
    }
    last_decades = std::max(std::log10(1.0 / std::max(s.reduction, 1e-300)), 0.3);
    last_ipd = s.iterations / last_decades;
    if (fresh) baseline_ipd = last_ipd;
    s.iterations = its_total;
    if (fresh) ++pc_setups;
    pc_valid = true;
    // Prescribed components stay exactly at their values (an AMG correction may touch them).
    PetscScalar* d = nullptr;
    UGS_PETSC(VecGetArray(du, &d));
    for (int a = 0; a < lm.n_owned; ++a)
      for (int c = 0; c < 3; ++c)
        if ((lm.fixed[a] >> c) & 1) d[3 * a + c] = 0.0;
    UGS_PETSC(VecRestoreArray(du, &d));
    return s;
  }

  // True when many hypo-plastic elements changed branch since the preconditioner was built: their
  // stiffness jumped by c_R, and a new setup (a few V-cycles) costs less than the iterations a stale
  // hierarchy needs.
  bool branches_moved() const {
    long long mine = 0, all = 0;
    for (std::size_t h = 0; h < assembled_phase.size(); ++h) mine += assembled_phase[h] != pc_phase[h];
    MPI_Allreduce(&mine, &all, 1, MPI_LONG_LONG, MPI_SUM, lm.comm);
    return static_cast<double>(all) > 0.005 * static_cast<double>(n_hyp_global);
  }

  // ---- predictor ------------------------------------------------------------------------------
  // The increments of earlier steps span most of a new one (the seasonal cycles repeat and the
  // flow fields are smooth in time): the first Newton correction starts from the Galerkin
  // projection on them. The basis W is A-orthonormal (W^T A W = I) and A W is kept, so the
  // projection du0 = W (W^T r) costs dot products only. W is orthonormal for the matrix it was
  // built with; when the matrix changes it stays a good (no longer optimal) guess until the
  // preconditioner is rebuilt, when A W is recomputed and W re-orthonormalized.
  bool predict() {
    const int m = static_cast<int>(basis.size());
    if (m == 0) return false;
    std::vector<PetscScalar> c(m);
    UGS_PETSC(VecMDot(r, m, basis.data(), c.data()));
    UGS_PETSC(VecSet(du, 0.0));
    UGS_PETSC(VecMAXPY(du, m, c.data(), basis.data()));
    return true;
  }

  // Re-orthonormalizes the basis for the current matrix (after a preconditioner rebuild).
  void refresh_basis() {
    const int m = static_cast<int>(basis.size());
    if (m == 0) return;
    PetscLogEventBegin(events().predictor, 0, 0, 0, 0);
    for (int j = 0; j < m; ++j) UGS_PETSC(MatMult(A, basis[j], abasis[j]));
    Eigen::MatrixXd G(m, m);
    std::vector<PetscScalar> dots(m);
    for (int j = 0; j < m; ++j) {
      UGS_PETSC(VecMDot(abasis[j], m, basis.data(), dots.data()));
      for (int i = 0; i < m; ++i) G(i, j) = dots[i];
    }
    G = 0.5 * (G + G.transpose());
    // W <- W V diag(lambda)^-1/2 over the eigenpairs above a cutoff (drops dependent directions).
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(G);
    const Eigen::VectorXd lam = es.eigenvalues();
    std::vector<Vec> nb, nab;
    for (int k = m - 1; k >= 0; --k) {
      if (!(lam(k) > 1e-10 * lam(m - 1))) break;
      Vec w, aw_k;
      UGS_PETSC(VecDuplicate(u, &w));
      UGS_PETSC(VecDuplicate(u, &aw_k));
      std::vector<PetscScalar> coef(m);
      for (int i = 0; i < m; ++i) coef[i] = es.eigenvectors()(i, k) / std::sqrt(lam(k));
      UGS_PETSC(VecSet(w, 0.0));
      UGS_PETSC(VecSet(aw_k, 0.0));
      UGS_PETSC(VecMAXPY(w, m, coef.data(), basis.data()));
      UGS_PETSC(VecMAXPY(aw_k, m, coef.data(), abasis.data()));
      nb.push_back(w);
      nab.push_back(aw_k);
    }
    for (Vec& v : basis) UGS_PETSC(VecDestroy(&v));
    for (Vec& v : abasis) UGS_PETSC(VecDestroy(&v));
    basis = std::move(nb);
    abasis = std::move(nab);
    PetscLogEventEnd(events().predictor, 0, 0, 0, 0);
  }

  // Adds the increment u - base of a converged (sub-)step to the basis, A-orthogonalized against it
  // (the oldest direction is dropped when full).
  void remember_increment_from(Vec base) {
    if (!mat_created) return;  // (no matrix yet: the step had no load)
    Vec v, av;
    UGS_PETSC(VecDuplicate(u, &v));
    UGS_PETSC(VecDuplicate(u, &av));
    UGS_PETSC(VecWAXPY(v, -1.0, base, u));
    // Prescribed components do not move: keep the basis in the free space.
    PetscScalar* a = nullptr;
    UGS_PETSC(VecGetArray(v, &a));
    for (int i = 0; i < lm.n_owned; ++i)
      for (int c = 0; c < 3; ++c)
        if ((lm.fixed[i] >> c) & 1) a[3 * i + c] = 0.0;
    UGS_PETSC(VecRestoreArray(v, &a));
    UGS_PETSC(MatMult(A, v, av));
    PetscScalar n0 = 0;
    UGS_PETSC(VecDot(v, av, &n0));
    if (!(n0 > 0)) {
      UGS_PETSC(VecDestroy(&v));
      UGS_PETSC(VecDestroy(&av));
      return;
    }
    const int m = static_cast<int>(basis.size());
    for (int pass = 0; pass < 2 && m > 0; ++pass) {
      std::vector<PetscScalar> c(m);
      UGS_PETSC(VecMDot(av, m, basis.data(), c.data()));  // W^T A v
      for (auto& x : c) x = -x;
      UGS_PETSC(VecMAXPY(v, m, c.data(), basis.data()));
      UGS_PETSC(VecMAXPY(av, m, c.data(), abasis.data()));
    }
    PetscScalar n1 = 0;
    UGS_PETSC(VecDot(v, av, &n1));
    if (!(n1 > 1e-14 * n0)) {
      UGS_PETSC(VecDestroy(&v));
      UGS_PETSC(VecDestroy(&av));
      return;
    }
    UGS_PETSC(VecScale(v, 1.0 / std::sqrt(n1)));
    UGS_PETSC(VecScale(av, 1.0 / std::sqrt(n1)));
    if (static_cast<int>(basis.size()) == kRecycle) {
      UGS_PETSC(VecDestroy(&basis.front()));
      UGS_PETSC(VecDestroy(&abasis.front()));
      basis.erase(basis.begin());
      abasis.erase(abasis.begin());
    }
    basis.push_back(v);
    abasis.push_back(av);
  }

  // ---- one (sub-)step -------------------------------------------------------------------------
  bool newton(const std::vector<double>& dp_target, StepReport& rep, std::string& why) {
    external_force(dp_target);
    for (std::size_t h = 0; h < hyp_cells.size(); ++h) {
      // First tangent: the element keeps its direction unless its pressure change reverses.
      const double d = dp_target[hyp_cells[h]] - dp_cell[hyp_cells[h]];
      const int sd = d < 0 ? -1 : d > 0 ? +1 : 0, dir = committed[h].hypo.direction;
      guess[h] = static_cast<std::int8_t>(sd != 0 && sd != last_ddp[h] ? -dir : dir);
      piece[h] = 0;
      flips[h] = 0;
      hold[h] = fem::Hold::None;
    }
    UGS_PETSC(VecCopy(u, u_save));
    rep.residuals.clear();
    const double r0 = residual();
    rep.residuals.push_back(1.0);
    if (r0 == 0) return true;
    double rk = r0, rprev = r0;
    // A step is nonlinear if an element is on the virgin branch or is expected to change direction.
    int nonlinear = 0;
    for (std::size_t h = 0; h < hyp_cells.size() && !nonlinear; ++h)
      nonlinear = guess[h] != committed[h].hypo.direction ||
                  (guess[h] > 0 && start_sigma(static_cast<int>(h)) >= committed[h].hypo.sigma_max * (1 - 1e-9)) ||
                  lm.materials[lm.cell_material[hyp_cells[h]]].hypo.rule == fem::InversionRule::StressDependent;
    int any_nonlinear = 0;
    MPI_Allreduce(&nonlinear, &any_nonlinear, 1, MPI_INT, MPI_MAX, lm.comm);
    double eta = any_nonlinear || coupling ? 1e-4 : 0.0;
    for (int k = 1; k <= opt.max_newton; ++k) {
      assemble();
      // Inexact Newton (Eisenstat-Walker): no sharper than the nonlinearity warrants, but never
      // looser than what reaches the target in one more iteration of a linear problem.
      const double floor_rtol = 0.5 * opt.tolerance * r0 / rk;
      const double rtol = std::min(0.5, std::max(floor_rtol, eta));
      const int setups_before = pc_setups;
      const bool guess = !coupling && k == 1 && predict();
      SolveResult s;
      if (coupling) {
        const CouplingSolve cs = coupling->solve(A, r, du, rtol);
        s.iterations = cs.iterations;
        if (!cs.ok) {
          why = cs.failure;
          return false;
        }
      } else {
        s = solve(rtol, guess);
      }
      rep.linear_iterations += s.iterations;
      rep.preconditioner_setups += pc_setups - setups_before;
      ++rep.newton_iterations;
      if (s.reason < 0 && !(s.reason == KSP_DIVERGED_ITS && s.reduction < 0.5)) {
        why = fmt::format("linear solver failed ({}) after {} iterations", KSPConvergedReasons[s.reason], s.iterations);
        return false;
      }
      UGS_PETSC(VecAXPY(u, 1.0, du));
      rprev = rk;
      std::vector<int> before(hyp_cells.size());
      for (std::size_t h = 0; h < hyp_cells.size(); ++h) before[h] = static_cast<int>(trial[h].phase);
      rk = residual();
      track_branches();
      long long moved = 0, moved_all = 0;
      for (std::size_t h = 0; h < hyp_cells.size(); ++h) moved += before[h] != static_cast<int>(trial[h].phase);
      MPI_Allreduce(&moved, &moved_all, 1, MPI_LONG_LONG, MPI_SUM, lm.comm);
      if (std::getenv("UGS_DEBUG")) {
        int nflip = 0, virgin = 0, unl = 0, rel = 0;
        for (std::size_t h = 0; h < hyp_cells.size(); ++h) {
          nflip += before[h] != static_cast<int>(trial[h].phase);
          virgin += trial[h].phase == fem::LoadingPhase::Virgin;
          unl += trial[h].phase == fem::LoadingPhase::Unloading;
          rel += trial[h].phase == fem::LoadingPhase::Reloading;
        }
        int nlock = 0;
        for (auto l : hold) nlock += l != fem::Hold::None;
        std::fprintf(stderr, "  it %d rtol %.1e its %d r %.3e flips %d (virgin %d unloading %d reloading %d) held %d\n", k,
                     rtol, s.iterations, rk / r0, nflip, virgin, unl, rel, nlock);
      }
      rep.residuals.push_back(rk / r0);
      if (!std::isfinite(rk)) {
        why = "the residual is not finite";
        return false;
      }
      if (rk <= opt.tolerance * r0 && (!coupling || coupling->settled())) {
        rep.off_branch = std::max(rep.off_branch, held_off_branch() / r0);
        return true;
      }
      if (rk > 1e4 * r0) {
        why = "Newton diverged";
        return false;
      }
      if (coupling) {
        why = coupling->stalled();
        if (!why.empty()) return false;
      }
      if (has_hyp || coupling) eta = std::min(0.1, 0.9 * (rk / rprev) * (rk / rprev));
      // While elements still change branch the next residual is set by them, not by the accuracy
      // of the linear solve: a sharper solve would be wasted.
      if (moved_all > 0) eta = std::max(eta, 1e-2);
    }
    int sat = saturated ? 1 : 0, any_sat = 0;
    MPI_Allreduce(&sat, &any_sat, 1, MPI_INT, MPI_MAX, lm.comm);
    why = fmt::format("Newton did not converge in {} iterations{}", opt.max_newton,
                      any_sat ? " (the virgin compressibility law cannot absorb the strain of some elements)" : "");
    if (coupling) why += coupling->diagnosis();
    return false;
  }

  // An element that changes branch twice within a (sub-)step sits at the knee, where its stiffness
  // jumps by c_R (at J = 0 on the virgin curve even its lateral stress jumps): Newton would cycle.
  // It is held on the unloading/reloading branch (the stiffer one: Newton with the softer tangent
  // overshoots); the residual is then smooth (hypoplastic.hpp).
  void track_branches() {
    for (std::size_t h = 0; h < hyp_cells.size(); ++h) {
      const auto p = static_cast<std::int8_t>(trial[h].phase);
      if (piece[h] != 0 && p != piece[h] && ++flips[h] >= 2 && hold[h] == fem::Hold::None) {
        hold[h] = fem::Hold::UnloadReload;
        hold_dir[h] = static_cast<std::int8_t>(trial[h].J > 0 ? +1 : trial[h].J < 0 ? -1 : guess[h]);
      }
      piece[h] = p;
    }
  }

  // The consistency of the held branches at a converged iterate. A held element whose J ended on
  // the other side of its knee, at distance delta = J - J_knee, is a point of the law's graph
  // after a vertical strain change of delta (the stress moves by delta Dhat e_z / c_t): its
  // residual is within ||V B^T delta Dhat e_z / c_t|| of the residual of a state that obeys the
  // law everywhere (at the knee the response is set-valued: either branch's stiffness is
  // admissible). Returns the sum of these bounds over the inconsistent elements (all ranks).
  double held_off_branch() {
    double mine = 0;
    for (std::size_t h = 0; h < hyp_cells.size(); ++h) {
      if (hold[h] == fem::Hold::None) continue;
      const double delta = trial[h].J - trial[h].J_knee;
      const bool wrong = hold[h] == fem::Hold::Virgin ? delta < 0 : delta > 0;
      if (!wrong) continue;
      const int c = hyp_cells[h];
      if (lm.cell_owned[c]) {
        const fem::Material& m = lm.materials[lm.cell_material[c]];
        Vec6 ds;
        for (int i = 0; i < 6; ++i) ds[i] = delta * m.Dhat[6 * i + ZZ] * 1e6 / trial[h].c_tangent;
        double fe[12] = {};
        fem::tet4_add_internal_force(geo[c], ds, fe);
        double n2 = 0;
        for (double f : fe) n2 += f * f;
        mine += std::sqrt(n2);
      }
    }
    double all = 0;
    MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_SUM, lm.comm);
    return all;
  }

  void commit(const std::vector<double>& dp_target) {
    for (std::size_t h = 0; h < hyp_cells.size(); ++h) {
      const double d = dp_target[hyp_cells[h]] - dp_cell[hyp_cells[h]];
      if (d != 0) last_ddp[h] = d < 0 ? -1 : +1;
      committed[h].eps = trial_eps[h];
      committed[h].dsig = trial[h].dsig;
      committed[h].hypo = trial[h].hypo;
      committed_phase[h] = trial[h].phase;
      committed_c[h] = trial[h].c_tangent;
    }
    dp_cell = dp_target;
  }

  void restore_u() {
    UGS_PETSC(VecCopy(u_save, u));
    UGS_PETSC(VecGhostUpdateBegin(u, INSERT_VALUES, SCATTER_FORWARD));
    UGS_PETSC(VecGhostUpdateEnd(u, INSERT_VALUES, SCATTER_FORWARD));
  }

  StepReport advance(const std::vector<double>& dp_rank0, const std::string& label) {
    const auto t0 = std::chrono::steady_clock::now();
    StepReport rep;
    rep.substeps = 0;
    // Every rank needs the pressure change of its elements.
    std::vector<double> dp_all;
    std::uint64_t n = lm.rank == 0 ? dp_rank0.size() : 0;
    MPI_Bcast(&n, 1, MPI_UINT64_T, 0, lm.comm);
    if (n != static_cast<std::uint64_t>(lm.n_global_cells))
      throw std::logic_error("MechanicsSolver::advance: pressure vector of wrong size");
    dp_all.resize(n);
    if (lm.rank == 0) std::copy(dp_rank0.begin(), dp_rank0.end(), dp_all.begin());
    MPI_Bcast(dp_all.data(), static_cast<int>(n), MPI_DOUBLE, 0, lm.comm);
    std::vector<double> target(lm.n_cells());
    for (std::size_t c = 0; c < lm.n_cells(); ++c) target[c] = dp_all[lm.cell_index[c]];
    dp_all = {};

    // A failed step leaves the state of the previous one (committed sub-steps are undone).
    const std::vector<double> start = dp_cell;
    const auto committed_start = committed;
    const auto phase_start = committed_phase;
    const auto c_start = committed_c;
    UGS_PETSC(VecCopy(u, u_step));
    if (coupling) coupling->begin_step();
    double done = 0, h = 1;
    const double h_min = 1.0 / opt.max_substeps;
    std::vector<double> dp_b(lm.n_cells());
    while (done < 1) {
      const double b = std::min(1.0, done + h);
      for (std::size_t k = 0; k < dp_b.size(); ++k) dp_b[k] = b == 1.0 ? target[k] : start[k] + b * (target[k] - start[k]);
      std::string why;
      if (coupling) coupling->begin_substep(b);
      if (newton(dp_b, rep, why)) {
        if (coupling) coupling->commit();
        commit(dp_b);
        remember_increment_from(u_save);
        done = b;
        ++rep.substeps;
        continue;
      }
      restore_u();
      if (coupling) coupling->revert_substep();
      if (h / 2 < h_min * (1 - 1e-12) || (!has_hyp && !coupling)) {
        if (coupling) coupling->revert_step();
        committed = committed_start;
        committed_phase = phase_start;
        committed_c = c_start;
        dp_cell = start;
        UGS_PETSC(VecCopy(u_step, u));
        UGS_PETSC(VecGhostUpdateBegin(u, INSERT_VALUES, SCATTER_FORWARD));
        UGS_PETSC(VecGhostUpdateEnd(u, INSERT_VALUES, SCATTER_FORWARD));
        rep.converged = false;
        rep.failure = fmt::format("{}: {} (relative residuals {}){}", label, why, history_text(rep.residuals),
                                  h < 1 ? fmt::format("; sub-step of 1/{:.0f} of the step", 1 / h) : "");
        rep.seconds = seconds_since(t0);
        return rep;
      }
      h /= 2;
    }
    rep.converged = true;
    rep.seconds = seconds_since(t0);
    return rep;
  }


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

  // Owned-cell values (k per cell) to output order on rank 0.
  std::vector<double> gather_cells_k(const std::vector<double>& owned, int k) const {
    const auto all = gatherv(owned);
    std::vector<double> out;
    if (lm.rank == 0) {
      out.resize(static_cast<std::size_t>(lm.n_global_cells) * k);
      std::size_t pos = 0;
      for (int p = 0; p < lm.size; ++p)
        for (auto e : lm.owned_cells_of_rank[p]) {
          for (int c = 0; c < k; ++c) out[static_cast<std::size_t>(e) * k + c] = all[pos + c];
          pos += k;
        }
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

MechanicsSolver::MechanicsSolver(MPI_Comm comm, const Model* model, const SolverOptions& options)
    : impl_(std::make_unique<Impl>()) {
  events();
  impl_->opt = options;
  impl_->lm = distribute(comm, model, options.partition);
  impl_->setup_elements();
  impl_->setup_pattern();
  collective(comm, [&] {
    impl_->setup_vectors();
    impl_->setup_ksp();
  });
}

MechanicsSolver::~MechanicsSolver() = default;

void MechanicsSolver::set_coupling(Coupling& coupling) {
  Impl& s = *impl_;
  CouplingContext ctx;
  ctx.comm = s.lm.comm;
  ctx.rank = s.lm.rank;
  ctx.size = s.lm.size;
  ctx.n_global_nodes = s.lm.n_global_nodes;
  ctx.node_begin = s.lm.node_begin;
  ctx.n_owned = s.lm.n_owned;
  ctx.node_begin_of_rank.resize(s.lm.size + 1, 0);
  {
    std::vector<std::int64_t> owned(s.lm.size);
    const std::int64_t mine = s.lm.n_owned;
    MPI_Allgather(&mine, 1, MPI_INT64_T, owned.data(), 1, MPI_INT64_T, s.lm.comm);
    for (int p = 0; p < s.lm.size; ++p) ctx.node_begin_of_rank[p + 1] = ctx.node_begin_of_rank[p] + owned[p];
  }
  ctx.owned_x = &s.lm.x;
  ctx.owned_fixed = &s.lm.fixed;
  if (s.lm.rank == 0) {
    ctx.global_of_mesh_node.assign(s.lm.orig_of_global.size(), -1);
    for (std::size_t g = 0; g < s.lm.orig_of_global.size(); ++g) ctx.global_of_mesh_node[s.lm.orig_of_global[g]] = static_cast<std::int64_t>(g);
  }
  ctx.u = s.u;
  coupling.setup(ctx);  // collective
  s.coupling = &coupling;
}

StepReport MechanicsSolver::advance(const std::vector<double>& dp, const std::string& label) {
  return impl_->advance(dp, label);
}

std::vector<double> MechanicsSolver::gather_displacement() {
  PetscLogEventBegin(events().gather, 0, 0, 0, 0);
  auto out = impl_->gather_nodes(impl_->owned_u(), 3);
  PetscLogEventEnd(events().gather, 0, 0, 0, 0);
  return out;
}

CellResults MechanicsSolver::gather_cells() {
  PetscLogEventBegin(events().gather, 0, 0, 0, 0);
  Impl& s = *impl_;
  const LocalMesh& lm = s.lm;
  UGS_PETSC(VecGhostUpdateBegin(s.u, INSERT_VALUES, SCATTER_FORWARD));
  UGS_PETSC(VecGhostUpdateEnd(s.u, INSERT_VALUES, SCATTER_FORWARD));
  Vec ul;
  const PetscScalar* ua = nullptr;
  UGS_PETSC(VecGhostGetLocalForm(s.u, &ul));
  UGS_PETSC(VecGetArrayRead(ul, &ua));
  std::vector<double> strain, stress, dstress, cm, state, smax;
  for (std::size_t ci = 0; ci < lm.n_cells(); ++ci) {
    if (!lm.cell_owned[ci]) continue;
    const int c = static_cast<int>(ci);
    const fem::Material& m = lm.materials[lm.cell_material[c]];
    double ue[12];
    s.gather_element(ua, c, ue);
    const Vec6 eps = fem::tet4_strain(s.geo[c], ue);
    const int h = s.hyp_of_cell[c];
    const Vec6 ds = h < 0 ? s.elastic_stress(c, eps) : s.committed[h].dsig;
    const auto& t = lm.cells[c];
    const double zc = 0.25 * (lm.x[t[0]][2] + lm.x[t[1]][2] + lm.x[t[2]][2] + lm.x[t[3]][2]);
    const Vec6 s0 = lm.initial.effective_stress(zc, m.biot);
    Vec6 tot;
    for (int k = 0; k < 6; ++k) tot[k] = s0[k] + ds[k];
    for (double v : fem::strain_to_output(eps)) strain.push_back(v);
    for (double v : fem::stress_to_output(tot)) stress.push_back(v);
    for (double v : fem::stress_to_output(ds)) dstress.push_back(v);
    if (h >= 0) {
      cm.push_back(s.committed_c[h] * 1e-6);
      state.push_back(static_cast<double>(static_cast<int>(s.committed_phase[h])));
      smax.push_back(s.committed[h].hypo.sigma_max * 1e6);
    } else {
      cm.push_back(m.law == fem::Law::Linear ? fem::cm_from_ez(m.E_z, m.ratios) : 1.0 / s.inv_c0[c]);
      state.push_back(0.0);
      smax.push_back(0.0);
    }
  }
  UGS_PETSC(VecRestoreArrayRead(ul, &ua));
  UGS_PETSC(VecGhostRestoreLocalForm(s.u, &ul));
  CellResults out;
  out.strain = s.gather_cells_k(strain, 6);
  out.stress = s.gather_cells_k(stress, 6);
  out.stress_change = s.gather_cells_k(dstress, 6);
  out.cm = s.gather_cells_k(cm, 1);
  out.state = s.gather_cells_k(state, 1);
  out.sigma_max = s.gather_cells_k(smax, 1);
  PetscLogEventEnd(events().gather, 0, 0, 0, 0);
  return out;
}

SavedState MechanicsSolver::gather_state() {
  Impl& s = *impl_;
  const LocalMesh& lm = s.lm;
  SavedState st;
  st.u = s.gather_nodes(s.owned_u(), 3);
  std::vector<double> eps, dsig, hypo, dp;
  for (std::size_t ci = 0; ci < lm.n_cells(); ++ci) {
    if (!lm.cell_owned[ci]) continue;
    dp.push_back(s.dp_cell[ci]);
    const int h = s.hyp_of_cell[ci];
    const fem::PointState ps = h >= 0 ? s.committed[h] : fem::PointState{};
    eps.insert(eps.end(), ps.eps.begin(), ps.eps.end());
    dsig.insert(dsig.end(), ps.dsig.begin(), ps.dsig.end());
    hypo.push_back(ps.hypo.sigma_max);
    hypo.push_back(ps.hypo.sigma_inv);
    hypo.push_back(ps.hypo.direction);
    hypo.push_back(h >= 0 ? s.last_ddp[h] : 0);
  }
  st.eps = s.gather_cells_k(eps, 6);
  st.dsig = s.gather_cells_k(dsig, 6);
  st.hypo = s.gather_cells_k(hypo, 4);
  st.dp = s.gather_cells_k(dp, 1);
  return st;
}

void MechanicsSolver::restore_state(const SavedState& st) {
  Impl& s = *impl_;
  const LocalMesh& lm = s.lm;
  // Sizes checked on rank 0, agreed by all.
  collective(lm.comm, [&] {
    if (lm.rank != 0) return;
    const std::size_t nn = lm.n_global_nodes, nc = lm.n_global_cells;
    if (st.u.size() != 3 * nn || st.dp.size() != nc || st.eps.size() != 6 * nc || st.dsig.size() != 6 * nc ||
        st.hypo.size() != 4 * nc)
      throw InputError("--restart", fmt::format("the restart state does not match the mesh ({} nodes, {} cells)", nn, nc));
  });
  auto bcast = [&](const std::vector<double>& src, std::size_t n) {
    std::vector<double> v(n);
    if (lm.rank == 0) std::copy(src.begin(), src.end(), v.begin());
    MPI_Bcast(v.data(), static_cast<int>(n), MPI_DOUBLE, 0, lm.comm);
    return v;
  };
  const std::size_t nn = lm.n_global_nodes, nc = lm.n_global_cells;
  {
    const auto u = bcast(st.u, 3 * nn);
    Vec ul;
    PetscScalar* a = nullptr;
    UGS_PETSC(VecGhostGetLocalForm(s.u, &ul));
    UGS_PETSC(VecGetArray(ul, &a));
    for (int k = 0; k < lm.n_local(); ++k) {
      for (int c = 0; c < 3; ++c) a[3 * k + c] = u[3 * lm.orig[k] + c];
    }
    UGS_PETSC(VecRestoreArray(ul, &a));
    UGS_PETSC(VecGhostRestoreLocalForm(s.u, &ul));
  }
  const auto eps = bcast(st.eps, 6 * nc), dsig = bcast(st.dsig, 6 * nc), hypo = bcast(st.hypo, 4 * nc);
  {
    const auto dp = bcast(st.dp, nc);
    for (std::size_t c = 0; c < lm.n_cells(); ++c) s.dp_cell[c] = dp[lm.cell_index[c]];
  }
  for (std::size_t h = 0; h < s.hyp_cells.size(); ++h) {
    const int c = s.hyp_cells[h];
    const std::size_t e = lm.cell_index[c];
    fem::PointState& ps = s.committed[h];
    for (int k = 0; k < 6; ++k) ps.eps[k] = eps[6 * e + k], ps.dsig[k] = dsig[6 * e + k];
    ps.hypo.sigma_max = hypo[4 * e];
    ps.hypo.sigma_inv = hypo[4 * e + 1];
    ps.hypo.direction = hypo[4 * e + 2] < 0 ? -1 : +1;
    s.last_ddp[h] = hypo[4 * e + 3] > 0 ? +1 : -1;
    const fem::HypoResult r =
        fem::hypo_integrate(lm.materials[lm.cell_material[c]].hypo, ps.hypo, s.start_sigma(static_cast<int>(h)), 0.0,
                            ps.hypo.direction);
    s.committed_phase[h] = r.phase;
    s.committed_c[h] = r.c_tangent;
  }
}

std::size_t MechanicsSolver::global_nodes() const { return impl_->lm.n_global_nodes; }
std::size_t MechanicsSolver::global_cells() const { return impl_->lm.n_global_cells; }
std::size_t MechanicsSolver::local_nodes() const { return impl_->lm.n_owned; }
std::size_t MechanicsSolver::local_cells() const { return impl_->lm.n_cells(); }

std::string MechanicsSolver::solver_description() const {
  const Impl& s = *impl_;
  KSPType kt;
  PCType pt;
  PC pc;
  KSPGetType(s.ksp, &kt);
  KSPGetPC(s.ksp, &pc);
  PCGetType(pc, &pt);
  return fmt::format("KSP {} + PC {} ({}), {} process{}, {} partition", kt ? kt : "?", pt ? pt : "?",
                     linear_solver_name(s.opt.linear), s.lm.size, s.lm.size > 1 ? "es" : "",
                     s.opt.partition == PartitionMethod::PtScotch ? "PT-Scotch" : "RCB");
}

}  // namespace ugs::mech
