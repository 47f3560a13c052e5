#include "ugs/fem/elasticity.hpp"

#include <cmath>

#include <Eigen/Dense>
#include <fmt/format.h>

namespace ugs::fem {

std::string ti_check(const TIRatios& r) {
  const double nu_h = r.nu_z * r.nuh_over_nuz;
  if (!(r.nu_z > -1 && r.nu_z < 0.5)) return fmt::format("Poisson ratio nu_z = {} outside (-1, 0.5)", r.nu_z);
  if (!(r.Eh_over_Ez > 0) || !std::isfinite(r.Eh_over_Ez)) return fmt::format("E_h/E_z = {} must be positive", r.Eh_over_Ez);
  if (!(r.Gh_over_Gz > 0) || !std::isfinite(r.Gh_over_Gz)) return fmt::format("G_h/G_z = {} must be positive", r.Gh_over_Gz);
  if (!(nu_h > -1 && nu_h < 1)) return fmt::format("horizontal Poisson ratio nu_h = {} outside (-1, 1)", nu_h);
  if (!(ti_kappa(r) > 0))
    return fmt::format("not positive definite: 1 - nu_h - 2 nu_z^2 E_h/E_z = {:.4g} must be positive",
                       1 - nu_h - 2 * r.nu_z * r.nu_z * r.Eh_over_Ez);
  return "";
}

double ti_kappa(const TIRatios& r) {
  const double nu_h = r.nu_z * r.nuh_over_nuz;
  return 1.0 - 2.0 * r.nu_z * r.nu_z * r.Eh_over_Ez / (1.0 - nu_h);
}

double ez_from_cm(double cm, const TIRatios& r) { return ti_kappa(r) / cm; }
double cm_from_ez(double E_z, const TIRatios& r) { return ti_kappa(r) / E_z; }

Mat6 ti_constitutive_matrix(double Ez, const TIRatios& r) {
  const double Eh = r.Eh_over_Ez * Ez, nu_z = r.nu_z, nu_h = r.nu_z * r.nuh_over_nuz;
  const double Gh = Eh / (2.0 * (1.0 + nu_h)), Gz = Gh / r.Gh_over_Gz;
  Eigen::Matrix3d S;
  S << 1 / Eh, -nu_h / Eh, -nu_z / Ez,  //
      -nu_h / Eh, 1 / Eh, -nu_z / Ez,   //
      -nu_z / Ez, -nu_z / Ez, 1 / Ez;
  const Eigen::Matrix3d C = S.inverse();
  Mat6 D{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) D[6 * i + j] = 0.5 * (C(i, j) + C(j, i));  // exact symmetry
  D[6 * YZ + YZ] = Gz;
  D[6 * XZ + XZ] = Gz;
  D[6 * XY + XY] = Gh;
  return D;
}

}  // namespace ugs::fem
