#include "saddle_system.hpp"

#include "petsc_call.hpp"
#include "ugs/contact/dof_mask.hpp"

#define CHK UGS_CONTACT_PETSC

namespace ugs::contact::detail {

SaddleSystem::~SaddleSystem() {
  for (Mat* a : {&Ct, &C, &B, &D})
    if (*a) MatDestroy(a);
  for (Vec* v : {&dl, &fc})
    if (*v) VecDestroy(v);
}

void SaddleSystem::create(const mech::CouplingContext& c, const PairDistribution& pd) {
  const int m = pd.m;
  const PetscInt n3 = 3 * c.n_owned, m3 = 3 * m;
  // C^T (multiplier rows, constant) and the pattern of B: both twins' free components.
  auto owned_col = [&](std::int64_t gnode) { return gnode >= c.node_begin && gnode < c.node_begin + c.n_owned; };
  std::vector<PetscInt> dnz(m3, 0), onz(m3, 0);
  for (int q = 0; q < m; ++q)
    for (int j = 0; j < 3; ++j) {
      const PairData& d = pd.pairs[q];
      for (int k = 0; k < 3; ++k) {
        if (is_free(d.fixed1, k)) ++(owned_col(d.g1) ? dnz : onz)[3 * q + j];
        if (is_free(d.fixed2, k)) ++(owned_col(d.g2) ? dnz : onz)[3 * q + j];
      }
    }
  CHK(MatCreateAIJ(c.comm, m3, n3, PETSC_DETERMINE, PETSC_DETERMINE, 0, dnz.data(), 0, onz.data(), &Ct));
  CHK(MatCreateAIJ(c.comm, m3, n3, PETSC_DETERMINE, PETSC_DETERMINE, 0, dnz.data(), 0, onz.data(), &B));
  for (int q = 0; q < m; ++q) {
    const PairData& d = pd.pairs[q];
    for (int j = 0; j < 3; ++j) {
      const PetscInt row = static_cast<PetscInt>(3 * (pd.first + q) + j);
      PetscInt cols[6];
      double vals[6], zeros[6] = {0, 0, 0, 0, 0, 0};
      int n = 0;
      for (int k = 0; k < 3; ++k)
        if (is_free(d.fixed1, k)) cols[n] = static_cast<PetscInt>(3 * d.g1 + k), vals[n++] = -d.area * d.R[3 * k + j];
      for (int k = 0; k < 3; ++k)
        if (is_free(d.fixed2, k)) cols[n] = static_cast<PetscInt>(3 * d.g2 + k), vals[n++] = d.area * d.R[3 * k + j];
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
  CHK(MatCreateAIJ(c.comm, m3, m3, PETSC_DETERMINE, PETSC_DETERMINE, 3, nullptr, 0, nullptr, &D));
  for (int q = 0; q < m; ++q) {
    const PetscInt r0 = static_cast<PetscInt>(3 * (pd.first + q));
    const PetscInt rows[3] = {r0, r0 + 1, r0 + 2};
    const double zeros[9] = {};
    CHK(MatSetValues(D, 3, rows, 3, rows, zeros, INSERT_VALUES));
  }
  CHK(MatAssemblyBegin(D, MAT_FINAL_ASSEMBLY));
  CHK(MatAssemblyEnd(D, MAT_FINAL_ASSEMBLY));
  CHK(MatSetOption(D, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  CHK(MatCreateVecs(C, &dl, &fc));
}

void SaddleSystem::subtract_coupling_force(const PairDistribution& pd, const std::vector<std::array<double, 3>>& lam, Vec r) {
  PetscScalar* a = nullptr;
  CHK(VecGetArray(dl, &a));
  for (int q = 0; q < pd.m; ++q)
    for (int j = 0; j < 3; ++j) a[3 * q + j] = lam[q][j] - pd.pairs[q].lam0[j];
  CHK(VecRestoreArray(dl, &a));
  CHK(MatMult(C, dl, fc));
  CHK(VecAXPY(r, -1.0, fc));
}

void SaddleSystem::fill(const PairDistribution& pd, const std::vector<PairEquations>& eq) {
  for (int q = 0; q < pd.m; ++q) {
    const PairData& d = pd.pairs[q];
    const PairEquations& e = eq[q];
    const PetscInt r0 = static_cast<PetscInt>(3 * (pd.first + q));
    for (int j = 0; j < 3; ++j) {
      // dF_j/du2_k = sum_i Jg[j][i] R[k][i], dF_j/du1_k = -(same).
      PetscInt cols[6];
      double vals[6];
      int n = 0;
      double w[3];
      for (int k = 0; k < 3; ++k) w[k] = e.Jg[3 * j] * d.R[3 * k] + e.Jg[3 * j + 1] * d.R[3 * k + 1] + e.Jg[3 * j + 2] * d.R[3 * k + 2];
      for (int k = 0; k < 3; ++k)
        if (is_free(d.fixed1, k)) cols[n] = static_cast<PetscInt>(3 * d.g1 + k), vals[n++] = -w[k];
      for (int k = 0; k < 3; ++k)
        if (is_free(d.fixed2, k)) cols[n] = static_cast<PetscInt>(3 * d.g2 + k), vals[n++] = w[k];
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

}  // namespace ugs::contact::detail
