// The hypo-plastic vertical compressibility of thesis 4.2 (eq. 4.1) and its exact integration over
// a load step.
//
// sigma is the magnitude of the effective vertical stress in MPa (compression positive), J the
// vertical "oedometric" strain increment (compression positive): d J = c(sigma) d sigma.
//  - virgin loading (sigma above the preconsolidation stress sigma_max): c = a sigma^-b;
//  - unloading, and reloading below sigma_max, by the inversion rule:
//      sigma-max        c = c_M(sigma_max) / c_R          (default; VERIFICATION.md V1)
//      sigma-inversion  c = c_M(sigma_inv) / c_R, sigma_inv the stress at the last load inversion
//      stress-dependent c = c_M(sigma) / c_R
//  - reloading past sigma_max continues on the virgin curve.
// Below sigma_min the law is held at c_M(sigma_min) (the law is singular at sigma = 0).
//
// Integration over a step is exact for a proportional strain path: sigma1 solves
// integral_{sigma0}^{sigma1} c = J piecewise in closed form, including the crossing of sigma_max, so
// load inversions inside the pressure history need no sub-steps in the constitutive update.
#pragma once
#include <string>

namespace ugs::fem {

enum class InversionRule { SigmaMax, SigmaInversion, StressDependent };
// "sigma-max" | "sigma-inversion" | "stress-dependent"; throws std::invalid_argument otherwise.
InversionRule parse_inversion_rule(const std::string& s);
const char* inversion_rule_name(InversionRule r);

struct HypoParams {
  double a = 1.0044e-2;  // 1/MPa at 1 MPa
  double b = 1.1347;
  double c_R = 5.0;      // virgin / unloading-reloading compressibility ratio at the inversion
  double sigma_min = 0.1;  // MPa
  InversionRule rule = InversionRule::SigmaMax;

  // Virgin compressibility c_M(sigma) [1/MPa] with the sigma_min floor.
  double cm(double sigma) const;
};

struct HypoState {
  double sigma_max = 0;  // MPa, preconsolidation: the largest sigma reached so far
  double sigma_inv = 0;  // MPa, sigma at the last load inversion (sigma-inversion rule)
  int direction = +1;    // +1 last moved in compression (sigma up), -1 in unloading

  // A normally consolidated start at sigma0 (the geostatic state is the first virgin point).
  static HypoState virgin(double sigma0) { return {sigma0, sigma0, +1}; }
};

enum class LoadingPhase : int { Elastic = 0, Virgin = 1, Unloading = 2, Reloading = 3 };

// A branch the solver holds an element on for the rest of a Newton solve (the law's response is
// continuous, but its stiffness jumps by c_R at the knee J = J_knee between the unloading/reloading
// and the virgin branch; at J = 0 on the virgin curve even the lateral stress jumps, because the
// whole Dhat scales with 1/c). Held, the element follows the analytic continuation of that branch
// through the knee, so the residual is smooth; the solver checks at convergence that the held
// branch agrees with the side of the knee the element ended on (docs/mechanics.md).
// (The stiffer branch is the one Newton converges with: the softer one overshoots.)
enum class Hold : int { None = 0, UnloadReload = 2 };

struct HypoResult {
  double sigma1 = 0;     // MPa
  double c_secant = 0;   // 1/MPa: J / (sigma1 - sigma0)
  double c_tangent = 0;  // 1/MPa at sigma1, on the branch the step ended on
  HypoState state;       // the state after the step
  LoadingPhase phase = LoadingPhase::Virgin;
  bool saturated = false;  // J exceeds what the virgin law can absorb (sigma1 would be infinite)
  double J_knee = 0;       // J at which the step passes from the unloading/reloading to the virgin branch
};

// Integrates from sigma0 with the state at the start of the step. When J == 0 the tangent of the
// branch in `direction_guess` (+1 or -1) is returned (the first Newton iteration needs one).
// `hold` keeps the element on one branch on both sides of the knee (Hold above); with
// Hold::UnloadReload, `direction_guess` also fixes the inversion stress (sigma-inversion rule).
HypoResult hypo_integrate(const HypoParams& p, const HypoState& start, double sigma0, double J, int direction_guess,
                          Hold hold = Hold::None);

}  // namespace ugs::fem
