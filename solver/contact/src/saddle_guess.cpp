#include "saddle_guess.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "petsc_call.hpp"

#define CHK UGS_CONTACT_PETSC

namespace ugs::contact::detail {

SaddleGuess::~SaddleGuess() {
  for (auto* v : {&x_, &y_})
    for (Vec& x : *v) VecDestroy(&x);
  if (w_) VecDestroy(&w_);
}

namespace {

// c minimising || b - Y c || through the normal equations G c = g (G = Y^T Y, g = Y^T b): the
// pseudo-inverse over the eigenpairs above 1e-12 of the largest. Scaled, the eigenpairs are those
// of D G D with D = diag(G)^-1/2 (every stored solution of unit product), so that a small
// solution's direction is judged by its own size, not by the largest one's.
Eigen::VectorXd coefficients(const Eigen::MatrixXd& G, const Eigen::VectorXd& g, bool scaled) {
  const int k = static_cast<int>(G.rows());
  Eigen::VectorXd d = Eigen::VectorXd::Ones(k);
  if (scaled)
    for (int i = 0; i < k; ++i) d(i) = G(i, i) > 0 ? 1 / std::sqrt(G(i, i)) : 0.0;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(d.asDiagonal() * G * d.asDiagonal());
  const Eigen::VectorXd lam = es.eigenvalues();
  const Eigen::VectorXd gs = d.cwiseProduct(g);
  Eigen::VectorXd c = Eigen::VectorXd::Zero(k);
  for (int e = 0; e < k; ++e)
    if (lam(e) > 1e-12 * lam(k - 1)) c += es.eigenvectors().col(e) * (es.eigenvectors().col(e).dot(gs) / lam(e));
  return d.cwiseProduct(c);
}

}  // namespace

double SaddleGuess::form(Mat J, Vec b, Vec x, bool same_operator, double enough) {
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
  PetscReal bn = 0;
  CHK(VecNorm(b, NORM_2, &bn));
  // ||b - Y c|| for coefficients c, from the kept products.
  auto residual_of = [&](const Eigen::VectorXd& c) {
    std::vector<PetscScalar> mc(k);
    for (int i = 0; i < k; ++i) mc[i] = -c(i);
    CHK(VecCopy(b, w_));
    CHK(VecMAXPY(w_, k, mc.data(), y_.data()));
    PetscReal wn = 0;
    CHK(VecNorm(w_, NORM_2, &wn));
    return wn;
  };
  auto combine = [&](const Eigen::VectorXd& c) {
    std::vector<PetscScalar> cc(c.data(), c.data() + k);
    CHK(VecMAXPY(x, k, cc.data(), x_.data()));
  };
  // The stored solutions are nearly dependent (a month's increment repeats last month's shape),
  // and the Newton corrections of a nonlinear month are ~1e-3 of the increments: with the
  // eigenvalue cutoff relative to the largest product their directions fall below it. So when
  // the plain projection leaves more than the solve's target, the normal equations scaled to a
  // unit diagonal are tried too, and taken when they claim to halve the residual and the true
  // residual (one more product: a scaled direction may be resolved below the products' round-off)
  // confirms it. Thesis scale, 12 production months from 1960: 179 -> 113 field-split iterations,
  // steady months 12 -> 3-6. (Alone, before the junction weight of contact.hpp, the scaled
  // projection moved junction tractions: 2026-11-27.)
  const Eigen::VectorXd c = coefficients(G, g, false);
  const PetscReal wn = residual_of(c);
  if (bn > 0 && wn > enough * bn) {
    const Eigen::VectorXd cs = coefficients(G, g, true);
    if (residual_of(cs) < 0.5 * wn) {
      combine(cs);
      CHK(MatMult(J, x, w_));
      ++products_;
      CHK(VecAYPX(w_, -1.0, b));
      PetscReal tn = 0;
      CHK(VecNorm(w_, NORM_2, &tn));
      if (tn < wn) return tn / bn;
      CHK(VecSet(x, 0.0));
    }
  }
  if (!(bn > 0) || !(wn < bn)) return 1.0;  // no reduction: start from zero
  combine(c);
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
