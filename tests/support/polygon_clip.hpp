// Planar polygons in 3D for tests that measure a fault's area inside a box independently of the
// fault cut (test_dipping_faults, test_surface_faults).
#pragma once
#include <cmath>
#include <vector>

#include "ugs/formats/mesh.hpp"

namespace ugs::test {

// Sutherland-Hodgman: the part of a planar polygon where m . x <= d.
inline std::vector<Point3> clip_polygon(const std::vector<Point3>& poly, const Point3& m, double d) {
  const auto side = [&](const Point3& p) { return m[0] * p[0] + m[1] * p[1] + m[2] * p[2] - d; };
  std::vector<Point3> out;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point3& a = poly[i];
    const Point3& b = poly[(i + 1) % poly.size()];
    const double fa = side(a), fb = side(b);
    if (fa <= 0) out.push_back(a);
    if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) {
      const double s = fa / (fa - fb);
      out.push_back({a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), a[2] + s * (b[2] - a[2])});
    }
  }
  return out;
}

// The part of a planar polygon inside the box [0, x1] x [0, y1] x [z0, 0] (z0 < 0).
inline std::vector<Point3> clip_to_box(std::vector<Point3> q, double x1, double y1, double z0) {
  q = clip_polygon(q, {1, 0, 0}, x1);
  q = clip_polygon(q, {-1, 0, 0}, 0);
  q = clip_polygon(q, {0, 1, 0}, y1);
  q = clip_polygon(q, {0, -1, 0}, 0);
  q = clip_polygon(q, {0, 0, 1}, 0);
  return clip_polygon(q, {0, 0, -1}, -z0);
}

// Area of a planar polygon (fan of triangles from its first vertex).
inline double polygon_area(const std::vector<Point3>& p) {
  double s[3] = {0, 0, 0};
  for (std::size_t i = 1; i + 1 < p.size(); ++i) {
    const double u[3] = {p[i][0] - p[0][0], p[i][1] - p[0][1], p[i][2] - p[0][2]};
    const double v[3] = {p[i + 1][0] - p[0][0], p[i + 1][1] - p[0][1], p[i + 1][2] - p[0][2]};
    s[0] += u[1] * v[2] - u[2] * v[1];
    s[1] += u[2] * v[0] - u[0] * v[2];
    s[2] += u[0] * v[1] - u[1] * v[0];
  }
  return 0.5 * std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
}

}  // namespace ugs::test
