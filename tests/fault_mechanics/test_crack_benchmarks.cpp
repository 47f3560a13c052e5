// Slip and opening of a crack in plane strain (VERIFICATION.md), through the library calls of
// ugs-solve on a slab one element thick (u_z = 0 on front and back), 80 x 80 m, rollers on the four
// sides, E = 25 GPa, nu = 0.25:
//  V5 — Sneddon: crack of half-length a = 1 m along the x axis, fluid pressure p = 2 MPa on its
//       faces, no initial stress: opening w(s) = 4 (1 - nu^2) p / E sqrt(a^2 - s^2) within 5 %
//       for |s| <= 0.8 a; the faces are open and carry no contact traction.
//  V4 — Phan et al. (2003): crack of half-length b = 1 m at psi = 20 degrees under an initial
//       sigma_xx = -100 MPa, cohesion 0, friction coefficient tan 30: normal traction
//       t_N = -sigma sin^2 psi = -11.698 MPa within 3 %, slip
//       g_T(s) = 4 (1 - nu^2) / E sigma sin psi (cos psi - mu sin psi) sqrt(b^2 - s^2) within 5 %
//       for |s| <= 0.8 b; the crack slips over its length, and Newton converges in at most
//       kNewtonBound iterations (the active set settles after the first).
// The profiles go to <build>/tests/fault_mechanics/v4_profile.csv and v5_profile.csv; plot_cracks.py draws
// them against the closed forms.
#include <cmath>
#include <fstream>

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

constexpr double kE = 25e9, kNu = 0.25;
constexpr int kNewtonBound = 6;

CaseFile slab_case(double friction_deg) {
  CaseFile c;
  c.path = "crack.toml";
  c.materials.push_back(test::linear_material("rock", "crack.toml:1", kE, kNu));
  c.fixed_boundaries.clear();
  c.roller_boundaries = {"west", "east", "south", "north", "bottom", "top"};
  c.faults.push_back(test::fault_spec("crack", "crack.toml:2", 0, friction_deg));
  return c;
}

struct CrackRun {
  Mesh mesh;
  mech::Model model;
  contact::FaultModel fm;
  contact::PairResults res;
  mech::StepReport rep;
};

// One step from the initial state sigma0 with fluid pressure p on the crack faces.
void run(CrackRun& c, double psi, double friction_deg, const fem::Vec6& sigma0, double p, contact::SaddleSolver solver) {
  c.mesh = test::crack_slab_mesh(psi, 1.0, 40, 8, 80.0, 1.18);
  const CaseFile cs = slab_case(friction_deg);
  c.model = mech::build_model(c.mesh, cs, true);
  contact::InitialFaultState init;
  init.total_stress = [&](const Point3&, double, const std::array<double, 2>&, const GasColumn&) { return sigma0; };
  init.pressure = [](const Point3&, const GasColumn&) { return 0.0; };
  c.fm = contact::build_fault_model(c.mesh, cs, c.model, init);
  contact::ContactOptions copt;
  copt.solver = solver;
  contact::FaultContact fc(MPI_COMM_WORLD, &c.fm, copt);
  mech::SolverOptions opt;
  opt.linear = mech::LinearSolver::Mumps;
  opt.tolerance = 1e-10;
  opt.max_substeps = 1;
  mech::MechanicsSolver solver_(MPI_COMM_WORLD, &c.model, opt);
  solver_.set_coupling(fc);
  fc.set_pressure_change(std::vector<double>(c.fm.pairs.size(), p));
  c.rep = solver_.advance(std::vector<double>(c.model.tets.size(), 0.0), "crack");
  c.res = fc.gather();
  std::printf("%zu nodes, %zu tetrahedra, %zu node pairs; %d Newton iterations (residuals", c.mesh.num_nodes(),
              c.model.tets.size(), c.fm.pairs.size(), c.rep.newton_iterations);
  for (double r : c.rep.residuals) std::printf(" %.1e", r);
  std::printf("), %d linear iterations\n", c.rep.linear_iterations);
}

// Position along the crack (x cos psi + y sin psi).
double along(const contact::NodePair& p, double psi) { return p.x[0] * std::cos(psi) + p.x[1] * std::sin(psi); }

}  // namespace

TEST(V5, SneddonPressurisedCrackOpening) {
  const double a = 1.0, p = 2e6, w0 = 4 * (1 - kNu * kNu) * p / kE;
  CrackRun c;
  run(c, 0.0, 30.0, fem::Vec6{}, p, contact::SaddleSolver::Mumps);
  ASSERT_TRUE(c.rep.converged) << c.rep.failure;
  std::ofstream csv(std::string(UGS_BINARY_DIR) + "/tests/fault_mechanics/v5_profile.csv");
  csv << "s_m,opening_mm,exact_mm,normal_traction_MPa\n";
  double worst = 0;
  int checked = 0, open = 0;
  for (std::size_t q = 0; q < c.fm.pairs.size(); ++q) {
    const double s = along(c.fm.pairs[q], 0.0), w = c.res.g[3 * q + 2], exact = w0 * std::sqrt(std::max(0.0, a * a - s * s));
    csv << s << ',' << w * 1e3 << ',' << exact * 1e3 << ',' << c.res.lambda[3 * q + 2] * 1e-6 << '\n';
    open += c.res.state[q] == static_cast<int>(contact::PairState::Open);
    EXPECT_NEAR(c.res.lambda[3 * q + 2], -p, 1e-6 * p);  // the fluid pressure is the only traction
    if (std::abs(s) > 0.8 * a) continue;
    worst = std::max(worst, std::abs(w - exact) / exact);
    ++checked;
  }
  std::printf("V5: w(0) exact %.4f mm; worst opening error %.2f %% over %d node pairs with |s| <= 0.8 a\n", w0 * 1e3,
              100 * worst, checked);
  EXPECT_EQ(open, static_cast<int>(c.fm.pairs.size()));
  EXPECT_GT(checked, 50);
  EXPECT_LT(worst, 0.05);
  EXPECT_LE(c.rep.newton_iterations, kNewtonBound);
}

TEST(V4, PhanInclinedCrackWithFriction) {
  const double psi = 20 * M_PI / 180, b = 1.0, sigma = 100e6, mu = std::tan(30 * M_PI / 180);
  const double tN = -sigma * std::sin(psi) * std::sin(psi);
  const double g0 = 4 * (1 - kNu * kNu) / kE * sigma * std::sin(psi) * (std::cos(psi) - mu * std::sin(psi));
  CrackRun c;
  run(c, psi, 30.0, fem::Vec6{-sigma, 0, 0, 0, 0, 0}, 0.0, contact::SaddleSolver::Mumps);
  ASSERT_TRUE(c.rep.converged) << c.rep.failure;
  std::ofstream csv(std::string(UGS_BINARY_DIR) + "/tests/fault_mechanics/v4_profile.csv");
  csv << "s_m,slip_mm,exact_mm,normal_traction_MPa,shear_traction_MPa\n";
  double worst_g = 0, worst_t = 0;
  int checked = 0, slipping = 0;
  for (std::size_t q = 0; q < c.fm.pairs.size(); ++q) {
    const double s = along(c.fm.pairs[q], psi);
    const double slip = std::hypot(c.res.g[3 * q], c.res.g[3 * q + 1]), exact = g0 * std::sqrt(std::max(0.0, b * b - s * s));
    const double t = c.res.lambda[3 * q + 2];
    csv << s << ',' << slip * 1e3 << ',' << exact * 1e3 << ',' << t * 1e-6 << ','
        << std::hypot(c.res.lambda[3 * q], c.res.lambda[3 * q + 1]) * 1e-6 << '\n';
    slipping += c.res.state[q] == static_cast<int>(contact::PairState::Slip);
    if (std::abs(s) > 0.8 * b) continue;
    worst_g = std::max(worst_g, std::abs(slip - exact) / exact);
    worst_t = std::max(worst_t, std::abs(t - tN) / std::abs(tN));
    EXPECT_NEAR(std::abs(c.res.g[3 * q + 2]), 0.0, 1e-9);  // closed
    ++checked;
  }
  std::printf("V4: t_N exact %.3f MPa, g_T(0) exact %.4f mm; worst errors over %d node pairs with |s| <= 0.8 b: "
              "normal traction %.2f %%, slip %.2f %%\n",
              tN * 1e-6, g0 * 1e3, checked, 100 * worst_t, 100 * worst_g);
  EXPECT_GT(checked, 50);
  EXPECT_LT(worst_t, 0.03);
  EXPECT_LT(worst_g, 0.05);
  EXPECT_EQ(slipping, static_cast<int>(c.fm.pairs.size()));
  EXPECT_LE(c.rep.newton_iterations, kNewtonBound);
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ugs::mech::PetscSession petsc;
  return RUN_ALL_TESTS();
}
