// K_gamma = K + G written straight into the values of a matrix whose nonzero pattern holds both
// (SaddlePointSolver::augment), through the positions of K's and G's entries in it, found once.
//
// PETSc's MatCopy and MatAXPY between AIJ matrices of different patterns go through MatGetRow and
// MatSetValues row by row and a new assembly (MatCopy_Basic, MatAXPY_Basic): on the thesis mesh that
// was a copy of the whole stiffness matrix by insertion at every saddle-point solve. The positions
// depend only on the patterns; they are found again when either term's nonzero state changes.
// AIJ only (sequential or MPI); other types answer false and the caller adds the usual way.
#pragma once
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

private:
  struct Term {
    Mat m = nullptr;
    PetscObjectState nonzero_state = -1;
    std::vector<PetscInt> pos;  // per entry (diagonal part, then off-diagonal): >= 0 in to's diagonal part, -1 - k in its off-diagonal part
  };
  bool map(Term& t, Mat from, Mat to);
  Term a_, b_;
  Mat to_ = nullptr;
  PetscObjectState to_state_ = -1;
  int maps_built_ = 0;
};

}  // namespace ugs::contact::detail
