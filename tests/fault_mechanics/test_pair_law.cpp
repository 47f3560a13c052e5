// The contact law of one node pair (pair_law.hpp): states from the Mohr-Coulomb criterion with
// the effective normal traction, the slip direction, the Jacobian against finite differences, and
// the safety factor chi of eq. 4.2.
#include <cmath>

#include <gtest/gtest.h>

#include "ugs/contact/fault_model.hpp"
#include "ugs/contact/pair_law.hpp"

using namespace ugs::contact;

namespace {

PairLaw law() {
  PairLaw L;
  L.area = 2.0;
  L.k = 1e8;
  L.cohesion = 1e6;
  L.mu = std::tan(30 * M_PI / 180);
  return L;
}

using A3 = std::array<double, 3>;

}  // namespace

TEST(PairLaw, StickBelowTheMohrCoulombLimit) {
  // sigma_n = -20 MPa, p = 5 MPa: sigma'_n = -15 MPa, tau_L = 1 + 15 tan 30 = 9.66 MPa.
  const A3 lam{6e6, 3e6, -20e6}, zero{0, 0, 0};
  const auto e = pair_equations(law(), lam, lam, lam, zero, zero, 5e6, PairState::Stick);
  EXPECT_EQ(e.state, PairState::Stick);
  for (double f : e.F) EXPECT_EQ(f, 0.0);
  EXPECT_NEAR(safety_factor(std::hypot(6e6, 3e6), -15e6, 1e6, law().mu, e.state), std::hypot(6, 3) / (1 + 15 * law().mu), 1e-12);
}

TEST(PairLaw, SlipAboveTheLimitAlongTheShear) {
  // The same shear with a higher fluid pressure: sigma'_n = -5 MPa, tau_L = 3.89 MPa < 6.7 MPa.
  const A3 lam{6e6, 3e6, -20e6}, zero{0, 0, 0};
  const auto e = pair_equations(law(), lam, lam, lam, zero, zero, 15e6, PairState::Stick);
  ASSERT_EQ(e.state, PairState::Slip);
  const double tauL = 1e6 + 5e6 * law().mu, t = std::hypot(6e6, 3e6);
  // F_T = A (lambda_T - tau_L lambda_T / |lambda_T|): the excess shear, along the shear.
  EXPECT_NEAR(e.F[0], 2.0 * (6e6 - tauL * 6e6 / t), 1e-6);
  EXPECT_NEAR(e.F[1], 2.0 * (3e6 - tauL * 3e6 / t), 1e-6);
  EXPECT_EQ(e.F[2], 0.0);
  EXPECT_EQ(safety_factor(t, -5e6, 1e6, law().mu, e.state), 1.0);
}

TEST(PairLaw, OpenWhenTheEffectiveNormalTractionIsTensile) {
  const A3 lam{1e6, 0, -2e6}, zero{0, 0, 0};
  const auto e = pair_equations(law(), lam, lam, lam, zero, zero, 3e6, PairState::Stick);
  ASSERT_EQ(e.state, PairState::Open);
  EXPECT_NEAR(e.F[2], 2.0 * 1e6, 1e-9);  // lambda_n + p_f = 1 MPa must vanish
  EXPECT_NEAR(e.F[0], 2.0 * 1e6, 1e-9);  // no shear on open faces
  // An opening gap keeps it open even under a compressive traction estimate.
  const A3 g{0, 0, 1e-3};
  EXPECT_EQ(pair_equations(law(), {0, 0, -5e4}, lam, lam, g, zero, 0.0, PairState::Open).state, PairState::Open);
}

TEST(PairLaw, JacobianMatchesFiniteDifferences) {
  const PairLaw L = law();
  const A3 lam{7e6, -4e6, -12e6}, lam0{5e6, -2e6, -12e6}, gc{1e-4, 2e-4, 0}, g{1.3e-4, 1.5e-4, 1e-9};
  const double pf = 2e6;
  const auto e = pair_equations(L, lam, lam0, lam0, g, gc, pf, PairState::Slip);
  ASSERT_EQ(e.state, PairState::Slip);
  for (int i = 0; i < 3; ++i) {
    A3 lp = lam, lm = lam, gp = g, gm = g;
    const double hl = 1.0, hg = 1e-10;
    lp[i] += hl, lm[i] -= hl, gp[i] += hg, gm[i] -= hg;
    const auto fp = pair_equations(L, lp, lam0, lam0, g, gc, pf, PairState::Slip).F;
    const auto fm = pair_equations(L, lm, lam0, lam0, g, gc, pf, PairState::Slip).F;
    const auto gpF = pair_equations(L, lam, lam0, lam0, gp, gc, pf, PairState::Slip).F;
    const auto gmF = pair_equations(L, lam, lam0, lam0, gm, gc, pf, PairState::Slip).F;
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(e.Jl[3 * j + i], (fp[j] - fm[j]) / (2 * hl), 1e-6 * L.area) << "dF" << j << "/dl" << i;
      EXPECT_NEAR(e.Jg[3 * j + i], (gpF[j] - gmF[j]) / (2 * hg), 1e-5 * L.k * L.area) << "dF" << j << "/dg" << i;
    }
  }
}

TEST(PairLaw, InactiveComponentsKeepTheirInitialTraction) {
  PairLaw L = law();
  L.active = 1 | 4;  // the dip component acts on prescribed displacements only (plane strain)
  const A3 lam{6e6, 5e6, -20e6}, lam0{6e6, 0, -20e6}, zero{0, 0, 0};
  const auto e = pair_equations(L, lam, lam0, lam0, zero, zero, 15e6, PairState::Stick);
  EXPECT_EQ(e.state, PairState::Slip);  // |tau| = 6 MPa on the strike alone > tau_L = 3.89 MPa
  EXPECT_NEAR(e.F[1], L.area * 5e6, 1e-6);
  EXPECT_EQ(e.Jl[4], L.area);
}

TEST(PairLaw, HysteresisKeepsAPairOnTheLimitInItsState) {
  // |eta| = tau_L exactly (to round-off): the previous state stands.
  const double tauL = 1e6 + 10e6 * law().mu;
  const A3 lam{tauL * (1 + 1e-13), 0, -10e6}, zero{0, 0, 0};
  EXPECT_EQ(pair_equations(law(), lam, lam, lam, zero, zero, 0, PairState::Stick).state, PairState::Stick);
  EXPECT_EQ(pair_equations(law(), lam, lam, lam, zero, zero, 0, PairState::Slip).state, PairState::Slip);
}

TEST(FaultFrame, StrikeDipNormalRightHanded) {
  const double d = 60 * M_PI / 180;
  const auto R = fault_frame({-std::sin(d), 0, -std::cos(d)});
  // t1 horizontal, t2 = n x t1, t1 x t2 = n.
  EXPECT_NEAR(R[6], 0, 1e-15);
  const double t1[3] = {R[0], R[3], R[6]}, t2[3] = {R[1], R[4], R[7]}, n[3] = {R[2], R[5], R[8]};
  const double c[3] = {t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2], t1[0] * t2[1] - t1[1] * t2[0]};
  // Unit vectors from libm's sin/cos (last bit CPU-dependent) through normalisations and a cross
  // product: a few ulps each, so 1e-14 (45 u), not 1e-15 (4.5 u).
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], n[k], 1e-14);
  const auto H = fault_frame({0, 0, -1});
  EXPECT_NEAR(H[0], 1.0, 1e-15);  // horizontal fault: strike along x
}
