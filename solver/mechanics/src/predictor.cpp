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
  // G = W^T A W, one column per product A w_j (in aw_: A W is not kept, 24 vectors less).
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
  std::vector<Vec> nb;
  for (int k = m - 1; k >= 0; --k) {
    if (!(lam(k) > 1e-10 * lam(m - 1))) break;
    Vec w;
    UGS_PETSC(VecDuplicate(like_, &w));
    std::vector<PetscScalar> coef(m);
    for (int i = 0; i < m; ++i) coef[i] = es.eigenvectors()(i, k) / std::sqrt(lam(k));
    UGS_PETSC(VecSet(w, 0.0));
    UGS_PETSC(VecMAXPY(w, m, coef.data(), basis_.data()));
    nb.push_back(w);
  }
  for (Vec& v : basis_) UGS_PETSC(VecDestroy(&v));
  basis_ = std::move(nb);
  PetscLogEventEnd(events().predictor, 0, 0, 0, 0);
}

void Predictor::remember(Mat A, Vec v) {
  // A v in aw_, recomputed after each Gram-Schmidt pass (two products more per step instead of
  // keeping A W: 24 vectors of the size of u).
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
  if (static_cast<int>(basis_.size()) == kRecycle) {
    UGS_PETSC(VecDestroy(&basis_.front()));
    basis_.erase(basis_.begin());
  }
  basis_.push_back(v);
}

}  // namespace ugs::mech
