// Location on the top surface with two CGAL AABB trees: the 3-D triangles for the vertical
// through a point (highest crossing wins: faulted or folded surfaces may overlap in plan), and
// the triangles flattened to z = 0 for the nearest footprint point of a point outside.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <vector>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include "ugs/formats/error.hpp"
#include "ugs/insar/surface.hpp"

namespace ugs::insar {

namespace {
using K = CGAL::Simple_cartesian<double>;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

// Barycentric weights of (x, y) in the plan projection of triangle (a, b, c).
std::array<double, 3> plan_weights(const Point3& a, const Point3& b, const Point3& c, double x, double y) {
  const double det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
  const double l1 = ((x - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (y - a[1])) / det;
  const double l2 = ((b[0] - a[0]) * (y - a[1]) - (x - a[0]) * (b[1] - a[1])) / det;
  return {1.0 - l1 - l2, l1, l2};
}

double plan_area2(const Point3& a, const Point3& b, const Point3& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
}
}  // namespace

struct SurfaceLocator::Impl {
  Triangles solid, flat;
  std::vector<std::uint32_t> solid_id;  // tree primitive (in both trees) -> surface triangle
  Tree solid_tree, flat_tree;
  double zmin = 0, zmax = 0, tol = 0, area_tol = 0;
};

SurfaceLocator::SurfaceLocator(const TopSurface& s) : impl_(std::make_unique<Impl>()), surface_(s) {
  if (s.triangles.empty()) throw InputError(s.source, "top surface has no triangles");
  auto& m = *impl_;
  const auto e = s.extent();
  const double size = std::max({e[1] - e[0], e[3] - e[2], 1.0});
  m.tol = 1e-9 * size;
  m.area_tol = 1e-14 * size * size;
  m.zmin = std::numeric_limits<double>::max();
  m.zmax = -m.zmin;
  for (std::uint32_t t = 0; t < s.triangles.size(); ++t) {
    const auto& tr = s.triangles[t];
    const Point3 &a = s.points[tr[0]], &b = s.points[tr[1]], &c = s.points[tr[2]];
    if (std::abs(plan_area2(a, b, c)) <= m.area_tol) continue;  // vertical: no plan footprint
    for (const auto* p : {&a, &b, &c}) {
      m.zmin = std::min(m.zmin, (*p)[2]);
      m.zmax = std::max(m.zmax, (*p)[2]);
    }
    m.solid.emplace_back(K::Point_3(a[0], a[1], a[2]), K::Point_3(b[0], b[1], b[2]), K::Point_3(c[0], c[1], c[2]));
    m.flat.emplace_back(K::Point_3(a[0], a[1], 0), K::Point_3(b[0], b[1], 0), K::Point_3(c[0], c[1], 0));
    m.solid_id.push_back(t);
  }
  if (m.solid.empty()) throw InputError(s.source, "top surface has no triangle with a plan footprint");
  m.solid_tree.insert(m.solid.begin(), m.solid.end());
  m.solid_tree.build();
  m.flat_tree.insert(m.flat.begin(), m.flat.end());
  m.flat_tree.build();
  m.flat_tree.accelerate_distance_queries();
}

SurfaceLocator::~SurfaceLocator() = default;

SurfaceHit SurfaceLocator::locate(double x, double y) const {
  const auto& m = *impl_;
  const auto& s = surface_;
  SurfaceHit best;
  double best_z = -std::numeric_limits<double>::max();
  const double pad = 1.0 + 1e-3 * (m.zmax - m.zmin);
  K::Segment_3 vertical(K::Point_3(x, y, m.zmax + pad), K::Point_3(x, y, m.zmin - pad));
  std::vector<Tree::Primitive_id> hits;
  m.solid_tree.all_intersected_primitives(vertical, std::back_inserter(hits));
  for (const auto& h : hits) {
    const std::uint32_t t = m.solid_id[static_cast<std::size_t>(h - m.solid.begin())];
    const auto& tr = s.triangles[t];
    const auto w = plan_weights(s.points[tr[0]], s.points[tr[1]], s.points[tr[2]], x, y);
    if (std::min({w[0], w[1], w[2]}) < -1e-9) continue;
    const double z = w[0] * s.points[tr[0]][2] + w[1] * s.points[tr[1]][2] + w[2] * s.points[tr[2]][2];
    if (z > best_z) {
      best_z = z;
      best.inside = true;
      best.triangle = t;
      best.weights = w;
      best.point = {x, y, z};
      best.distance = 0;
    }
  }
  if (best.inside) return best;
  // Outside (or exactly on an edge the segment test missed): nearest point of the plan footprint.
  const auto [p, id] = m.flat_tree.closest_point_and_primitive(K::Point_3(x, y, 0));
  const std::uint32_t t = m.solid_id[static_cast<std::size_t>(id - m.flat.begin())];
  const auto& tr = s.triangles[t];
  auto w = plan_weights(s.points[tr[0]], s.points[tr[1]], s.points[tr[2]], p.x(), p.y());
  for (double& v : w) v = std::max(v, 0.0);
  const double sum = w[0] + w[1] + w[2];
  for (double& v : w) v /= sum;
  best.triangle = t;
  best.weights = w;
  best.distance = std::hypot(p.x() - x, p.y() - y);
  best.inside = best.distance <= m.tol;
  const double z = w[0] * s.points[tr[0]][2] + w[1] * s.points[tr[1]][2] + w[2] * s.points[tr[2]][2];
  best.point = {best.inside ? x : p.x(), best.inside ? y : p.y(), z};
  if (best.inside) best.distance = 0;
  return best;
}

}  // namespace ugs::insar
