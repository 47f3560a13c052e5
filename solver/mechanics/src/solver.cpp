// The mechanics solver's public interface (ugs/mechanics/solver.hpp); its pieces: solver_impl.hpp.
#include "ugs/mechanics/solver.hpp"

#include <stdexcept>

#include "cell_gather.hpp"
#include "solver_impl.hpp"

namespace ugs::mech {

LinearSolver parse_linear_solver(const std::string& s) {
  if (s == "cg-gamg") return LinearSolver::CgGamg;
  if (s == "cg-hypre") return LinearSolver::CgHypre;
  if (s == "mumps") return LinearSolver::Mumps;
  if (s == "cholmod") return LinearSolver::Cholmod;
  throw InputError("linear solver", "'" + s + "' is not one of cg-gamg, cg-hypre, mumps, cholmod");
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
  if (impl_->released) throw std::logic_error("MechanicsSolver::advance after release_linear_system");
  return impl_->advance(dp, label);
}

void MechanicsSolver::release_linear_system() {
  Impl& s = *impl_;
  if (s.ksp) UGS_PETSC(KSPDestroy(&s.ksp));
  if (s.A) UGS_PETSC(MatDestroy(&s.A));
  if (s.P) UGS_PETSC(MatDestroy(&s.P));
  s.newton.predictor.release();
  s.release_pattern();
  s.released = true;
}

std::vector<double> MechanicsSolver::gather_displacement() {
  PetscLogEventBegin(events().gather, 0, 0, 0, 0);
  auto out = impl_->gather_nodes(impl_->owned_u(), 3);
  PetscLogEventEnd(events().gather, 0, 0, 0, 0);
  return out;
}

CellResults MechanicsSolver::gather_cells() {
  CellResults out;
  out.strain = gather_cell_field(CellField::Strain);
  out.stress = gather_cell_field(CellField::Stress);
  out.stress_change = gather_cell_field(CellField::StressChange);
  out.cm = gather_cell_field(CellField::Cm);
  out.state = gather_cell_field(CellField::State);
  out.sigma_max = gather_cell_field(CellField::SigmaMax);
  return out;
}

std::vector<double> MechanicsSolver::gather_cell_field(CellField field) {
  PetscLogEventBegin(events().gather, 0, 0, 0, 0);
  Impl& s = *impl_;
  const LocalMesh& lm = s.lm;
  const bool tensor = field == CellField::Strain || field == CellField::Stress || field == CellField::StressChange;
  const int k = tensor ? 6 : 1;
  CellGather gather(lm, k);
  Vec ul = nullptr;
  const PetscScalar* ua = nullptr;
  if (tensor) {
    UGS_PETSC(VecGhostUpdateBegin(s.u, INSERT_VALUES, SCATTER_FORWARD));
    UGS_PETSC(VecGhostUpdateEnd(s.u, INSERT_VALUES, SCATTER_FORWARD));
    UGS_PETSC(VecGhostGetLocalForm(s.u, &ul));
    UGS_PETSC(VecGetArrayRead(ul, &ua));
  }
  for (std::size_t ci = 0; ci < lm.n_cells(); ++ci) {
    if (!lm.cell_owned[ci]) continue;
    const int c = static_cast<int>(ci);
    const fem::Material& m = lm.materials[lm.cell_material[c]];
    const int h = s.hyp.of_cell[c];
    if (tensor) {
      double ue[12];
      s.gather_element(ua, c, ue);
      const Vec6 eps = fem::tet4_strain(s.geo[c], ue);
      if (field == CellField::Strain) {
        const auto v = fem::strain_to_output(eps);
        std::copy(v.begin(), v.end(), gather.next());
        continue;
      }
      const Vec6 ds = h < 0 ? s.elastic_stress(c, eps) : s.hyp.committed[h].dsig;
      if (field == CellField::StressChange) {
        const auto v = fem::stress_to_output(ds);
        std::copy(v.begin(), v.end(), gather.next());
        continue;
      }
      const auto& t = lm.cells[c];
      const double zc = 0.25 * (lm.x[t[0]][2] + lm.x[t[1]][2] + lm.x[t[2]][2] + lm.x[t[3]][2]);
      const Vec6 s0 = lm.initial.effective_stress(zc, m.biot, lm.material_k[lm.cell_material[c]],
                                                  lm.material_gas[lm.cell_material[c]]);
      Vec6 tot;
      for (int j = 0; j < 6; ++j) tot[j] = s0[j] + ds[j];
      const auto v = fem::stress_to_output(tot);
      std::copy(v.begin(), v.end(), gather.next());
    } else if (field == CellField::Cm) {
      *gather.next() = h >= 0 ? s.hyp.committed_c[h] * 1e-6
                              : (m.law == fem::Law::Linear ? fem::cm_from_ez(m.E_z, m.ratios) : 1.0 / s.inv_c0[c]);
    } else if (field == CellField::State) {
      *gather.next() = h >= 0 ? static_cast<double>(static_cast<int>(s.hyp.committed_phase[h])) : 0.0;
    } else {
      *gather.next() = h >= 0 ? s.hyp.committed[h].hypo.sigma_max * 1e6 : 0.0;
    }
  }
  if (tensor) {
    UGS_PETSC(VecRestoreArrayRead(ul, &ua));
    UGS_PETSC(VecGhostRestoreLocalForm(s.u, &ul));
  }
  std::vector<double> out = gather.finish();
  PetscLogEventEnd(events().gather, 0, 0, 0, 0);
  return out;
}

SavedState MechanicsSolver::gather_state() {
  SavedState st;
  st.u = gather_displacement();
  st.eps = gather_state_field(StateField::Eps);
  st.dsig = gather_state_field(StateField::Dsig);
  st.hypo = gather_state_field(StateField::Hypo);
  st.dp = gather_state_field(StateField::Dp);
  return st;
}

std::vector<double> MechanicsSolver::gather_state_field(StateField field) {
  Impl& s = *impl_;
  const LocalMesh& lm = s.lm;
  const int k = field == StateField::Dp ? 1 : field == StateField::Hypo ? 4 : 6;
  CellGather gather(lm, k);
  for (std::size_t ci = 0; ci < lm.n_cells(); ++ci) {
    if (!lm.cell_owned[ci]) continue;
    const int h = s.hyp.of_cell[ci];
    const fem::PointState ps = h >= 0 ? s.hyp.committed[h] : fem::PointState{};
    double* v = gather.next();
    switch (field) {
      case StateField::Dp: v[0] = s.dp_cell[ci]; break;
      case StateField::Eps: std::copy(ps.eps.begin(), ps.eps.end(), v); break;
      case StateField::Dsig: std::copy(ps.dsig.begin(), ps.dsig.end(), v); break;
      case StateField::Hypo:
        v[0] = ps.hypo.sigma_max;
        v[1] = ps.hypo.sigma_inv;
        v[2] = ps.hypo.direction;
        v[3] = h >= 0 ? s.hyp.last_ddp[h] : 0;
        break;
    }
  }
  return gather.finish();
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
      throw InputError("restart state", fmt::format("the restart state does not match the mesh ({} nodes, {} cells)", nn, nc));
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
  for (std::size_t h = 0; h < s.hyp.cells.size(); ++h) {
    const int c = s.hyp.cells[h];
    const std::size_t e = lm.cell_index[c];
    fem::PointState& ps = s.hyp.committed[h];
    for (int k = 0; k < 6; ++k) ps.eps[k] = eps[6 * e + k], ps.dsig[k] = dsig[6 * e + k];
    ps.hypo.sigma_max = hypo[4 * e];
    ps.hypo.sigma_inv = hypo[4 * e + 1];
    ps.hypo.direction = hypo[4 * e + 2] < 0 ? -1 : +1;
    s.hyp.last_ddp[h] = hypo[4 * e + 3] > 0 ? +1 : -1;
    const fem::HypoResult r =
        fem::hypo_integrate(lm.materials[lm.cell_material[c]].hypo, ps.hypo, s.start_sigma(static_cast<int>(h)), 0.0,
                            ps.hypo.direction);
    s.hyp.committed_phase[h] = r.phase;
    s.hyp.committed_c[h] = r.c_tangent;
  }
}

std::size_t MechanicsSolver::global_nodes() const { return impl_->lm.n_global_nodes; }
std::size_t MechanicsSolver::global_cells() const { return impl_->lm.n_global_cells; }
std::size_t MechanicsSolver::local_nodes() const { return impl_->lm.n_owned; }
std::size_t MechanicsSolver::local_cells() const { return impl_->lm.n_cells(); }

std::string MechanicsSolver::matrix_type() const {
  MatType t = nullptr;
  if (impl_->A) UGS_PETSC(MatGetType(impl_->A, &t));
  return t ? t : "";
}

std::string MechanicsSolver::solver_description() const {
  const Impl& s = *impl_;
  KSPType kt;
  PCType pt;
  PC pc;
  KSPGetType(s.ksp, &kt);
  KSPGetPC(s.ksp, &pc);
  PCGetType(pc, &pt);
  // The Krylov method actually used: the cg-* solvers run GMRES when the tangent is not symmetric
  // (set_krylov), or whatever -ksp_type asked for.
  const std::string name = linear_solver_name(s.opt.linear);
  const std::string krylov = kt ? kt : "?";
  std::string why;
  if (name.rfind("cg-", 0) == 0 && krylov != KSPCG)
    why = s.has_hyp && krylov == KSPGMRES ? ", with GMRES: the hypo-plastic tangent is not symmetric"
                                          : fmt::format(", with {} (-ksp_type)", krylov);
  return fmt::format("KSP {} + PC {} (linear solver {}{}), {} process{}, {} partition", krylov, pt ? pt : "?", name, why,
                     s.lm.size, s.lm.size > 1 ? "es" : "", s.opt.partition == PartitionMethod::PtScotch ? "PT-Scotch" : "RCB");
}

}  // namespace ugs::mech

