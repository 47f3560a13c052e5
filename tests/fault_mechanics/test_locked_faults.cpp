// Fault contact in stick (locked faults), through the library calls of ugs-solve:
//  V6 — a faulted mesh whose fault cannot slip or open (high cohesion) gives the displacement of
//       the continuous model within 1e-8 relative (VERIFICATION.md), with MUMPS and with the
//       Schur field split.
//  Projection — a 60-degree dipping fault in a homogeneous block under uniform stress: the fault
//       tractions (Lagrange multipliers) equal the stress tensor projected on the plane, t = sigma n,
//       to 1e-6 relative, in the local frame (strike, dip, normal).
#include <cmath>

#include <gtest/gtest.h>

#include "case_builders.hpp"
#include "cell_values.hpp"
#include "fault_meshes.hpp"
#include "ugs/contact/contact.hpp"
#include "ugs/contact/fault_model.hpp"
#include "ugs/fem/voigt.hpp"
#include "ugs/mechanics/model.hpp"
#include "ugs/mechanics/petsc_session.hpp"
#include "ugs/mechanics/solver.hpp"

using namespace ugs;

namespace {

CaseFile base_case(double cohesion_Pa) {
  CaseFile c;
  c.path = "test.toml";
  c.materials.push_back(test::linear_material("rock", "test", 10e9, 0.25));
  c.initial_stress.k0 = 0.7;
  c.faults.push_back(test::fault_spec("F", "test.toml:1", cohesion_Pa, 30));
  return c;
}

}  // namespace

class V6 : public ::testing::TestWithParam<contact::SaddleSolver> {};

TEST_P(V6, LockedFaultEqualsContinuousSolution) {
  const Mesh plain = test::dipping_fault_box(50);
  Mesh faulted = plain;
  const auto rep = test::insert_all_faults(faulted);
  ASSERT_EQ(rep.faults.size(), 1u);
  EXPECT_GT(rep.faults[0].triangles, 120u);
  const CaseFile cs = base_case(1e11);  // 100 GPa of cohesion: the fault cannot slip

  // Pressure change in a block crossed by the fault.
  auto dp_of = [](const mech::Model& model) {
    return test::cell_values_in(
        model, [](const Point3& c) { return c[0] > 300 && c[0] < 700 && c[1] > 100 && c[1] < 500 && c[2] > -700 && c[2] < -300; },
        -10e6);
  };
  mech::SolverOptions opt;
  opt.linear = mech::LinearSolver::Mumps;
  opt.tolerance = 1e-12;

  const mech::Model m0 = mech::build_model(plain, cs);
  mech::MechanicsSolver continuous(MPI_COMM_WORLD, &m0, opt);
  ASSERT_TRUE(continuous.advance(dp_of(m0), "continuous").converged);
  const auto u0 = continuous.gather_displacement();

  const mech::Model m1 = mech::build_model(faulted, cs, true);
  const contact::FaultModel fm = contact::build_fault_model(faulted, cs, m1, contact::geostatic_fault_state(m1.initial));
  EXPECT_GT(fm.pairs.size(), 60u);
  EXPECT_EQ(fm.redundant_pairs, 0u);
  contact::ContactOptions copt;
  copt.solver = GetParam();
  contact::FaultContact fc(MPI_COMM_WORLD, &fm, copt);
  mech::MechanicsSolver faulted_solver(MPI_COMM_WORLD, &m1, opt);
  faulted_solver.set_coupling(fc);
  fc.set_pressure_change(std::vector<double>(fm.pairs.size(), 0.0));
  const auto r = faulted_solver.advance(dp_of(m1), "faulted");
  ASSERT_TRUE(r.converged) << r.failure;
  const auto u1 = faulted_solver.gather_displacement();

  const auto orig = test::original_nodes(faulted, plain);
  double umax = 0, diff = 0;
  for (double v : u0) umax = std::max(umax, std::abs(v));
  for (std::size_t i = 0; i < faulted.num_nodes(); ++i)
    for (int c = 0; c < 3; ++c) diff = std::max(diff, std::abs(u1[3 * i + c] - u0[3 * orig[i] + c]));
  const auto res = fc.gather();
  int slipping = 0;
  for (auto s : res.state) slipping += s != 0;
  std::printf("V6 (%s): max |u| %.4e m, max difference %.3e (relative %.2e); %d Newton, %d linear iterations; %zu pairs, %d "
              "not sticking\n",
              GetParam() == contact::SaddleSolver::Mumps ? "mumps" : "fieldsplit", umax, diff, diff / umax, r.newton_iterations,
              r.linear_iterations, fm.pairs.size(), slipping);
  EXPECT_GT(umax, 1e-3);
  EXPECT_LT(diff / umax, 1e-8);
  EXPECT_EQ(slipping, 0);
}

INSTANTIATE_TEST_SUITE_P(Solvers, V6, ::testing::Values(contact::SaddleSolver::Mumps, contact::SaddleSolver::FieldSplit),
                         [](const auto& info) {
                           return std::string(info.param == contact::SaddleSolver::Mumps ? "mumps" : "fieldsplit");
                         });

// ---- projection of a uniform stress ------------------------------------------------------------
TEST(Projection, DippingFaultTractionsEqualProjectedStress) {
  const double dip = 60 * M_PI / 180, dx = 50, dz = dx * std::tan(dip);
  Mesh mesh = test::nine_layer_box(1000, 600, dz);
  const double z0 = -9 * dz;
  // Plane through (200, y, z0) rising with slope dz/dx: normal (-dz, 0, dx).
  test::add_planar_fault(
      mesh, "F", {300, 0, z0}, {-dz, 0, dx},
      [&](const Point3& c) { return c[1] > 100 && c[1] < 500 && c[2] > z0 + 1.5 * dz && c[2] < -1.5 * dz; }, 1e-6);
  test::insert_all_faults(mesh);

  CaseFile cs = base_case(20e6);
  cs.fixed_boundaries = {"west", "east", "south", "north", "bottom", "top"};
  mech::Model model = mech::build_model(mesh, cs, true);
  // Uniform strain on the boundary (u = E x) and a uniform initial stress: the fault sticks.
  const double E[3][3] = {{-2.0e-4, 0.5e-4, 0.3e-4}, {0.5e-4, -1.0e-4, -0.2e-4}, {0.3e-4, -0.2e-4, -3.0e-4}};
  for (std::size_t v = 0; v < model.num_nodes(); ++v)
    for (int a = 0; a < 3; ++a)
      model.prescribed[v][a] = E[a][0] * model.x[v][0] + E[a][1] * model.x[v][1] + E[a][2] * model.x[v][2];
  const fem::Vec6 sigma0{-30e6, -25e6, -40e6, 2e6, -3e6, 1e6};  // thesis order xx yy zz yz xz xy
  contact::InitialFaultState init;
  init.total_stress = [&](const Point3&, double, const std::array<double, 2>&, const GasColumn&) { return sigma0; };
  init.pressure = [](const Point3&, const GasColumn&) { return 0.0; };
  const contact::FaultModel fm = contact::build_fault_model(mesh, cs, model, init);
  ASSERT_GT(fm.pairs.size(), 20u);

  mech::SolverOptions opt;
  opt.linear = mech::LinearSolver::Mumps;
  opt.tolerance = 1e-12;
  contact::FaultContact fc(MPI_COMM_WORLD, &fm, {});
  mech::MechanicsSolver solver(MPI_COMM_WORLD, &model, opt);
  solver.set_coupling(fc);
  fc.set_pressure_change(std::vector<double>(fm.pairs.size(), 0.0));
  const auto r = solver.advance(std::vector<double>(model.tets.size(), 0.0), "uniform strain");
  ASSERT_TRUE(r.converged) << r.failure;
  const auto res = fc.gather();

  // Expected: sigma = sigma0 + D eps (uniform), t = sigma n in the frame of the plane.
  const fem::Vec6 eps{E[0][0], E[1][1], E[2][2], E[1][2] + E[2][1], E[0][2] + E[2][0], E[0][1] + E[1][0]};
  const fem::Vec6 ds = fem::mat_vec(model.materials[0].D_linear, eps);
  fem::Vec6 s;
  for (int k = 0; k < 6; ++k) s[k] = sigma0[k] + ds[k];
  const double ln = std::hypot(dz, dx);
  const Point3 plane{-dz / ln, 0, dx / ln};
  double worst = 0, shear = 0, normal = 0;
  int sticking = 0;
  for (std::size_t q = 0; q < fm.pairs.size(); ++q) {
    const auto& R = fm.pairs[q].R;
    const Point3 n{R[2], R[5], R[8]};
    // The frame: the normal of the plane (either way), the strike horizontal.
    EXPECT_NEAR(std::abs(n[0] * plane[0] + n[1] * plane[1] + n[2] * plane[2]), 1.0, 1e-12);
    EXPECT_NEAR(R[6], 0.0, 1e-12);
    const std::array<double, 3> t{s[0] * n[0] + s[5] * n[1] + s[4] * n[2], s[5] * n[0] + s[1] * n[1] + s[3] * n[2],
                                  s[4] * n[0] + s[3] * n[1] + s[2] * n[2]};
    const double tn = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (int j = 0; j < 3; ++j) {
      const double expect = R[j] * t[0] + R[3 + j] * t[1] + R[6 + j] * t[2];
      worst = std::max(worst, std::abs(res.lambda[3 * q + j] - expect) / tn);
      if (j == 2) normal = expect;
      else shear = std::hypot(shear, expect);
    }
    sticking += res.state[q] == 0;
  }
  std::printf("projection: %zu pairs, normal traction %.4f MPa, shear %.4f MPa, worst relative error %.2e\n", fm.pairs.size(),
              normal * 1e-6, shear * 1e-6, worst);
  EXPECT_LT(worst, 1e-6);
  EXPECT_EQ(sticking, static_cast<int>(fm.pairs.size()));
  EXPECT_LT(normal, 0);   // compression
  EXPECT_GT(shear, 1e6);  // and shear on the plane
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ugs::mech::PetscSession petsc;
  return RUN_ALL_TESTS();
}
