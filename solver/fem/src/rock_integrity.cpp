#include "ugs/fem/rock_integrity.hpp"

#include <cmath>

#include <Eigen/Eigenvalues>

namespace ugs::fem {

std::array<double, 3> principal_values(const std::array<double, 6>& s) {
  Eigen::Matrix3d m;
  m << s[0], s[3], s[5],  //
      s[3], s[1], s[4],   //
      s[5], s[4], s[2];
  // Closed-form 3x3 solver: no iteration, the same result for the same input on every run.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(m, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d v = es.eigenvalues();  // ascending
  return {v[0], v[1], v[2]};
}

RockMargins rock_margins(const std::array<double, 6>& total_stress, double p, const RockStrength& strength) {
  const std::array<double, 3> e = principal_values(total_stress);
  RockMargins r;
  r.S1_Pa = -e[0];  // the most compressive (tension positive: the smallest value)
  r.S3_Pa = -e[2];
  r.fracture_pressure_Pa = r.S3_Pa + strength.tensile_strength_Pa;
  r.tensile_margin_Pa = r.fracture_pressure_Pa - p;
  const double s1 = r.S1_Pa - p, s3 = r.S3_Pa - p;  // Terzaghi effective, compression positive
  const double phi = strength.friction_deg * M_PI / 180.0;
  const double mean = 0.5 * (s1 + s3), radius = 0.5 * (s1 - s3);
  r.shear_margin_Pa = strength.cohesion_Pa * std::cos(phi) + mean * std::sin(phi) - radius;
  return r;
}

}  // namespace ugs::fem
