// The mechanical earth model of [initial_stress] (issue 42), read from case files written by the
// test-case builder, against closed forms:
//  Forms — the S_v table with one interval, and a constant density log, equal the gradient form to
//       round-off; a linear density log and steps of gradient integrate exactly.
//  Tables — S_hmin between two leak-off points (linear), above the first and below the last (the
//       points' own gradients); S_Hmax by ratio and by table; the table form's effective tensor.
//  Pore pressure — overpressure between and beyond its rows; a pool's gas column above its contact.
//  Checks — the regime (table and ratio forms), S_Hmax below S_hmin, an overpressure reaching S_v,
//       a gas-water contact above the pool's top: InputError naming file:line.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "case_toml.hpp"
#include "input_error.hpp"
#include "run_tool.hpp"
#include "ugs/meshing/box_mesh.hpp"
#include "ugs/mechanics/model.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

constexpr double g = 9.81;

// The case file of `s` (and `pools`, with one material "rock"), read back.
CaseFile read_case(const testcase::InitialStress& s, const std::vector<testcase::Pool>& pools = {}) {
  const fs::path dir = test::temp_dir("earth-model");
  testcase::CaseToml c;
  c.initial_stress(s).material(testcase::linear("rock", 10000, 0.25));
  for (const auto& p : pools) c.pool(p);
  testcase::write_text(dir / "c.toml", c.str());
  testcase::write_text(dir / "p.csv", "date,p_MPa\n2000-01-01,10\n");
  try {
    CaseFile cs = read_case_file((dir / "c.toml").string());
    fs::remove_all(dir);
    return cs;
  } catch (...) {
    fs::remove_all(dir);
    throw;
  }
}

testcase::InitialStress base() {
  testcase::InitialStress s;
  s.surface_elevation_m = 20;
  return s;
}

}  // namespace

TEST(EarthModel, OneIntervalTableEqualsTheGradientForm) {
  testcase::InitialStress table = base();
  table.lithostatic_gradient_MPa_per_m.reset();
  table.Sv_gradients_MPa_per_m = {{0, 0.0226}};
  testcase::InitialStress gradient = base();
  gradient.k0 = 0.8;
  table.k0 = 0.8;
  const InitialState a = initial_state_of(read_case(gradient), 4000), b = initial_state_of(read_case(table), 4000);
  EXPECT_TRUE(a.sv_gradient.empty());
  ASSERT_EQ(b.sv_gradient.size(), 1u);
  for (double z : {30.0, -10.0, -777.7, -3000.0}) {
    EXPECT_EQ(a.vertical_stress(z), b.vertical_stress(z)) << z;
    for (double biot : {1.0, 0.8}) {
      const auto sa = a.effective_stress(z, biot), sb = b.effective_stress(z, biot);
      for (int k = 0; k < 6; ++k) EXPECT_NEAR(sa[k], sb[k], 1e-12 * std::abs(sa[2]) + 1e-300) << z << " " << k;
    }
  }
}

TEST(EarthModel, ConstantDensityLogEqualsTheGradient) {
  testcase::InitialStress log = base();
  log.lithostatic_gradient_MPa_per_m.reset();
  log.Sv_density_kg_per_m3 = {{0, 2400}, {1200, 2400}, {3000, 2400}};
  testcase::InitialStress gradient = base();
  gradient.lithostatic_gradient_MPa_per_m = 2400 * g * 1e-6;  // 0.023544 MPa/m
  const InitialState a = initial_state_of(read_case(gradient), 4000), b = initial_state_of(read_case(log), 4000);
  for (double z : {-10.0, -1180.0, -1500.0, -3500.0}) {
    EXPECT_NEAR(b.vertical_stress(z), 2400 * g * (20 - z), 1e-9 * 2400 * g * (20 - z)) << z;
    const auto sa = a.effective_stress(z, 0.9), sb = b.effective_stress(z, 0.9);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(sa[k], sb[k], 1e-12 * std::abs(sa[2])) << z << " " << k;
  }
}

TEST(EarthModel, DensityLogAndIntervalsIntegrateExactly) {
  testcase::InitialStress log = base();
  log.lithostatic_gradient_MPa_per_m.reset();
  log.Sv_density_kg_per_m3 = {{100, 2000}, {1100, 2400}};
  const InitialState a = initial_state_of(read_case(log), 4000);
  // Above the first sample its density; linear between; the last one's below.
  EXPECT_NEAR(a.vertical_stress(20 - 50), 2000 * g * 50, 1e-6);
  EXPECT_NEAR(a.vertical_stress(20 - 700), g * (2000 * 700 + 0.5 * 400 * 600.0 * 600.0 / 1000), 1e-6);
  EXPECT_NEAR(a.vertical_stress(20 - 1500), g * (2000 * 100 + 2200 * 1000 + 2400 * 400), 1e-6);

  testcase::InitialStress steps = base();
  steps.lithostatic_gradient_MPa_per_m.reset();
  steps.Sv_gradients_MPa_per_m = {{0, 0.020}, {800, 0.025}};
  const InitialState b = initial_state_of(read_case(steps), 4000);
  EXPECT_NEAR(b.vertical_stress(20 - 500), 0.020e6 * 500, 1e-6);
  EXPECT_NEAR(b.vertical_stress(20 - 800), 16e6, 1e-6);
  EXPECT_NEAR(b.vertical_stress(20 - 1000), 16e6 + 0.025e6 * 200, 1e-6);
}

TEST(EarthModel, ShminBetweenLeakOffPoints) {
  testcase::InitialStress s = base();
  s.Shmin_MPa = {{1000, 18}, {2000, 40}};
  s.SHmax_over_Shmin = 1.25;
  s.Hmax_azimuth_deg = 0;
  const InitialState a = initial_state_of(read_case(s), 4000);
  ASSERT_TRUE(a.horizontal_table());
  EXPECT_NEAR(a.hmin_stress(20 - 1400), (18 + 22 * 0.4) * 1e6, 1e-6);  // between the points
  EXPECT_NEAR(a.hmin_stress(20 - 500), 9e6, 1e-6);                     // above: 18 MPa / 1000 m
  EXPECT_NEAR(a.hmin_stress(20 - 2500), 50e6, 1e-6);                   // below: 40 MPa / 2000 m
  EXPECT_NEAR(a.Hmax_stress(20 - 1400), 1.25 * 26.8e6, 1e-6);
  // The effective tensor: S_Hmax along y (azimuth 0), S_hmin along x, sigma' = -(S - alpha p0).
  const double d = 1400, alpha = 0.8, p0 = 0.0100e6 * d;
  const auto e = a.effective_stress(20 - d, alpha);
  EXPECT_NEAR(e[0], -(26.8e6 - alpha * p0), 1e-6);
  EXPECT_NEAR(e[1], -(1.25 * 26.8e6 - alpha * p0), 1e-6);
  EXPECT_NEAR(e[2], -(0.0226e6 * d - alpha * p0), 1e-6);
  EXPECT_NEAR(e[5], 0, 1e-6);
  // Per-material ratios play no part in the table form.
  const auto e2 = a.effective_stress(20 - d, alpha, {0.5, 0.5});
  for (int k = 0; k < 6; ++k) EXPECT_EQ(e[k], e2[k]);

  s.SHmax_over_Shmin.reset();
  s.SHmax_MPa = {{1000, 24}, {3000, 80}};
  const InitialState b = initial_state_of(read_case(s), 4000);
  EXPECT_NEAR(b.Hmax_stress(20 - 1400), (24 + 56 * 0.2) * 1e6, 1e-6);
}

TEST(EarthModel, OverpressureAndGasColumn) {
  testcase::InitialStress s = base();
  s.overpressure_MPa = {{1000, 0}, {1500, 8}};
  const testcase::Pool pool{.name = "store", .materials = {"rock"}, .schedule = "p.csv", .gas_water_contact_m = -1200,
                            .gas_density_kg_per_m3 = 200};
  const CaseFile cs = read_case(s, {pool});
  const InitialState a = initial_state_of(cs, 4000);
  EXPECT_NEAR(a.pore_pressure(20 - 500), 5e6, 1e-6);                  // above the first row: its value, 0
  EXPECT_NEAR(a.pore_pressure(20 - 1250), 12.5e6 + 4e6, 1e-6);        // between
  EXPECT_NEAR(a.pore_pressure(20 - 2000), 20e6 + 8e6, 1e-6);          // below the last row: its value
  const GasColumn gas = gas_column_of(cs, "rock");
  EXPECT_EQ(gas.contact_elevation, -1200);
  EXPECT_NEAR(gas.gradient, 200 * g, 1e-12);
  EXPECT_FALSE(gas_column_of(cs, "other").holds_gas(1e6));
  // Water pressure at the contact (depth 1220 m: 12.2 MPa + 3.52 MPa of overpressure), the gas gradient above it.
  const double pw = 12.2e6 + 8e6 * 220 / 500;
  EXPECT_NEAR(a.pore_pressure(-1200, gas), pw, 1e-6);
  EXPECT_NEAR(a.pore_pressure(-1100, gas), pw - 200 * g * 100, 1e-6);
  EXPECT_NEAR(a.pore_pressure(-1300, gas), a.pore_pressure(-1300), 0);  // below the contact: water
  // The effective vertical stress in the gas: S_v - alpha p0.
  EXPECT_NEAR(a.effective_vertical_stress(-1100, 0.9, gas), 0.0226e6 * 1120 - 0.9 * (pw - 200 * g * 100), 1e-6);
}

TEST(EarthModel, RegimeAndConsistencyChecksNameTheLine) {
  // Line 5 of the case: [initial_stress], surface, two gradients, then the keys below.
  testcase::InitialStress s = base();
  s.Shmin_MPa = {{1000, 20}, {2000, 48}};  // above S_v = 45.2 MPa at 2000 m
  s.regime = "normal";
  EXPECT_NE(test::input_error_of([&] { initial_state_of(read_case(s), 2500); })
                .find("c.toml:6: regime = \"normal\" but S_hmin above S_v at depth"),
            std::string::npos);
  // Within the regime over the model's depth: above 1481 m S_hmin stays below S_v (20 + 0.028 (d - 1000) < 0.0226 d).
  EXPECT_EQ(test::input_error_of([&] { initial_state_of(read_case(s), 1400); }), "(no InputError)");
  s.regime = "strike-slip";
  s.Shmin_MPa = {{1000, 18}};
  s.SHmax_over_Shmin = 1.2;  // S_Hmax = 0.0216 d < S_v
  EXPECT_NE(test::input_error_of([&] { initial_state_of(read_case(s), 2500); }).find("but S_Hmax below S_v"), std::string::npos);
  // The ratio form: the regime orders the ratios about 1.
  testcase::InitialStress r = base();
  r.k_Hmax = 1.1;
  r.k_hmin = 0.7;
  r.regime = "normal";
  EXPECT_NE(test::input_error_of([&] { initial_state_of(read_case(r), 2500); })
                .find("regime = \"normal\" but k_Hmax = 1.1, k_hmin = 0.7"),
            std::string::npos);
  r.regime = "strike-slip";
  EXPECT_EQ(test::input_error_of([&] { initial_state_of(read_case(r), 2500); }), "(no InputError)");
  // S_Hmax below S_hmin, an overpressure that reaches S_v.
  testcase::InitialStress t = base();
  t.Shmin_MPa = {{1000, 18}};
  t.SHmax_MPa = {{1000, 20}, {2000, 30}};
  // (the largest shortfall at the model's bottom, 2500 m: S_Hmax = 30 MPa 2500 / 2000, S_hmin = 18 MPa 2500 / 1000)
  EXPECT_NE(test::input_error_of([&] { initial_state_of(read_case(t), 2500); })
                .find("c.toml:6: S_Hmax 37.5 MPa is below S_hmin 45 MPa at depth 2500.0 m"),
            std::string::npos);
  testcase::InitialStress o = base();
  // p0 = 0.01 d + 0.1 (d - 1000) MPa reaches S_v = 0.0226 d at 1144.2 m; the excess is largest at 1200 m.
  o.overpressure_MPa = {{1000, 0}, {1200, 20}};
  EXPECT_NE(test::input_error_of([&] { initial_state_of(read_case(o), 2500); })
                .find("c.toml:5: the pore pressure 32 MPa reaches S_v 27.12 MPa at depth 1200.0 m"),
            std::string::npos);
  EXPECT_EQ(test::input_error_of([&] { initial_state_of(read_case(o), 1100); }), "(no InputError)");
}

TEST(EarthModel, GasContactAboveThePoolTopIsRefused) {
  BoxMeshSpec spec;
  spec.x = {0, 100};
  spec.y = {0, 100};
  spec.z = linspace(-1300, -1000, 3);
  const Mesh mesh = make_box_mesh(spec);
  testcase::InitialStress s = base();
  testcase::Pool pool{.name = "store", .materials = {"rock"}, .schedule = "p.csv", .gas_water_contact_m = -990,
                      .gas_density_kg_per_m3 = 200};
  const std::string e = test::input_error_of([&] { mech::build_model(mesh, read_case(s, {pool})); });
  EXPECT_NE(e.find("c.toml:12: pool 'store': gas_water_contact_m = -990 m lies at or above the pool's top (-1000 m"), std::string::npos)
      << e;
  // A gas column whose pressure at the pool's top reaches S_v there: 100 m below the surface, the
  // contact 400 m deep (4 MPa of water) and 300 m of gas of 100 kg/m3 give 3.706 MPa against S_v 2.26 MPa.
  testcase::InitialStress shallow = base();
  shallow.surface_elevation_m = -900;
  testcase::Pool tall = pool;
  tall.gas_water_contact_m = -1300;
  tall.gas_density_kg_per_m3 = 100;
  EXPECT_NE(test::input_error_of([&] { mech::build_model(mesh, read_case(shallow, {tall})); })
                .find("c.toml:12: pool 'store': the gas pressure 3.706 MPa at the pool's top (-1000 m) reaches S_v 2.26 MPa"),
            std::string::npos);
  // A contact inside the pool, and one below it (the whole pool in gas), are fine; the model's
  // materials carry their gas column.
  for (double contact : {-1100.0, -1400.0}) {
    pool.gas_water_contact_m = contact;
    const mech::Model m = mech::build_model(mesh, read_case(s, {pool}));
    ASSERT_EQ(m.material_gas.size(), 1u);
    EXPECT_EQ(m.material_gas[0].contact_elevation, contact);
  }
}

// The worked example of docs/case-file.md ("Tables by depth"): its numbers, as the page quotes them.
TEST(EarthModel, WorkedExampleOfTheCaseFilePage) {
  testcase::InitialStress s;
  s.surface_elevation_m = 0;
  s.lithostatic_gradient_MPa_per_m.reset();
  s.Sv_density_kg_per_m3 = {{0, 2100}, {1000, 2350}, {2500, 2500}};
  s.Shmin_MPa = {{1200, 20.5}, {2100, 38.0}};
  s.SHmax_over_Shmin = 1.1;
  s.Hmax_azimuth_deg = 150;
  s.overpressure_MPa = {{1800, 0}, {1900, 6.0}};
  s.regime = "normal";
  const testcase::Pool pool{.name = "Pool C", .materials = {"rock"}, .schedule = "p.csv", .gas_water_contact_m = -1540,
                            .gas_density_kg_per_m3 = 180};
  const CaseFile cs = read_case(s, {pool});
  const InitialState a = initial_state_of(cs, 3000);  // (the regime holds down to 3000 m)
  EXPECT_NEAR(a.vertical_stress(-1500) * 1e-6, 33.477, 5e-4);
  EXPECT_NEAR(a.hmin_stress(-1500) * 1e-6, 26.333, 5e-4);
  EXPECT_NEAR(a.Hmax_stress(-1500) * 1e-6, 28.967, 5e-4);
  EXPECT_NEAR(a.pore_pressure(-1500) * 1e-6, 15.0, 1e-12);
  const GasColumn gas = gas_column_of(cs, "rock");
  EXPECT_NEAR(a.pore_pressure(-1540, gas) * 1e-6, 15.40, 1e-12);
  EXPECT_NEAR(a.pore_pressure(-1500, gas) * 1e-6, 15.329, 5e-4);
  EXPECT_NEAR(a.effective_vertical_stress(-1500, 1.0, gas) * 1e-6, 33.477 - 15.329, 1e-3);
}
