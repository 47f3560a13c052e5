// A slipping patch on a buried fault in 3D (library calls of ugs-solve): a box with a fault dipping
// 45 degrees under the geostatic stress (k0 = 0.6, friction 20 degrees, no cohesion: chi about 0.7),
// then a fluid pressure rise of 1.8 MPa on the fault faces in its middle (fluid injected along the
// fault; the rock around keeps its pressure). Checks:
//  - Newton with the active set converges in at most kNewtonBound = 8 iterations (the states
//    settle within the first few; the slip direction then converges quadratically);
//  - part of the fault slips, the rest sticks; slipping pairs sit on the Mohr-Coulomb limit
//    |tau| = c - sigma'_n tan(phi), sticking ones below it, their slip is aligned with the shear
//    traction (maximum plastic dissipation), the faces stay closed;
//  - MUMPS and the Schur field split give the same answer;
//  - a state that keeps changing stops the step, naming the fault and its node pairs (here with a
//    limit of one change per pair, so that the first iteration trips it).
#include <cmath>

#include <gtest/gtest.h>

#include "case_builders.hpp"
#include "fault_meshes.hpp"
#include "ugs/contact/contact.hpp"
#include "ugs/contact/fault_model.hpp"
#include "ugs/mechanics/model.hpp"
#include "ugs/mechanics/petsc_session.hpp"
#include "ugs/mechanics/solver.hpp"

using namespace ugs;

namespace {

constexpr int kNewtonBound = 8;

bool in_block(const Point3& c) { return c[1] > 140 && c[1] < 460 && c[2] > -710 && c[2] < -290; }

struct Result {
  std::vector<double> u;
  contact::PairResults res;
  mech::StepReport rep;
  contact::FaultModel fm;
};

Result run(contact::SaddleSolver solver, int max_state_changes = 4) {
  Mesh mesh = test::dipping_fault_box(50);
  test::insert_all_faults(mesh);
  CaseFile cs;
  cs.path = "patch.toml";
  cs.materials.push_back(test::linear_material("rock", "patch.toml:1", 10e9, 0.25));
  cs.initial_stress.k0 = 0.6;
  cs.faults.push_back(test::fault_spec("F", "patch.toml:2", 0, 20));
  const mech::Model model = mech::build_model(mesh, cs, true);
  Result r;
  r.fm = contact::build_fault_model(mesh, cs, model, contact::geostatic_fault_state(model.initial));
  contact::ContactOptions copt;
  copt.solver = solver;
  copt.max_state_changes = max_state_changes;
  contact::FaultContact fc(MPI_COMM_WORLD, &r.fm, copt);
  mech::SolverOptions opt;
  opt.linear = mech::LinearSolver::Mumps;
  opt.tolerance = 1e-10;
  opt.max_substeps = 1;
  mech::MechanicsSolver s(MPI_COMM_WORLD, &model, opt);
  s.set_coupling(fc);
  // The geostatic state first (it holds: chi < 1 everywhere), then the pressure rise.
  fc.set_pressure_change(std::vector<double>(r.fm.pairs.size(), 0.0));
  EXPECT_TRUE(s.advance(std::vector<double>(model.tets.size(), 0.0), "geostatic").converged);
  EXPECT_EQ(fc.gather().state, std::vector<std::uint8_t>(r.fm.pairs.size(), 0));
  std::vector<double> dpf(r.fm.pairs.size(), 0.0), dpc(model.tets.size(), 0.0);
  for (std::size_t q = 0; q < dpf.size(); ++q)
    if (in_block(r.fm.pairs[q].x)) dpf[q] = 1.8e6;
  for (std::size_t e = 0; e < dpc.size(); ++e) {
    Point3 c{0, 0, 0};
    for (auto v : model.tets[e])
      for (int d = 0; d < 3; ++d) c[d] += 0.25 * model.x[v][d];
    if (in_block(c)) dpc[e] = 0.0;  // the rock keeps its pressure
  }
  fc.set_pressure_change(dpf);
  r.rep = s.advance(dpc, "pressure rise");
  r.u = s.gather_displacement();
  r.res = fc.gather();
  std::printf("%s: %d Newton iterations (relative residuals", solver == contact::SaddleSolver::Mumps ? "mumps" : "fieldsplit",
              r.rep.newton_iterations);
  for (double x : r.rep.residuals) std::printf(" %.1e", x);
  std::printf("), %d linear iterations, %zu state changes\n", r.rep.linear_iterations, fc.stats().state_changes);
  return r;
}

}  // namespace

TEST(SlipPatch, ConvergesInBoundedNewtonIterationsOnTheMohrCoulombLimit) {
  const Result a = run(contact::SaddleSolver::Mumps);
  ASSERT_TRUE(a.rep.converged) << a.rep.failure;
  EXPECT_LE(a.rep.newton_iterations, kNewtonBound);
  const double mu = std::tan(20 * M_PI / 180);
  int slip = 0, stick = 0;
  double worst_limit = 0, worst_align = 0, max_slip = 0;
  for (std::size_t q = 0; q < a.fm.pairs.size(); ++q) {
    // Pairs on the fixed east side (the fault reaches it at z = -300) keep their initial traction:
    // the support carries it.
    if (a.fm.pairs[q].active != 7) {
      EXPECT_NEAR(a.fm.pairs[q].x[0], 1000.0, 1e-9);
      continue;
    }
    const double* l = &a.res.lambda[3 * q];
    const double tau = std::hypot(l[0], l[1]), tauL = -(l[2] + a.res.p_f[q]) * mu;
    EXPECT_LT(l[2] + a.res.p_f[q], 0);                 // effective compression
    EXPECT_LT(std::abs(a.res.g[3 * q + 2]), 1e-12);    // closed
    if (a.res.state[q] == 1) {
      ++slip;
      worst_limit = std::max(worst_limit, std::abs(tau - tauL) / tauL);
      const double* g = &a.res.g[3 * q];
      const double s = std::hypot(g[0], g[1]);
      max_slip = std::max(max_slip, s);
      if (s > 1e-6) worst_align = std::max(worst_align, 1 - (g[0] * l[0] + g[1] * l[1]) / (s * tau));
    } else {
      ++stick;
      EXPECT_LE(tau, tauL * (1 + 1e-9)) << "pair " << q;
    }
  }
  std::printf("slip patch: %d of %zu node pairs slip (max slip %.3f mm), %d stick; |tau| on the limit to %.1e, slip "
              "aligned with the shear to 1 - cos = %.1e\n",
              slip, a.fm.pairs.size(), max_slip * 1e3, stick, worst_limit, worst_align);
  EXPECT_GE(slip, 5);
  EXPECT_GE(stick, 5);
  EXPECT_LT(worst_limit, 1e-8);
  EXPECT_LT(worst_align, 1e-6);
  EXPECT_GT(max_slip, 1e-5);

  const Result b = run(contact::SaddleSolver::FieldSplit);
  ASSERT_TRUE(b.rep.converged) << b.rep.failure;
  EXPECT_LE(b.rep.newton_iterations, kNewtonBound);
  double umax = 0, diff = 0;
  for (std::size_t i = 0; i < a.u.size(); ++i) umax = std::max(umax, std::abs(a.u[i])), diff = std::max(diff, std::abs(a.u[i] - b.u[i]));
  EXPECT_LT(diff / umax, 1e-6);
  EXPECT_EQ(a.res.state, b.res.state);
}

TEST(SlipPatch, CyclingStateStopsNamingTheFaultAndNodes) {
  const Result a = run(contact::SaddleSolver::Mumps, 1);
  ASSERT_FALSE(a.rep.converged);
  EXPECT_NE(a.rep.failure.find("keeps cycling"), std::string::npos) << a.rep.failure;
  EXPECT_NE(a.rep.failure.find("fault 'F'"), std::string::npos) << a.rep.failure;
  EXPECT_NE(a.rep.failure.find("node pairs"), std::string::npos) << a.rep.failure;
  // The step is undone: the faults keep the geostatic state.
  for (auto st : a.res.state) EXPECT_EQ(st, 0);
  std::printf("%s\n", a.rep.failure.substr(0, 240).c_str());
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ugs::mech::PetscSession petsc;
  return RUN_ALL_TESTS();
}
