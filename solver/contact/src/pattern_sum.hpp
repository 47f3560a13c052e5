// K_gamma = K + G written straight into the values of a matrix whose nonzero pattern holds both
// (SaddlePointSolver::augment), through the positions of K's and G's entries in it, found once.
//
// PETSc's MatCopy and MatAXPY between AIJ matrices of different patterns go through MatGetRow and
// MatSetValues row by row and a new assembly (MatCopy_Basic, MatAXPY_Basic): on the thesis mesh that
// was a copy of the whole stiffness matrix by insertion at every saddle-point solve. The positions
// depend only on the patterns; they are found again when either term's nonzero state changes.
// A row part (diagonal or off-diagonal block) of a term with as many entries as the sum's has the
// same columns in the same order (a subset of equal size; PETSc's off-diagonal columns are sorted by
// global column): its entries go to the same offsets and no position is stored. Only the rows that
// G adds to (the fault pairs' nodes) keep one position per entry: K's map was 4 bytes per nonzero,
// a third of K's own size, before 2026-11-27.
// AIJ only (sequential or MPI); other types answer false and the caller adds the usual way.
#pragma once
#include <cstddef>
#include <vector>

#include <petscmat.h>

namespace ugs::contact::detail {

class PatternSum {
public:
  // to = a + b, with to's pattern containing a's and b's (all three assembled, same row layout).
  // Returns false (to untouched) when one of them is not AIJ.
  bool sum(Mat a, Mat b, Mat to);
  // How many times the positions were found (a count for tests).
  int maps_built() const { return maps_built_; }
  // How many positions are stored (a count for tests: only the rows whose pattern differs from the sum's).
  std::size_t positions_stored() const { return a_.pos.size() + b_.pos.size(); }

private:
  struct Term {
    Mat m = nullptr;
    PetscObjectState nonzero_state = -1;
    // Per row: bit 0 set when the diagonal part has the sum's pattern there, bit 1 the off-diagonal part.
    std::vector<unsigned char> same;
    // The other row parts' entries in row order (diagonal part, then off-diagonal, row by row):
    // >= 0 in to's diagonal part, -1 - k in its off-diagonal part.
    std::vector<PetscInt> pos;
  };
  bool map(Term& t, Mat from, Mat to);
  Term a_, b_;
  Mat to_ = nullptr;
  PetscObjectState to_state_ = -1;
  int maps_built_ = 0;
};

}  // namespace ugs::contact::detail
