#include "ugs/mechanics/partition.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>  // (scotch.h uses FILE)
#include <numeric>

#include <scotch/scotch.h>

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

std::vector<int> scotch_parts(const Model& model, std::size_t n, int nparts) {
  // Node graph of the tetrahedra (no self loops), rows sorted.
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
  std::vector<SCOTCH_Num> adj;
  adj.reserve(model.tets.size() * 5);
  std::vector<SCOTCH_Num> row;
  std::vector<SCOTCH_Num> ia_v(n + 1, 0);
  for (std::size_t v = 0; v < n; ++v) {
    row.clear();
    for (auto k = inc_ptr[v]; k < inc_ptr[v + 1]; ++k)
      for (auto w : model.tets[inc[k]])
        if (w != v) row.push_back(static_cast<SCOTCH_Num>(w));
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    adj.insert(adj.end(), row.begin(), row.end());
    ia_v[v + 1] = static_cast<SCOTCH_Num>(adj.size());
  }
  // Scotch's graph partitioner, run on this process (rank 0 partitions the whole mesh), in a
  // context of its own with a fixed seed and the deterministic option: the same mesh is split the
  // same way every run. (Through PETSc's PT-Scotch interface the split changed from run to run:
  // 248,900 / 248,898 / 248,879 nodes on rank 0 of the thesis-scale box, and with it the rounding
  // of every sum and the Newton path.)
  std::vector<SCOTCH_Num> parttab(n, 0);
  SCOTCH_Context context;
  SCOTCH_Graph graph, bound;
  SCOTCH_Strat strat;
  SCOTCH_contextInit(&context);
  SCOTCH_graphInit(&graph);
  SCOTCH_stratInit(&strat);
  bool ok = SCOTCH_contextRandomClone(&context) == 0 &&
            SCOTCH_contextOptionSetNum(&context, SCOTCH_OPTIONNUMDETERMINISTIC, 1) == 0;
  if (ok) SCOTCH_contextRandomSeed(&context, 1);
  ok = ok &&
       SCOTCH_graphBuild(&graph, 0, static_cast<SCOTCH_Num>(n), ia_v.data(), nullptr, nullptr, nullptr,
                         static_cast<SCOTCH_Num>(adj.size()), adj.data(), nullptr) == 0 &&
       SCOTCH_contextBindGraph(&context, &graph, &bound) == 0;
  ok = ok && SCOTCH_stratGraphMapBuild(&strat, SCOTCH_STRATQUALITY | SCOTCH_STRATBALANCE, nparts, 0.01) == 0 &&
       SCOTCH_graphPart(&bound, nparts, &strat, parttab.data()) == 0;
  if (ok) SCOTCH_graphExit(&bound);
  SCOTCH_stratExit(&strat);
  SCOTCH_graphExit(&graph);
  SCOTCH_contextExit(&context);
  if (!ok) throw ComputeError("Scotch could not partition the mesh graph; try the rcb partition method");
  std::vector<int> part(parttab.begin(), parttab.end());
  return part;
}

}  // namespace

std::vector<int> partition_nodes(const Model& model, const std::vector<Point3>& coords, int nparts, PartitionMethod method) {
  const std::size_t n = coords.size();
  if (nparts <= 1) return std::vector<int>(n, 0);
  if (method == PartitionMethod::PtScotch) {
    std::vector<int> part = scotch_parts(model, n, nparts);
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
