// Locating points in hexahedral cells given by their 8 corners (corner-point grid cells of a
// reservoir simulator; faces need not be planar, cells may be pinched or distorted).
//
// A cell is the union of 24 tetrahedra: its centre joined to the 4 triangles of each face, cut
// from the face's centre (the mean of its 4 corners). Two cells sharing a face's 4 corners share its
// triangles, so neighbours tile space without gap or overlap even where faces are bilinear, not
// planar. Candidates come from a plan-view bucket grid over the cells' bounding boxes, each bucket's
// cells sorted by their top: a point tests only the cells whose box holds it.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "ugs/formats/mesh.hpp"

namespace ugs {

// Corner order: bottom-or-top face (i,j) (i+1,j) (i,j+1) (i+1,j+1), then the opposite face the
// same way (ECLIPSE's order; which face comes first does not matter).
using HexCorners = std::array<Point3, 8>;

class HexLocator {
public:
  explicit HexLocator(std::span<const HexCorners> cells);

  // Index of a cell holding p, or -1. Where cells overlap (a point on a shared face, or faulted
  // faces that do not match), the lowest index wins, so the answer does not depend on the order
  // of the points.
  std::int64_t locate(const Point3& p) const;
  // locate() for many points, on every core.
  std::vector<std::int64_t> locate(std::span<const Point3> points) const;

  // Bounding box of all cells: xmin ymin zmin xmax ymax zmax.
  const std::array<double, 6>& extent() const { return extent_; }

private:
  bool inside(std::size_t cell, const Point3& p) const;
  std::span<const HexCorners> cells_;
  std::vector<std::array<double, 6>> box_;
  std::array<double, 6> extent_{};
  double x0_ = 0, y0_ = 0, h_ = 1;
  std::size_t nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> start_;  // CSR: cells of bucket b at items_[start_[b] .. start_[b+1])
  std::vector<std::uint32_t> items_;
  std::vector<double> height_;        // per bucket: the tallest cell's height
};

}  // namespace ugs
