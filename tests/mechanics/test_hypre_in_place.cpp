// The in-place reassembly of hypre's matrix (solver/mechanics/src/hypre_in_place.hpp) gives the
// same bits as MatSetValues(ADD_VALUES), whatever order hypre keeps a row in, on one process and
// (ctest HypreInPlace.TwoProcesses) on two, where a row has entries in hypre's off-diagonal block;
// an entry outside the pattern is refused with nothing added.
#include <petscmat.h>

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "hypre_in_place.hpp"
#include "mpi_gtest_main.hpp"

namespace {

// A banded 3-block pattern of n nodes (node a couples with a-3 .. a+3), rows set whole and sorted
// as the solver sets them, values from a fixed sequence.
constexpr PetscInt kNodes = 40;

PetscInt first_row() {
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return 3 * (kNodes * rank / size);
}
PetscInt end_row() {
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return 3 * (kNodes * (rank + 1) / size);
}

std::vector<PetscInt> row_cols(PetscInt row) {
  std::vector<PetscInt> c;
  const PetscInt a = row / 3;
  for (PetscInt b = std::max<PetscInt>(0, a - 3); b <= std::min<PetscInt>(kNodes - 1, a + 3); ++b)
    for (int k = 0; k < 3; ++k) c.push_back(3 * b + k);
  return c;
}

double value(std::uint64_t& s) {  // a fixed pseudo-random sequence in (-1, 1), all bits used
  s = s * 6364136223846793005ULL + 1442695040888963407ULL;
  return static_cast<double>(s >> 11) / 4503599627370496.0 - 1.0;
}

Mat make_matrix() {
  Mat A;
  const PetscInt lo = first_row(), hi = end_row();
  EXPECT_EQ(MatCreate(PETSC_COMM_WORLD, &A), 0);
  MatSetSizes(A, hi - lo, hi - lo, PETSC_DETERMINE, PETSC_DETERMINE);
  MatSetType(A, MATHYPRE);
  std::vector<PetscInt> dnnz, onnz;
  for (PetscInt r = lo; r < hi; ++r) {
    PetscInt d = 0, o = 0;
    for (PetscInt c : row_cols(r)) ++(c >= lo && c < hi ? d : o);
    dnnz.push_back(d);
    onnz.push_back(o);
  }
  MatSetOption(A, MAT_SORTED_FULL, PETSC_TRUE);
  MatHYPRESetPreallocation(A, 0, dnnz.data(), 0, onnz.data());
  std::uint64_t s = 7;
  for (PetscInt r = lo; r < hi; ++r) {
    const std::vector<PetscInt> c = row_cols(r);
    std::vector<double> v(c.size());
    for (double& x : v) x = value(s);
    MatSetValues(A, 1, &r, static_cast<PetscInt>(c.size()), c.data(), v.data(), INSERT_VALUES);
  }
  MatSetOption(A, MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE);
  MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
  return A;
}

// Every entry of A and B, owned rows, as AIJ: equal bit for bit.
void expect_same_bits(Mat A, Mat B) {
  Mat a, b;
  ASSERT_EQ(MatConvert(A, MATAIJ, MAT_INITIAL_MATRIX, &a), 0);
  ASSERT_EQ(MatConvert(B, MATAIJ, MAT_INITIAL_MATRIX, &b), 0);
  for (PetscInt r = first_row(); r < end_row(); ++r) {
    PetscInt na, nb;
    const PetscInt *ca, *cb;
    const PetscScalar *va, *vb;
    MatGetRow(a, r, &na, &ca, &va);
    MatGetRow(b, r, &nb, &cb, &vb);
    ASSERT_EQ(na, nb) << "row " << r;
    for (PetscInt k = 0; k < na; ++k) {
      EXPECT_EQ(ca[k], cb[k]) << "row " << r;
      EXPECT_EQ(va[k], vb[k]) << "row " << r << " column " << ca[k];
    }
    MatRestoreRow(a, r, &na, &ca, &va);
    MatRestoreRow(b, r, &nb, &cb, &vb);
  }
  MatDestroy(&a);
  MatDestroy(&b);
}

}  // namespace

TEST(HypreInPlace, SameBitsAsMatSetValues) {
  Mat A = make_matrix(), B = make_matrix();
  ugs::mech::HypreInPlace writer;
  ASSERT_TRUE(writer.bind(A));
  // "Elements" of 4 nodes within the band (a .. a+2, and a node repeated is no element: a, a+1,
  // a+2 and a-1), 12 x 12 values, some columns left out (-1: prescribed), rows of other processes
  // skipped as the solver skips them; every element added twice, so entries are summed in order.
  std::uint64_t s = 11;
  int added = 0;
  for (int pass = 0; pass < 2; ++pass)
    for (PetscInt a = 1; a + 2 < kNodes; ++a) {
      const PetscInt nodes[4] = {a + 1, a - 1, a + 2, a};
      PetscInt rows[12], cols[12];
      for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) {
          const PetscInt g = 3 * nodes[i] + c;
          cols[3 * i + c] = (a + c) % 7 == 0 ? -1 : g;
          rows[3 * i + c] = cols[3 * i + c] < 0 || g < first_row() || g >= end_row() ? -1 : g;
        }
      double Ke[144];
      for (double& x : Ke) x = value(s);
      for (int r = 0; r < 12; ++r) {
        if (rows[r] < 0) continue;
        ASSERT_TRUE(writer.add(rows[r], 12, cols, Ke + 12 * r)) << "row " << rows[r];
        ++added;
      }
      MatSetValues(B, 12, rows, 12, cols, Ke, ADD_VALUES);
    }
  EXPECT_GT(added, 100);
  MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
  MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY);
  expect_same_bits(A, B);

  // Outside the band: refused, and the entries of the row before it untouched.
  const PetscInt row = first_row();
  const PetscInt cols[2] = {row, 3 * kNodes - 1};
  const double v[2] = {1.0, 1.0};
  EXPECT_FALSE(writer.add(row, 2, cols, v));
  expect_same_bits(A, B);
  MatDestroy(&A);
  MatDestroy(&B);
}

TEST(HypreInPlace, BindsToHypreMatricesOnly) {
  Mat A;
  ASSERT_EQ(MatCreateAIJ(PETSC_COMM_WORLD, 3, 3, PETSC_DETERMINE, PETSC_DETERMINE, 3, nullptr, 0, nullptr, &A), 0);
  MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
  ugs::mech::HypreInPlace writer;
  EXPECT_FALSE(writer.bind(A));
  const PetscInt c = 0;
  const double v = 1;
  EXPECT_FALSE(writer.add(0, 1, &c, &v));
  MatDestroy(&A);
}

int main(int argc, char** argv) { return ugs::test::run_mpi_gtests(argc, argv); }
