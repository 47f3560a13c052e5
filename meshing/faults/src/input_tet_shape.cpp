// The input tetrahedra's shape for the fault cut's quality reference (cut_band_improvement.hpp).
#include <algorithm>
#include <limits>

#include "cut_band_improvement.hpp"
#include "ugs/meshing/mesh_quality.hpp"
#include "ugs/meshing/vec3.hpp"

namespace ugs {

InputTetShape::InputTetShape(std::vector<Point3> nodes, std::vector<std::span<const std::uint32_t>> tet_arrays)
    : nodes_(std::move(nodes)), arrays_(std::move(tet_arrays)) {
  std::size_t n = 0;
  for (const auto& a : arrays_) {
    first_.push_back(static_cast<std::uint32_t>(n));
    n += a.size() / 4;
  }
  quality_.assign(n, kUnknown);
  min_edge_.assign(n, kUnknown);
}

std::array<std::uint32_t, 4> InputTetShape::tet(std::uint32_t p) const {
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(first_.begin(), first_.end(), p) - first_.begin()) - 1;
  const std::uint32_t* e = arrays_[k].data() + std::size_t{4} * (p - first_[k]);
  return {e[0], e[1], e[2], e[3]};
}

double InputTetShape::quality(std::uint32_t p) const {
  if (quality_[p] == kUnknown) {
    const auto e = tet(p);
    quality_[p] = min_dihedral_angle_deg(nodes_[e[0]], nodes_[e[1]], nodes_[e[2]], nodes_[e[3]]);
  }
  return quality_[p];
}

double InputTetShape::min_edge(std::uint32_t p) const {
  if (min_edge_[p] == kUnknown) {
    const auto e = tet(p);
    double shortest = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) shortest = std::min(shortest, vec3::norm(vec3::sub(nodes_[e[i]], nodes_[e[j]])));
    min_edge_[p] = shortest;
  }
  return min_edge_[p];
}

}  // namespace ugs
