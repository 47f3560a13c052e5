#include "pair_distribution.hpp"

#include <algorithm>
#include <cstring>
#include <numeric>

#include "petsc_call.hpp"

#define CHK UGS_CONTACT_PETSC

namespace ugs::contact::detail {

PairDistribution::~PairDistribution() {
  if (useq_) VecDestroy(&useq_);
  if (scatter_) VecScatterDestroy(&scatter_);
}

void PairDistribution::build(const mech::CouplingContext& ctx, const FaultModel* fm) {
  comm = ctx.comm;
  rank = ctx.rank;
  size = ctx.size;
  std::vector<PairData> all;
  std::vector<int> counts(size, 0);
  if (rank == 0) {
    const auto& nb = ctx.node_begin_of_rank;
    std::vector<int> owner(fm->pairs.size());
    for (std::size_t q = 0; q < fm->pairs.size(); ++q) {
      const std::int64_t g1 = ctx.global_of_mesh_node[fm->pairs[q].side1];
      owner[q] = static_cast<int>(std::upper_bound(nb.begin(), nb.end(), g1) - nb.begin()) - 1;
      ++counts[owner[q]];
    }
    order.resize(fm->pairs.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return owner[a] < owner[b]; });
    all.resize(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
      const NodePair& p = fm->pairs[order[i]];
      const FaultProperties& f = fm->faults[p.fault];
      PairData& d = all[i];
      std::memset(&d, 0, sizeof d);
      d.g1 = ctx.global_of_mesh_node[p.side1];
      d.g2 = ctx.global_of_mesh_node[p.side2];
      d.tag1 = p.tag1;
      d.tag2 = p.tag2;
      d.model_index = order[i];
      d.fault = p.fault;
      d.area = p.area;
      d.k = p.k;
      d.cohesion = f.cohesion;
      d.mu = f.mu;
      d.p0 = p.p0;
      std::copy(p.R.begin(), p.R.end(), d.R);
      std::copy(p.lambda0.begin(), p.lambda0.end(), d.lam0);
      std::copy(p.x.begin(), p.x.end(), d.x);
      d.fixed1 = p.fixed1;
      d.fixed2 = p.fixed2;
      d.active = p.active;
      d.redundant = p.redundant ? 1 : 0;
      d.junction = p.junction;
    }
  }
  MPI_Bcast(counts.data(), size, MPI_INT, 0, comm);
  per_rank = counts;
  m = counts[rank];
  M = 0;
  for (int r = 0; r < size; ++r) {
    if (r == rank) first = M;
    M += counts[r];
  }
  pairs.resize(m);
  std::vector<int> bytes(size), displs(size, 0);
  for (int r = 0; r < size; ++r) bytes[r] = counts[r] * static_cast<int>(sizeof(PairData));
  for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + bytes[r - 1];
  MPI_Scatterv(all.data(), bytes.data(), displs.data(), MPI_BYTE, pairs.data(), bytes[rank], MPI_BYTE, 0, comm);

  // u at both twins of every owned pair.
  std::vector<PetscInt> idx(6 * m);
  for (int q = 0; q < m; ++q)
    for (int k = 0; k < 3; ++k) {
      idx[6 * q + k] = static_cast<PetscInt>(3 * pairs[q].g1 + k);
      idx[6 * q + 3 + k] = static_cast<PetscInt>(3 * pairs[q].g2 + k);
    }
  IS is;
  CHK(ISCreateGeneral(PETSC_COMM_SELF, 6 * m, idx.data(), PETSC_COPY_VALUES, &is));
  CHK(VecCreateSeq(PETSC_COMM_SELF, 6 * m, &useq_));
  CHK(VecScatterCreate(ctx.u, is, useq_, nullptr, &scatter_));
  CHK(ISDestroy(&is));
}

void PairDistribution::scatter(const std::vector<double>& model_order, int k, double* mine) const {
  std::vector<double> sorted;
  if (rank == 0) {
    sorted.resize(static_cast<std::size_t>(k) * order.size());
    for (std::size_t i = 0; i < order.size(); ++i)
      for (int c = 0; c < k; ++c) sorted[static_cast<std::size_t>(k) * i + c] = model_order[static_cast<std::size_t>(k) * order[i] + c];
  }
  std::vector<int> counts(size), displs(size, 0);
  for (int r = 0; r < size; ++r) counts[r] = k * per_rank[r];
  for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  MPI_Scatterv(sorted.data(), counts.data(), displs.data(), MPI_DOUBLE, mine, k * m, MPI_DOUBLE, 0, comm);
}

std::vector<double> PairDistribution::gather(const std::vector<double>& mine, int k) const {
  std::vector<int> counts(size), displs(size, 0);
  for (int r = 0; r < size; ++r) counts[r] = k * per_rank[r];
  for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  std::vector<double> all(rank == 0 ? static_cast<std::size_t>(k) * M : 0);
  MPI_Gatherv(mine.data(), k * m, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, 0, comm);
  std::vector<double> out(all.size());
  if (rank == 0)
    for (std::size_t i = 0; i < order.size(); ++i)
      for (int c = 0; c < k; ++c) out[static_cast<std::size_t>(k) * order[i] + c] = all[static_cast<std::size_t>(k) * i + c];
  return out;
}

const PetscScalar* PairDistribution::twins(Vec u) {
  CHK(VecScatterBegin(scatter_, u, useq_, INSERT_VALUES, SCATTER_FORWARD));
  CHK(VecScatterEnd(scatter_, u, useq_, INSERT_VALUES, SCATTER_FORWARD));
  const PetscScalar* a = nullptr;
  CHK(VecGetArrayRead(useq_, &a));
  return a;
}

void PairDistribution::restore_twins(const PetscScalar* a) { CHK(VecRestoreArrayRead(useq_, &a)); }

}  // namespace ugs::contact::detail
