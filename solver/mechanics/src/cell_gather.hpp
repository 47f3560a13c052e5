// Gathers k values per owned cell into the output order on rank 0, without a whole copy of any
// rank's part: rank 0 writes its own cells' values straight into the result, every other rank
// sends messages of kChunkCells cells as it fills them, received rank by rank into place. Rank 0
// holds the result and one message (6.3 MB for a tensor), the other ranks one message each.
// (Before, every rank built its whole part first: at the thesis scale 68 MB on each of two ranks
// beside rank 0's 137 MB stress field, the peak of a history at its output dates.)
#pragma once

#include <cstddef>
#include <vector>

#include "local_mesh.hpp"

namespace ugs::mech {

class CellGather {
 public:
  static constexpr std::size_t kChunkCells = std::size_t{1} << 17;
  // k values per cell; messages of chunk_cells cells (the default: 6.3 MB for a tensor).
  CellGather(const LocalMesh& lm, int k, std::size_t chunk_cells = kChunkCells);
  // Where the k values of the rank's next owned cell go (cells in the order of the local mesh).
  double* next();
  // Rank 0: the values of every cell in output order; the other ranks: {} (collective).
  std::vector<double> finish();

 private:
  static constexpr int kTag = 7301;
  void send();
  const LocalMesh& lm_;
  const int k_;
  const std::size_t chunk_;   // values per message
  std::size_t next_ = 0;      // cells pushed so far (rank 0) / values in the buffer (others)
  std::vector<double> out_;   // rank 0: the result; the others: one message
};

}  // namespace ugs::mech
