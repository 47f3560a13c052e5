// General in-situ stress (issue 21): [initial_stress] k_Hmax, k_hmin, Hmax_azimuth_deg; the
// mechanical earth model (issue 42, V9 extended at the end): overpressure, gas cap, S_hmin table.
//  Tensor — mech::InitialState::effective_stress against the hand formula
//       sigma' = sigma'_v (k_Hmax s s^T + k_hmin h h^T + e_z e_z^T), s = (sin a, cos a, 0),
//       h = (cos a, -sin a, 0), at azimuths 0, 30, 90 and 135 degrees; k_Hmax = k_hmin = k0 gives
//       the bytes of the former k0 formula {k0 sv, k0 sv, sv, 0, 0, 0}.
//  Fault tractions — the initial tractions of build_fault_model (geostatic_fault_state) on a
//       vertical fault and on 60-degree dipping faults at three strikes against
//       sigma_n = n.S.n and tau = |S n - sigma_n n| with S = sigma' - alpha p0 I.
#include <cmath>
#include <cstring>
#include <functional>

#include <gtest/gtest.h>

#include "case_builders.hpp"
#include "fault_meshes.hpp"
#include "ugs/contact/fault_model.hpp"
#include "ugs/contact/pair_law.hpp"
#include "ugs/fem/voigt.hpp"
#include "ugs/mechanics/model.hpp"

using namespace ugs;

namespace {

using M3 = std::array<std::array<double, 3>, 3>;

// The hand formula, written out independently of the library (tension positive, mesh axes).
M3 hand_effective(double sv, double kH, double kh, double az_deg) {
  const double a = az_deg * M_PI / 180;
  const double s[3] = {std::sin(a), std::cos(a), 0}, h[3] = {std::cos(a), -std::sin(a), 0};
  M3 S{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) S[i][j] = sv * (kH * s[i] * s[j] + kh * h[i] * h[j]);
  S[2][2] = sv;
  return S;
}

M3 from_voigt(const fem::Vec6& v) {
  using namespace fem;
  return M3{{{v[XX], v[XY], v[XZ]}, {v[XY], v[YY], v[YZ]}, {v[XZ], v[YZ], v[ZZ]}}};
}

}  // namespace

TEST(InsituTensor, MatchesHandFormulaAtFourAzimuths) {
  mech::InitialState st;
  st.surface_elevation = 20;
  st.k_Hmax = 1.3;
  st.k_hmin = 0.9;
  const double z = -1480, biot = 0.8;
  const double sv = -(st.lithostatic - biot * st.hydrostatic) * 1500;
  for (double az : {0.0, 30.0, 90.0, 135.0}) {
    st.Hmax_azimuth_deg = az;
    const M3 got = from_voigt(st.effective_stress(z, biot)), want = hand_effective(sv, 1.3, 0.9, az);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(got[i][j], want[i][j], 1e-9 * std::abs(sv)) << "azimuth " << az << " [" << i << j << "]";
  }
  // Spot values: at 30 degrees sigma_xy = (k_H - k_h) sv sin 30 cos 30; at 90 sigma_H lies along x.
  st.Hmax_azimuth_deg = 30;
  EXPECT_NEAR(st.effective_stress(z, biot)[fem::XY], 0.4 * sv * 0.5 * std::sqrt(3.0) / 2, 1e-6);
  st.Hmax_azimuth_deg = 90;
  EXPECT_NEAR(st.effective_stress(z, biot)[fem::XX], 1.3 * sv, 1e-6);
  EXPECT_NEAR(st.effective_stress(z, biot)[fem::YY], 0.9 * sv, 1e-6);
}

TEST(InsituTensor, K0ShorthandGivesTheFormerBytes) {
  CaseFile cs;
  cs.initial_stress.k0 = 0.7;
  cs.initial_stress.Hmax_azimuth_deg = 30;  // irrelevant when both ratios are equal
  EXPECT_EQ(cs.initial_stress.kH(), 0.7);
  EXPECT_EQ(cs.initial_stress.kh(), 0.7);
  mech::InitialState st;
  st.k_Hmax = cs.initial_stress.kH();
  st.k_hmin = cs.initial_stress.kh();
  st.Hmax_azimuth_deg = 30;
  for (double z : {-10.0, -777.7, -3000.0}) {
    const double sv = -(st.lithostatic - 1.0 * st.hydrostatic) * -z;
    const fem::Vec6 before{0.7 * sv, 0.7 * sv, sv, 0, 0, 0};
    const fem::Vec6 now = st.effective_stress(z, 1.0);
    EXPECT_EQ(std::memcmp(before.data(), now.data(), sizeof(before)), 0) << "z " << z;
  }
}

// ---- initial fault tractions ---------------------------------------------------------------------
namespace {

// A plane through the grid nodes (a grid plane or the Kuhn diagonal of the cells it crosses:
// fault_meshes.hpp): normal (nx h, ny h, nz dz) with dz = h tan(dip) the cell height.
struct FaultCase {
  const char* name;
  double dip_deg;     // 90: vertical (dz = h)
  double nx, ny, nz;  // the normal in cell units
  double azimuth;     // of sigma_Hmax, degrees
};

Point3 unit_normal(const FaultCase& f) {
  const double h = 50, dz = f.dip_deg == 90 ? h : h * std::tan(f.dip_deg * M_PI / 180);
  // A plane x_loc - z_loc = 0 has the normal (1/h, 0, -1/dz): scale each axis by its cell size.
  Point3 n{f.nx / h, f.ny / h, f.nz / dz};
  const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (auto& v : n) v /= l;
  return n;
}

// Box of 20 x 20 x 9 cells, with a buried planar fault through (500, 500, z of the 5th layer), inserted.
Mesh faulted_box(const FaultCase& f) {
  const double h = 50, dz = f.dip_deg == 90 ? h : h * std::tan(f.dip_deg * M_PI / 180);
  Mesh mesh = test::nine_layer_box(1000, 1000, dz);
  const double zb = -9 * dz;
  test::add_planar_fault(
      mesh, "F", {500, 500, zb + 5 * dz}, unit_normal(f),
      [&](const Point3& c) {
        return c[0] > 200 && c[0] < 800 && c[1] > 200 && c[1] < 800 && c[2] > zb + 1.5 * dz && c[2] < -1.5 * dz;
      },
      1e-6);
  test::insert_all_faults(mesh);
  return mesh;
}

CaseFile faulted_case() {
  CaseFile c;
  c.path = "insitu.toml";
  MaterialSpec m = test::linear_material("rock", "insitu.toml:1", 10e9, 0.25);
  m.biot = 0.9;
  c.materials.push_back(m);
  c.initial_stress.k_Hmax = 1.3;
  c.initial_stress.k_hmin = 0.9;
  c.faults.push_back(test::fault_spec("F", "insitu.toml:2", 0.0, 30));
  return c;
}

}  // namespace

// The normal traction sigma_n and the shear traction's magnitude tau of S on the plane of unit normal n.
struct PlaneTraction {
  double sn, tau;
};
PlaneTraction on_plane(const M3& S, const Point3& n) {
  double Sn[3];
  for (int i = 0; i < 3; ++i) Sn[i] = S[i][0] * n[0] + S[i][1] * n[1] + S[i][2] * n[2];
  const double sn = Sn[0] * n[0] + Sn[1] * n[1] + Sn[2] * n[2];
  return {sn, std::sqrt(std::pow(Sn[0] - sn * n[0], 2) + std::pow(Sn[1] - sn * n[1], 2) + std::pow(Sn[2] - sn * n[2], 2))};
}

// Largest error of the pairs' initial tractions against the hand formula with ratios kH, kh; also
// the largest tau / |sigma_n| seen (the tensor must put shear on the plane).
double worst_traction_error(const contact::FaultModel& fm, const mech::Model& model, const FaultCase& f, double kH, double kh,
                            double& tau_seen, double& sn_seen) {
  const Point3 plane = unit_normal(f);  // either sign: sigma_n and tau do not depend on it
  const auto& is = model.initial;
  double worst = 0;
  tau_seen = sn_seen = 0;
  for (const auto& p : fm.pairs) {
    const Point3 n{p.R[2], p.R[5], p.R[8]};
    EXPECT_NEAR(std::abs(n[0] * plane[0] + n[1] * plane[1] + n[2] * plane[2]), 1.0, 1e-9);
    const double d = -p.x[2], alpha = 0.9, p0 = is.hydrostatic * d;
    M3 S = hand_effective(-(is.lithostatic - alpha * is.hydrostatic) * d, kH, kh, f.azimuth);
    for (int k = 0; k < 3; ++k) S[k][k] -= alpha * p0;
    const auto [sn, tau] = on_plane(S, plane);
    const double scale = std::abs(sn);
    worst = std::max(worst, std::abs(p.lambda0[2] - sn) / scale);
    worst = std::max(worst, std::abs(std::hypot(p.lambda0[0], p.lambda0[1]) - tau) / scale);
    tau_seen = std::max(tau_seen, tau / scale);
    sn_seen = std::max(sn_seen, -sn);
  }
  return worst;
}

class FaultTractions : public ::testing::TestWithParam<FaultCase> {};

TEST_P(FaultTractions, EqualTheProjectedInsituTensor) {
  const FaultCase f = GetParam();
  const Mesh mesh = faulted_box(f);
  CaseFile cs = faulted_case();
  cs.initial_stress.Hmax_azimuth_deg = f.azimuth;
  const mech::Model model = mech::build_model(mesh, cs, true);
  EXPECT_EQ(model.initial.k_Hmax, 1.3);
  EXPECT_EQ(model.initial.k_hmin, 0.9);
  EXPECT_EQ(model.initial.Hmax_azimuth_deg, f.azimuth);
  const contact::FaultModel fm = contact::build_fault_model(mesh, cs, model, contact::geostatic_fault_state(model.initial));
  ASSERT_GT(fm.pairs.size(), 20u);
  double tau_seen = 0, sn_seen = 0;
  const double worst = worst_traction_error(fm, model, f, 1.3, 0.9, tau_seen, sn_seen);
  std::printf("%s: %zu pairs, max tau/|sigma_n| %.4f, max |sigma_n| %.3f MPa, worst relative error %.2e\n", f.name,
              fm.pairs.size(), tau_seen, sn_seen * 1e-6, worst);
  EXPECT_LT(worst, 1e-9);
  EXPECT_GT(tau_seen, 0.02);  // the tensor puts shear on every one of these planes
}

// Strikes (normal azimuth + 90): the vertical fault N-S (plane x = 500) and N45E (x_loc = y_loc);
// the 60-degree faults N-S dipping east (x_loc = z_loc), E-W dipping south (y_loc = z_loc), and the
// N-S one under sigma_Hmax at 135 degrees (a third strike relative to the stress).
INSTANTIATE_TEST_SUITE_P(Planes, FaultTractions,
                         ::testing::Values(FaultCase{"vertical_strike_N", 90, 1, 0, 0, 30},
                                           FaultCase{"vertical_strike_N45E", 90, 1, -1, 0, 30},
                                           FaultCase{"dip60_strike_N", 60, 1, 0, -1, 30},
                                           FaultCase{"dip60_strike_E", 60, 0, 1, -1, 30},
                                           FaultCase{"dip60_strike_N_Hmax135", 60, 1, 0, -1, 135}),
                         [](const auto& info) { return std::string(info.param.name); });

// Per-material ratios beside a fault: the initial fault tractions take the ratios of the rock on
// side 1 (here the only material, with ratios other than [initial_stress]'s), not the global ones.
TEST(InsituTensor, OwnRatiosBesideAFaultGiveItsTractions) {
  const FaultCase f{"dip60_strike_N", 60, 1, 0, -1, 30};
  const Mesh mesh = faulted_box(f);
  CaseFile cs = faulted_case();
  cs.materials[0].k_Hmax = 1.1;  // global 1.3
  cs.materials[0].k_hmin = 0.7;  // global 0.9
  cs.initial_stress.Hmax_azimuth_deg = f.azimuth;
  const mech::Model model = mech::build_model(mesh, cs, true);
  EXPECT_EQ(model.material_k[0][0], 1.1);
  EXPECT_EQ(model.material_k[0][1], 0.7);
  const contact::FaultModel fm = contact::build_fault_model(mesh, cs, model, contact::geostatic_fault_state(model.initial));
  double tau_seen = 0, sn_seen = 0;
  EXPECT_LT(worst_traction_error(fm, model, f, 1.1, 0.7, tau_seen, sn_seen), 1e-9);
  // The global ratios would give other tractions: the check above can fail.
  EXPECT_GT(worst_traction_error(fm, model, f, 1.3, 0.9, tau_seen, sn_seen), 1e-2);
}

// ---- V9 extended: the mechanical earth model on faults (issue 42) --------------------------------
// A fault in an overpressured interval (ratio form) and a fault in a pool's gas cap (table form:
// S_hmin from two leak-off points, S_Hmax by ratio): every pair's initial normal and shear traction,
// pore pressure and safety factor chi against the closed form written out here:
//   S_v = gamma_lith d, p0 = gamma_hyd d + dp(d) in water, p0 = p_w(z_gwc) - gamma_gas (z - z_gwc) in gas,
//   sigma' = -(S - alpha p0) per principal direction (table form) or k sigma'_v (ratio form),
//   S_total = sigma' - alpha p0 I, sigma_n = n.S.n, tau = |S n - sigma_n n|,
//   chi = tau / (c - (sigma_n + p0) tan phi).
namespace {

struct ClosedForm {
  std::function<double(double d)> p0;        // pore pressure at depth d
  std::function<M3(double d, double p)> S;   // total stress at depth d with pore pressure p
};

// Largest relative errors of the pairs' tractions and p0 (err) and of chi (chi_err) against cf.
// Depth d = surface - z (the case's surface_elevation_m, 0 unless a test puts the box under an overburden).
void compare_with_closed_form(const contact::FaultModel& fm, const FaultCase& f, const ClosedForm& cf, double& err,
                              double& chi_err, double& p_min, double& p_max, double surface = 0) {
  const Point3 plane = unit_normal(f);
  const double mu = std::tan(30 * M_PI / 180);
  err = chi_err = 0;
  p_min = 1e300, p_max = -1e300;
  for (const auto& p : fm.pairs) {
    const double d = surface - p.x[2], p0 = cf.p0(d);
    const auto [sn, tau] = on_plane(cf.S(d, p0), plane);
    const double scale = std::abs(sn);
    err = std::max({err, std::abs(p.lambda0[2] - sn) / scale, std::abs(std::hypot(p.lambda0[0], p.lambda0[1]) - tau) / scale,
                    std::abs(p.p0 - p0) / scale});
    const double chi_want = tau / (0.0 - (sn + p0) * mu);
    const double chi_got = contact::safety_factor(std::hypot(p.lambda0[0], p.lambda0[1]), p.lambda0[2] + p.p0, 0.0, mu,
                                                  contact::PairState::Stick);
    chi_err = std::max(chi_err, std::abs(chi_got - chi_want) / chi_want);
    p_min = std::min(p_min, p0 - 0.0100e6 * d), p_max = std::max(p_max, p0 - 0.0100e6 * d);
  }
}

}  // namespace

TEST(InsituEarthModel, FaultInAnOverpressuredInterval) {
  const FaultCase f{"dip60_strike_N", 60, 1, 0, -1, 30};
  const Mesh mesh = faulted_box(f);
  CaseFile cs = faulted_case();
  cs.initial_stress.Hmax_azimuth_deg = f.azimuth;
  // 0 above 300 m, rising to 2 MPa at 480 m and held below: the fault's pairs (depths 260 to 520 m, every
  // 86.6 m) lie above the ramp, on it and below it.
  cs.initial_stress.overpressure = {{300, 0}, {480, 2e6}};
  const mech::Model model = mech::build_model(mesh, cs, true);
  const contact::FaultModel fm = contact::build_fault_model(mesh, cs, model, contact::geostatic_fault_state(model.initial));
  ASSERT_GT(fm.pairs.size(), 20u);
  const double alpha = 0.9;
  ClosedForm cf;
  cf.p0 = [](double d) { return 0.0100e6 * d + (d <= 300 ? 0.0 : d >= 480 ? 2e6 : 2e6 * (d - 300) / 180); };
  cf.S = [&](double d, double p) {
    M3 S = hand_effective(-(0.0226e6 * d - alpha * p), 1.3, 0.9, f.azimuth);
    for (int k = 0; k < 3; ++k) S[k][k] -= alpha * p;
    return S;
  };
  double err, chi_err, op_min, op_max;
  compare_with_closed_form(fm, f, cf, err, chi_err, op_min, op_max);
  std::printf("overpressure: %zu pairs, overpressure %.2f to %.2f MPa, worst relative error %.2e, chi %.2e\n", fm.pairs.size(),
              op_min * 1e-6, op_max * 1e-6, err, chi_err);
  EXPECT_LT(err, 1e-9);
  EXPECT_LT(chi_err, 1e-9);
  EXPECT_LT(op_min, 1.0);     // pairs above the ramp (hydrostatic)
  EXPECT_GT(op_max, 1.99e6);  // and below it
  // The hydrostatic state gives other tractions: the comparison can fail.
  CaseFile hydro_case = faulted_case();
  hydro_case.initial_stress.Hmax_azimuth_deg = f.azimuth;
  const mech::Model hydro_model = mech::build_model(mesh, hydro_case, true);
  const contact::FaultModel hydro =
      contact::build_fault_model(mesh, hydro_case, hydro_model, contact::geostatic_fault_state(hydro_model.initial));
  compare_with_closed_form(hydro, f, cf, err, chi_err, op_min, op_max);
  EXPECT_GT(err, 1e-2);
}

TEST(InsituEarthModel, FaultInTheGasCap) {
  const FaultCase f{"vertical_strike_N45E", 90, 1, -1, 0, 30};
  const Mesh mesh = faulted_box(f);  // fault pairs from z = -350 to -150 m
  CaseFile cs = faulted_case();
  cs.initial_stress.k_Hmax.reset();
  cs.initial_stress.k_hmin.reset();
  cs.initial_stress.Hmax_azimuth_deg = f.azimuth;
  // The box under 300 m of overburden: the pool (the whole box) then tops out at 300 m depth, where
  // its gas (5.06 MPa) stays below S_v (6.78 MPa); a gas column reaching the ground is refused.
  const double zs = 300;
  cs.initial_stress.surface_elevation = zs;
  // S_hmin from two leak-off points (the fault, 450-650 m deep, lies between them), S_Hmax = 1.2 S_hmin.
  cs.initial_stress.shmin = {{400, 8.0e6}, {700, 14.0e6}};
  cs.initial_stress.sHmax_over_shmin = 1.2;
  PoolSpec pool;
  pool.name = "store";
  pool.where = "insitu.toml:3";
  pool.materials = {"rock"};
  pool.gas_water_contact_m = -250;
  pool.gas_gradient_Pa_per_m = 180 * kGravity;  // 180 kg/m3
  cs.pools.push_back(pool);
  const mech::Model model = mech::build_model(mesh, cs, true);
  ASSERT_EQ(model.material_gas.size(), 1u);
  EXPECT_EQ(model.material_gas[0].contact_elevation, -250);
  const contact::FaultModel fm = contact::build_fault_model(mesh, cs, model, contact::geostatic_fault_state(model.initial));
  ASSERT_GT(fm.pairs.size(), 20u);
  const double alpha = 0.9, a = f.azimuth * M_PI / 180;
  ClosedForm cf;
  cf.p0 = [&](double d) {
    const double z = zs - d;
    return z > -250 ? 0.0100e6 * (zs + 250) - 180 * 9.81 * (z + 250) : 0.0100e6 * d;
  };
  cf.S = [&](double d, double p) {
    const double sh = d <= 400 ? 8.0e6 * d / 400 : d >= 700 ? 14.0e6 * d / 700 : 8.0e6 + 6.0e6 * (d - 400) / 300;
    const double sH = 1.2 * sh, sv = 0.0226e6 * d;
    const double s[3] = {std::sin(a), std::cos(a), 0}, h[3] = {std::cos(a), -std::sin(a), 0};
    M3 S{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) S[i][j] = -(sH - alpha * p) * s[i] * s[j] - (sh - alpha * p) * h[i] * h[j];
    S[2][2] = -(sv - alpha * p);
    for (int k = 0; k < 3; ++k) S[k][k] -= alpha * p;
    return S;
  };
  double err, chi_err, excess_min, excess_max;
  compare_with_closed_form(fm, f, cf, err, chi_err, excess_min, excess_max, zs);
  std::printf("gas cap: %zu pairs, p0 - hydrostatic %.3f to %.3f MPa, worst relative error %.2e, chi %.2e\n", fm.pairs.size(),
              excess_min * 1e-6, excess_max * 1e-6, err, chi_err);
  EXPECT_LT(err, 1e-9);
  EXPECT_LT(chi_err, 1e-9);
  // Pairs in the gas (p0 - hydrostatic = (gamma_w - gamma_g) (z - z_gwc) at the highest) and in water.
  double z_top = -1e300;
  for (const auto& p : fm.pairs) z_top = std::max(z_top, p.x[2]);
  EXPECT_GT(z_top, -200);
  EXPECT_NEAR(excess_max, (0.0100e6 - 180 * 9.81) * (z_top + 250), 1e-6);
  EXPECT_NEAR(excess_min, 0.0, 1e-6);
}
