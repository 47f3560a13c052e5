#include "ugs/meshing/natural_neighbour.hpp"

#include <map>
#include <stdexcept>
#include <string>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/natural_neighbor_coordinates_2.h>

namespace ugs {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_2;
using Delaunay = CGAL::Delaunay_triangulation_2<K>;
}  // namespace

struct NaturalNeighbourSurface::Impl {
  Delaunay dt;
  std::map<Point, double, K::Less_xy_2> z;
};

NaturalNeighbourSurface::NaturalNeighbourSurface(const std::vector<std::array<double, 3>>& picks)
    : impl_(std::make_unique<Impl>()) {
  std::vector<Point> pts;
  pts.reserve(picks.size());
  for (std::size_t i = 0; i < picks.size(); ++i) {
    const Point p(picks[i][0], picks[i][1]);
    auto [it, fresh] = impl_->z.emplace(p, picks[i][2]);
    if (!fresh) {
      if (it->second != picks[i][2])
        throw std::invalid_argument("pick " + std::to_string(i + 1) + " has the x, y of an earlier pick but another z");
      continue;
    }
    pts.push_back(p);
  }
  impl_->dt.insert(pts.begin(), pts.end());
  if (impl_->dt.dimension() < 2) throw std::invalid_argument("needs at least three picks that are not on one line");
}

NaturalNeighbourSurface::~NaturalNeighbourSurface() = default;
NaturalNeighbourSurface::NaturalNeighbourSurface(NaturalNeighbourSurface&&) noexcept = default;
NaturalNeighbourSurface& NaturalNeighbourSurface::operator=(NaturalNeighbourSurface&&) noexcept = default;

std::optional<double> NaturalNeighbourSurface::at(double x, double y) const {
  const Point p(x, y);
  // Exactly at a pick: its value (the coordinates would be 1 there anyway).
  if (auto it = impl_->z.find(p); it != impl_->z.end()) return it->second;
  std::vector<std::pair<Point, K::FT>> coords;
  const auto result = CGAL::natural_neighbor_coordinates_2(impl_->dt, p, std::back_inserter(coords));
  if (!result.third || !(result.second > 0)) return std::nullopt;
  double sum = 0;
  for (const auto& [q, w] : coords) sum += w * impl_->z.at(q);
  return sum / result.second;
}

}  // namespace ugs
