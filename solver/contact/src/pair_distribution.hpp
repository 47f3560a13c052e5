// Pair distribution of the contact solver: which rank owns which node pair (the rank owning its
// side-1 node), what the owner needs to know about a pair (PairData, built on rank 0 from the
// FaultModel and scattered as bytes), the exchange of per-pair values between rank 0 (FaultModel
// order) and the owners, and the scatter of the twins' displacements to the owner of their pair.
#pragma once
#include <cstdint>
#include <vector>

#include <mpi.h>
#include <petscvec.h>

#include "ugs/contact/fault_model.hpp"
#include "ugs/mechanics/coupling.hpp"

namespace ugs::contact::detail {

struct PairData {
  std::int64_t g1, g2;              // global nodes of side 1 and side 2
  std::uint64_t tag1, tag2;         // mesh node tags (messages)
  std::uint32_t model_index;
  std::int32_t fault;
  std::int32_t junction;            // NodePair::junction
  double area, k, cohesion, mu, p0;
  double R[9];
  double lam0[3];
  double x[3];
  std::uint8_t fixed1, fixed2, active, redundant;
};

class PairDistribution {
public:
  PairDistribution() = default;
  ~PairDistribution();
  PairDistribution(const PairDistribution&) = delete;
  PairDistribution& operator=(const PairDistribution&) = delete;

  // Collective: distributes the pairs of `fm` (rank 0 only; may be null elsewhere) over the ranks
  // of ctx and sets up the scatter of the twins' displacements from ctx.u.
  void build(const mech::CouplingContext& ctx, const FaultModel* fm);

  // Collective: rank 0's values, k per pair in FaultModel order, to the owners (k per owned pair).
  void scatter(const std::vector<double>& model_order, int k, double* mine) const;
  // Collective: the owners' values (k per owned pair) on rank 0, k per pair in FaultModel order
  // (empty elsewhere).
  std::vector<double> gather(const std::vector<double>& mine, int k) const;

  // The displacement at both twins of every owned pair: 6 per pair (side 1 x y z, side 2 x y z).
  // Collective; release with restore_twins.
  const PetscScalar* twins(Vec u);
  void restore_twins(const PetscScalar* a);

  MPI_Comm comm = MPI_COMM_NULL;
  int rank = 0, size = 1;
  std::vector<PairData> pairs;          // owned pairs
  int m = 0;                            // owned pairs
  std::int64_t M = 0, first = 0;        // global pairs, global index of the first owned pair
  std::vector<int> per_rank;            // owned pairs of every rank
  std::vector<std::uint32_t> order;     // rank 0: global pair -> model pair

private:
  VecScatter scatter_ = nullptr;
  Vec useq_ = nullptr;
};

}  // namespace ugs::contact::detail
