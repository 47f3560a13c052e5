// What one rank holds of the model after distribution: its owned nodes (a contiguous block of
// global numbers, 3 matrix rows each), the ghost nodes its elements touch, and every element that
// touches an owned node. Rank 0 also keeps what it needs to put gathered results in mesh order.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include <mpi.h>

#include "ugs/mechanics/model.hpp"
#include "ugs/mechanics/partition.hpp"

namespace ugs::mech {

struct LocalMesh {
  MPI_Comm comm = MPI_COMM_NULL;
  int rank = 0, size = 1;
  std::int64_t n_global_nodes = 0, n_global_cells = 0;
  std::int64_t node_begin = 0;                 // global number of the first owned node
  int n_owned = 0;                             // local nodes [0, n_owned) are owned, the rest ghosts
  std::vector<std::int64_t> global;            // global node number per local node
  std::vector<std::uint32_t> orig;             // mesh node index per local node
  std::vector<Point3> x;
  std::vector<std::uint8_t> fixed;             // bit c: component c prescribed
  std::vector<std::array<double, 3>> prescribed;
  std::vector<std::array<double, 3>> traction;     // Model::traction_force per local node
  std::vector<std::array<std::int32_t, 4>> cells;  // local node ids
  std::vector<std::int32_t> cell_material;
  std::vector<std::uint32_t> cell_index;       // output index (position among the model's tets)
  std::vector<std::uint8_t> cell_owned;        // this rank reports the cell
  std::vector<fem::Material> materials;
  InitialState initial;
  std::vector<std::array<double, 2>> material_k;   // Model::material_k
  std::vector<GasColumn> material_gas;             // Model::material_gas

  // Rank 0 only.
  std::vector<std::uint32_t> orig_of_global;               // mesh node index of each global node
  std::vector<std::int64_t> node_begin_of_rank;            // size + 1 entries
  std::vector<std::vector<std::uint32_t>> owned_cells_of_rank;  // output indices in each rank's order

  int n_local() const { return static_cast<int>(global.size()); }
  std::size_t n_cells() const { return cells.size(); }
};

// Collective: rank 0 partitions `model` and sends each rank its part.
LocalMesh distribute(MPI_Comm comm, const Model* model, PartitionMethod method);

// Large point-to-point transfers (chunks below INT_MAX bytes).
void send_bytes(MPI_Comm comm, const void* data, std::size_t n, int dest, int tag);
void recv_bytes(MPI_Comm comm, void* data, std::size_t n, int src, int tag);

}  // namespace ugs::mech
