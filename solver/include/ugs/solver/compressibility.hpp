// Vertical uniaxial compressibility c_M as a function of the effective vertical stress
// (thesis eq. 4.1): c_M = a * sigma_z^-b, sigma_z in MPa (compression positive), c_M in 1/MPa.
// Used by the flow model (specific storage) and the mechanics (E_z from c_M, eq. 3.23).
#pragma once

namespace ugs {

struct CompressibilityLaw {
  double a = 1.0044e-2;  // 1/MPa at 1 MPa
  double b = 1.1347;

  // Virgin-loading compressibility at effective vertical stress sigma_z [MPa], in 1/MPa.
  double cm(double sigma_z_mpa) const;
  // Vertical strain magnitude accumulated on the virgin curve from s0 to s1 [MPa]:
  // the integral of c_M over sigma, a (s1^(1-b) - s0^(1-b)) / (1-b).
  double virgin_strain(double s0_mpa, double s1_mpa) const;
};

// Oedometric (constrained) vertical modulus from c_M, E_oed = 1/c_M, and the vertical Young's
// modulus of eq. 3.23 for a transversely isotropic medium: E_z = (1 - 2 nu_h nu_z^2/(1-nu_h) ... )
// is implemented in the mechanics; here only the isotropic form used by the tests and flow:
// E = (1+nu)(1-2nu) / ((1-nu) c_M).
double young_from_cm(double cm_per_pa, double nu);

}  // namespace ugs
