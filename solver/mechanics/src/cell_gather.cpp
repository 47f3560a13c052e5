// Owned-cell values to output order on rank 0, in messages (cell_gather.hpp).
#include "cell_gather.hpp"

#include <algorithm>

namespace ugs::mech {

CellGather::CellGather(const LocalMesh& lm, int k, std::size_t chunk_cells)
    : lm_(lm), k_(k), chunk_(std::max<std::size_t>(chunk_cells, 1) * k) {
  if (lm.rank == 0) out_.resize(static_cast<std::size_t>(lm.n_global_cells) * k);
  else out_.resize(chunk_);
}

double* CellGather::next() {
  if (lm_.rank == 0) return out_.data() + static_cast<std::size_t>(lm_.owned_cells_of_rank[0][next_++]) * k_;
  if (next_ == out_.size()) send();
  double* at = out_.data() + next_;
  next_ += k_;
  return at;
}

void CellGather::send() {
  MPI_Send(out_.data(), static_cast<int>(next_), MPI_DOUBLE, 0, kTag, lm_.comm);
  next_ = 0;
}

std::vector<double> CellGather::finish() {
  if (lm_.rank != 0) {
    if (next_ > 0) send();
    std::vector<double>().swap(out_);
    return {};
  }
  std::vector<double> part;
  for (int p = 1; p < lm_.size; ++p) {
    const auto& cells = lm_.owned_cells_of_rank[p];
    const std::size_t n = cells.size() * k_;
    for (std::size_t lo = 0; lo < n; lo += chunk_) {
      part.resize(std::min(chunk_, n - lo));
      MPI_Recv(part.data(), static_cast<int>(part.size()), MPI_DOUBLE, p, kTag, lm_.comm, MPI_STATUS_IGNORE);
      const std::size_t first = lo / k_;
      for (std::size_t i = 0; i < part.size() / k_; ++i)
        std::copy_n(part.data() + i * k_, k_, out_.data() + static_cast<std::size_t>(cells[first + i]) * k_);
    }
  }
  return std::move(out_);
}

}  // namespace ugs::mech
