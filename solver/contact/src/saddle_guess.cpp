#include "saddle_guess.hpp"

#include <Eigen/Dense>

#include "petsc_call.hpp"

#define CHK UGS_CONTACT_PETSC

namespace ugs::contact::detail {

SaddleGuess::~SaddleGuess() {
  for (auto* v : {&x_, &y_})
    for (Vec& x : *v) VecDestroy(&x);
  if (w_) VecDestroy(&w_);
}

double SaddleGuess::form(Mat J, Vec b, Vec x) {
  CHK(VecSet(x, 0.0));
  const int k = static_cast<int>(x_.size());
  if (k == 0) return 1.0;
  while (static_cast<int>(y_.size()) < k) {
    Vec y;
    CHK(VecDuplicate(b, &y));
    y_.push_back(y);
  }
  if (!w_) CHK(VecDuplicate(b, &w_));
  for (int j = 0; j < k; ++j) CHK(MatMult(J, x_[j], y_[j]));
  Eigen::MatrixXd G(k, k);
  Eigen::VectorXd g(k);
  std::vector<PetscScalar> dots(k);
  for (int j = 0; j < k; ++j) {
    CHK(VecMDot(y_[j], k, y_.data(), dots.data()));
    for (int i = 0; i < k; ++i) G(i, j) = dots[i];
  }
  CHK(VecMDot(b, k, y_.data(), dots.data()));
  for (int i = 0; i < k; ++i) g(i) = dots[i];
  G = 0.5 * (G + G.transpose());
  // Pseudo-inverse over the eigenpairs above a cutoff: the stored solutions are nearly dependent
  // (the same seasonal shape), and the dropped directions add nothing to the residual reduction.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(G);
  const Eigen::VectorXd lam = es.eigenvalues();
  Eigen::VectorXd c = Eigen::VectorXd::Zero(k);
  for (int e = 0; e < k; ++e)
    if (lam(e) > 1e-12 * lam(k - 1)) c += es.eigenvectors().col(e) * (es.eigenvectors().col(e).dot(g) / lam(e));
  std::vector<PetscScalar> cc(c.data(), c.data() + k), mc(k);
  for (int i = 0; i < k; ++i) mc[i] = -cc[i];
  CHK(VecCopy(b, w_));
  CHK(VecMAXPY(w_, k, mc.data(), y_.data()));
  PetscReal bn = 0, wn = 0;
  CHK(VecNorm(b, NORM_2, &bn));
  CHK(VecNorm(w_, NORM_2, &wn));
  if (!(bn > 0) || !(wn < bn)) return 1.0;  // no reduction: start from zero
  CHK(VecMAXPY(x, k, cc.data(), x_.data()));
  return wn / bn;
}

void SaddleGuess::remember(Vec x) {
  Vec v;
  if (static_cast<int>(x_.size()) == kKeep) {
    v = x_.front();
    x_.erase(x_.begin());
  } else {
    CHK(VecDuplicate(x, &v));
  }
  CHK(VecCopy(x, v));
  x_.push_back(v);
}

}  // namespace ugs::contact::detail
