// Arithmetic on Point3 for the meshing sources (common, faults); not meant for code outside meshing/.
#pragma once

#include <cmath>

#include "ugs/formats/mesh.hpp"

namespace ugs::vec3 {

inline Point3 sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Point3 add(const Point3& a, const Point3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Point3 scaled(const Point3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline double norm(const Point3& a) { return std::sqrt(dot(a, a)); }
inline Point3 unit(const Point3& a) { return scaled(a, 1.0 / norm(a)); }

}  // namespace ugs::vec3
