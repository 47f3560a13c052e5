// The predictor of the first Newton correction: Galerkin projection on earlier increments
// (solver_impl.hpp).
#include "solver_impl.hpp"

namespace ugs::mech {

Predictor::~Predictor() {
  if (aw_) VecDestroy(&aw_);
  for (Vec& v : basis_) VecDestroy(&v);
}

void Predictor::release() {
  for (Vec& v : basis_) UGS_PETSC(VecDestroy(&v));
  basis_.clear();
  weight_.clear();
}

void Predictor::setup(Vec u) {
  like_ = u;
  UGS_PETSC(VecDuplicate(u, &aw_));
}

double Predictor::projection_residual(Mat A, Vec r, Vec du) {
  const int m = static_cast<int>(basis_.size());
  std::vector<PetscScalar> c(m);
  UGS_PETSC(VecMDot(r, m, basis_.data(), c.data()));
  UGS_PETSC(VecSet(du, 0.0));
  UGS_PETSC(VecMAXPY(du, m, c.data(), basis_.data()));
  // The residual the first Krylov iterate starts from, r - A du0, relative to r.
  PetscReal rn = 0, pn = 0;
  UGS_PETSC(MatMult(A, du, aw_));
  UGS_PETSC(VecAYPX(aw_, -1.0, r));
  UGS_PETSC(VecNorm(r, NORM_2, &rn));
  UGS_PETSC(VecNorm(aw_, NORM_2, &pn));
  return rn > 0 ? pn / rn : 0.0;
}

bool Predictor::predict(Mat A, Vec r, Vec du) {
  predicted_ = -1;
  if (basis_.empty()) return false;
  PetscLogEventBegin(events().predictor, 0, 0, 0, 0);
  // W is A-orthonormal for the matrix of the last preconditioner setup. When the matrix has
  // changed much since (elements reloading past sigma_max soften by c_R), the projection can be
  // far off: on the V1 column, unloading after the reload past sigma_max, it started the Krylov
  // solve from 1.3e9 times the residual, which then diverged (DIVERGED_DTOL) and forced a
  // sub-step. A prediction must reduce the residual; if it does not, the basis is made
  // A-orthonormal for the current matrix and the projection tried once more, else dropped.
  double rel = projection_residual(A, r, du);
  if (!(rel < 1.0)) {
    refresh(A);
    rel = basis_.empty() ? INFINITY : projection_residual(A, r, du);
  }
  PetscLogEventEnd(events().predictor, 0, 0, 0, 0);
  if (!(rel < 1.0)) {
    UGS_PETSC(VecSet(du, 0.0));
    predicted_ = INFINITY;
    return false;
  }
  predicted_ = rel;
  return true;
}

void Predictor::refresh(Mat A) {
  const int m = static_cast<int>(basis_.size());
  if (m == 0) return;
  PetscLogEventBegin(events().predictor, 0, 0, 0, 0);
  // G = W^T A W, one column per product A w_j (in aw_: A W is not kept, kRecycle vectors less).
  Eigen::MatrixXd G(m, m);
  std::vector<PetscScalar> dots(m);
  for (int j = 0; j < m; ++j) {
    UGS_PETSC(MatMult(A, basis_[j], aw_));
    UGS_PETSC(VecMDot(aw_, m, basis_.data(), dots.data()));
    for (int i = 0; i < m; ++i) G(i, j) = dots[i];
  }
  G = 0.5 * (G + G.transpose());
  // W <- W V diag(lambda)^-1/2 over the eigenpairs above a cutoff (drops dependent directions).
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(G);
  const Eigen::VectorXd lam = es.eigenvalues();
  // coef[t]: the combination of the old directions that gives new direction t (largest eigenvalue first).
  std::vector<std::vector<PetscScalar>> coef;
  std::vector<double> weight;  // the old directions' weights carried over by the rotation
  for (int k = m - 1; k >= 0; --k) {
    if (!(lam(k) > 1e-10 * lam(m - 1))) break;
    std::vector<PetscScalar> ck(m);
    double wk = 0;
    for (int i = 0; i < m; ++i) {
      ck[i] = es.eigenvectors()(i, k) / std::sqrt(lam(k));
      wk += weight_[static_cast<std::size_t>(i)] * es.eigenvectors()(i, k) * es.eigenvectors()(i, k);
    }
    coef.push_back(std::move(ck));
    weight.push_back(wk);
  }
  combine_in_place(coef);
  weight_ = std::move(weight);
  PetscLogEventEnd(events().predictor, 0, 0, 0, 0);
}

void Predictor::combine_in_place(const std::vector<std::vector<PetscScalar>>& coef) {
  const int m = static_cast<int>(basis_.size()), kept = static_cast<int>(coef.size());
  PetscInt n = 0;
  UGS_PETSC(VecGetLocalSize(basis_[0], &n));
  std::vector<PetscScalar*> w(m);
  for (int i = 0; i < m; ++i) UGS_PETSC(VecGetArray(basis_[i], &w[i]));
  // Block by block of the local entries: the new directions' block is VecMAXPY of the old
  // directions' block (sequential views on it), computed in full before it overwrites them. The
  // kernels work entry by entry (loops, or a BLAS axpy whose vector loop takes groups of entries
  // counted from the start: kBlock is a multiple of them), so every entry gets the bits of
  // VecMAXPY on the whole vectors, without a second basis in memory (kRecycle vectors of the size of u).
  static constexpr PetscInt kBlock = 4096;
  std::vector<PetscScalar> fresh(static_cast<std::size_t>(kept) * kBlock);
  // Blocks [lo, lo + len) for lo in [from, to), all of length len.
  auto run = [&](PetscInt from, PetscInt to, PetscInt len) {
    if (from >= to) return;
    std::vector<Vec> olds(m), news(kept);
    for (int i = 0; i < m; ++i) UGS_PETSC(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, len, nullptr, &olds[i]));
    for (int t = 0; t < kept; ++t)
      UGS_PETSC(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, len, fresh.data() + static_cast<std::size_t>(t) * kBlock, &news[t]));
    for (PetscInt lo = from; lo < to; lo += len) {
      for (int i = 0; i < m; ++i) UGS_PETSC(VecPlaceArray(olds[i], w[i] + lo));
      for (int t = 0; t < kept; ++t) {
        UGS_PETSC(VecSet(news[t], 0.0));
        UGS_PETSC(VecMAXPY(news[t], m, coef[t].data(), olds.data()));
      }
      for (int i = 0; i < m; ++i) UGS_PETSC(VecResetArray(olds[i]));
      for (int t = 0; t < kept; ++t) std::copy_n(fresh.data() + static_cast<std::size_t>(t) * kBlock, len, w[t] + lo);
    }
    for (Vec& v : olds) UGS_PETSC(VecDestroy(&v));
    for (Vec& v : news) UGS_PETSC(VecDestroy(&v));
  };
  const PetscInt whole = n / kBlock * kBlock;
  run(0, whole, kBlock);
  run(whole, n, n - whole);
  for (int i = 0; i < m; ++i) UGS_PETSC(VecRestoreArray(basis_[i], &w[i]));
  // The directions beyond the kept ones (dependent) go.
  for (int i = kept; i < m; ++i) UGS_PETSC(VecDestroy(&basis_[i]));
  basis_.resize(kept);
}

void Predictor::remember(Mat A, Vec v) {
  // A v in aw_, recomputed after each Gram-Schmidt pass (two products more per step instead of
  // keeping A W: kRecycle vectors of the size of u).
  UGS_PETSC(MatMult(A, v, aw_));
  PetscScalar n0 = 0;
  UGS_PETSC(VecDot(v, aw_, &n0));
  if (!(n0 > 0)) {
    UGS_PETSC(VecDestroy(&v));
    return;
  }
  const int m = static_cast<int>(basis_.size());
  for (int pass = 0; pass < 2 && m > 0; ++pass) {
    std::vector<PetscScalar> c(m);
    UGS_PETSC(VecMDot(aw_, m, basis_.data(), c.data()));  // W^T A v
    // The increment's energy along each direction (first pass: the second only removes rounding).
    if (pass == 0)
      for (int i = 0; i < m; ++i) weight_[static_cast<std::size_t>(i)] = kDecay * weight_[static_cast<std::size_t>(i)] + c[i] * c[i];
    for (auto& x : c) x = -x;
    UGS_PETSC(VecMAXPY(v, m, c.data(), basis_.data()));
    UGS_PETSC(MatMult(A, v, aw_));
  }
  PetscScalar n1 = 0;
  UGS_PETSC(VecDot(v, aw_, &n1));
  if (!(n1 > 1e-14 * n0)) {
    UGS_PETSC(VecDestroy(&v));
    return;
  }
  UGS_PETSC(VecScale(v, 1.0 / std::sqrt(n1)));
  // Full: the direction the recent increments used least goes. Dropping the oldest instead (until
  // 2026-11-29) lost the dominant directions, against which every later one was orthogonalized:
  // the seasonal storage months of the scale-0.1 box were predicted to only 0.1-0.9 of their residual.
  if (static_cast<int>(basis_.size()) == kRecycle) {
    const auto least = std::min_element(weight_.begin(), weight_.end());
    if (n1 <= *least) {
      UGS_PETSC(VecDestroy(&v));
      return;
    }
    const auto i = least - weight_.begin();
    UGS_PETSC(VecDestroy(&basis_[static_cast<std::size_t>(i)]));
    basis_.erase(basis_.begin() + i);
    weight_.erase(least);
  }
  basis_.push_back(v);
  weight_.push_back(n1);
}

}  // namespace ugs::mech
