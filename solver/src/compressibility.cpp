#include "ugs/solver/compressibility.hpp"

#include <cmath>
#include <stdexcept>

namespace ugs {

double CompressibilityLaw::cm(double sigma_z_mpa) const {
  if (!(sigma_z_mpa > 0)) throw std::domain_error("compressibility law needs a positive effective stress");
  return a * std::pow(sigma_z_mpa, -b);
}

double CompressibilityLaw::virgin_strain(double s0, double s1) const {
  return a * (std::pow(s1, 1.0 - b) - std::pow(s0, 1.0 - b)) / (1.0 - b);
}

double young_from_cm(double cm_per_pa, double nu) {
  return (1.0 + nu) * (1.0 - 2.0 * nu) / ((1.0 - nu) * cm_per_pa);
}

}  // namespace ugs
