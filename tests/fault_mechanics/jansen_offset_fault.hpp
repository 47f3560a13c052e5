// Closed form of V8 (VERIFICATION.md): the stress change around a depleted reservoir offset by a
// fault, in plane strain, in an infinite homogeneous linear elastic medium (Jansen, Singhal &
// Vossepoel 2019; inclusion theory: Goodier's displacement potential).
//
// A pressure change dp inside a region Omega with Biot coefficient alpha acts as an isotropic
// eigenstrain. With u = grad phi, Navier's equation gives lap phi = kappa chi_Omega,
// kappa = alpha dp / (lambda + 2 mu), so phi = kappa / (2 pi) int_Omega ln|x - x'| dA' and
//
//   eps_ij = kappa / (2 pi) H_ij,   H_ij(x) = d_i d_j int_Omega ln|x - x'| dA'
//          = - sum over the edges of Omega of n_j int_edge (x_i - x'_i) / |x - x'|^2 ds'
//
// (divergence theorem; n the outward normal of the edge). On a straight edge from a, unit tangent e,
// length L, with d = x - a, d_e = d.e, d_n = d.n, the integral is e I_e + n I_n with
//   I_e = 1/2 ln((d_e^2 + d_n^2) / ((d_e - L)^2 + d_n^2)),  I_n = atan2(L d_n, d_n^2 + d_e (d_e - L))
// (I_n is minus the angle the edge subtends at x; the angles add to -2 pi inside, 0 outside).
// The total stress change is sigma = lambda tr(eps) I + 2 mu eps - alpha dp chi_Omega I
// (tension positive); in the plane (x, z) with z up. Outside Omega tr(eps) = 0.
//
// Geometry (x horizontal, z up): the fault is the line through (0, zc) dipping theta,
// x_f(z) = (z - zc) / tan(theta) (it rises to +x). The reservoir is two blocks of height h, the
// hanging wall (x < x_f) from x = -W_left to the fault with z in [zc - (h + t)/2, zc + (h - t)/2]
// and the footwall (x > x_f) from the fault to x = W_right with z in [zc - (h - t)/2, zc + (h + t)/2]
// (throw t < h, a normal fault). Along the fault the four corners are, from the bottom,
// z = zc - (h + t)/2, zc - (h - t)/2, zc + (h - t)/2, zc + (h + t)/2. The normal and shear tractions
// on the fault are continuous across it (the stress tensor is not: the pressure jumps), singular
// (logarithmically) at the corners.
#pragma once
#include <array>
#include <cmath>
#include <vector>

namespace ugs::test::jansen {

struct OffsetReservoir {
  double h = 100;       // reservoir height [m]
  double t = 100.0 / 3; // throw [m], 0 <= t < h
  double theta = 0;     // dip [rad], in (0, pi/2]
  double W_left = 1000, W_right = 1000;  // lateral ends of the blocks: x = -W_left and x = W_right
  double zc = 0;        // the fault passes through (0, zc), the middle of the offset reservoir
  double E = 10e9, nu = 0.25, alpha = 1.0;
  double dp = -10e6;    // pressure change inside the reservoir [Pa]

  double fault_x(double z) const { return (z - zc) / std::tan(theta); }
  // The four corners along the fault (z), bottom to top.
  std::array<double, 4> corners() const {
    return {zc - (h + t) / 2, zc - (h - t) / 2, zc + (h - t) / 2, zc + (h + t) / 2};
  }
  // The two blocks as counter-clockwise polygons in (x, z).
  std::vector<std::vector<std::array<double, 2>>> blocks() const {
    const auto c = corners();
    const double zh0 = c[0], zh1 = c[2], zf0 = c[1], zf1 = c[3];
    return {{{-W_left, zh0}, {fault_x(zh0), zh0}, {fault_x(zh1), zh1}, {-W_left, zh1}},
            {{fault_x(zf0), zf0}, {W_right, zf0}, {W_right, zf1}, {fault_x(zf1), zf1}}};
  }
};

// H_ij of one polygon at (x, z) (indices 0 = x, 1 = z) and its winding term (-2 pi inside, 0 outside).
inline std::array<double, 4> polygon_H(const std::vector<std::array<double, 2>>& poly, double x, double z, double& winding) {
  std::array<double, 4> H{0, 0, 0, 0};  // xx, xz, zx, zz
  winding = 0;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const auto& a = poly[k];
    const auto& b = poly[(k + 1) % poly.size()];
    const double L = std::hypot(b[0] - a[0], b[1] - a[1]);
    const double e[2] = {(b[0] - a[0]) / L, (b[1] - a[1]) / L};
    const double n[2] = {e[1], -e[0]};  // outward for a counter-clockwise polygon
    const double d[2] = {x - a[0], z - a[1]};
    const double de = d[0] * e[0] + d[1] * e[1], dn = d[0] * n[0] + d[1] * n[1];
    const double Ie = 0.5 * std::log((de * de + dn * dn) / ((de - L) * (de - L) + dn * dn));
    const double In = std::atan2(L * dn, dn * dn + de * (de - L));
    winding += In;
    const double v[2] = {Ie * e[0] + In * n[0], Ie * e[1] + In * n[1]};
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) H[2 * i + j] -= v[i] * n[j];
  }
  return H;
}

// Total stress change (sxx, szz, sxz) [Pa] at (x, z); `inside` from the winding number.
inline std::array<double, 3> stress_change(const OffsetReservoir& r, double x, double z) {
  const double mu = r.E / (2 * (1 + r.nu)), lam = r.E * r.nu / ((1 + r.nu) * (1 - 2 * r.nu));
  const double kappa = r.alpha * r.dp / (lam + 2 * mu);
  std::array<double, 4> H{0, 0, 0, 0};
  double chi = 0;
  for (const auto& poly : r.blocks()) {
    double w = 0;
    const auto Hp = polygon_H(poly, x, z, w);
    for (int k = 0; k < 4; ++k) H[k] += Hp[k];
    chi += -w / (2 * M_PI);
  }
  const double c = kappa / (2 * M_PI);
  const double exx = c * H[0], ezz = c * H[3], exz = c * 0.5 * (H[1] + H[2]);
  const double p = r.alpha * r.dp * std::round(chi);
  return {lam * (exx + ezz) + 2 * mu * exx - p, lam * (exx + ezz) + 2 * mu * ezz - p, 2 * mu * exz};
}

// Traction change sigma n [Pa] (x, z components) on the fault at height z, for a unit normal
// n = (nx, nz) of the fault plane: the mean of the one-sided limits (offset 1e-7 h either side),
// which agree to ~1e-7 relative away from the corners.
inline std::array<double, 2> fault_traction_change(const OffsetReservoir& r, double z, double nx, double nz) {
  const double x = r.fault_x(z), eps = 1e-7 * r.h;
  std::array<double, 2> out{0, 0};
  for (double s : {-1.0, 1.0}) {
    const auto S = stress_change(r, x + s * eps * nx, z + s * eps * nz);
    out[0] += 0.5 * (S[0] * nx + S[2] * nz);
    out[1] += 0.5 * (S[2] * nx + S[1] * nz);
  }
  return out;
}

}  // namespace ugs::test::jansen
