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
  t.pos.assign(fdr.nnz() + for_.nnz(), 0);
  std::vector<std::pair<PetscInt, PetscInt>> row;  // (global column, position code) of to's row
  PetscInt off = fdr.nnz();
  for (PetscInt i = 0; i < fdr.n; ++i) {
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
    for (PetscInt k = fdr.ia[i]; k < fdr.ia[i + 1]; ++k) t.pos[k] = find(cstart + fdr.ja[k]);
    if (fo)
      for (PetscInt k = for_.ia[i]; k < for_.ia[i + 1]; ++k) t.pos[off + k] = find(fg[for_.ja[k]]);
  }
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
  PetscInt nd = 0, no = 0;
  {
    const Rows tdr(td), tor(to_o);
    nd = tdr.nnz();
    no = tor.nnz();
  }
  PetscScalar *vd = nullptr, *vo = nullptr;
  CHK(MatSeqAIJGetArray(td, &vd));
  if (to_o) CHK(MatSeqAIJGetArray(to_o, &vo));
  std::fill(vd, vd + nd, 0.0);
  if (vo) std::fill(vo, vo + no, 0.0);
  for (Term* t : {&a_, &b_}) {
    Mat fd, fo;
    const PetscInt* fg = nullptr;
    parts(t->m, fd, fo, fg);
    const PetscScalar *fv = nullptr, *fw = nullptr;
    CHK(MatSeqAIJGetArrayRead(fd, &fv));
    if (fo) CHK(MatSeqAIJGetArrayRead(fo, &fw));
    PetscInt nfd = 0, nfo = 0;
    {
      const Rows r(fd), s(fo);
      nfd = r.nnz();
      nfo = s.nnz();
    }
    const PetscInt* p = t->pos.data();
    for (PetscInt k = 0; k < nfd; ++k) (p[k] >= 0 ? vd[p[k]] : vo[-1 - p[k]]) += fv[k];
    for (PetscInt k = 0; k < nfo; ++k) (p[nfd + k] >= 0 ? vd[p[nfd + k]] : vo[-1 - p[nfd + k]]) += fw[k];
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
