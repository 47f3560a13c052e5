// Loads, residual and tangent assembly of the mechanics solver (solver_impl.hpp).
#include "solver_impl.hpp"

// PetscObjectStateGet (an advanced-level function PETSc declares with its object internals): whether
// u changed since the last residual.
#include <petsc/private/petscimpl.h>

namespace ugs::mech {

void MechanicsSolver::Impl::external_force(const std::vector<double>& dp) {
  // The constant boundary-traction load (boundary_traction.cpp; zero without [[boundary_traction]]).
  for (int a = 0; a < lm.n_owned; ++a)
    for (int k = 0; k < 3; ++k) fext[3 * a + k] = lm.traction[a][k];
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

double MechanicsSolver::Impl::load_norm() const {
  double sum = 0;
  for (int a = 0; a < lm.n_owned; ++a)
    for (int k = 0; k < 3; ++k)
      if (!owned_dof_fixed(a, k)) sum += fext[3 * a + k] * fext[3 * a + k];
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_DOUBLE, MPI_SUM, lm.comm);
  return std::sqrt(sum);
}

double MechanicsSolver::Impl::residual() {
  PetscLogEventBegin(events().residual, 0, 0, 0, 0);
  // The elements that are not hypo-plastic (nearly all of them) give the same forces as at the
  // last residual when u has not changed since: a step's first residual, where the step before
  // ended. Its state is read before the ghost update (which advances it) and kept after it.
  PetscObjectState state = 0;
  UGS_PETSC(PetscObjectStateGet(reinterpret_cast<PetscObject>(u), &state));
  const bool elastic_kept = fint_elastic_valid && state == fint_elastic_state;
  UGS_PETSC(VecGhostUpdateBegin(u, INSERT_VALUES, SCATTER_FORWARD));
  UGS_PETSC(VecGhostUpdateEnd(u, INSERT_VALUES, SCATTER_FORWARD));
  Vec ul;
  const PetscScalar* ua = nullptr;
  UGS_PETSC(VecGhostGetLocalForm(u, &ul));
  UGS_PETSC(VecGetArrayRead(ul, &ua));
  std::fill(fint.begin(), fint.end(), 0.0);
  if (!elastic_kept) fint_elastic.assign(fint.size(), 0.0);
  bool sat = false;
  for (std::size_t ci = 0; ci < lm.n_cells(); ++ci) {
    const int c = static_cast<int>(ci);
    const int h = hyp.of_cell[c];
    if (h < 0 && elastic_kept) continue;
    double ue[12];
    gather_element(ua, c, ue);
    const Vec6 eps = fem::tet4_strain(geo[c], ue);
    Vec6 ds;
    if (h < 0) {
      ds = elastic_stress(c, eps);
    } else {
      hyp.trial[h] = fem::hypo_update(lm.materials[lm.cell_material[c]], hyp.committed[h], start_sigma(h), eps,
                                  hyp.hold[h] == fem::Hold::None ? hyp.guess[h] : hyp.hold_dir[h], hyp.hold[h],
                                  fem::TangentForm::Consistent);
      hyp.trial_eps[h] = eps;
      ds = hyp.trial[h].dsig;
      sat = sat || hyp.trial[h].saturated;
    }
    double fe[12] = {};
    fem::tet4_add_internal_force(geo[c], ds, fe);
    add_owned(h < 0 ? fint_elastic : fint, c, fe);
  }
  for (std::size_t i = 0; i < fint.size(); ++i) fint[i] += fint_elastic[i];
  hyp.saturated = sat;
  UGS_PETSC(VecRestoreArrayRead(ul, &ua));
  UGS_PETSC(VecGhostRestoreLocalForm(u, &ul));
  UGS_PETSC(PetscObjectStateGet(reinterpret_cast<PetscObject>(u), &fint_elastic_state));
  fint_elastic_valid = true;
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

void MechanicsSolver::Impl::scatter(std::vector<double>& v, int c, const std::array<double, 144>& Ke, bool diag_too) {
  const auto& t = lm.cells[c];
  for (int i = 0; i < 4; ++i) {
    const int a = t[i];
    if (a >= lm.n_owned) continue;
    const PetscInt nb = assembler.node_ptr[a], d = assembler.node_ptr[a + 1] - nb;
    const std::int64_t* row = assembler.node_cols.data() + nb;
    for (int j = 0; j < 4; ++j) {
      const int b = t[j];
      const PetscInt k = static_cast<PetscInt>(std::lower_bound(row, row + d, lm.global[b]) - row);
      for (int ci = 0; ci < 3; ++ci) {
        if (diag_too && i == j) assembler.diag_scale[3 * a + ci] += Ke[(3 * i + ci) * 12 + 3 * j + ci];
        if ((lm.fixed[a] >> ci) & 1) continue;
        double* dst = v.data() + 9 * nb + ci * 3 * d + 3 * k;
        for (int e = 0; e < 3; ++e)
          if (!((lm.fixed[b] >> e) & 1)) dst[e] += Ke[(3 * i + ci) * 12 + 3 * j + e];
      }
    }
  }
}

void MechanicsSolver::Impl::set_constrained_diagonal(std::vector<double>& v) const {
  for (int a = 0; a < lm.n_owned; ++a) {
    if (!lm.fixed[a]) continue;
    const PetscInt nb = assembler.node_ptr[a], d = assembler.node_ptr[a + 1] - nb;
    const std::int64_t* row = assembler.node_cols.data() + nb;
    const PetscInt k = static_cast<PetscInt>(std::lower_bound(row, row + d, lm.global[a]) - row);
    for (int ci = 0; ci < 3; ++ci)
      if ((lm.fixed[a] >> ci) & 1) {
        const double s = assembler.diag_scale[3 * a + ci];
        v[9 * nb + ci * 3 * d + 3 * k + ci] = s > 0 ? s : 1.0;
      }
  }
}

void MechanicsSolver::Impl::assemble() {
  bool changed = !assembler.mat_created;
  if (!assembler.have_lin) {
    assembler.vals_lin.assign(assembler.cols.size(), 0.0);
    assembler.diag_scale.assign(3 * lm.n_owned, 0.0);
    for (std::size_t ci = 0; ci < lm.n_cells(); ++ci) {
      const int c = static_cast<int>(ci);
      if (hyp.of_cell[c] >= 0) {
        scatter_dummy_diag(c);
        continue;
      }
      scatter(assembler.vals_lin, c, fem::tet4_stiffness(geo[c], elastic_D(c)), true);
    }
    set_constrained_diagonal(assembler.vals_lin);  // (scatter never touches prescribed rows or columns)
    assembler.have_lin = true;
  }
  // Every element whose tangent changed adds the difference of its stiffness: Newton's own
  // tangent, not a quasi-Newton one. (Until 2026-11-27 only the elements whose tangent moved by
  // more than 0.5 % were updated: on small steps Newton then converged linearly, at about that
  // rate, and the faulted history's production months took 4 Newton iterations instead of 2;
  // docs/mechanics.md "Assembly".) A full assembly every kFullAssemblyEvery updates keeps the
  // sums fresh.
  const bool full = changed || assembler.updates_since_full >= Assembler::kFullAssemblyEvery;
  std::vector<std::int32_t> stale;
  for (std::size_t h = 0; h < hyp.cells.size(); ++h) {
    if (std::memcmp(tangent(h).data(), assembler.assembled_Dt[h].data(), sizeof(fem::Mat6)) == 0) continue;
    if (full) {
      changed = true;
      break;
    }
    stale.push_back(static_cast<std::int32_t>(h));
  }
  int mine = changed || !stale.empty() ? 1 : 0, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, lm.comm);
  if (!any) return;
  PetscLogEventBegin(events().assembly, 0, 0, 0, 0);
  if (full) upload_linear();
  assembler.in_place.bind(A);
  if (full) {
    for (std::size_t h = 0; h < hyp.cells.size(); ++h) {
      add_to_matrix(hyp.cells[h], fem::tet4_stiffness(geo[hyp.cells[h]], tangent(h)));
      assembler.assembled_Dt[h] = tangent(h);
      assembler.assembled_phase[h] = static_cast<std::int8_t>(hyp.trial[h].phase);
    }
    assembler.updates_since_full = 0;
  } else {
    for (const auto h : stale) {
      fem::Mat6 dD;
      for (int i = 0; i < 36; ++i) dD[i] = tangent(h)[i] - assembler.assembled_Dt[h][i];
      add_to_matrix(hyp.cells[h], fem::tet4_stiffness(geo[hyp.cells[h]], dD));
      assembler.assembled_Dt[h] = tangent(h);
      assembler.assembled_phase[h] = static_cast<std::int8_t>(hyp.trial[h].phase);
    }
    ++assembler.updates_since_full;
  }
  if (has_hyp) {  // (a linear A is complete once created)
    UGS_PETSC(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    UGS_PETSC(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  assembler.mat_changed = true;
  if (!has_hyp) release_pattern();  // the matrix can never change
  PetscLogEventEnd(events().assembly, 0, 0, 0, 0);
}

void MechanicsSolver::Impl::scatter_dummy_diag(int c) {
  const fem::Material& m = lm.materials[lm.cell_material[c]];
  fem::Mat6 D;
  const double ic = 1e6 / m.hypo.cm(s0[c]);
  for (int i = 0; i < 36; ++i) D[i] = m.Dhat[i] * ic;
  const auto Ke = fem::tet4_stiffness(geo[c], D);
  const auto& t = lm.cells[c];
  for (int i = 0; i < 4; ++i)
    if (t[i] < lm.n_owned)
      for (int ci = 0; ci < 3; ++ci) assembler.diag_scale[3 * t[i] + ci] += Ke[(3 * i + ci) * 12 + 3 * i + ci];
}

void MechanicsSolver::Impl::release_pattern() {
  std::vector<double>().swap(assembler.vals_lin);
  std::vector<PetscInt>().swap(assembler.cols);
  std::vector<PetscInt>().swap(assembler.rowptr);
  std::vector<std::int64_t>().swap(assembler.node_cols);
  std::vector<PetscInt>().swap(assembler.node_ptr);
}

void MechanicsSolver::Impl::upload_linear() {
  const PetscInt m = 3 * lm.n_owned;
  if (!assembler.mat_created) {
    UGS_PETSC(MatCreate(lm.comm, &A));
    UGS_PETSC(MatSetSizes(A, m, m, PETSC_DETERMINE, PETSC_DETERMINE));
    UGS_PETSC(MatSetBlockSize(A, 3));
    if (hypre_owns_matrix()) {
      // BoomerAMG works on hypre's own matrix: built there directly, A is that matrix and PCHYPRE
      // uses it as it is, instead of converting a PETSc copy (one matrix in memory, not two).
      UGS_PETSC(MatSetType(A, MATHYPRE));
      std::vector<PetscInt> dnnz(m, 0), onnz(m, 0);
      const PetscInt lo = 3 * static_cast<PetscInt>(lm.node_begin), hi = lo + m;
      for (PetscInt i = 0; i < m; ++i)
        for (PetscInt k = assembler.rowptr[i]; k < assembler.rowptr[i + 1]; ++k) ++(assembler.cols[k] >= lo && assembler.cols[k] < hi ? dnnz[i] : onnz[i]);
      // Every row is set once, whole and sorted (MAT_SORTED_FULL): on several processes hypre then
      // writes the values straight into its matrix instead of first into a row buffer of its own
      // (~16 B per nonzero more at the peak, mhypre.c), and PETSc's MatAssemblyEnd gives the
      // assembled matrix no new 30-entry row buffer per row (~0.4 kB a row, kept as long as the
      // matrix) for the values set later, which hypre writes in place anyway.
      UGS_PETSC(MatSetOption(A, MAT_SORTED_FULL, PETSC_TRUE));
      UGS_PETSC(MatHYPRESetPreallocation(A, 0, dnnz.data(), 0, onnz.data()));
      for (PetscInt i = 0; i < m; ++i) {
        const PetscInt row = lo + i;
        UGS_PETSC(MatSetValues(A, 1, &row, assembler.rowptr[i + 1] - assembler.rowptr[i], assembler.cols.data() + assembler.rowptr[i], assembler.vals_lin.data() + assembler.rowptr[i],
                               INSERT_VALUES));
      }
      // hypre holds the values now: the arrays go before hypre's assembly, which needs as much
      // again (the peak of the process); a hypo-plastic model keeps the rows it resets.
      if (has_hyp) compact_reset_rows();
      else release_pattern();
      UGS_PETSC(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
      UGS_PETSC(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
    } else {
      UGS_PETSC(MatSetType(A, MATAIJ));
      if (lm.size == 1) {
        UGS_PETSC(MatSeqAIJSetPreallocationCSR(A, assembler.rowptr.data(), assembler.cols.data(), assembler.vals_lin.data()));
      } else {
        UGS_PETSC(MatMPIAIJSetPreallocationCSR(A, assembler.rowptr.data(), assembler.cols.data(), assembler.vals_lin.data()));
      }
      UGS_PETSC(MatSetOption(A, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
    }
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
    assembler.mat_created = true;
    if (has_hyp && opt.linear != LinearSolver::Cholmod && !assembler.rowptr.empty()) compact_reset_rows();
  } else {
    // The rows hypo-plastic elements add to back to the elastic part (the others never change);
    // the hypo-plastic elements are added after this flush (INSERT and ADD cannot be mixed
    // between assemblies).
    // compact_reset_rows freed the full pattern (rowptr) and kept those rows; else (CHOLMOD) all rows.
    const Assembler& as = assembler;
    const bool compacted = as.rowptr.empty();
    const std::vector<PetscInt>& ptr = compacted ? as.reset_ptr : as.rowptr;
    const std::vector<PetscInt>& cols = compacted ? as.reset_cols : as.cols;
    const std::vector<double>& vals = compacted ? as.reset_vals : as.vals_lin;
    const std::size_t n = compacted ? as.reset_row.size() : static_cast<std::size_t>(m);
    for (std::size_t r = 0; r < n; ++r) {
      const PetscInt row = static_cast<PetscInt>(3 * lm.node_begin) + (compacted ? as.reset_row[r] : static_cast<PetscInt>(r));
      UGS_PETSC(MatSetValues(A, 1, &row, ptr[r + 1] - ptr[r], cols.data() + ptr[r], vals.data() + ptr[r], INSERT_VALUES));
    }
    // (MATHYPRE has no flush; its assembly of an assembled matrix only ends the insertion, the
    // values are already in place.)
    PetscBool is_hypre = PETSC_FALSE;
    UGS_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A), MATHYPRE, &is_hypre));
    const MatAssemblyType flush = is_hypre ? MAT_FINAL_ASSEMBLY : MAT_FLUSH_ASSEMBLY;
    UGS_PETSC(MatAssemblyBegin(A, flush));
    UGS_PETSC(MatAssemblyEnd(A, flush));
  }
}

// Once A holds the elastic part, only the rows of the hypo-plastic elements' owned nodes are ever
// reset (upload_linear); the rest of the pattern and elastic values (12-13 bytes per nonzero, as
// much as A itself) is freed: on the scale-0.1 history box 24 % of the rows are kept.
void MechanicsSolver::Impl::compact_reset_rows() {
  std::vector<char> touched(lm.n_owned, 0);
  for (const int c : hyp.cells)
    for (const int a : lm.cells[c])
      if (a < lm.n_owned) touched[a] = 1;
  Assembler& as = assembler;
  as.reset_row.clear();
  as.reset_ptr.assign(1, 0);
  for (int a = 0; a < lm.n_owned; ++a) {
    if (!touched[a]) continue;
    for (int ci = 0; ci < 3; ++ci) {
      const PetscInt i = 3 * a + ci;
      as.reset_row.push_back(i);
      as.reset_ptr.push_back(as.reset_ptr.back() + as.rowptr[i + 1] - as.rowptr[i]);
    }
  }
  as.reset_cols.resize(as.reset_ptr.back());
  as.reset_vals.resize(as.reset_ptr.back());
  for (std::size_t r = 0; r < as.reset_row.size(); ++r) {
    const PetscInt i = as.reset_row[r];
    std::copy(as.cols.begin() + as.rowptr[i], as.cols.begin() + as.rowptr[i + 1], as.reset_cols.begin() + as.reset_ptr[r]);
    std::copy(as.vals_lin.begin() + as.rowptr[i], as.vals_lin.begin() + as.rowptr[i + 1], as.reset_vals.begin() + as.reset_ptr[r]);
  }
  release_pattern();
}

void MechanicsSolver::Impl::add_to_matrix(int c, const std::array<double, 144>& Ke) {
  const auto& t = lm.cells[c];
  PetscInt rows[12], cols[12];  // negative: left out (PETSc skips negative indices)
  for (int i = 0; i < 4; ++i)
    for (int ci = 0; ci < 3; ++ci) {
      const bool fixed = (lm.fixed[t[i]] >> ci) & 1;
      const PetscInt g = static_cast<PetscInt>(3 * lm.global[t[i]] + ci);
      cols[3 * i + ci] = fixed ? -1 : g;
      rows[3 * i + ci] = fixed || t[i] >= lm.n_owned ? -1 : g;
    }
  if (assembler.in_place.bound()) {
    // Row by row straight into hypre's arrays; a row the writer cannot place (it adds nothing
    // then) goes through PETSc, which reports what is wrong with it.
    for (int r = 0; r < 12; ++r)
      if (rows[r] >= 0 && !assembler.in_place.add(rows[r], 12, cols, Ke.data() + 12 * r))
        UGS_PETSC(MatSetValues(A, 1, rows + r, 12, cols, Ke.data() + 12 * r, ADD_VALUES));
    return;
  }
  UGS_PETSC(MatSetValues(A, 12, rows, 12, cols, Ke.data(), ADD_VALUES));
}

}  // namespace ugs::mech
