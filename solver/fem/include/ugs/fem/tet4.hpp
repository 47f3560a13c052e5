// The linear tetrahedron of thesis 3.5.1: shape functions xi_i = (a_i + b_i x + c_i y + d_i z)/(6V)
// (eq. 3.37), their constant gradients, the strain matrix B (eq. 3.44, thesis Voigt order) and the
// element operations the solver needs, written out for speed (no temporaries on the heap).
#pragma once
#include <array>

#include "ugs/fem/voigt.hpp"
#include "ugs/formats/mesh.hpp"

namespace ugs::fem {

struct Tet4 {
  double volume = 0;                           // signed volume V^e (positive for Gmsh orientation)
  std::array<std::array<double, 3>, 4> grad{}; // d xi_i / d(x, y, z) = (b_i, c_i, d_i) / (6V)
};

// Geometry of the tetrahedron with vertices x[0..3]. Throws std::domain_error for a degenerate one.
Tet4 tet4(const std::array<Point3, 4>& x);

// Strain (thesis order, engineering shears) of nodal displacements u = [u1x u1y u1z u2x ...].
Vec6 tet4_strain(const Tet4& t, const double* u12);

// Strain matrix B (6 x 12, row-major) of eq. 3.44.
std::array<double, 72> tet4_strain_matrix(const Tet4& t);

// Adds V B^T sigma (the nodal forces of a constant stress) to f[12].
void tet4_add_internal_force(const Tet4& t, const Vec6& sigma, double* f12);

// Element stiffness V B^T D B (12 x 12, row-major, symmetric when D is).
std::array<double, 144> tet4_stiffness(const Tet4& t, const Mat6& D);

}  // namespace ugs::fem
