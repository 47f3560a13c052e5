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

double SaddleGuess::form(Mat J, Vec b, Vec x, bool same_operator) {
  CHK(VecSet(x, 0.0));
  const int k = static_cast<int>(x_.size());
  if (k == 0) return 1.0;
  if (!same_operator) have_y_.assign(k, false);
  if (!w_) CHK(VecDuplicate(b, &w_));
  std::vector<PetscScalar> dots(k);
  for (int j = 0; j < k; ++j) {
    if (have_y_[j]) continue;
    CHK(MatMult(J, x_[j], y_[j]));
    ++products_;
  }
  // The Gram matrix's rows and columns of the new products (one dot per pair: symmetric as built).
  for (int j = 0; j < k; ++j) {
    if (have_y_[j]) continue;
    CHK(VecMDot(y_[j], k, y_.data(), dots.data()));
    for (int i = 0; i < k; ++i) gram_[i][j] = gram_[j][i] = dots[i];
  }
  have_y_.assign(k, true);
  Eigen::MatrixXd G(k, k);
  Eigen::VectorXd g(k);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) G(i, j) = gram_[i][j];
  CHK(VecMDot(b, k, y_.data(), dots.data()));
  for (int i = 0; i < k; ++i) g(i) = dots[i];
  // Pseudo-inverse over the eigenpairs above a cutoff: the stored solutions are nearly dependent
  // (the same seasonal shape), and the dropped directions add nothing to the residual reduction.
  // (Scaled to a unit diagonal, the normal equations kept the small corrections' directions and
  // halved a production month's iterations on the coarsened history, but tripled those of the
  // months after a turning point: 2026-11-27.)
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
  Vec v, y;
  if (static_cast<int>(x_.size()) == kKeep) {  // the oldest goes, its vectors are reused
    v = x_.front(), y = y_.front();
    x_.erase(x_.begin()), y_.erase(y_.begin()), have_y_.erase(have_y_.begin());
    gram_.erase(gram_.begin());
    for (auto& row : gram_) row.erase(row.begin());
  } else {
    CHK(VecDuplicate(x, &v));
    CHK(VecDuplicate(x, &y));
  }
  CHK(VecCopy(x, v));
  x_.push_back(v), y_.push_back(y), have_y_.push_back(false);
  for (auto& row : gram_) row.push_back(0.0);
  gram_.emplace_back(x_.size(), 0.0);
}

}  // namespace ugs::contact::detail
