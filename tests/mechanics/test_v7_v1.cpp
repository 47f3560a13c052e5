// Verification through the mechanics library (VERIFICATION.md):
//  V7 — transversely isotropic patch test: a distorted box mesh with the displacement of a uniform
//       strain prescribed on its whole boundary reproduces that strain and the stress D eps of
//       eq. 3.22 in every element to round-off.
//  V1 — oedometer column with the hypo-plastic law along 20 -> 26 -> 23 -> 28 -> 25 MPa: the
//       column shortening at every turn within 0.5 % of the closed form, for the three inversion
//       rules (sigma-max is the default).
#include <cmath>

#include <gtest/gtest.h>

#include "case_builders.hpp"
#include "v1_oedometer.hpp"
#include "ugs/fem/voigt.hpp"
#include "ugs/mechanics/model.hpp"
#include "ugs/mechanics/petsc_session.hpp"
#include "ugs/mechanics/solver.hpp"
#include "ugs/meshing/box_mesh.hpp"

using namespace ugs;

namespace {

MaterialSpec ti_linear(const std::string& name) {
  MaterialSpec m = test::linear_material(name, "test", 2.0e9, 0.3);
  m.Eh_over_Ez = 3.0;
  m.nuh_over_nuz = 0.2;
  m.Gh_over_Gz = 1.7;
  return m;
}

CaseFile base_case() {
  CaseFile c;
  c.path = "test.toml";
  return c;
}

}  // namespace

class V7 : public ::testing::TestWithParam<mech::LinearSolver> {};

TEST_P(V7, TransverselyIsotropicPatchTest) {
  BoxMeshSpec spec;
  spec.x = {0, 0.7, 1.5, 2.0};
  spec.y = {0, 0.4, 1.1};
  spec.z = {-3.0, -2.2, -1.0, 0.0};
  Mesh mesh = make_box_mesh(spec);
  // Distort the interior nodes: the test must not depend on a regular mesh.
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    auto& p = mesh.nodes[i];
    const bool interior = p[0] > 0 && p[0] < 2.0 && p[1] > 0 && p[1] < 1.1 && p[2] > -3 && p[2] < 0;
    if (interior) p = {p[0] + 0.11, p[1] - 0.07, p[2] + 0.13};
  }
  CaseFile cs = base_case();
  cs.materials.push_back(ti_linear("rock"));
  cs.fixed_boundaries = {"west", "east", "south", "north", "bottom", "top"};
  mech::Model model = mech::build_model(mesh, cs);
  // u = E x on the boundary (E not symmetric: a rotation part must give no stress).
  const double E[3][3] = {{1.0e-3, 4.0e-4, -2.0e-4}, {-1.0e-4, -6.0e-4, 3.0e-4}, {5.0e-4, 2.0e-4, 2.0e-3}};
  for (std::size_t v = 0; v < model.num_nodes(); ++v)
    for (int a = 0; a < 3; ++a)
      model.prescribed[v][a] = E[a][0] * model.x[v][0] + E[a][1] * model.x[v][1] + E[a][2] * model.x[v][2];
  mech::SolverOptions opt;
  opt.linear = GetParam();
  opt.tolerance = 1e-13;
  mech::MechanicsSolver solver(MPI_COMM_WORLD, &model, opt);
  const auto rep = solver.advance(std::vector<double>(model.tets.size(), 0.0), "patch");
  ASSERT_TRUE(rep.converged) << rep.failure;
  const auto cells = solver.gather_cells();
  // Expected strain (output order, tensor components) and stress D eps.
  const fem::Vec6 eps{E[0][0], E[1][1], E[2][2], E[1][2] + E[2][1], E[0][2] + E[2][0], E[0][1] + E[1][0]};
  const fem::Vec6 sig = fem::mat_vec(model.materials[0].D_linear, eps);
  const auto eo = fem::strain_to_output(eps), so = fem::stress_to_output(sig);
  double emax = 0, smax = 0;
  for (int k = 0; k < 6; ++k) emax = std::max(emax, std::abs(eo[k])), smax = std::max(smax, std::abs(so[k]));
  const std::size_t nc = model.tets.size();
  ASSERT_EQ(cells.strain.size(), 6 * nc);
  double worst_e = 0, worst_s = 0;
  for (std::size_t c = 0; c < nc; ++c)
    for (int k = 0; k < 6; ++k) {
      worst_e = std::max(worst_e, std::abs(cells.strain[6 * c + k] - eo[k]) / emax);
      worst_s = std::max(worst_s, std::abs(cells.stress_change[6 * c + k] - so[k]) / smax);
    }
  std::printf("V7: worst strain error %.2e, stress error %.2e (relative), %d Newton, %d linear its\n", worst_e, worst_s,
              rep.newton_iterations, rep.linear_iterations);
  EXPECT_LT(worst_e, 1e-11);
  EXPECT_LT(worst_s, 1e-11);
  // The TI matrix really is anisotropic here (E_h = 3 E_z).
  EXPECT_GT(model.materials[0].D_linear[0] / model.materials[0].D_linear[6 * 2 + 2], 2.0);
}

INSTANTIATE_TEST_SUITE_P(Solvers, V7, ::testing::Values(mech::LinearSolver::Mumps, mech::LinearSolver::CgGamg),
                         [](const auto& info) { return std::string(info.param == mech::LinearSolver::Mumps ? "mumps" : "cg_gamg"); });

// ---- V1 ---------------------------------------------------------------------------------------
// The closed form of each layer: test::v1::layer_strain (tests/support/v1_oedometer.hpp).
class V1 : public ::testing::TestWithParam<std::string> {};

TEST_P(V1, OedometerPath) {
  const std::string rule = GetParam();
  // Column 1 x 1 x 1 m whose centre sits where sigma'_v0 = (0.0226 - 0.0100) d = 20 MPa.
  const double d20 = 20.0 / 0.0126, H = 1.0;
  const int nz = 4;
  BoxMeshSpec spec;
  spec.x = {0, 1};
  spec.y = {0, 1};
  spec.z = linspace(-d20 - H / 2, -d20 + H / 2, nz);
  Mesh mesh = make_box_mesh(spec);
  CaseFile cs = base_case();
  cs.materials.push_back(test::hypoplastic_material("rock", "test"));
  cs.fixed_boundaries = {"bottom"};
  cs.roller_boundaries = {"west", "east", "south", "north"};
  cs.inversion_rule = rule;
  const mech::Model model = mech::build_model(mesh, cs);
  mech::SolverOptions opt;
  mech::MechanicsSolver solver(MPI_COMM_WORLD, &model, opt);
  const std::vector<double> dS{0, 6, 3, 8, 5};  // MPa: 20 -> 26 -> 23 -> 28 -> 25
  // Reference: sum of the layers' closed forms, each from its own initial stress (elements of a
  // layer differ by a few kPa; the layer centre is used).
  std::vector<double> shortening(5, 0.0);
  for (int k = 0; k < nz; ++k) {
    const double zc = 0.5 * (spec.z[k] + spec.z[k + 1]), h = spec.z[k + 1] - spec.z[k];
    const auto e = test::v1::layer_strain(rule, 0.0126 * (-zc), 3.0, dS);
    for (int t = 0; t < 5; ++t) shortening[t] += e[t] * h;
  }
  std::vector<std::uint32_t> top;
  for (std::uint32_t v = 0; v < mesh.nodes.size(); ++v)
    if (mesh.nodes[v][2] == spec.z.back()) top.push_back(v);
  for (int t = 1; t < 5; ++t) {
    const auto rep = solver.advance(std::vector<double>(model.tets.size(), -dS[t] * 1e6), "V1 turn " + std::to_string(t));
    ASSERT_TRUE(rep.converged) << rep.failure;
    const auto u = solver.gather_displacement();
    double uz = 0;
    for (auto v : top) uz += u[3 * v + 2];
    uz /= top.size();
    std::printf("V1 %s turn %d: FE %.6e closed form %.6e ratio-1 %.2e (Newton %d, substeps %d)\n", rule.c_str(), t, -uz,
                shortening[t], -uz / shortening[t] - 1, rep.newton_iterations, rep.substeps);
    EXPECT_NEAR(-uz / shortening[t], 1.0, 0.005) << rule << " turn " << t << ": " << -uz << " vs " << shortening[t];
    EXPECT_NEAR(-uz / shortening[t], 1.0, 1e-3) << "tighter than the V1 tolerance is expected here";
  }
}

INSTANTIATE_TEST_SUITE_P(Rules, V1, ::testing::Values("sigma-max", "sigma-inversion", "stress-dependent"),
                         [](const auto& info) {
                           std::string s = info.param;
                           for (auto& c : s)
                             if (c == '-') c = '_';
                           return s;
                         });

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ugs::mech::PetscSession petsc;
  return RUN_ALL_TESTS();
}
