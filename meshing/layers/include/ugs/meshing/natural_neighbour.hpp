// A surface through scattered picks (x, y, z), interpolated with Sibson's natural-neighbour
// coordinates on their Delaunay triangulation (CGAL). Exact at the picks, C0 everywhere, defined
// inside the convex hull of the picks only.
#pragma once
#include <array>
#include <memory>
#include <optional>
#include <vector>

namespace ugs {

class NaturalNeighbourSurface {
public:
  // Picks with the same x, y must have the same z (std::invalid_argument otherwise, with the index);
  // at least three picks not on one line.
  explicit NaturalNeighbourSurface(const std::vector<std::array<double, 3>>& picks);
  ~NaturalNeighbourSurface();
  NaturalNeighbourSurface(NaturalNeighbourSurface&&) noexcept;
  NaturalNeighbourSurface& operator=(NaturalNeighbourSurface&&) noexcept;

  // Elevation at (x, y); nullopt outside the convex hull of the picks.
  std::optional<double> at(double x, double y) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ugs
