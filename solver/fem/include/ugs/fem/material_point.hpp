// The constitutive update of one element (one material point: strains and stresses are constant in
// a linear tetrahedron) for the three laws of the case file:
//   linear       sigma' - sigma'_0 = D eps, D of eq. 3.22 with a given E_z
//   elastic      the same with E_z from c_M (eq. 3.23) at the initial effective vertical stress
//   hypoplastic  d sigma' = D_t d eps, D_t = Dhat / c(sigma_z) with c from the hypo-plastic law
// Dhat is D at c_M = 1/Pa (so D = Dhat / c_M and Dhat_zz = 1): every stress component scales with
// the current vertical compressibility, the ratios of Table 4.3 stay fixed.
//
// Hypo-plastic step: for the strain increment de of the step, w = (Dhat de)_z and J = -w is the
// vertical strain magnitude the compressibility law must absorb; sigma_z moves from s0 to s1 with
// integral c = J (hypoplastic.hpp), and de sigma = Dhat de / c_sec, c_sec = J / (s1 - s0), which is
// exact for a proportional strain path. The tangent returned is
//   D_t = Dhat / c_sec + (1/c_1 - 1/c_sec) d d^T,  d = Dhat e_z,
// the consistent tangent for an oedometric increment and symmetric positive definite always (so CG
// applies); elsewhere it is a quasi-Newton approximation (docs/mechanics.md).
#pragma once
#include <string>

#include "ugs/fem/elasticity.hpp"
#include "ugs/fem/hypoplastic.hpp"
#include "ugs/fem/voigt.hpp"

namespace ugs::fem {

enum class Law { Linear, Elastic, Hypoplastic };

struct Material {
  std::string name;
  Law law = Law::Elastic;
  TIRatios ratios;
  double biot = 1.0;
  double E_z = 0;        // Pa, linear law only
  HypoParams hypo;       // compressibility law (elastic and hypoplastic), c_R and rule (hypoplastic)
  Mat6 Dhat{};           // D at c_M = 1/Pa
  Mat6 D_linear{};       // linear law

  // Fills Dhat (and D_linear); throws std::invalid_argument with the reason for a bad parameter set.
  void finalize();
  // Constitutive matrix of the elastic law for the initial vertical stress s0 [MPa].
  Mat6 elastic_D(double s0_mpa) const;
};

// Hypo-plastic state of an element at the start of a step.
struct PointState {
  Vec6 eps{};      // strain change from the initial state
  Vec6 dsig{};     // effective stress change from the initial state [Pa]
  HypoState hypo;  // preconsolidation, inversion stress, direction
};

struct PointUpdate {
  Vec6 dsig{};       // effective stress change from the initial state at the trial strain [Pa]
  Mat6 Dt{};         // tangent [Pa]
  double c_tangent;  // 1/MPa, at the end of the step
  double c_secant;   // 1/MPa, over the step
  LoadingPhase phase;
  HypoState hypo;    // the state if this trial is accepted
  bool saturated = false;
  double J = 0;
  double J_knee = 0; // J where the element passes from the unloading/reloading to the virgin branch
};

// The tangent of the hypo-plastic update: Consistent is the exact derivative of the stress (not
// symmetric: Newton converges quadratically, the linear solver must be GMRES or LU); Symmetric
// keeps only the oedometric part of the rank-one term (exact for oedometric strain; a quasi-Newton
// elsewhere, for Cholesky solvers).
enum class TangentForm { Consistent, Symmetric };

// Hypo-plastic update from `start` (whose total effective vertical stress magnitude is s_start
// [MPa]) to the trial strain `eps`.
// `hold`: see hypo_integrate. PointUpdate::J is the vertical strain magnitude of the step.
PointUpdate hypo_update(const Material& m, const PointState& start, double s_start_mpa, const Vec6& eps, int direction_guess,
                        Hold hold = Hold::None, TangentForm form = TangentForm::Consistent);

// The symmetric form of an update's tangent (SPD: 1/c_tangent > 0 and Dhat_zz,zz = 1).
Mat6 symmetric_tangent(const Material& m, const PointUpdate& u);

}  // namespace ugs::fem
