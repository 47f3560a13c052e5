// Unit tests of the finite element kernels (ugs_fem): the linear tetrahedron, the transversely
// isotropic D of eq. 3.22 with E_z from c_M (eq. 3.23), and the hypo-plastic law at one material
// point against the closed forms of VERIFICATION.md V1 (all three inversion rules).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include <gtest/gtest.h>

#include "v1_oedometer.hpp"
#include "ugs/fem/elasticity.hpp"
#include "ugs/fem/hypoplastic.hpp"
#include "ugs/fem/material_point.hpp"
#include "ugs/fem/tet4.hpp"

using namespace ugs;
using namespace ugs::fem;

namespace {

// 3x3 normal block of D times S (compliance) must be the identity.
std::array<double, 9> normal_compliance(double Ez, const TIRatios& r) {
  const double Eh = r.Eh_over_Ez * Ez, nu_z = r.nu_z, nu_h = r.nu_z * r.nuh_over_nuz;
  return {1 / Eh, -nu_h / Eh, -nu_z / Ez, -nu_h / Eh, 1 / Eh, -nu_z / Ez, -nu_z / Ez, -nu_z / Ez, 1 / Ez};
}

}  // namespace

TEST(Tet4, GradientsVolumeAndLinearFieldsAreExact) {
  const std::array<Point3, 4> x{{{0.1, 0.2, 0.0}, {2.0, 0.1, 0.3}, {0.4, 1.7, 0.2}, {0.3, 0.5, 1.9}}};
  const Tet4 t = tet4(x);
  EXPECT_NEAR(t.volume, tet_signed_volume(x[0], x[1], x[2], x[3]), 1e-14);
  // A linear displacement u = E x + c gives the strain of E in every component.
  const double E[3][3] = {{1e-3, 2e-4, -3e-4}, {5e-4, -2e-3, 1e-4}, {-4e-4, 7e-4, 3e-3}};
  double u[12];
  for (int i = 0; i < 4; ++i)
    for (int a = 0; a < 3; ++a) u[3 * i + a] = 0.01 * (a + 1) + E[a][0] * x[i][0] + E[a][1] * x[i][1] + E[a][2] * x[i][2];
  const Vec6 e = tet4_strain(t, u);
  EXPECT_NEAR(e[XX], E[0][0], 1e-15);
  EXPECT_NEAR(e[YY], E[1][1], 1e-15);
  EXPECT_NEAR(e[ZZ], E[2][2], 1e-15);
  EXPECT_NEAR(e[YZ], E[1][2] + E[2][1], 1e-15);
  EXPECT_NEAR(e[XZ], E[0][2] + E[2][0], 1e-15);
  EXPECT_NEAR(e[XY], E[0][1] + E[1][0], 1e-15);
  // The stiffness annihilates the six rigid-body modes.
  const Mat6 D = ti_constitutive_matrix(1e9, TIRatios{0.3, 3.0, 0.2, 1.0});
  const auto K = tet4_stiffness(t, D);
  for (int mode = 0; mode < 6; ++mode) {
    double r[12];
    for (int i = 0; i < 4; ++i) {
      const double X = x[i][0], Y = x[i][1], Z = x[i][2];
      const double m[6][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-Y, X, 0}, {0, -Z, Y}, {Z, 0, -X}};
      for (int a = 0; a < 3; ++a) r[3 * i + a] = m[mode][a];
    }
    for (int i = 0; i < 12; ++i) {
      double s = 0;
      for (int j = 0; j < 12; ++j) s += K[12 * i + j] * r[j];
      EXPECT_NEAR(s, 0.0, 1e-6 * K[12 * i + i]);
    }
  }
}

// tet4_stiffness skips the zeros of B: the same bits as the dense V B^T D B it replaced, for
// tetrahedra of every shape and scale and a non-symmetric D with entries of both signs.
TEST(Tet4, StiffnessHasTheDenseProductsBits) {
  auto dense = [](const Tet4& t, const Mat6& D) {
    const auto B = tet4_strain_matrix(t);
    double DB[72];
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 12; ++j) {
        double s = 0;
        for (int k = 0; k < 6; ++k) s += D[6 * i + k] * B[12 * k + j];
        DB[12 * i + j] = s;
      }
    std::array<double, 144> K{};
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j) {
        double s = 0;
        for (int k = 0; k < 6; ++k) s += B[12 * k + i] * DB[12 * k + j];
        K[12 * i + j] = std::abs(t.volume) * s;
      }
    return K;
  };
  std::uint64_t state = 12345;
  auto next = [&] {  // a fixed LCG: the same cases on every machine
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5;
  };
  int nonzero = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const double scale = std::pow(10.0, 4 * next());
    std::array<Point3, 4> x;
    for (auto& p : x) p = {scale * next(), scale * next(), 0.01 * scale * next()};  // flat ones too
    Tet4 t;
    try {
      t = tet4(x);
    } catch (const std::domain_error&) {
      continue;
    }
    Mat6 D;
    for (double& d : D) d = 1e9 * next();
    if (trial % 3 == 0) D = ti_constitutive_matrix(1e9 * (1 + next()), TIRatios{0.3, 3.0, 0.2, 1.0});
    const auto a = tet4_stiffness(t, D), b = dense(t, D);
    ASSERT_EQ(std::memcmp(a.data(), b.data(), sizeof a), 0) << "trial " << trial;
    ++nonzero;
  }
  EXPECT_GT(nonzero, 1900);
}

TEST(Elasticity, TransverselyIsotropicDInvertsTheCompliance) {
  const TIRatios r{0.3, 3.0, 0.2, 1.0};  // thesis Table 4.3, hypo-plastic units
  ASSERT_EQ(ti_check(r), "");
  const double Ez = 2.5e8;
  const Mat6 D = ti_constitutive_matrix(Ez, r);
  const auto S = normal_compliance(Ez, r);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0;
      for (int k = 0; k < 3; ++k) s += D[6 * i + k] * S[3 * k + j];
      EXPECT_NEAR(s, i == j ? 1.0 : 0.0, 1e-12);
    }
  const double Eh = 3 * Ez, nu_h = 0.06, Gh = Eh / (2 * (1 + nu_h));
  EXPECT_NEAR(D[6 * XY + XY] / Gh, 1.0, 1e-14);
  EXPECT_NEAR(D[6 * YZ + YZ] / Gh, 1.0, 1e-14);  // G_h / G_z = 1
  // Eq. 3.23: c_M = (1/E_z)(1 - 2 nu_z^2 E_h / (E_z (1 - nu_h))) is the oedometric compliance 1/D_zz.
  const double cm = (1.0 / Ez) * (1.0 - 2.0 * 0.09 * 3.0 / (1.0 - nu_h));
  EXPECT_NEAR(cm_from_ez(Ez, r) / cm, 1.0, 1e-14);
  EXPECT_NEAR(1.0 / D[6 * ZZ + ZZ] / cm, 1.0, 1e-12);
  EXPECT_NEAR(ez_from_cm(cm, r) / Ez, 1.0, 1e-14);
}

TEST(Elasticity, IsotropicLimitIsEquation320) {
  const double E = 1e10, nu = 0.25;
  const Mat6 D = ti_constitutive_matrix(E, TIRatios{nu, 1, 1, 1});
  const double f = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
  EXPECT_NEAR(D[0] / f, 1.0, 1e-13);
  EXPECT_NEAR(D[1] / f, nu / (1 - nu), 1e-13);
  EXPECT_NEAR(D[6 * YZ + YZ] / f, (1 - 2 * nu) / (2 * (1 - nu)), 1e-13);
  // c_M of eq. 3.21
  EXPECT_NEAR(cm_from_ez(E, TIRatios{nu, 1, 1, 1}) * E, (1 + nu) * (1 - 2 * nu) / (1 - nu), 1e-14);
}

TEST(Elasticity, RejectsNonPhysicalParameters) {
  EXPECT_NE(ti_check({0.5, 1, 1, 1}), "");
  EXPECT_NE(ti_check({-1.0, 1, 1, 1}), "");
  EXPECT_NE(ti_check({0.3, 0.0, 1, 1}), "");
  EXPECT_NE(ti_check({0.3, -2.0, 1, 1}), "");
  EXPECT_NE(ti_check({0.3, 1, 1, 0.0}), "");
  EXPECT_NE(ti_check({0.45, 3.0, 1.0, 1}), "");  // 1 - nu_h - 2 nu_z^2 E_h/E_z < 0
  EXPECT_EQ(ti_check({0.3, 3.0, 0.2, 1}), "");
}

// ---- V1 at one material point --------------------------------------------------------------------
namespace {
using test::v1::a, test::v1::b, test::v1::cM, test::v1::virgin;  // tests/support/v1_oedometer.hpp
double sdep(double s0, double s1, double cR) { return virgin(s0, s1) / cR; }

// Integrates the path with hypo_integrate in one call per leg and returns the cumulative strain
// magnitude at each turn; also checks that J -> sigma1 reproduces the turn.
std::vector<double> strains_along(const HypoParams& p, const std::vector<double>& path, const std::vector<double>& J_legs) {
  HypoState st = HypoState::virgin(path[0]);
  std::vector<double> out;
  double total = 0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const HypoResult r = hypo_integrate(p, st, path[i - 1], J_legs[i - 1], 0);
    EXPECT_NEAR(r.sigma1, path[i], 1e-9 * path[i]) << "leg " << i;
    st = r.state;
    total += J_legs[i - 1];
    out.push_back(total);
  }
  return out;
}
}  // namespace

TEST(HypoplasticV1, DefaultRuleSigmaMax) {
  const double cR = 3.0;
  HypoParams p{a, b, cR, 0.1, InversionRule::SigmaMax};
  const std::vector<double> path{20, 26, 23, 28, 25};
  const std::vector<double> J{virgin(20, 26), cM(26) / cR * (23 - 26), cM(26) / cR * (26 - 23) + virgin(26, 28),
                              cM(28) / cR * (25 - 28)};
  strains_along(p, path, J);
  // Each turn: a reload that passes sigma_max ends on the virgin branch.
  HypoState st = HypoState::virgin(20);
  st = hypo_integrate(p, st, 20, J[0], 0).state;
  EXPECT_EQ(hypo_integrate(p, st, 26, J[1], 0).phase, LoadingPhase::Unloading);
  st = hypo_integrate(p, st, 26, J[1], 0).state;
  const HypoResult r = hypo_integrate(p, st, 23, J[2], 0);
  EXPECT_EQ(r.phase, LoadingPhase::Virgin);
  EXPECT_NEAR(r.state.sigma_max, 28, 1e-9);
  EXPECT_NEAR(r.c_tangent, cM(28), 1e-12);
}

TEST(HypoplasticV1, SigmaInversionRule) {
  const double cR = 5.0;
  HypoParams p{a, b, cR, 0.1, InversionRule::SigmaInversion};
  const std::vector<double> path{20, 26, 23, 28, 25};
  const std::vector<double> J{virgin(20, 26), cM(26) / cR * (23 - 26), cM(23) / cR * (26 - 23) + virgin(26, 28),
                              cM(28) / cR * (25 - 28)};
  strains_along(p, path, J);
}

TEST(HypoplasticV1, StressDependentRule) {
  const double cR = 4.0;
  HypoParams p{a, b, cR, 0.1, InversionRule::StressDependent};
  const std::vector<double> path{20, 26, 23, 28, 25};
  const std::vector<double> J{virgin(20, 26), sdep(26, 23, cR), sdep(23, 26, cR) + virgin(26, 28), sdep(28, 25, cR)};
  strains_along(p, path, J);
}

TEST(HypoplasticV1, SecantAndTangentOfAStep) {
  HypoParams p{a, b, 5.0, 0.1, InversionRule::SigmaMax};
  const HypoState st = HypoState::virgin(20);
  const double J = virgin(20, 21);
  const HypoResult r = hypo_integrate(p, st, 20, J, 0);
  EXPECT_NEAR(r.c_secant, J / 1.0, 1e-14);
  EXPECT_NEAR(r.c_tangent, cM(21), 1e-15);
  // J = 0: the tangent of the guessed branch.
  EXPECT_NEAR(hypo_integrate(p, st, 20, 0.0, +1).c_tangent, cM(20), 1e-15);
  EXPECT_NEAR(hypo_integrate(p, st, 20, 0.0, -1).c_tangent, cM(20) / 5.0, 1e-15);
}

// Transversely isotropic (E_h = 3 E_z), hypo-plastic with c_R = 3 and the sigma-max rule.
static Material hypoplastic_test_material() {
  Material m;
  m.law = Law::Hypoplastic;
  m.ratios = {0.3, 3.0, 0.2, 1.0};
  m.hypo = {a, b, 3.0, 0.1, InversionRule::SigmaMax};
  m.finalize();
  return m;
}

TEST(MaterialPoint, OedometricHypoplasticStepAndTangent) {
  const Material m = hypoplastic_test_material();
  EXPECT_NEAR(m.Dhat[6 * ZZ + ZZ], 1.0, 1e-12);
  PointState st;
  st.hypo = HypoState::virgin(20);
  // An oedometric strain that takes sigma_z from 20 to 26 MPa on the virgin curve.
  Vec6 eps{};
  eps[ZZ] = -virgin(20, 26);
  const PointUpdate u = hypo_update(m, st, 20, eps, +1);
  EXPECT_NEAR(u.dsig[ZZ], -6e6, 1e-3);
  // Horizontal stress change follows the oedometric ratio D_xz / D_zz of the TI matrix.
  EXPECT_NEAR(u.dsig[XX] / u.dsig[ZZ], m.Dhat[6 * XX + ZZ] / m.Dhat[6 * ZZ + ZZ], 1e-12);
  // Consistent tangent along the oedometric direction: a finite difference of sigma_zz.
  Vec6 eps2 = eps;
  const double h = 1e-9;
  eps2[ZZ] -= h;
  const PointUpdate u2 = hypo_update(m, st, 20, eps2, +1);
  EXPECT_NEAR((u2.dsig[ZZ] - u.dsig[ZZ]) / (-h), u.Dt[6 * ZZ + ZZ], 1e-5 * u.Dt[6 * ZZ + ZZ]);
  EXPECT_NEAR(u.Dt[6 * ZZ + ZZ], 1e6 / cM(26), 1e-6 * 1e6 / cM(26));
}

// The tangent is the derivative of the stress for any strain increment, not only the oedometric
// one: Newton converges quadratically only with it. A central difference of every column, on the
// virgin branch, on the unloading branch and across the knee (unloading then past sigma_max).
TEST(MaterialPoint, ConsistentTangentIsTheDerivativeForAnyStrain) {
  const Material m = hypoplastic_test_material();
  const double ez = virgin(20, 23);
  PointState below;  // unloaded to 18 MPa from a preconsolidation of 20 MPa
  below.hypo = {20, 20, -1};
  struct Case {
    const char* what;
    PointState st;
    double s0, ezz;
    bool linear_branch;  // c constant along the step (sigma-max rule, unloading): both forms exact
  };
  const Case cases[] = {{"virgin loading", PointState{{}, {}, HypoState::virgin(20)}, 20, -ez, false},
                        {"unloading", PointState{{}, {}, HypoState::virgin(20)}, 20, 0.2 * ez, true},
                        {"reloading past the knee", below, 18, -ez, false}};
  for (const Case& c : cases) {
    // Lateral and shear strains of the size of the vertical one: far from oedometric.
    const Vec6 eps{0.4 * c.ezz, -0.3 * c.ezz, c.ezz, 0.2 * c.ezz, -0.1 * c.ezz, 0.3 * c.ezz};
    const PointUpdate u = hypo_update(m, c.st, c.s0, eps, c.ezz < 0 ? +1 : -1);
    const PointUpdate us = hypo_update(m, c.st, c.s0, eps, c.ezz < 0 ? +1 : -1, Hold::None, TangentForm::Symmetric);
    double err = 0, err_sym = 0, scale = 0;
    for (int j = 0; j < 6; ++j) {
      const double h = 1e-7 * std::abs(c.ezz);
      Vec6 ep = eps, em = eps;
      ep[j] += h;
      em[j] -= h;
      const PointUpdate up = hypo_update(m, c.st, c.s0, ep, c.ezz < 0 ? +1 : -1);
      const PointUpdate um = hypo_update(m, c.st, c.s0, em, c.ezz < 0 ? +1 : -1);
      for (int i = 0; i < 6; ++i) {
        const double fd = (up.dsig[i] - um.dsig[i]) / (2 * h);
        err = std::max(err, std::abs(fd - u.Dt[6 * i + j]));
        err_sym = std::max(err_sym, std::abs(fd - us.Dt[6 * i + j]));
        scale = std::max(scale, std::abs(fd));
      }
    }
    EXPECT_LT(err, 1e-6 * scale) << c.what;
    // The symmetric form is off by the non-oedometric part of the rank-one term.
    if (c.linear_branch) EXPECT_LT(err_sym, 1e-6 * scale) << c.what;
    else EXPECT_GT(err_sym, 1e-3 * scale) << c.what;
  }
}
