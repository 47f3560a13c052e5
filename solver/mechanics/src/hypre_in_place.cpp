// Adds into an assembled MATHYPRE matrix's CSR arrays (hypre_in_place.hpp).
#include "hypre_in_place.hpp"

#include <petscmathypre.h>

#include <algorithm>

#include "petsc_check.hpp"

namespace ugs::mech {
namespace {

// Strictly increasing on [b, e).
template <class T>
bool increasing(const T* b, const T* e) {
  return std::adjacent_find(b, e, [](T x, T y) { return !(x < y); }) == e;
}

// Position of `key` in [b, e): a binary search, right if the range is increasing (hypre keeps its
// rows in the order they were set, ours increasing, but moves the diagonal to the front by a swap:
// a few entries of a row can be out of order), verified, else a scan. -1 if absent.
template <class T>
HYPRE_Int find(const T* b, const T* e, T key) {
  const T* p = std::lower_bound(b, e, key);
  if (p == e || *p != key) p = std::find(b, e, key);
  return p != e ? static_cast<HYPRE_Int>(p - b) : -1;
}

// find() with a position tried first (the entry after the last one found).
template <class T>
HYPRE_Int find_from(const T* b, const T* e, HYPRE_Int hint, T key) {
  return hint >= 0 && hint < e - b && b[hint] == key ? hint : find(b, e, key);
}

}  // namespace

bool HypreInPlace::bind(Mat A) {
  PetscBool is_hypre = PETSC_FALSE;
  UGS_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A), MATHYPRE, &is_hypre));
  if (!is_hypre) return ok_ = false, parcsr_ = nullptr, false;
  hypre_ParCSRMatrix* p = nullptr;
  UGS_PETSC(MatHYPREGetParCSR(A, &p));
  if (p == parcsr_) return ok_;
  parcsr_ = p;
  ok_ = false;
  if (!p) return false;
  const hypre_CSRMatrix* diag = hypre_ParCSRMatrixDiag(p);
  const hypre_CSRMatrix* offd = hypre_ParCSRMatrixOffd(p);
  const HYPRE_Int *di = hypre_CSRMatrixI(diag), *dj = hypre_CSRMatrixJ(diag);
  const HYPRE_Int *oi = hypre_CSRMatrixI(offd), *oj = hypre_CSRMatrixJ(offd);
  const HYPRE_BigInt* cmap = hypre_ParCSRMatrixColMapOffd(p);
  const HYPRE_Int n_offd = hypre_CSRMatrixNumCols(offd);
  if (!di || !dj || !hypre_CSRMatrixData(diag) || (n_offd > 0 && (!oi || !oj || !cmap || !hypre_CSRMatrixData(offd))))
    return false;
  if (hypre_ParCSRMatrixFirstRowIndex(p) != hypre_ParCSRMatrixFirstColDiag(p)) return false;
  // The columns of the off-diagonal block in increasing order (hypre's own rule; searched by bisection).
  if (n_offd > 0 && !increasing(cmap, cmap + n_offd)) return false;
  return ok_ = true;
}

bool HypreInPlace::add(PetscInt row, int n, const PetscInt* cols, const double* v) const {
  if (!ok_ || n > kMaxEntries) return false;
  auto* p = static_cast<hypre_ParCSRMatrix*>(parcsr_);
  hypre_CSRMatrix* diag = hypre_ParCSRMatrixDiag(p);
  hypre_CSRMatrix* offd = hypre_ParCSRMatrixOffd(p);
  const HYPRE_BigInt first = hypre_ParCSRMatrixFirstColDiag(p);
  const HYPRE_Int n_rows = hypre_CSRMatrixNumRows(diag);
  const HYPRE_BigInt i_big = row - first;
  if (i_big < 0 || i_big >= n_rows) return false;
  const auto i = static_cast<HYPRE_Int>(i_big);
  const HYPRE_Int *di = hypre_CSRMatrixI(diag), *dj = hypre_CSRMatrixJ(diag);
  const HYPRE_Int *oi = hypre_CSRMatrixI(offd), *oj = hypre_CSRMatrixJ(offd);
  const HYPRE_Int n_offd = hypre_CSRMatrixNumCols(offd);
  const HYPRE_BigInt* cmap = hypre_ParCSRMatrixColMapOffd(p);
  // Every entry is found before any is added: a miss leaves the matrix as it was.
  // An element's columns come in node blocks of 3 consecutive ones, which sit side by side in
  // either block (but for the diagonal, first in its row): the entry after the last one found is
  // tried before a search.
  HYPRE_Complex* at[kMaxEntries];
  HYPRE_Int d_next = -1, o_next = -1;  // in its row, the position after the last entry found in diag / offd
  HYPRE_Int c_next = -1;               // the offd column after the last one found
  for (int k = 0; k < n; ++k) {
    at[k] = nullptr;
    if (cols[k] < 0) continue;
    const HYPRE_BigInt j = cols[k] - first;
    if (j >= 0 && j < n_rows) {
      // (The diagonal is first in hypre's rows.)
      const HYPRE_Int q = find_from(dj + di[i], dj + di[i + 1], j == i ? 0 : d_next, static_cast<HYPRE_Int>(j));
      if (q < 0) return false;
      at[k] = hypre_CSRMatrixData(diag) + di[i] + q;
      d_next = q + 1;
    } else {
      const HYPRE_Int c = n_offd > 0 ? find_from(cmap, cmap + n_offd, c_next, static_cast<HYPRE_BigInt>(cols[k])) : -1;
      const HYPRE_Int q = c < 0 ? -1 : find_from(oj + oi[i], oj + oi[i + 1], o_next, c);
      if (q < 0) return false;
      at[k] = hypre_CSRMatrixData(offd) + oi[i] + q;
      o_next = q + 1;
      c_next = c + 1;
    }
  }
  for (int k = 0; k < n; ++k)
    if (at[k]) *at[k] += v[k];
  return true;
}

}  // namespace ugs::mech
