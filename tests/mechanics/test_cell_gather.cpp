// CellGather (solver/mechanics/src/cell_gather.hpp) puts every rank's owned-cell values at their
// output places on rank 0, whatever the message size: one cell a message, a few, one for all; a
// scalar, 4 and 6 values per cell; run on one process and (ctest CellGather.ThreeProcesses) on
// three, where ranks own interleaved cells and one rank owns none.
#include <mpi.h>

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "cell_gather.hpp"
#include "mpi_gtest_main.hpp"

namespace {

constexpr int kCells = 23;

// Cell i goes to rank (i % 5) % size, except that with 3 processes rank 2 owns nothing; each rank
// holds its cells in decreasing output order (the local order is not the output order).
ugs::mech::LocalMesh mesh() {
  ugs::mech::LocalMesh lm;
  lm.comm = MPI_COMM_WORLD;
  MPI_Comm_rank(lm.comm, &lm.rank);
  MPI_Comm_size(lm.comm, &lm.size);
  lm.n_global_cells = kCells;
  lm.owned_cells_of_rank.assign(lm.size, {});
  for (int i = kCells - 1; i >= 0; --i) {
    int owner = (i % 5) % lm.size;
    if (lm.size == 3 && owner == 2) owner = 0;
    lm.owned_cells_of_rank[owner].push_back(static_cast<std::uint32_t>(i));
  }
  return lm;
}

double value(std::uint32_t cell, int c) { return 1000.0 * cell + c + 0.25; }

}  // namespace

TEST(CellGather, EveryValueAtItsOutputPlace) {
  const ugs::mech::LocalMesh lm = mesh();
  const std::vector<std::uint32_t> mine = lm.owned_cells_of_rank[lm.rank];  // (every rank has the table here)
  for (const int k : {1, 4, 6})
    for (const std::size_t chunk : {std::size_t{1}, std::size_t{3}, std::size_t{7}, ugs::mech::CellGather::kChunkCells}) {
      ugs::mech::CellGather gather(lm, k, chunk);
      for (const std::uint32_t cell : mine) {
        double* v = gather.next();
        for (int c = 0; c < k; ++c) v[c] = value(cell, c);
      }
      const std::vector<double> out = gather.finish();
      if (lm.rank != 0) {
        EXPECT_TRUE(out.empty());
        continue;
      }
      ASSERT_EQ(out.size(), static_cast<std::size_t>(kCells) * k);
      for (std::uint32_t cell = 0; cell < kCells; ++cell)
        for (int c = 0; c < k; ++c) EXPECT_EQ(out[cell * k + c], value(cell, c)) << "cell " << cell << ", k " << k << ", chunk " << chunk;
    }
}

int main(int argc, char** argv) { return ugs::test::run_mpi_gtests(argc, argv); }
