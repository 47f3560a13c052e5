// Transversely isotropic linear elasticity with a vertical axis of symmetry (thesis eq. 3.22) and
// E_z from the vertical uniaxial compressibility c_M (eq. 3.23, Gambolati et al. 1984).
//
// Compliance (thesis Voigt order [xx yy zz yz xz xy], engineering shears):
//   eps_xx = s_xx/E_h - nu_h s_yy/E_h - nu_z s_zz/E_z      gamma_yz = tau_yz / G_z
//   eps_yy = -nu_h s_xx/E_h + s_yy/E_h - nu_z s_zz/E_z     gamma_xz = tau_xz / G_z
//   eps_zz = -nu_z (s_xx + s_yy)/E_z + s_zz/E_z            gamma_xy = tau_xy / G_h, G_h = E_h/(2(1+nu_h))
// and D is its inverse. (The thesis prints 1/G_h in the yz slot of 3.22 with its shear order
// xy, yz, xz of eq. 3.5; physically the horizontal-plane shear xy carries G_h, the vertical planes
// G_z, as written here.) The material is described by E_z and the ratios of Table 4.3.
#pragma once
#include <string>

#include "ugs/fem/voigt.hpp"

namespace ugs::fem {

struct TIRatios {
  double nu_z = 0.3;
  double Eh_over_Ez = 1.0;
  double nuh_over_nuz = 1.0;
  double Gh_over_Gz = 1.0;
};

// Why a parameter set is not a valid (positive definite) TI material, or "" if it is.
std::string ti_check(const TIRatios& r);

// D of eq. 3.22 for vertical modulus E_z [Pa]. Assumes ti_check(r) is empty.
Mat6 ti_constitutive_matrix(double E_z, const TIRatios& r);

// kappa = 1 - 2 nu_z^2 (E_h/E_z) / (1 - nu_h): eq. 3.23 reads c_M = kappa / E_z.
double ti_kappa(const TIRatios& r);
// E_z [Pa] from c_M [1/Pa] by eq. 3.23.
double ez_from_cm(double cm_per_pa, const TIRatios& r);
// c_M [1/Pa] of a TI material of vertical modulus E_z: the inverse of D_zz (oedometric compliance).
double cm_from_ez(double E_z, const TIRatios& r);

}  // namespace ugs::fem
