#include "ugs/mechanics/partition.hpp"

#include <algorithm>
#include <numeric>

#include <petscmat.h>

#include "petsc_check.hpp"
#include "ugs/formats/error.hpp"

namespace ugs::mech {
namespace {

void rcb(const std::vector<Point3>& x, std::vector<std::uint32_t>& idx, std::size_t lo, std::size_t hi, int part0, int nparts,
         std::vector<int>& part) {
  if (nparts == 1) {
    for (std::size_t i = lo; i < hi; ++i) part[idx[i]] = part0;
    return;
  }
  Point3 a = x[idx[lo]], b = a;
  for (std::size_t i = lo; i < hi; ++i)
    for (int k = 0; k < 3; ++k) a[k] = std::min(a[k], x[idx[i]][k]), b[k] = std::max(b[k], x[idx[i]][k]);
  int ax = 0;
  for (int k = 1; k < 3; ++k)
    if (b[k] - a[k] > b[ax] - a[ax]) ax = k;
  const int left = nparts / 2;
  const std::size_t mid = lo + (hi - lo) * left / nparts;
  std::nth_element(idx.begin() + lo, idx.begin() + mid, idx.begin() + hi, [&](std::uint32_t p, std::uint32_t q) {
    return x[p][ax] < x[q][ax] || (x[p][ax] == x[q][ax] && p < q);
  });
  rcb(x, idx, lo, mid, part0, left, part);
  rcb(x, idx, mid, hi, part0 + left, nparts - left, part);
}

std::vector<int> ptscotch(const Model& model, std::size_t n, int nparts) {
  // Node graph of the tetrahedra (no self loops), rows sorted.
  std::vector<PetscInt> deg(n + 1, 0);
  std::vector<std::uint32_t> inc_ptr(n + 1, 0), inc;
  for (const auto& t : model.tets)
    for (auto v : t) ++inc_ptr[v + 1];
  for (std::size_t i = 0; i < n; ++i) inc_ptr[i + 1] += inc_ptr[i];
  inc.resize(inc_ptr[n]);
  {
    std::vector<std::uint32_t> fill(inc_ptr.begin(), inc_ptr.end() - 1);
    for (std::uint32_t e = 0; e < model.tets.size(); ++e)
      for (auto v : model.tets[e]) inc[fill[v]++] = e;
  }
  std::vector<PetscInt> adj;
  adj.reserve(model.tets.size() * 5);
  std::vector<PetscInt> row;
  std::vector<PetscInt> ia_v(n + 1, 0);
  for (std::size_t v = 0; v < n; ++v) {
    row.clear();
    for (auto k = inc_ptr[v]; k < inc_ptr[v + 1]; ++k)
      for (auto w : model.tets[inc[k]])
        if (w != v) row.push_back(static_cast<PetscInt>(w));
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    adj.insert(adj.end(), row.begin(), row.end());
    ia_v[v + 1] = static_cast<PetscInt>(adj.size());
  }
  // MatCreateMPIAdj takes ownership of PetscMalloc'ed arrays.
  PetscInt *ia = nullptr, *ja = nullptr;
  UGS_PETSC(PetscMalloc1(n + 1, &ia));
  UGS_PETSC(PetscMalloc1(adj.size() + 1, &ja));
  std::copy(ia_v.begin(), ia_v.end(), ia);
  std::copy(adj.begin(), adj.end(), ja);
  Mat graph = nullptr;
  MatPartitioning mp = nullptr;
  IS is = nullptr;
  std::vector<int> part(n, 0);
  const PetscInt pn = static_cast<PetscInt>(n);
  UGS_PETSC(MatCreateMPIAdj(PETSC_COMM_SELF, pn, pn, ia, ja, nullptr, &graph));
  UGS_PETSC(MatPartitioningCreate(PETSC_COMM_SELF, &mp));
  UGS_PETSC(MatPartitioningSetAdjacency(mp, graph));
  UGS_PETSC(MatPartitioningSetNParts(mp, nparts));
  UGS_PETSC(MatPartitioningSetType(mp, MATPARTITIONINGPTSCOTCH));
  UGS_PETSC(MatPartitioningApply(mp, &is));
  const PetscInt* p = nullptr;
  UGS_PETSC(ISGetIndices(is, &p));
  for (std::size_t i = 0; i < n; ++i) part[i] = static_cast<int>(p[i]);
  UGS_PETSC(ISRestoreIndices(is, &p));
  UGS_PETSC(ISDestroy(&is));
  UGS_PETSC(MatPartitioningDestroy(&mp));
  UGS_PETSC(MatDestroy(&graph));
  return part;
}

}  // namespace

PartitionMethod parse_partition_method(const std::string& s) {
  if (s == "ptscotch") return PartitionMethod::PtScotch;
  if (s == "rcb") return PartitionMethod::Rcb;
  throw InputError("--partition", "'" + s + "' is not one of ptscotch, rcb");
}

std::vector<int> partition_nodes(const Model& model, const std::vector<Point3>& coords, int nparts, PartitionMethod method) {
  const std::size_t n = coords.size();
  if (nparts <= 1) return std::vector<int>(n, 0);
  if (method == PartitionMethod::PtScotch) {
    std::vector<int> part = ptscotch(model, n, nparts);
    // Every part must own something (a rank without rows would break the matrix layout).
    std::vector<std::size_t> count(nparts, 0);
    for (int p : part) ++count[p];
    if (std::find(count.begin(), count.end(), 0u) == count.end()) return part;
  }
  std::vector<std::uint32_t> idx(n);
  std::iota(idx.begin(), idx.end(), 0u);
  std::vector<int> part(n, 0);
  rcb(coords, idx, 0, n, 0, nparts, part);
  return part;
}

}  // namespace ugs::mech
