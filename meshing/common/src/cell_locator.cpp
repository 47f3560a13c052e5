// Points in corner-point cells (see cell_locator.hpp).
#include "ugs/meshing/cell_locator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>

#include "ugs/meshing/vec3.hpp"

namespace ugs {
namespace {

// The 6 faces as corner cycles (ECLIPSE order: 0-3 one k face, 4-7 the other).
constexpr int kFaces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}};

using vec3::sub;
// Six times the signed volume spanned by a, b, c.
inline double det(const Point3& a, const Point3& b, const Point3& c) { return vec3::dot(a, vec3::cross(b, c)); }

// p in the tetrahedron (a, b, c, d), all relative to p's frame; barycentric coordinates >= -tol.
bool in_tet(const Point3& a, const Point3& b, const Point3& c, const Point3& d, const Point3& p, double min_volume) {
  const Point3 ab = sub(b, a), ac = sub(c, a), ad = sub(d, a);
  const double v = det(ab, ac, ad);
  if (std::abs(v) <= min_volume) return false;  // degenerate piece (pinched cell, collapsed face)
  const Point3 pa = sub(a, p), pb = sub(b, p), pc = sub(c, p), pd = sub(d, p);
  const double tol = -1e-10 * std::abs(v);
  // Sub-volumes with p in place of each vertex; all of v's sign inside.
  const double s = v > 0 ? 1.0 : -1.0;
  if (s * det(pb, pc, pd) < tol) return false;  // (p, b, c, d): a replaced by p
  if (s * -det(pa, pc, pd) < tol) return false;
  if (s * det(pa, pb, pd) < tol) return false;
  if (s * -det(pa, pb, pc) < tol) return false;
  return true;
}

}  // namespace

HexLocator::HexLocator(std::span<const HexCorners> cells) : cells_(cells) {
  if (cells.empty()) throw std::invalid_argument("HexLocator: no cells");
  if (cells.size() > std::numeric_limits<std::uint32_t>::max()) throw std::invalid_argument("HexLocator: too many cells");
  constexpr double inf = std::numeric_limits<double>::infinity();
  extent_ = {inf, inf, inf, -inf, -inf, -inf};
  box_.resize(cells.size());
  std::vector<double> sizes;
  sizes.reserve(cells.size());
  for (std::size_t c = 0; c < cells.size(); ++c) {
    auto& b = box_[c];
    b = {inf, inf, inf, -inf, -inf, -inf};
    for (const auto& x : cells[c])
      for (int d = 0; d < 3; ++d) {
        b[d] = std::min(b[d], x[d]);
        b[d + 3] = std::max(b[d + 3], x[d]);
      }
    for (int d = 0; d < 3; ++d) {
      extent_[d] = std::min(extent_[d], b[d]);
      extent_[d + 3] = std::max(extent_[d + 3], b[d + 3]);
    }
    sizes.push_back(std::max(b[3] - b[0], b[4] - b[1]));
  }
  // Bucket size: the median plan size of a cell, so a cell spans a few buckets; at most ~4 buckets
  // per cell overall.
  std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
  const double W = extent_[3] - extent_[0], H = extent_[4] - extent_[1];
  h_ = std::max({sizes[sizes.size() / 2], std::sqrt(W * H / (4.0 * cells.size())), 1e-9 * std::max({W, H, 1.0})});
  x0_ = extent_[0];
  y0_ = extent_[1];
  nx_ = static_cast<std::size_t>(W / h_) + 1;
  ny_ = static_cast<std::size_t>(H / h_) + 1;
  auto range = [&](const std::array<double, 6>& b, std::size_t& i0, std::size_t& i1, std::size_t& j0, std::size_t& j1) {
    i0 = std::min(nx_ - 1, static_cast<std::size_t>((b[0] - x0_) / h_));
    i1 = std::min(nx_ - 1, static_cast<std::size_t>((b[3] - x0_) / h_));
    j0 = std::min(ny_ - 1, static_cast<std::size_t>((b[1] - y0_) / h_));
    j1 = std::min(ny_ - 1, static_cast<std::size_t>((b[4] - y0_) / h_));
  };
  start_.assign(nx_ * ny_ + 1, 0);
  std::size_t i0, i1, j0, j1;
  for (const auto& b : box_) {
    range(b, i0, i1, j0, j1);
    for (std::size_t j = j0; j <= j1; ++j)
      for (std::size_t i = i0; i <= i1; ++i) ++start_[j * nx_ + i + 1];
  }
  for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
  items_.resize(start_.back());
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::uint32_t c = 0; c < box_.size(); ++c) {
    range(box_[c], i0, i1, j0, j1);
    for (std::size_t j = j0; j <= j1; ++j)
      for (std::size_t i = i0; i <= i1; ++i) items_[fill[j * nx_ + i]++] = c;
  }
  // Each bucket by the cells' bottom, so a query looks at a window of the column only.
  height_.assign(nx_ * ny_, 0.0);
  for (std::size_t b = 0; b + 1 < start_.size(); ++b) {
    auto first = items_.begin() + start_[b], last = items_.begin() + start_[b + 1];
    std::sort(first, last, [&](std::uint32_t a, std::uint32_t c) { return box_[a][2] < box_[c][2] || (box_[a][2] == box_[c][2] && a < c); });
    for (auto it = first; it != last; ++it) height_[b] = std::max(height_[b], box_[*it][5] - box_[*it][2]);
  }
}

bool HexLocator::inside(std::size_t cell, const Point3& p) const {
  const auto& x = cells_[cell];
  Point3 centre{0, 0, 0};
  for (const auto& c : x)
    for (int d = 0; d < 3; ++d) centre[d] += 0.125 * c[d];
  // Everything relative to the centre: map coordinates of 5e6 m keep their precision.
  std::array<Point3, 8> r;
  for (int k = 0; k < 8; ++k) r[k] = sub(x[k], centre);
  const Point3 q = sub(p, centre);
  const auto& b = box_[cell];
  const double scale = std::max({b[3] - b[0], b[4] - b[1], b[5] - b[2]});
  const double min_volume = 1e-12 * scale * scale * scale;
  const Point3 o{0, 0, 0};
  for (const auto& f : kFaces) {
    Point3 fc{0, 0, 0};
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 3; ++d) fc[d] += 0.25 * r[f[k]][d];
    for (int k = 0; k < 4; ++k)
      if (in_tet(o, fc, r[f[k]], r[f[(k + 1) % 4]], q, min_volume)) return true;
  }
  return false;
}

std::int64_t HexLocator::locate(const Point3& p) const {
  if (!(p[0] >= extent_[0] && p[0] <= extent_[3] && p[1] >= extent_[1] && p[1] <= extent_[4] && p[2] >= extent_[2] &&
        p[2] <= extent_[5]))
    return -1;
  const std::size_t i = std::min(nx_ - 1, static_cast<std::size_t>((p[0] - x0_) / h_));
  const std::size_t j = std::min(ny_ - 1, static_cast<std::size_t>((p[1] - y0_) / h_));
  const std::size_t bucket = j * nx_ + i;
  const auto first = items_.begin() + start_[bucket], last = items_.begin() + start_[bucket + 1];
  // Cells whose bottom is at or below p and above p - (tallest cell of the bucket).
  auto hi = std::upper_bound(first, last, p[2], [&](double z, std::uint32_t c) { return z < box_[c][2]; });
  const double lowest = p[2] - height_[bucket];
  std::int64_t best = -1;
  for (auto it = hi; it != first;) {
    --it;
    const auto& b = box_[*it];
    if (b[2] < lowest) break;
    if (best >= 0 && *it > best) continue;
    if (p[0] < b[0] || p[0] > b[3] || p[1] < b[1] || p[1] > b[4] || p[2] > b[5]) continue;
    if (inside(*it, p)) best = *it;
  }
  return best;
}

std::vector<std::int64_t> HexLocator::locate(std::span<const Point3> points) const {
  std::vector<std::int64_t> cell(points.size(), -1);
  const std::size_t threads = std::max<std::size_t>(1, std::min<std::size_t>(std::thread::hardware_concurrency(), 8));
  const std::size_t chunk = (points.size() + threads - 1) / threads;
  std::vector<std::thread> pool;
  for (std::size_t t = 0; t < threads && t * chunk < points.size(); ++t)
    pool.emplace_back([&, t] {
      const std::size_t end = std::min(points.size(), (t + 1) * chunk);
      for (std::size_t k = t * chunk; k < end; ++k) cell[k] = locate(points[k]);
    });
  for (auto& th : pool) th.join();
  return cell;
}

}  // namespace ugs
