// Voigt notation of the thesis (eqs. 3.3-3.4) and the one conversion to the order of output fields.
//
// Inside the solver, symmetric tensors are 6-vectors in the thesis order
//     [xx, yy, zz, yz, xz, xy]
// with engineering shear strains (gamma_yz = 2 eps_yz), so that sigma = D eps and the strain
// matrix B of eq. 3.44 read as in the thesis. Output fields (formats/field.hpp, ParaView's Tensor6)
// use [xx, yy, zz, xy, yz, xz] with tensor components (eps_xy, not gamma_xy).
#pragma once
#include <array>

namespace ugs::fem {

using Vec6 = std::array<double, 6>;
using Mat6 = std::array<double, 36>;  // row-major 6 x 6

enum Voigt : int { XX = 0, YY = 1, ZZ = 2, YZ = 3, XZ = 4, XY = 5 };

// Thesis order -> output order [xx, yy, zz, xy, yz, xz]; shear strains are halved.
inline std::array<double, 6> stress_to_output(const Vec6& s) { return {s[XX], s[YY], s[ZZ], s[XY], s[YZ], s[XZ]}; }
inline std::array<double, 6> strain_to_output(const Vec6& e) {
  return {e[XX], e[YY], e[ZZ], 0.5 * e[XY], 0.5 * e[YZ], 0.5 * e[XZ]};
}
// Output order -> thesis order (inverse of the two above).
inline Vec6 stress_from_output(const std::array<double, 6>& o) { return {o[0], o[1], o[2], o[4], o[5], o[3]}; }
inline Vec6 strain_from_output(const std::array<double, 6>& o) {
  return {o[0], o[1], o[2], 2.0 * o[4], 2.0 * o[5], 2.0 * o[3]};
}

inline Vec6 mat_vec(const Mat6& m, const Vec6& v) {
  Vec6 r{};
  for (int i = 0; i < 6; ++i) {
    double s = 0;
    for (int j = 0; j < 6; ++j) s += m[6 * i + j] * v[j];
    r[i] = s;
  }
  return r;
}

}  // namespace ugs::fem
