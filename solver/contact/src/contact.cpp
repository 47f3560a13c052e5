#include "ugs/contact/contact.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>

#include <fmt/format.h>
#include <petscksp.h>

#include "petsc_call.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/mechanics/petsc_session.hpp"

#define CHK UGS_CONTACT_PETSC

namespace ugs::contact {
namespace {

// -ugs_contact_monitor: every node pair that changes state (stick, slip, open) in an iteration.
bool contact_monitor() {
  static const bool on = mech::petsc_option_given("-ugs_contact_monitor");
  return on;
}

// What the owner of a pair needs to know about it (sent from rank 0 as bytes).
struct PairData {
  std::int64_t g1, g2;              // global nodes of side 1 and side 2
  std::uint64_t tag1, tag2;         // mesh node tags (messages)
  std::uint32_t model_index;
  std::int32_t fault;
  double area, k, cohesion, mu, p0;
  double R[9];
  double lam0[3];
  double x[3];
  std::uint8_t fixed1, fixed2, active, redundant;
};

std::string broadcast_string(MPI_Comm comm, std::string s) {
  unsigned long n = s.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG, 0, comm);
  s.resize(n);
  if (n) MPI_Bcast(s.data(), static_cast<int>(n), MPI_CHAR, 0, comm);
  return s;
}

bool has_option(const char* name) {
  PetscBool has = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, name, &has);
  return has == PETSC_TRUE;
}

void default_option(const char* name, const char* value) {
  if (!has_option(name)) CHK(PetscOptionsSetValue(nullptr, name, value));
}

}  // namespace

SaddleSolver parse_saddle_solver(const std::string& s) {
  if (s == "auto") return SaddleSolver::Auto;
  if (s == "mumps") return SaddleSolver::Mumps;
  if (s == "fieldsplit") return SaddleSolver::FieldSplit;
  throw InputError("--fault-solver", "'" + s + "' is not one of auto, mumps, fieldsplit");
}

struct FaultContact::Impl {
  MPI_Comm comm;
  int rank = 0, size = 1;
  const FaultModel* fm = nullptr;
  ContactOptions opt;
  SaddleSolver solver = SaddleSolver::Mumps;
  std::vector<std::string> fault_names;

  // ---- pairs of this rank ---------------------------------------------------------------------
  std::vector<PairData> P_;
  int m = 0;                                  // owned pairs
  PetscInt M = 0, lam_begin = 0;              // global pairs, first owned pair
  std::vector<int> pairs_of_rank;             // every rank
  std::vector<std::uint32_t> order;           // rank 0: global pair -> model pair
  std::vector<std::array<double, 3>> lam, lam_c, lam_step, g, gc, gc_step;
  std::vector<double> dp_now, dp_c, dp_start, dp_target;  // fluid pressure change [Pa]
  std::vector<PairState> st, st_prev, st_c, st_step;
  std::vector<int> flips;
  std::vector<std::uint8_t> changed_last;
  std::vector<PairEquations> eq;
  bool settled_flag = true;

  // ---- displacement layout --------------------------------------------------------------------
  mech::CouplingContext ctx;
  std::vector<std::uint8_t> owned_fixed;
  std::vector<Point3> owned_x;

  // ---- PETSc ----------------------------------------------------------------------------------
  VecScatter scatter = nullptr;
  Vec useq = nullptr, dl = nullptr, fc = nullptr, rhs = nullptr, sol = nullptr, wr = nullptr;
  Mat Ct = nullptr, C = nullptr, B = nullptr, D = nullptr, WB = nullptr, G = nullptr, Kg = nullptr;
  Mat J = nullptr, Jaij = nullptr;
  Mat A_seen = nullptr;
  KSP ksp = nullptr;
  bool pc_built = false;
  int baseline_its = 0, last_its = 0;
  ContactStats stats;

  ~Impl() {
    if (ksp) KSPDestroy(&ksp);
    for (Mat* a : {&Ct, &C, &B, &D, &WB, &G, &Kg, &J, &Jaij})
      if (*a) MatDestroy(a);
    for (Vec* v : {&useq, &dl, &fc, &rhs, &sol, &wr})
      if (*v) VecDestroy(v);
    if (scatter) VecScatterDestroy(&scatter);
  }

  PairLaw law(int q) const {
    const PairData& d = P_[q];
    PairLaw L;
    L.area = d.area;
    L.k = d.k;
    L.cohesion = d.cohesion;
    L.mu = d.mu;
    L.active = d.active;
    L.regularization = d.redundant ? opt.regularization : 0.0;
    return L;
  }

  // ---- setup ----------------------------------------------------------------------------------
  void distribute_pairs() {
    std::vector<PairData> all;
    std::vector<int> counts(size, 0);
    if (rank == 0) {
      const auto& nb = ctx.node_begin_of_rank;
      std::vector<int> owner(fm->pairs.size());
      for (std::size_t q = 0; q < fm->pairs.size(); ++q) {
        const std::int64_t g1 = ctx.global_of_mesh_node[fm->pairs[q].side1];
        owner[q] = static_cast<int>(std::upper_bound(nb.begin(), nb.end(), g1) - nb.begin()) - 1;
        ++counts[owner[q]];
      }
      order.resize(fm->pairs.size());
      std::iota(order.begin(), order.end(), 0u);
      std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return owner[a] < owner[b]; });
      all.resize(order.size());
      for (std::size_t i = 0; i < order.size(); ++i) {
        const NodePair& p = fm->pairs[order[i]];
        const FaultProperties& f = fm->faults[p.fault];
        PairData& d = all[i];
        std::memset(&d, 0, sizeof d);
        d.g1 = ctx.global_of_mesh_node[p.side1];
        d.g2 = ctx.global_of_mesh_node[p.side2];
        d.tag1 = p.tag1;
        d.tag2 = p.tag2;
        d.model_index = order[i];
        d.fault = p.fault;
        d.area = p.area;
        d.k = p.k;
        d.cohesion = f.cohesion;
        d.mu = f.mu;
        d.p0 = p.p0;
        std::copy(p.R.begin(), p.R.end(), d.R);
        std::copy(p.lambda0.begin(), p.lambda0.end(), d.lam0);
        std::copy(p.x.begin(), p.x.end(), d.x);
        d.fixed1 = p.fixed1;
        d.fixed2 = p.fixed2;
        d.active = p.active;
        d.redundant = p.redundant ? 1 : 0;
      }
    }
    MPI_Bcast(counts.data(), size, MPI_INT, 0, comm);
    pairs_of_rank = counts;
    m = counts[rank];
    M = 0;
    for (int r = 0; r < size; ++r) {
      if (r == rank) lam_begin = M;
      M += counts[r];
    }
    P_.resize(m);
    std::vector<int> bytes(size), displs(size, 0);
    for (int r = 0; r < size; ++r) bytes[r] = counts[r] * static_cast<int>(sizeof(PairData));
    for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + bytes[r - 1];
    MPI_Scatterv(all.data(), bytes.data(), displs.data(), MPI_BYTE, P_.data(), bytes[rank], MPI_BYTE, 0, comm);
  }

  void setup(const mech::CouplingContext& c) {
    ctx = c;
    comm = c.comm;
    rank = c.rank;
    size = c.size;
    owned_fixed.assign(c.owned_fixed->begin(), c.owned_fixed->begin() + c.n_owned);
    owned_x.assign(c.owned_x->begin(), c.owned_x->begin() + c.n_owned);
    std::string names;
    if (rank == 0)
      for (const auto& f : fm->faults) names += f.name + '\n';
    names = broadcast_string(comm, names);
    for (std::size_t p = 0; p < names.size();) {
      const auto e = names.find('\n', p);
      fault_names.push_back(names.substr(p, e - p));
      p = e + 1;
    }
    distribute_pairs();

    lam.resize(m);
    for (int q = 0; q < m; ++q) lam[q] = {P_[q].lam0[0], P_[q].lam0[1], P_[q].lam0[2]};
    lam_c = lam_step = lam;
    g.assign(m, {0, 0, 0});
    gc = gc_step = g;
    dp_now.assign(m, 0.0);
    dp_c = dp_start = dp_target = dp_now;
    st.assign(m, PairState::Stick);
    st_prev = st_c = st_step = st;
    flips.assign(m, 0);
    changed_last.assign(m, 0);
    eq.resize(m);

    const PetscInt n3 = 3 * c.n_owned, m3 = 3 * m;
    // u at both twins of every owned pair.
    {
      std::vector<PetscInt> idx(6 * m);
      for (int q = 0; q < m; ++q)
        for (int k = 0; k < 3; ++k) {
          idx[6 * q + k] = static_cast<PetscInt>(3 * P_[q].g1 + k);
          idx[6 * q + 3 + k] = static_cast<PetscInt>(3 * P_[q].g2 + k);
        }
      IS is;
      CHK(ISCreateGeneral(PETSC_COMM_SELF, 6 * m, idx.data(), PETSC_COPY_VALUES, &is));
      CHK(VecCreateSeq(PETSC_COMM_SELF, 6 * m, &useq));
      CHK(VecScatterCreate(c.u, is, useq, nullptr, &scatter));
      CHK(ISDestroy(&is));
    }
    // C^T (multiplier rows, constant) and the pattern of B: both twins' free components.
    auto owned_col = [&](std::int64_t gnode) { return gnode >= c.node_begin && gnode < c.node_begin + c.n_owned; };
    std::vector<PetscInt> dnz(m3, 0), onz(m3, 0);
    for (int q = 0; q < m; ++q)
      for (int j = 0; j < 3; ++j) {
        const PairData& d = P_[q];
        for (int k = 0; k < 3; ++k) {
          if (!((d.fixed1 >> k) & 1)) ++(owned_col(d.g1) ? dnz : onz)[3 * q + j];
          if (!((d.fixed2 >> k) & 1)) ++(owned_col(d.g2) ? dnz : onz)[3 * q + j];
        }
      }
    CHK(MatCreateAIJ(comm, m3, n3, PETSC_DETERMINE, PETSC_DETERMINE, 0, dnz.data(), 0, onz.data(), &Ct));
    CHK(MatCreateAIJ(comm, m3, n3, PETSC_DETERMINE, PETSC_DETERMINE, 0, dnz.data(), 0, onz.data(), &B));
    for (int q = 0; q < m; ++q) {
      const PairData& d = P_[q];
      for (int j = 0; j < 3; ++j) {
        const PetscInt row = static_cast<PetscInt>(3 * (lam_begin + q) + j);
        PetscInt cols[6];
        double vals[6], zeros[6] = {0, 0, 0, 0, 0, 0};
        int n = 0;
        for (int k = 0; k < 3; ++k)
          if (!((d.fixed1 >> k) & 1)) cols[n] = static_cast<PetscInt>(3 * d.g1 + k), vals[n++] = -d.area * d.R[3 * k + j];
        for (int k = 0; k < 3; ++k)
          if (!((d.fixed2 >> k) & 1)) cols[n] = static_cast<PetscInt>(3 * d.g2 + k), vals[n++] = d.area * d.R[3 * k + j];
        CHK(MatSetValues(Ct, 1, &row, n, cols, vals, INSERT_VALUES));
        CHK(MatSetValues(B, 1, &row, n, cols, zeros, INSERT_VALUES));
      }
    }
    CHK(MatAssemblyBegin(Ct, MAT_FINAL_ASSEMBLY));
    CHK(MatAssemblyEnd(Ct, MAT_FINAL_ASSEMBLY));
    CHK(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
    CHK(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
    CHK(MatSetOption(B, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
    CHK(MatTranspose(Ct, MAT_INITIAL_MATRIX, &C));
    CHK(MatCreateAIJ(comm, m3, m3, PETSC_DETERMINE, PETSC_DETERMINE, 3, nullptr, 0, nullptr, &D));
    for (int q = 0; q < m; ++q) {
      const PetscInt r0 = static_cast<PetscInt>(3 * (lam_begin + q));
      const PetscInt rows[3] = {r0, r0 + 1, r0 + 2};
      const double zeros[9] = {};
      CHK(MatSetValues(D, 3, rows, 3, rows, zeros, INSERT_VALUES));
    }
    CHK(MatAssemblyBegin(D, MAT_FINAL_ASSEMBLY));
    CHK(MatAssemblyEnd(D, MAT_FINAL_ASSEMBLY));
    CHK(MatSetOption(D, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
    CHK(MatCreateVecs(C, &dl, &fc));
    CHK(VecCreateMPI(comm, n3 + m3, PETSC_DETERMINE, &rhs));
    CHK(VecDuplicate(rhs, &sol));
    CHK(VecDuplicate(dl, &wr));

    // The linear solver (-contact_augmentation overrides the augmentation of the field split).
    {
      PetscReal g = opt.augmentation;
      PetscBool set = PETSC_FALSE;
      CHK(PetscOptionsGetReal(nullptr, nullptr, "-contact_augmentation", &g, &set));
      if (set) opt.augmentation = g;
    }
    const double unknowns = 3.0 * static_cast<double>(c.n_global_nodes) + 3.0 * static_cast<double>(M);
    solver = opt.solver;
    if (solver == SaddleSolver::Auto) solver = unknowns <= static_cast<double>(opt.direct_limit) ? SaddleSolver::Mumps : SaddleSolver::FieldSplit;
    CHK(KSPCreate(comm, &ksp));
    CHK(KSPSetOptionsPrefix(ksp, "contact_"));
    PC pc;
    CHK(KSPGetPC(ksp, &pc));
    if (solver == SaddleSolver::Mumps) {
      CHK(KSPSetType(ksp, KSPPREONLY));
      CHK(PCSetType(pc, PCLU));
      CHK(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
      // Extra workspace: pivoting on the multiplier rows fills more than MUMPS' estimate.
      default_option("-contact_mat_mumps_icntl_14", "60");
    } else {
      CHK(KSPSetType(ksp, KSPFGMRES));
      CHK(KSPGMRESSetRestart(ksp, 200));
      CHK(PCSetType(pc, PCFIELDSPLIT));
      CHK(PCFieldSplitSetType(pc, PC_COMPOSITE_SCHUR));
      // Upper block-triangular: one multigrid cycle per iteration (full: two, for ~20 % fewer iterations).
      CHK(PCFieldSplitSetSchurFactType(pc, PC_FIELDSPLIT_SCHUR_FACT_UPPER));
      CHK(PCFieldSplitSetSchurPre(pc, PC_FIELDSPLIT_SCHUR_PRE_SELFP, nullptr));
      default_option("-contact_fieldsplit_u_ksp_type", "preonly");
      default_option("-contact_fieldsplit_u_pc_type", opt.amg == "hypre" ? "hypre" : "gamg");
      if (opt.amg == "hypre") {
        default_option("-contact_fieldsplit_u_pc_hypre_type", "boomeramg");
        default_option("-contact_fieldsplit_u_pc_hypre_boomeramg_nodal_coarsen", "6");
        // Variant 3 (as the continuous solver uses) crashes inside BoomerAMG on this block
        // (hypre 2.26, hypre_BoomerAMG_LNExpandInterp); variant 2 works.
        default_option("-contact_fieldsplit_u_pc_hypre_boomeramg_vec_interp_variant", "2");
        default_option("-contact_fieldsplit_u_pc_hypre_boomeramg_strong_threshold", "0.5");
      }
      default_option("-contact_fieldsplit_lambda_ksp_type", "preonly");
      default_option("-contact_fieldsplit_lambda_pc_type", "bjacobi");
    }
    CHK(KSPSetTolerances(ksp, 1e-9, 1e-300, PETSC_DEFAULT, 2000));
  }

  // ---- residual -------------------------------------------------------------------------------
  double residual(Vec u, Vec r) {
    CHK(VecScatterBegin(scatter, u, useq, INSERT_VALUES, SCATTER_FORWARD));
    CHK(VecScatterEnd(scatter, u, useq, INSERT_VALUES, SCATTER_FORWARD));
    const PetscScalar* ua = nullptr;
    CHK(VecGetArrayRead(useq, &ua));
    double ss = 0;
    int changes = 0;
    for (int q = 0; q < m; ++q) {
      const PairData& d = P_[q];
      double ur[3];
      for (int k = 0; k < 3; ++k) ur[k] = ua[6 * q + 3 + k] - ua[6 * q + k];
      for (int j = 0; j < 3; ++j) g[q][j] = d.R[j] * ur[0] + d.R[3 + j] * ur[1] + d.R[6 + j] * ur[2];
      const std::array<double, 3> lam0{d.lam0[0], d.lam0[1], d.lam0[2]};
      eq[q] = pair_equations(law(q), lam[q], lam0, lam_c[q], g[q], gc[q], d.p0 + dp_now[q], st_prev[q]);
      st[q] = eq[q].state;
      changed_last[q] = st[q] != st_prev[q];
      if (changed_last[q] && contact_monitor())
        std::fprintf(stderr, "    pair %d (%.0f %.0f %.0f): %s -> %s  lam %.3e %.3e %.3e g %.3e %.3e %.3e p %.3e\n", q, d.x[0], d.x[1],
                     d.x[2], pair_state_name(st_prev[q]), pair_state_name(st[q]), lam[q][0], lam[q][1], lam[q][2], g[q][0],
                     g[q][1], g[q][2], d.p0 + dp_now[q]);
      if (changed_last[q]) ++flips[q], ++changes;
      st_prev[q] = st[q];
      for (double f : eq[q].F) ss += f * f;
    }
    CHK(VecRestoreArrayRead(useq, &ua));
    stats.state_changes += changes;
    int any = 0;
    MPI_Allreduce(&changes, &any, 1, MPI_INT, MPI_SUM, comm);
    settled_flag = any == 0;
    // r -= C (lambda - lambda_0)
    PetscScalar* a = nullptr;
    CHK(VecGetArray(dl, &a));
    for (int q = 0; q < m; ++q)
      for (int j = 0; j < 3; ++j) a[3 * q + j] = lam[q][j] - P_[q].lam0[j];
    CHK(VecRestoreArray(dl, &a));
    CHK(MatMult(C, dl, fc));
    CHK(VecAXPY(r, -1.0, fc));
    double total = 0;
    MPI_Allreduce(&ss, &total, 1, MPI_DOUBLE, MPI_SUM, comm);
    return total;
  }

  // ---- Newton system --------------------------------------------------------------------------
  void fill_blocks() {
    for (int q = 0; q < m; ++q) {
      const PairData& d = P_[q];
      const PairEquations& e = eq[q];
      const PetscInt r0 = static_cast<PetscInt>(3 * (lam_begin + q));
      for (int j = 0; j < 3; ++j) {
        // dF_j/du2_k = sum_i Jg[j][i] R[k][i], dF_j/du1_k = -(same).
        PetscInt cols[6];
        double vals[6];
        int n = 0;
        double w[3];
        for (int k = 0; k < 3; ++k) w[k] = e.Jg[3 * j] * d.R[3 * k] + e.Jg[3 * j + 1] * d.R[3 * k + 1] + e.Jg[3 * j + 2] * d.R[3 * k + 2];
        for (int k = 0; k < 3; ++k)
          if (!((d.fixed1 >> k) & 1)) cols[n] = static_cast<PetscInt>(3 * d.g1 + k), vals[n++] = -w[k];
        for (int k = 0; k < 3; ++k)
          if (!((d.fixed2 >> k) & 1)) cols[n] = static_cast<PetscInt>(3 * d.g2 + k), vals[n++] = w[k];
        const PetscInt row = r0 + j;
        CHK(MatSetValues(B, 1, &row, n, cols, vals, INSERT_VALUES));
      }
      const PetscInt rows[3] = {r0, r0 + 1, r0 + 2};
      CHK(MatSetValues(D, 3, rows, 3, rows, e.Jl.data(), INSERT_VALUES));
    }
    CHK(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
    CHK(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
    CHK(MatAssemblyBegin(D, MAT_FINAL_ASSEMBLY));
    CHK(MatAssemblyEnd(D, MAT_FINAL_ASSEMBLY));
  }

  // Augmented Lagrangian for the field split: rows that are pure constraints (no multiplier
  // coefficient) are added to the displacement rows with weight gamma / A_q, turning the twin
  // constraints into springs of stiffness gamma k A_q in the (0,0) block: K_gamma = K + C W B.
  void augment(Mat A, PetscScalar* rl, std::vector<double>& wdiag) {
    wdiag.assign(3 * m, 0.0);
    for (int q = 0; q < m; ++q)
      for (int j = 0; j < 3; ++j) {
        const auto& e = eq[q];
        const bool constraint = e.Jl[3 * j] == 0 && e.Jl[3 * j + 1] == 0 && e.Jl[3 * j + 2] == 0 &&
                                (e.Jg[3 * j] != 0 || e.Jg[3 * j + 1] != 0 || e.Jg[3 * j + 2] != 0);
        if (constraint) wdiag[3 * q + j] = opt.augmentation / P_[q].area;
      }
    PetscScalar* a = nullptr;
    CHK(VecGetArray(wr, &a));
    for (int i = 0; i < 3 * m; ++i) a[i] = wdiag[i];
    CHK(VecRestoreArray(wr, &a));
    if (!WB) CHK(MatDuplicate(B, MAT_COPY_VALUES, &WB));
    else CHK(MatCopy(B, WB, SAME_NONZERO_PATTERN));
    CHK(MatDiagonalScale(WB, wr, nullptr));
    if (!G) CHK(MatMatMult(C, WB, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &G));
    else CHK(MatMatMult(C, WB, MAT_REUSE_MATRIX, PETSC_DEFAULT, &G));
    if (!Kg) {
      CHK(MatDuplicate(A, MAT_COPY_VALUES, &Kg));
      CHK(MatAXPY(Kg, 1.0, G, DIFFERENT_NONZERO_PATTERN));
      MatNullSpace nsp = nullptr;
      CHK(MatGetNearNullSpace(A, &nsp));
      if (nsp) CHK(MatSetNearNullSpace(Kg, nsp));
    } else {
      CHK(MatCopy(A, Kg, SUBSET_NONZERO_PATTERN));
      CHK(MatAXPY(Kg, 1.0, G, SUBSET_NONZERO_PATTERN));
    }
    // Right-hand side: r_u += C W r_lambda.
    CHK(VecGetArray(wr, &a));
    for (int i = 0; i < 3 * m; ++i) a[i] = wdiag[i] * rl[i];
    CHK(VecRestoreArray(wr, &a));
  }

  mech::CouplingSolve solve(Mat A, Vec r, Vec du, double rtol) {
    const auto t0 = std::chrono::steady_clock::now();
    fill_blocks();
    const PetscInt n3 = 3 * ctx.n_owned;
    // Right-hand side [r; -F].
    PetscScalar* b = nullptr;
    const PetscScalar* ra = nullptr;
    CHK(VecGetArray(rhs, &b));
    CHK(VecGetArrayRead(r, &ra));
    std::copy(ra, ra + n3, b);
    CHK(VecRestoreArrayRead(r, &ra));
    for (int q = 0; q < m; ++q)
      for (int j = 0; j < 3; ++j) b[n3 + 3 * q + j] = -eq[q].F[j];
    Mat op = nullptr;
    if (solver == SaddleSolver::FieldSplit) {
      std::vector<double> wdiag;
      augment(A, b + n3, wdiag);
      CHK(VecRestoreArray(rhs, &b));
      CHK(MatMult(C, wr, fc));  // C W r_lambda
      CHK(VecGetArray(rhs, &b));
      const PetscScalar* f = nullptr;
      CHK(VecGetArrayRead(fc, &f));
      for (PetscInt i = 0; i < n3; ++i)
        if (f[i] != 0) b[i] += f[i];
      CHK(VecRestoreArrayRead(fc, &f));
    }
    CHK(VecRestoreArray(rhs, &b));
    if (!J || A != A_seen) {
      if (J) CHK(MatDestroy(&J));
      Mat blocks[4] = {solver == SaddleSolver::FieldSplit ? Kg : A, C, B, D};
      CHK(MatCreateNest(comm, 2, nullptr, 2, nullptr, blocks, &J));
      A_seen = A;
      if (solver == SaddleSolver::FieldSplit) {
        IS isr[2];
        CHK(MatNestGetISs(J, isr, nullptr));
        // The rigid-body modes reach the displacement block's multigrid through its index set
        // (GAMG's aggregates, BoomerAMG's interpolation vectors).
        MatNullSpace nsp = nullptr;
        CHK(MatGetNearNullSpace(A, &nsp));
        if (nsp) CHK(PetscObjectCompose(reinterpret_cast<PetscObject>(isr[0]), "nearnullspace", reinterpret_cast<PetscObject>(nsp)));
        PC pc;
        CHK(KSPGetPC(ksp, &pc));
        CHK(PCFieldSplitSetIS(pc, "u", isr[0]));
        CHK(PCFieldSplitSetIS(pc, "lambda", isr[1]));
      }
    } else {
      CHK(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
      CHK(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
    }
    if (solver == SaddleSolver::Mumps) {
      CHK(MatConvert(J, MATAIJ, Jaij ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, &Jaij));
      op = Jaij;
    } else {
      op = J;
    }
    CHK(KSPSetOperators(ksp, op, op));
    if (stats.solves == 0) CHK(KSPSetFromOptions(ksp));
    PetscReal old_rtol, abstol, dtol;
    PetscInt maxit;
    CHK(KSPGetTolerances(ksp, &old_rtol, &abstol, &dtol, &maxit));
    CHK(KSPSetTolerances(ksp, std::min(rtol, 1e-3), abstol, dtol, maxit));
    // The field split keeps its multigrid hierarchy while the iteration counts stay close to those
    // of a fresh setup (the tangent and the active set change little from one iteration, or one
    // step, to the next); a stale one that fails is rebuilt at once.
    const bool iterative = solver == SaddleSolver::FieldSplit;
    bool reuse = iterative && opt.reuse_preconditioner && pc_built && last_its <= std::max(2 * baseline_its, baseline_its + 10);
    PetscInt its = 0;
    KSPConvergedReason reason;
    for (;;) {
      CHK(KSPSetReusePreconditioner(ksp, reuse ? PETSC_TRUE : PETSC_FALSE));
      CHK(KSPSolve(ksp, rhs, sol));
      CHK(KSPGetIterationNumber(ksp, &its));
      CHK(KSPGetConvergedReason(ksp, &reason));
      stats.linear_iterations += its;
      if (!reuse || reason >= 0) break;
      reuse = false;
    }
    if (!reuse) {
      ++stats.preconditioner_setups;
      baseline_its = static_cast<int>(its);
    }
    pc_built = true;
    last_its = static_cast<int>(its);
    mech::CouplingSolve out;
    out.iterations = static_cast<int>(its);
    if (reason < 0) {
      out.ok = false;
      out.failure = fmt::format("the saddle-point solver ({}) failed: {} after {} iterations", solver_name(),
                                KSPConvergedReasons[reason], its);
    }
    // du (zero on prescribed components) and lambda += dlambda.
    const PetscScalar* x = nullptr;
    PetscScalar* d = nullptr;
    CHK(VecGetArrayRead(sol, &x));
    CHK(VecGetArray(du, &d));
    for (int a = 0; a < ctx.n_owned; ++a)
      for (int k = 0; k < 3; ++k) d[3 * a + k] = ((owned_fixed[a] >> k) & 1) ? 0.0 : x[3 * a + k];
    CHK(VecRestoreArray(du, &d));
    for (int q = 0; q < m; ++q)
      for (int j = 0; j < 3; ++j) lam[q][j] += x[n3 + 3 * q + j];
    CHK(VecRestoreArrayRead(sol, &x));
    ++stats.solves;
    stats.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
  }

  const char* solver_name() const { return solver == SaddleSolver::Mumps ? "MUMPS" : "field split"; }

  // ---- messages -------------------------------------------------------------------------------
  // Lists pairs flagged on any rank: "fault 'F': nodes 12/40012 at (x, y, z), ...".
  std::string describe(const std::vector<int>& mine, const std::string& what) {
    std::string local;
    for (int q : mine) {
      const PairData& d = P_[q];
      local += fmt::format("{}\t{}/{} at ({:.1f}, {:.1f}, {:.1f})\n", d.fault, d.tag1, d.tag2, d.x[0], d.x[1], d.x[2]);
    }
    int n = static_cast<int>(local.size());
    std::vector<int> counts(size), displs(size, 0);
    MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
    std::string all;
    if (rank == 0) {
      for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
      all.resize(displs[size - 1] + counts[size - 1]);
    }
    MPI_Gatherv(local.data(), n, MPI_CHAR, all.data(), counts.data(), displs.data(), MPI_CHAR, 0, comm);
    std::string msg;
    if (rank == 0 && !all.empty()) {
      // Per fault: the count and the first few node pairs.
      std::vector<std::vector<std::string>> per(fault_names.size());
      for (std::size_t p = 0; p < all.size();) {
        const auto e = all.find('\n', p);
        const std::string line = all.substr(p, e - p);
        const auto tab = line.find('\t');
        per[std::stoi(line.substr(0, tab))].push_back(line.substr(tab + 1));
        p = e + 1;
      }
      for (std::size_t f = 0; f < per.size(); ++f) {
        if (per[f].empty()) continue;
        std::string list;
        for (std::size_t i = 0; i < per[f].size() && i < 6; ++i) list += (i ? ", " : "") + per[f][i];
        if (per[f].size() > 6) list += fmt::format(", ... ({} more)", per[f].size() - 6);
        msg += fmt::format("{}fault '{}': {} {} (node pairs side 1/side 2): {}", msg.empty() ? "" : "; ", fault_names[f],
                           per[f].size(), what, list);
      }
    }
    return broadcast_string(comm, msg);
  }
};

FaultContact::FaultContact(MPI_Comm comm, const FaultModel* model, const ContactOptions& options)
    : impl_(std::make_unique<Impl>()) {
  impl_->comm = comm;
  MPI_Comm_rank(comm, &impl_->rank);
  MPI_Comm_size(comm, &impl_->size);
  impl_->fm = model;
  impl_->opt = options;
}

FaultContact::~FaultContact() = default;

void FaultContact::setup(const mech::CouplingContext& ctx) { impl_->setup(ctx); }

void FaultContact::set_pressure_change(const std::vector<double>& dp_pairs) {
  Impl& s = *impl_;
  std::vector<double> sorted;
  if (s.rank == 0) {
    if (dp_pairs.size() != s.order.size()) throw std::logic_error("FaultContact::set_pressure_change: wrong size");
    sorted.resize(s.order.size());
    for (std::size_t i = 0; i < s.order.size(); ++i) sorted[i] = dp_pairs[s.order[i]];
  }
  std::vector<int> displs(s.size, 0);
  for (int r = 1; r < s.size; ++r) displs[r] = displs[r - 1] + s.pairs_of_rank[r - 1];
  MPI_Scatterv(sorted.data(), s.pairs_of_rank.data(), displs.data(), MPI_DOUBLE, s.dp_target.data(), s.m, MPI_DOUBLE, 0,
               s.comm);
}

PairResults FaultContact::gather() const {
  const Impl& s = *impl_;
  std::vector<double> lam(3 * s.m), g(3 * s.m), pf(s.m), st(s.m);
  for (int q = 0; q < s.m; ++q) {
    for (int j = 0; j < 3; ++j) lam[3 * q + j] = s.lam_c[q][j], g[3 * q + j] = s.gc[q][j];
    pf[q] = s.P_[q].p0 + s.dp_c[q];
    st[q] = static_cast<double>(static_cast<int>(s.st_c[q]));
  }
  auto gatherv = [&](const std::vector<double>& v, int k) {
    std::vector<int> counts(s.size), displs(s.size, 0);
    for (int r = 0; r < s.size; ++r) counts[r] = k * s.pairs_of_rank[r];
    for (int r = 1; r < s.size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
    std::vector<double> all(s.rank == 0 ? static_cast<std::size_t>(k) * s.M : 0);
    MPI_Gatherv(v.data(), k * s.m, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, 0, s.comm);
    std::vector<double> out(all.size());
    if (s.rank == 0)
      for (std::size_t i = 0; i < s.order.size(); ++i)
        for (int c = 0; c < k; ++c) out[static_cast<std::size_t>(k) * s.order[i] + c] = all[static_cast<std::size_t>(k) * i + c];
    return out;
  };
  PairResults out;
  out.lambda = gatherv(lam, 3);
  out.g = gatherv(g, 3);
  out.p_f = gatherv(pf, 1);
  const auto sv = gatherv(st, 1);
  out.state.resize(sv.size());
  for (std::size_t i = 0; i < sv.size(); ++i) out.state[i] = static_cast<std::uint8_t>(sv[i]);
  return out;
}

FaultContact::Snapshot FaultContact::save() const {
  const Impl& s = *impl_;
  Snapshot snap;
  for (int q = 0; q < s.m; ++q) {
    snap.lambda.insert(snap.lambda.end(), s.lam_c[q].begin(), s.lam_c[q].end());
    snap.g.insert(snap.g.end(), s.gc[q].begin(), s.gc[q].end());
    snap.state.push_back(static_cast<std::uint8_t>(s.st_c[q]));
  }
  snap.dp = s.dp_c;
  return snap;
}

void FaultContact::restore(const Snapshot& snap) {
  Impl& s = *impl_;
  for (int q = 0; q < s.m; ++q) {
    for (int j = 0; j < 3; ++j) s.lam_c[q][j] = snap.lambda[3 * q + j], s.gc[q][j] = snap.g[3 * q + j];
    s.st_c[q] = static_cast<PairState>(snap.state[q]);
  }
  s.lam = s.lam_step = s.lam_c;
  s.g = s.gc_step = s.gc;
  s.st = s.st_prev = s.st_step = s.st_c;
  s.dp_c = s.dp_start = s.dp_now = s.dp_target = snap.dp;
}

const ContactStats& FaultContact::stats() const { return impl_->stats; }

std::string FaultContact::description() const {
  const Impl& s = *impl_;
  if (s.solver == SaddleSolver::Mumps) return fmt::format("{} node pairs, saddle point by MUMPS (LU)", s.M);
  return fmt::format("{} node pairs, saddle point by FGMRES + Schur field split ({} on the displacement block, augmentation {:g})",
                     s.M, s.opt.amg == "hypre" ? "BoomerAMG" : "GAMG", s.opt.augmentation);
}

std::size_t FaultContact::global_pairs() const { return static_cast<std::size_t>(impl_->M); }

void FaultContact::begin_step() {
  Impl& s = *impl_;
  s.lam_step = s.lam_c;
  s.gc_step = s.gc;
  s.st_step = s.st_c;
  s.dp_start = s.dp_c;
}

void FaultContact::begin_substep(double fraction) {
  Impl& s = *impl_;
  for (int q = 0; q < s.m; ++q) s.dp_now[q] = s.dp_start[q] + fraction * (s.dp_target[q] - s.dp_start[q]);
  s.lam = s.lam_c;
  s.st_prev = s.st_c;
  std::fill(s.flips.begin(), s.flips.end(), 0);
}

double FaultContact::residual(Vec u, Vec r) { return impl_->residual(u, r); }

bool FaultContact::settled() { return impl_->settled_flag; }

std::string FaultContact::stalled() {
  Impl& s = *impl_;
  std::vector<int> cyc;
  for (int q = 0; q < s.m; ++q)
    if (s.flips[q] >= s.opt.max_state_changes) cyc.push_back(q);
  int mine = cyc.empty() ? 0 : 1, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, s.comm);
  if (!any) return {};
  return "the contact state keeps cycling (stick <-> slip <-> open): " +
         s.describe(cyc, fmt::format("node pairs changed state {} times or more", s.opt.max_state_changes));
}

mech::CouplingSolve FaultContact::solve(Mat A, Vec r, Vec du, double rtol) { return impl_->solve(A, r, du, rtol); }

std::string FaultContact::diagnosis() {
  Impl& s = *impl_;
  // The pairs whose state changed during the iteration; failing those, the largest residuals.
  std::vector<int> changed;
  for (int q = 0; q < s.m; ++q)
    if (s.flips[q] > 0) changed.push_back(q);
  int mine = changed.empty() ? 0 : 1, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, s.comm);
  if (any) return "; contact states changing: " + s.describe(changed, "node pairs changed state during the iteration");
  std::vector<std::pair<double, int>> worst;
  for (int q = 0; q < s.m; ++q) worst.push_back({std::hypot(s.eq[q].F[0], s.eq[q].F[1], s.eq[q].F[2]), q});
  std::sort(worst.begin(), worst.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  double local_max = worst.empty() ? 0.0 : worst.front().first, global_max = 0;
  MPI_Allreduce(&local_max, &global_max, 1, MPI_DOUBLE, MPI_MAX, s.comm);
  if (!(global_max > 0)) {  // e.g. the first solve failed: say so rather than list nothing
    std::string faults;
    for (const auto& n : s.fault_names) faults += fmt::format("{}fault '{}'", faults.empty() ? "" : ", ", n);
    return "; every node pair satisfies its contact equations (" + faults + ")";
  }
  std::vector<int> top;
  for (std::size_t i = 0; i < worst.size() && i < 6; ++i)
    if (worst[i].first > 0.1 * global_max) top.push_back(worst[i].second);
  return "; largest contact residuals: " + s.describe(top, "node pairs far from equilibrium");
}

void FaultContact::commit() {
  Impl& s = *impl_;
  s.lam_c = s.lam;
  s.gc = s.g;
  s.st_c = s.st;
  s.dp_c = s.dp_now;
}

void FaultContact::revert_substep() {
  Impl& s = *impl_;
  s.lam = s.lam_c;
  s.st = s.st_prev = s.st_c;
}

void FaultContact::revert_step() {
  Impl& s = *impl_;
  s.lam = s.lam_c = s.lam_step;
  s.gc = s.gc_step;
  s.st = s.st_prev = s.st_c = s.st_step;
  s.dp_c = s.dp_start;
}

}  // namespace ugs::contact
