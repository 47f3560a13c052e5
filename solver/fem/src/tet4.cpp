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
  // The one flat test, which ugs-meshgen checks every tetrahedron against (formats/mesh.hpp).
  if (tet_is_degenerate(x[0], x[1], x[2], x[3])) throw std::domain_error("degenerate tetrahedron");
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
  // K = V B^T D B with B's three nonzeros per column (tet4_strain_matrix): the products skip B's
  // zeros, which the dense product adds as +-0 to a sum begun at +0 and so leaves unchanged, and
  // take the others in the same order: the dense product's bits at half its work.
  int rows[12][3];
  double vals[12][3];
  auto column = [&](int j, int r0, int r1, int r2, double v0, double v1, double v2) {
    rows[j][0] = r0, rows[j][1] = r1, rows[j][2] = r2;  // increasing, as the dense sum runs
    vals[j][0] = v0, vals[j][1] = v1, vals[j][2] = v2;
  };
  for (int i = 0; i < 4; ++i) {
    const double bx = t.grad[i][0], by = t.grad[i][1], bz = t.grad[i][2];
    column(3 * i, XX, XZ, XY, bx, bz, by);
    column(3 * i + 1, YY, YZ, XY, by, bz, bx);
    column(3 * i + 2, ZZ, YZ, XZ, bz, by, bx);
  }
  const double v = std::abs(t.volume);
  double DB[72];  // D * B (6 x 12)
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 12; ++j) {
      double s = 0;
      for (int q = 0; q < 3; ++q) s += D[6 * i + rows[j][q]] * vals[j][q];
      DB[12 * i + j] = s;
    }
  // D need not be symmetric (the consistent hypo-plastic tangent is not): every entry is formed.
  std::array<double, 144> K{};
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) {
      double s = 0;
      for (int q = 0; q < 3; ++q) s += vals[i][q] * DB[12 * rows[i][q] + j];
      K[12 * i + j] = v * s;
    }
  return K;
}

}  // namespace ugs::fem
