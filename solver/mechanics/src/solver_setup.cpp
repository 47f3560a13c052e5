// Setup of the mechanics solver: elements, the sparsity pattern, the vectors (solver_impl.hpp).
#include "solver_impl.hpp"

namespace ugs::mech {

void MechanicsSolver::Impl::setup_elements() {
  const std::size_t nc = lm.n_cells();
  geo.resize(nc);
  s0.resize(nc);
  inv_c0.assign(nc, 0.0);
  hyp.of_cell.assign(nc, -1);
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
      s0[c] = lm.initial.effective_vertical_stress(zc, m.biot, lm.material_gas[lm.cell_material[c]]) * 1e-6;
      if (m.law == fem::Law::Elastic) inv_c0[c] = 1e6 / m.hypo.cm(s0[c]);
      if (m.law == fem::Law::Hypoplastic) {
        hyp.of_cell[c] = static_cast<std::int32_t>(hyp.cells.size());
        hyp.cells.push_back(static_cast<std::int32_t>(c));
      }
    }
  });
  const std::size_t nh = hyp.cells.size();
  int mine = nh ? 1 : 0, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, lm.comm);
  has_hyp = any != 0;
  hyp.committed.resize(nh);
  hyp.committed_phase.assign(nh, fem::LoadingPhase::Virgin);
  hyp.committed_c.resize(nh);
  hyp.trial.resize(nh);
  hyp.trial_eps.resize(nh);
  hyp.guess.assign(nh, +1);
  hyp.last_ddp.assign(nh, -1);  // the geostatic state ends a virgin compression
  hyp.piece.assign(nh, 0);
  hyp.flips.assign(nh, 0);
  hyp.hold.assign(nh, fem::Hold::None);
  hyp.hold_dir.assign(nh, +1);
  assembler.assembled_Dt.resize(nh);
  assembler.assembled_phase.assign(nh, -1);
  reuse.phase.assign(nh, -1);
  {
    long long mine_h = static_cast<long long>(nh);
    MPI_Allreduce(&mine_h, &hyp.n_global, 1, MPI_LONG_LONG, MPI_SUM, lm.comm);
  }
  for (std::size_t h = 0; h < nh; ++h) {
    const int c = hyp.cells[h];
    hyp.committed[h].hypo = fem::HypoState::virgin(s0[c]);
    hyp.committed_c[h] = lm.materials[lm.cell_material[c]].hypo.cm(s0[c]);
  }
  dp_cell.assign(lm.n_cells(), 0.0);
  fext.assign(3 * lm.n_owned, 0.0);
  fint.assign(3 * lm.n_owned, 0.0);
}

void MechanicsSolver::Impl::setup_pattern() {
  const int n = lm.n_owned;
  std::vector<std::vector<std::int32_t>> cells_of(n);
  for (std::size_t c = 0; c < lm.n_cells(); ++c)
    for (auto v : lm.cells[c])
      if (v < n) cells_of[v].push_back(static_cast<std::int32_t>(c));
  assembler.node_ptr.assign(n + 1, 0);
  assembler.node_cols.clear();
  std::vector<std::int64_t> row;
  for (int a = 0; a < n; ++a) {
    row.clear();
    for (auto c : cells_of[a])
      for (auto v : lm.cells[c]) row.push_back(lm.global[v]);
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    assembler.node_cols.insert(assembler.node_cols.end(), row.begin(), row.end());
    assembler.node_ptr[a + 1] = static_cast<PetscInt>(assembler.node_cols.size());
  }
  assembler.rowptr.assign(3 * n + 1, 0);
  assembler.cols.resize(9 * assembler.node_cols.size());
  for (int a = 0; a < n; ++a) {
    const PetscInt nb = assembler.node_ptr[a], d = assembler.node_ptr[a + 1] - nb;
    for (int ci = 0; ci < 3; ++ci) {
      assembler.rowptr[3 * a + ci] = 9 * nb + ci * 3 * d;
      for (PetscInt k = 0; k < d; ++k)
        for (int e = 0; e < 3; ++e) assembler.cols[9 * nb + ci * 3 * d + 3 * k + e] = static_cast<PetscInt>(3 * assembler.node_cols[nb + k] + e);
    }
  }
  assembler.rowptr[3 * n] = static_cast<PetscInt>(assembler.cols.size());
}

void MechanicsSolver::Impl::setup_vectors() {
  std::vector<PetscInt> ghosts;
  for (int k = lm.n_owned; k < lm.n_local(); ++k) ghosts.push_back(static_cast<PetscInt>(lm.global[k]));
  UGS_PETSC(VecCreateGhostBlock(lm.comm, 3, 3 * lm.n_owned, 3 * lm.n_global_nodes, static_cast<PetscInt>(ghosts.size()),
                                ghosts.data(), &u));
  UGS_PETSC(VecDuplicate(u, &u_save));
  UGS_PETSC(VecDuplicate(u, &u_step));
  newton.predictor.setup(u);
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

}  // namespace ugs::mech
