// Integrity of intact rock at one point (docs/caprock.md): the tensile margin against hydraulic
// fracturing and the Mohr-Coulomb shear margin, from the total stress and the pore pressure.
//   fracture pressure  p_frac = S3 + T0, S3 the least compressive principal total stress (a
//                      magnitude, compression positive) and T0 the tensile strength;
//   tensile margin     p_frac - p (fractures open at p >= p_frac);
//   shear margin       c cos(phi) + s'_m sin(phi) - t_m, with s'_m = (s'1 + s'3) / 2 and
//                      t_m = (s'1 - s'3) / 2 of the Terzaghi effective principal stresses
//                      s' = S - p (compression positive): the Mohr circle touches the
//                      Mohr-Coulomb line at a margin of zero.
// Failure criteria of rock use Terzaghi's effective stress (Biot's alpha only enters the
// deformation, through the solver's effective stress).
#pragma once
#include <array>

namespace ugs::fem {

struct RockStrength {
  double cohesion_Pa = 0;
  double friction_deg = 30;
  double tensile_strength_Pa = 0;
};

struct RockMargins {
  double fracture_pressure_Pa = 0;  // S3 + T0
  double tensile_margin_Pa = 0;     // fracture pressure - p
  double shear_margin_Pa = 0;       // distance (in shear stress) of the Mohr circle below the line
  double S1_Pa = 0, S3_Pa = 0;      // most and least compressive principal total stresses (magnitudes)
};

// `total_stress` in output Voigt order (xx, yy, zz, xy, yz, xz; Pa, tension positive) and the pore
// pressure p (Pa).
RockMargins rock_margins(const std::array<double, 6>& total_stress, double p, const RockStrength& strength);

// The principal values of a symmetric stress (output Voigt order), ascending (tension positive:
// the first is the most compressive).
std::array<double, 3> principal_values(const std::array<double, 6>& s);

}  // namespace ugs::fem
