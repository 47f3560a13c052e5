#include "pattern_sum.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "petsc_call.hpp"

#define CHK UGS_CONTACT_PETSC

namespace ugs::contact::detail {
namespace {

// The sequential diagonal and off-diagonal parts of an AIJ matrix (off = null when sequential) and
// the global column of each off-diagonal column; false when not AIJ.
bool parts(Mat m, Mat& d, Mat& o, const PetscInt*& garray) {
  PetscBool mpi = PETSC_FALSE, seq = PETSC_FALSE;
  CHK(PetscObjectBaseTypeCompare(reinterpret_cast<PetscObject>(m), MATMPIAIJ, &mpi));
  CHK(PetscObjectBaseTypeCompare(reinterpret_cast<PetscObject>(m), MATSEQAIJ, &seq));
  if (mpi) {
    CHK(MatMPIAIJGetSeqAIJ(m, &d, &o, &garray));
    return true;
  }
  d = seq ? m : nullptr;
  o = nullptr;
  garray = nullptr;
  return seq == PETSC_TRUE;
}

// Row structure of a sequential AIJ part.
struct Rows {
  Mat m = nullptr;
  PetscInt n = 0;
  const PetscInt *ia = nullptr, *ja = nullptr;
  explicit Rows(Mat part) : m(part) {
    PetscBool done = PETSC_FALSE;
    if (m) CHK(MatGetRowIJ(m, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
    if (m && !done) throw std::runtime_error("PatternSum: no row structure");
  }
  ~Rows() {
    PetscBool done = PETSC_FALSE;
    if (m) MatRestoreRowIJ(m, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done);
  }
  PetscInt nnz() const { return m ? ia[n] : 0; }
};

}  // namespace

bool PatternSum::map(Term& t, Mat from, Mat to) {
  PetscObjectState nz = 0;
  CHK(MatGetNonzeroState(from, &nz));
  if (t.m == from && t.nonzero_state == nz && to == to_) return true;
  Mat fd, fo, td, to_o;
  const PetscInt *fg = nullptr, *tg = nullptr;
  if (!parts(from, fd, fo, fg) || !parts(to, td, to_o, tg)) return false;
  PetscInt cstart = 0, cend = 0;
  CHK(MatGetOwnershipRangeColumn(to, &cstart, &cend));
  const Rows fdr(fd), for_(fo), tdr(td), tor(to_o);
  t.same.assign(fdr.n, 0);
  t.pos.clear();
  std::vector<std::pair<PetscInt, PetscInt>> row;  // (global column, position code) of to's row
  for (PetscInt i = 0; i < fdr.n; ++i) {
    const PetscInt nfd = fdr.ia[i + 1] - fdr.ia[i], nfo = fo ? for_.ia[i + 1] - for_.ia[i] : 0;
    const PetscInt ntd = tdr.ia[i + 1] - tdr.ia[i], nto = to_o ? tor.ia[i + 1] - tor.ia[i] : 0;
    const bool same_d = nfd == ntd, same_o = nfo == nto;
    t.same[i] = static_cast<unsigned char>((same_d ? 1 : 0) | (same_o ? 2 : 0));
    if (same_d && same_o) continue;
    row.clear();
    for (PetscInt k = tdr.ia[i]; k < tdr.ia[i + 1]; ++k) row.emplace_back(cstart + tdr.ja[k], k);
    if (to_o)
      for (PetscInt k = tor.ia[i]; k < tor.ia[i + 1]; ++k) row.emplace_back(tg[tor.ja[k]], -1 - k);
    std::sort(row.begin(), row.end());
    auto find = [&](PetscInt col) {
      const auto it = std::lower_bound(row.begin(), row.end(), std::make_pair(col, PETSC_MIN_INT));
      if (it == row.end() || it->first != col) throw std::logic_error("PatternSum: a term's entry is outside the sum's pattern");
      return it->second;
    };
    if (!same_d)
      for (PetscInt k = fdr.ia[i]; k < fdr.ia[i + 1]; ++k) t.pos.push_back(find(cstart + fdr.ja[k]));
    if (!same_o)
      for (PetscInt k = for_.ia[i]; k < for_.ia[i + 1]; ++k) t.pos.push_back(find(fg[for_.ja[k]]));
  }
  t.pos.shrink_to_fit();
  t.m = from;
  t.nonzero_state = nz;
  ++maps_built_;
  return true;
}

bool PatternSum::sum(Mat a, Mat b, Mat to) {
  PetscObjectState tnz = 0;
  CHK(MatGetNonzeroState(to, &tnz));
  if (to != to_ || tnz != to_state_) a_.m = b_.m = nullptr;  // the sum's pattern changed: find again
  const bool ok_a = map(a_, a, to), ok_b = ok_a && map(b_, b, to);
  to_ = to;
  to_state_ = tnz;
  if (!ok_a || !ok_b) return false;
  Mat td, to_o;
  const PetscInt* tg = nullptr;
  parts(to, td, to_o, tg);
  const Rows tdr(td), tor(to_o);
  PetscScalar *vd = nullptr, *vo = nullptr;
  CHK(MatSeqAIJGetArray(td, &vd));
  if (to_o) CHK(MatSeqAIJGetArray(to_o, &vo));
  std::fill(vd, vd + tdr.nnz(), 0.0);
  if (vo) std::fill(vo, vo + tor.nnz(), 0.0);
  // Each sum entry is 0 + a + b, in that order, whichever way the entries are found.
  for (Term* t : {&a_, &b_}) {
    Mat fd, fo;
    const PetscInt* fg = nullptr;
    parts(t->m, fd, fo, fg);
    const Rows fdr(fd), for_(fo);
    const PetscScalar *fv = nullptr, *fw = nullptr;
    CHK(MatSeqAIJGetArrayRead(fd, &fv));
    if (fo) CHK(MatSeqAIJGetArrayRead(fo, &fw));
    auto add = [&](PetscInt p, PetscScalar v) { (p >= 0 ? vd[p] : vo[-1 - p]) += v; };
    const PetscInt* p = t->pos.data();
    for (PetscInt i = 0; i < fdr.n; ++i) {
      if (t->same[i] & 1) {
        PetscScalar* out = vd + tdr.ia[i];
        for (PetscInt k = fdr.ia[i]; k < fdr.ia[i + 1]; ++k) *out++ += fv[k];
      } else {
        for (PetscInt k = fdr.ia[i]; k < fdr.ia[i + 1]; ++k) add(*p++, fv[k]);
      }
      if (!fo) continue;
      if (t->same[i] & 2) {
        PetscScalar* out = vo + tor.ia[i];
        for (PetscInt k = for_.ia[i]; k < for_.ia[i + 1]; ++k) *out++ += fw[k];
      } else {
        for (PetscInt k = for_.ia[i]; k < for_.ia[i + 1]; ++k) add(*p++, fw[k]);
      }
    }
    CHK(MatSeqAIJRestoreArrayRead(fd, &fv));
    if (fo) CHK(MatSeqAIJRestoreArrayRead(fo, &fw));
  }
  CHK(MatSeqAIJRestoreArray(td, &vd));
  if (to_o) CHK(MatSeqAIJRestoreArray(to_o, &vo));
  // No values to communicate (none were set): the assembly only marks the matrix as changed.
  CHK(MatAssemblyBegin(to, MAT_FINAL_ASSEMBLY));
  CHK(MatAssemblyEnd(to, MAT_FINAL_ASSEMBLY));
  return true;
}

}  // namespace ugs::contact::detail
