#include "ugs/fem/tet4.hpp"

#include <cmath>
#include <stdexcept>

namespace ugs::fem {

Tet4 tet4(const std::array<Point3, 4>& x) {
  // Jacobian columns: edges from vertex 0; gradients of xi_1..3 are the rows of J^-1, xi_0 = 1 - sum.
  const double a[3] = {x[1][0] - x[0][0], x[1][1] - x[0][1], x[1][2] - x[0][2]};
  const double b[3] = {x[2][0] - x[0][0], x[2][1] - x[0][1], x[2][2] - x[0][2]};
  const double c[3] = {x[3][0] - x[0][0], x[3][1] - x[0][1], x[3][2] - x[0][2]};
  // Rows of the inverse of [a b c] (as columns) are (b x c, c x a, a x b) / det.
  const double bxc[3] = {b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]};
  const double cxa[3] = {c[1] * a[2] - c[2] * a[1], c[2] * a[0] - c[0] * a[2], c[0] * a[1] - c[1] * a[0]};
  const double axb[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  const double det = a[0] * bxc[0] + a[1] * bxc[1] + a[2] * bxc[2];
  const double scale = std::abs(a[0]) + std::abs(a[1]) + std::abs(a[2]) + std::abs(b[0]) + std::abs(b[1]) +
                       std::abs(b[2]) + std::abs(c[0]) + std::abs(c[1]) + std::abs(c[2]);
  if (!(std::abs(det) > 1e-14 * scale * scale * scale)) throw std::domain_error("degenerate tetrahedron");
  Tet4 t;
  t.volume = det / 6.0;
  for (int k = 0; k < 3; ++k) {
    t.grad[1][k] = bxc[k] / det;
    t.grad[2][k] = cxa[k] / det;
    t.grad[3][k] = axb[k] / det;
    t.grad[0][k] = -(t.grad[1][k] + t.grad[2][k] + t.grad[3][k]);
  }
  return t;
}

Vec6 tet4_strain(const Tet4& t, const double* u) {
  Vec6 e{};
  for (int i = 0; i < 4; ++i) {
    const double bx = t.grad[i][0], by = t.grad[i][1], bz = t.grad[i][2];
    const double ux = u[3 * i], uy = u[3 * i + 1], uz = u[3 * i + 2];
    e[XX] += bx * ux;
    e[YY] += by * uy;
    e[ZZ] += bz * uz;
    e[YZ] += bz * uy + by * uz;
    e[XZ] += bz * ux + bx * uz;
    e[XY] += by * ux + bx * uy;
  }
  return e;
}

std::array<double, 72> tet4_strain_matrix(const Tet4& t) {
  std::array<double, 72> B{};
  for (int i = 0; i < 4; ++i) {
    const double bx = t.grad[i][0], by = t.grad[i][1], bz = t.grad[i][2];
    const int c = 3 * i;
    B[12 * XX + c] = bx;
    B[12 * YY + c + 1] = by;
    B[12 * ZZ + c + 2] = bz;
    B[12 * YZ + c + 1] = bz;
    B[12 * YZ + c + 2] = by;
    B[12 * XZ + c] = bz;
    B[12 * XZ + c + 2] = bx;
    B[12 * XY + c] = by;
    B[12 * XY + c + 1] = bx;
  }
  return B;
}

void tet4_add_internal_force(const Tet4& t, const Vec6& s, double* f) {
  const double v = std::abs(t.volume);
  for (int i = 0; i < 4; ++i) {
    const double bx = t.grad[i][0], by = t.grad[i][1], bz = t.grad[i][2];
    f[3 * i] += v * (bx * s[XX] + bz * s[XZ] + by * s[XY]);
    f[3 * i + 1] += v * (by * s[YY] + bz * s[YZ] + bx * s[XY]);
    f[3 * i + 2] += v * (bz * s[ZZ] + by * s[YZ] + bx * s[XZ]);
  }
}

std::array<double, 144> tet4_stiffness(const Tet4& t, const Mat6& D) {
  const auto B = tet4_strain_matrix(t);
  const double v = std::abs(t.volume);
  // DB = D * B (6 x 12), then K = V B^T (DB); B is sparse but the dense product is cheap enough.
  double DB[72];
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 12; ++j) {
      double s = 0;
      for (int k = 0; k < 6; ++k) s += D[6 * i + k] * B[12 * k + j];
      DB[12 * i + j] = s;
    }
  // D need not be symmetric (the consistent hypo-plastic tangent is not): every entry is formed.
  std::array<double, 144> K{};
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) {
      double s = 0;
      for (int k = 0; k < 6; ++k) s += B[12 * k + i] * DB[12 * k + j];
      K[12 * i + j] = v * s;
    }
  return K;
}

}  // namespace ugs::fem
