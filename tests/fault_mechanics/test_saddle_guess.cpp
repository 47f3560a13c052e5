// The field split's first iterate (solver/contact/src/saddle_guess.cpp): the least-squares
// projection of b on J times the stored solutions, exact when b lies in that span.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <petscksp.h>

#include "saddle_guess.hpp"
#include "ugs/mechanics/petsc_session.hpp"

namespace {

using ugs::contact::detail::SaddleGuess;

constexpr PetscInt kN = 12;

// A non-symmetric, non-singular test matrix: diagonal 1..n, 0.5 above, -0.25 below.
Mat make_matrix() {
  Mat J;
  MatCreateSeqAIJ(PETSC_COMM_SELF, kN, kN, 3, nullptr, &J);
  for (PetscInt i = 0; i < kN; ++i) {
    MatSetValue(J, i, i, 1.0 + i, INSERT_VALUES);
    if (i + 1 < kN) MatSetValue(J, i, i + 1, 0.5, INSERT_VALUES);
    if (i > 0) MatSetValue(J, i, i - 1, -0.25, INSERT_VALUES);
  }
  MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY);
  return J;
}

Vec vec(const std::vector<double>& v) {
  Vec x;
  VecCreateSeq(PETSC_COMM_SELF, kN, &x);
  for (PetscInt i = 0; i < kN; ++i) VecSetValue(x, i, v[i], INSERT_VALUES);
  VecAssemblyBegin(x);
  VecAssemblyEnd(x);
  return x;
}

std::vector<double> values(Vec x) {
  std::vector<double> v(kN);
  const PetscScalar* a = nullptr;
  VecGetArrayRead(x, &a);
  for (PetscInt i = 0; i < kN; ++i) v[i] = a[i];
  VecRestoreArrayRead(x, &a);
  return v;
}

std::vector<double> unit(int k) {
  std::vector<double> v(kN, 0.0);
  v[k] = 1.0;
  return v;
}

TEST(SaddleGuess, StartsFromZeroWithoutHistory) {
  Mat J = make_matrix();
  Vec b = vec(std::vector<double>(kN, 1.0)), x = vec(std::vector<double>(kN, 7.0));
  SaddleGuess g;
  EXPECT_EQ(g.form(J, b, x), 1.0);
  for (double v : values(x)) EXPECT_EQ(v, 0.0);
  VecDestroy(&b), VecDestroy(&x), MatDestroy(&J);
}

TEST(SaddleGuess, ExactWhenTheSolutionLiesInTheSpan) {
  Mat J = make_matrix();
  std::vector<double> x1(kN), x2(kN), xs(kN);
  for (int i = 0; i < kN; ++i) {
    x1[i] = std::sin(0.3 * i + 0.1);
    x2[i] = std::cos(0.7 * i) * (i % 3 == 0 ? 2.0 : 1.0);
    xs[i] = 2.0 * x1[i] - 3.0 * x2[i];
  }
  SaddleGuess g;
  Vec v1 = vec(x1), v2 = vec(x2), vs = vec(xs), b, x = vec(std::vector<double>(kN, 0.0));
  g.remember(v1);
  g.remember(v2);
  g.remember(v1);  // a repeated direction: dropped by the eigenvalue cutoff, not a failure
  VecDuplicate(vs, &b);
  MatMult(J, vs, b);
  const double rel = g.form(J, b, x);
  // The projection solves normal equations (Gram matrix of J x_j, PETSc's dot products and Eigen's
  // eigensolver): their round-off is eps x cond(Y)^2 (~1e-14 here) and its last bits depend on the
  // BLAS kernels and the compiler; 1e-10 leaves room for that and still fails any real error.
  EXPECT_LT(rel, 1e-10);
  const std::vector<double> got = values(x);
  for (int i = 0; i < kN; ++i) EXPECT_NEAR(got[i], xs[i], 1e-10);
  // A right-hand side partly outside the span: the ratio is that of the returned iterate.
  VecSetValue(b, 5, 10.0, ADD_VALUES);
  VecAssemblyBegin(b);
  VecAssemblyEnd(b);
  const double rel2 = g.form(J, b, x);
  Vec r;
  VecDuplicate(b, &r);
  MatMult(J, x, r);
  VecAYPX(r, -1.0, b);
  PetscReal rn = 0, bn = 0;
  VecNorm(r, NORM_2, &rn);
  VecNorm(b, NORM_2, &bn);
  EXPECT_GT(rel2, 0.01);
  EXPECT_LT(rel2, 1.0);
  EXPECT_NEAR(rel2, rn / bn, 1e-10);  // two residual norms of O(1) values: round-off, as above
  for (Vec* v : {&v1, &v2, &vs, &b, &x, &r}) VecDestroy(v);
  MatDestroy(&J);
}

TEST(SaddleGuess, KeepsTheLastEightAndFallsBackToZero) {
  Mat J = make_matrix();
  SaddleGuess g;
  for (int k = 0; k <= SaddleGuess::kKeep; ++k) {
    Vec e = vec(unit(k));
    g.remember(e);
    VecDestroy(&e);
  }
  // J e_8 (kept) is reproduced exactly; J e_0 (the oldest, dropped) is not.
  Vec e8 = vec(unit(SaddleGuess::kKeep)), b8, x8 = vec(std::vector<double>(kN, 0.0));
  VecDuplicate(e8, &b8);
  MatMult(J, e8, b8);
  EXPECT_LT(g.form(J, b8, x8), 1e-10);  // exact but for the normal equations' round-off (above)
  Vec e0 = vec(unit(0)), b, x = vec(std::vector<double>(kN, 0.0));
  VecDuplicate(e0, &b);
  MatMult(J, e0, b);
  EXPECT_GT(g.form(J, b, x), 1e-6);
  for (Vec* v : {&e8, &b8, &x8}) VecDestroy(v);
  // J e_1 .. J e_8 reach rows 0 .. 9 only: a right-hand side in row 11 is not reduced, and the
  // iterate is zero.
  Vec far = vec(unit(11)), bf, xf = vec(std::vector<double>(kN, 3.0));
  VecDuplicate(far, &bf);
  VecSet(bf, 0.0);
  VecSetValue(bf, 11, 1.0, INSERT_VALUES);
  VecAssemblyBegin(bf);
  VecAssemblyEnd(bf);
  EXPECT_EQ(g.form(J, bf, xf), 1.0);
  for (double v : values(xf)) EXPECT_EQ(v, 0.0);
  for (Vec* v : {&e0, &b, &x, &far, &bf, &xf}) VecDestroy(v);
  MatDestroy(&J);
}

// Storage months: the operator keeps its values from one solve to the next, so the products J x_j
// are kept and only the newest solution is multiplied; the iterate is the same, bit for bit, as
// with every product recomputed. A changed operator (same_operator false) multiplies all again.
TEST(SaddleGuess, KeepsItsProductsWhileTheOperatorKeepsItsValues) {
  Mat J = make_matrix();
  SaddleGuess kept, fresh;
  std::vector<Vec> xs;
  for (int k = 0; k < SaddleGuess::kKeep + 3; ++k) {
    std::vector<double> v(kN);
    for (int i = 0; i < kN; ++i) v[i] = std::sin(0.37 * (k + 1) * i + 0.2 * k) + (i == k % kN ? 1.0 : 0.0);
    xs.push_back(vec(v));
  }
  Vec b = vec(std::vector<double>(kN, 0.0)), x1 = vec(std::vector<double>(kN, 0.0)), x2 = vec(std::vector<double>(kN, 0.0));
  long long expected = 0;
  for (std::size_t k = 0; k < xs.size(); ++k) {
    kept.remember(xs[k]);
    fresh.remember(xs[k]);
    std::vector<double> bv(kN);
    for (int i = 0; i < kN; ++i) bv[i] = std::cos(0.11 * i * (k + 2)) + 0.01 * i;
    VecDestroy(&b);
    b = vec(bv);
    const double r1 = kept.form(J, b, x1, k > 0);  // the first form has no products yet
    const double r2 = fresh.form(J, b, x2, false);
    ++expected;  // one new solution a solve
    EXPECT_EQ(kept.products(), expected) << k;
    EXPECT_EQ(r1, r2) << k;
    const std::vector<double> a1 = values(x1), a2 = values(x2);
    for (int i = 0; i < kN; ++i) EXPECT_EQ(a1[i], a2[i]) << k << " " << i;
  }
  const int stored = std::min<int>(static_cast<int>(xs.size()), SaddleGuess::kKeep);
  EXPECT_EQ(fresh.products(), [&] {
    long long n = 0;
    for (std::size_t k = 0; k < xs.size(); ++k) n += std::min<int>(static_cast<int>(k) + 1, SaddleGuess::kKeep);
    return n;
  }());
  // Another operator: every stored solution multiplied again.
  MatScale(J, 2.0);
  const long long before = kept.products();
  kept.form(J, b, x1, false);
  fresh.form(J, b, x2, false);
  EXPECT_EQ(kept.products(), before + stored);
  const std::vector<double> a1 = values(x1), a2 = values(x2);
  for (int i = 0; i < kN; ++i) EXPECT_EQ(a1[i], a2[i]) << i;
  for (Vec& v : xs) VecDestroy(&v);
  for (Vec* v : {&b, &x1, &x2}) VecDestroy(v);
  MatDestroy(&J);
}

}  // namespace

// A large increment and two small corrections that differ by 1e-3 of their size: the direction of
// their difference is 1e-14 of the largest eigenvalue of the plain normal equations (cut), 1e-6 of
// the scaled ones (kept). A right-hand side along that difference is reached through the scaled
// projection, checked by one more product; with a target above the plain projection's residual the
// scaled one is not tried.
TEST(SaddleGuess, ReachesSmallCorrectionsBesideLargeIncrements) {
  Mat J = make_matrix();
  std::vector<double> big(kN), q(kN), s(kN), c1(kN), c2(kN), xs(kN);
  for (int i = 0; i < kN; ++i) {
    big[i] = std::sin(0.3 * i + 0.1);
    q[i] = std::cos(0.7 * i);
    s[i] = (i % 4 == 1 ? 1.0 : 0.0) - (i % 5 == 2 ? 0.5 : 0.0);
    c1[i] = 1e-4 * q[i];
    c2[i] = 1e-4 * (q[i] + 1e-3 * s[i]);
    xs[i] = 1e-7 * s[i];  // = c2 - c1
  }
  Vec vb = vec(big), v1 = vec(c1), v2 = vec(c2), vs = vec(xs), b, x = vec(std::vector<double>(kN, 0.0));
  VecDuplicate(vs, &b);
  MatMult(J, vs, b);
  SaddleGuess g;
  g.remember(vb);
  g.remember(v1);
  g.remember(v2);
  const double reached = g.form(J, b, x);
  EXPECT_LT(reached, 1e-6);
  EXPECT_EQ(g.products(), 4);  // three stored solutions and the check of the scaled projection
  const std::vector<double> got = values(x);
  for (int i = 0; i < kN; ++i) EXPECT_NEAR(got[i], xs[i], 1e-6 * 1e-7);
  SaddleGuess plain_only;  // a target the plain projection already meets: no scaled try
  plain_only.remember(vb);
  plain_only.remember(v1);
  plain_only.remember(v2);
  const double plain = plain_only.form(J, b, x, false, 2.0);
  EXPECT_GT(plain, 1e-2);
  EXPECT_EQ(plain_only.products(), 3);
  for (Vec* v : {&vb, &v1, &v2, &vs, &b, &x}) VecDestroy(v);
  MatDestroy(&J);
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ugs::mech::PetscSession petsc;
  return RUN_ALL_TESTS();
}
