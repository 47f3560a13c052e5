// Adds element stiffnesses straight into an assembled MATHYPRE matrix's arrays.
//
// MatSetValues(ADD_VALUES) on an assembled MATHYPRE ends in hypre_IJMatrixAddToValuesParCSR,
// which finds every entry by a linear search of its row: 2/3 of the reassembly of the
// hypo-plastic elements' tangents (11 % of a history run on one process, perf, scale-0.25 box).
// This writer finds the entry by bisection in hypre's own CSR arrays (rows in the order they were
// set, increasing, but for the diagonal that hypre swaps to the front; an entry the bisection
// misses is scanned for) and adds to it: the same additions in the same order, so the same bits.
#pragma once

#include <petscmat.h>

namespace ugs::mech {

class HypreInPlace {
 public:
  // Binds to A's ParCSR arrays if A is a MATHYPRE (with hypre's own layout: the diagonal block
  // square, the off-diagonal block's columns increasing). False: not bound.
  bool bind(Mat A);
  bool bound() const { return ok_; }
  // a(row, cols[k]) += v[k] for the cols[k] >= 0 (at most kMaxEntries), row global and owned. False,
  // with nothing added, if not bound or an entry is not in the pattern (then use MatSetValues).
  bool add(PetscInt row, int n, const PetscInt* cols, const double* v) const;
  static constexpr int kMaxEntries = 12;

 private:
  void* parcsr_ = nullptr;  // hypre_ParCSRMatrix of the last bind
  bool ok_ = false;
};

}  // namespace ugs::mech
