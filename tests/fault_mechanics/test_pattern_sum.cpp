// K_gamma = K + G into a matrix of the union pattern (solver/contact/src/pattern_sum.cpp): the
// values of PETSc's MatAXPY bit for bit, with positions stored only for the rows where a term's
// pattern differs from the sum's, and the positions kept while the patterns stay.
#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include <petscmat.h>

#include "pattern_sum.hpp"
#include "ugs/mechanics/petsc_session.hpp"

namespace {

using ugs::contact::detail::PatternSum;

constexpr PetscInt kN = 40;

Mat create(MatType type, PetscInt per_row) {
  Mat m;
  MatCreate(PETSC_COMM_SELF, &m);
  MatSetSizes(m, kN, kN, kN, kN);
  MatSetType(m, type);
  MatSeqAIJSetPreallocation(m, per_row, nullptr);
  MatMPIAIJSetPreallocation(m, per_row, nullptr, per_row, nullptr);
  return m;
}

void assemble(Mat m) {
  MatAssemblyBegin(m, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(m, MAT_FINAL_ASSEMBLY);
}

// K: a banded stiffness-like pattern (5 diagonals), values scaled by `scale`.
Mat stiffness(MatType type, double scale) {
  Mat k = create(type, 5);
  for (PetscInt i = 0; i < kN; ++i)
    for (PetscInt j = i - 2; j <= i + 2; ++j)
      if (j >= 0 && j < kN) MatSetValue(k, i, j, scale * (1.0 + 0.37 * i - 0.11 * j + (i == j ? 10.0 : 0.0)), INSERT_VALUES);
  assemble(k);
  return k;
}

// G: couplings between far-apart rows (the twins of a fault), outside K's pattern, on 6 rows, and
// one entry on K's diagonal.
Mat coupling(MatType type) {
  Mat g = create(type, 3);
  const PetscInt pairs[3][2] = {{3, 30}, {10, 25}, {17, 38}};
  for (const auto& p : pairs) {
    MatSetValue(g, p[0], p[0], 0.125, INSERT_VALUES);
    MatSetValue(g, p[0], p[1], -0.125, INSERT_VALUES);
    MatSetValue(g, p[1], p[0], -0.125, INSERT_VALUES);
    MatSetValue(g, p[1], p[1], 0.125, INSERT_VALUES);
  }
  assemble(g);
  return g;
}

std::vector<PetscScalar> dense(Mat m) {
  std::vector<PetscScalar> v(kN * kN, 0.0);
  for (PetscInt i = 0; i < kN; ++i) {
    PetscInt n = 0;
    const PetscInt* cols = nullptr;
    const PetscScalar* vals = nullptr;
    MatGetRow(m, i, &n, &cols, &vals);
    for (PetscInt k = 0; k < n; ++k) v[i * kN + cols[k]] = vals[k];
    MatRestoreRow(m, i, &n, &cols, &vals);
  }
  return v;
}

void check(MatType type) {
  Mat k = stiffness(type, 1.0), g = coupling(type), to = nullptr, ref = nullptr;
  MatDuplicate(k, MAT_COPY_VALUES, &to);
  MatAXPY(to, 1.0, g, DIFFERENT_NONZERO_PATTERN);
  MatZeroEntries(to);
  PatternSum sum;
  ASSERT_TRUE(sum.sum(k, g, to));
  MatDuplicate(k, MAT_COPY_VALUES, &ref);
  MatAXPY(ref, 1.0, g, DIFFERENT_NONZERO_PATTERN);
  EXPECT_EQ(dense(to), dense(ref));  // bit for bit
  // Positions only for the 6 rows G adds to: K's entries there (5, and 4 on row 38) and G's 12.
  EXPECT_EQ(sum.positions_stored(), std::size_t{5 * 5 + 4 + 12});
  EXPECT_EQ(sum.maps_built(), 2);
  // New values on the same patterns: the positions are kept.
  Mat k2 = stiffness(type, -2.5);
  MatCopy(k2, k, SAME_NONZERO_PATTERN);
  ASSERT_TRUE(sum.sum(k, g, to));
  MatCopy(k2, ref, DIFFERENT_NONZERO_PATTERN);
  MatAXPY(ref, 1.0, g, DIFFERENT_NONZERO_PATTERN);
  EXPECT_EQ(dense(to), dense(ref));
  EXPECT_EQ(sum.maps_built(), 2);
  for (Mat* m : {&k, &k2, &g, &to, &ref}) MatDestroy(m);
}

TEST(PatternSum, SequentialAIJGivesMatAXPYsValuesWithPositionsOnlyWhereThePatternsDiffer) { check(MATSEQAIJ); }

TEST(PatternSum, MPIAIJGivesMatAXPYsValuesWithPositionsOnlyWhereThePatternsDiffer) { check(MATMPIAIJ); }

TEST(PatternSum, AnotherMatrixTypeIsLeftToTheCaller) {
  Mat k = stiffness(MATSEQAIJ, 1.0), g = coupling(MATSEQAIJ), dk = nullptr;
  MatConvert(k, MATSEQDENSE, MAT_INITIAL_MATRIX, &dk);
  PatternSum sum;
  EXPECT_FALSE(sum.sum(dk, g, k));
  for (Mat* m : {&k, &g, &dk}) MatDestroy(m);
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ugs::mech::PetscSession petsc;
  return RUN_ALL_TESTS();
}
