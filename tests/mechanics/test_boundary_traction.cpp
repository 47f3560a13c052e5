// Issue 21: per-material stress ratios and traction boundary conditions, through the mechanics
// library (PETSc initialised by this test's own main).
//  PerMaterialRatios — the output stress of a two-material box with no pressure change equals the
//       hand formula sigma' = sigma'_v (k_Hmax s s^T + k_hmin h h^T + e_z e_z^T) with each element's
//       material's ratios (the global ones for the material without its own), sigma'_v(z) from the
//       gradients and the material's Biot coefficient.
//  Forces — boundary_traction_forces on a face at depth: in_situ adds nothing (every node exactly
//       0); traction_MPa = [0, 0, 0] on the east face (removing the in-situ load) sums to the closed
//       form F_x = (k_xx (g_l - alpha g_w) + alpha g_w) W H^2 / 2, F_y = F_z = 0.
//  InsituLoadKeepsTheInitialState — a box with rollers on west, south and bottom, in_situ on east
//       and north, free top, no pressure change: u = 0 (below 1e-9 of the same box with its east and
//       north sides traction-free, which visibly deforms).
//  ConstantTractionUniaxial — [0, 0, -5 MPa] on the top (at the surface elevation, where
//       sigma_0 n = 0) of a box on rollers (west, south, bottom): the closed-form uniaxial stress
//       solution u_z = s (z + H) / E, u_x = -nu s x / E, u_y = -nu s y / E, sigma_zz change = s,
//       to round-off (P1 reproduces a linear field).
#include <cmath>

#include <gtest/gtest.h>

#include "case_builders.hpp"
#include "ugs/fem/voigt.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/mechanics/model.hpp"
#include "ugs/mechanics/petsc_session.hpp"
#include "ugs/mechanics/solver.hpp"
#include "ugs/meshing/box_mesh.hpp"

using namespace ugs;

namespace {

MaterialSpec linear_rock(const std::string& name, double E = 10e9, double nu = 0.25) {
  return test::linear_material(name, "bt.toml:1", E, nu);
}

// A box [0, L]^2 x [-H, 0] of n x n x nz cells, the surface elevation at its top.
Mesh box(double L, double H, int n, int nz, std::function<std::string(const Point3&)> material = {}) {
  BoxMeshSpec spec;
  spec.x = linspace(0, L, n);
  spec.y = linspace(0, L, n);
  spec.z = linspace(-H, 0, nz);
  spec.material = std::move(material);
  return make_box_mesh(spec);
}

CaseFile rollers_case() {
  CaseFile c;
  c.path = "bt.toml";
  c.fixed_boundaries = {};
  c.roller_boundaries = {"west", "south", "bottom"};
  c.free_boundaries = {"top"};
  c.initial_stress.k_Hmax = 0.8;
  c.initial_stress.k_hmin = 0.6;
  c.initial_stress.Hmax_azimuth_deg = 0;  // sigma'_Hmax along y: sigma'_xx = 0.6 sv, sigma'_yy = 0.8 sv
  return c;
}

TractionSpec traction(const std::string& group, bool in_situ, std::array<double, 3> t = {0, 0, 0}) {
  TractionSpec s;
  s.group = group;
  s.where = "bt.toml:9";
  s.in_situ = in_situ;
  s.traction_Pa = t;
  return s;
}

std::vector<double> solve_zero_step(mech::Model& model, mech::CellResults* cells = nullptr) {
  mech::SolverOptions opt;
  opt.linear = mech::LinearSolver::Mumps;
  opt.tolerance = 1e-12;
  mech::MechanicsSolver solver(MPI_COMM_WORLD, &model, opt);
  const auto rep = solver.advance(std::vector<double>(model.tets.size(), 0.0), "step");
  EXPECT_TRUE(rep.converged) << rep.failure;
  if (cells) *cells = solver.gather_cells();
  return solver.gather_displacement();
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace

TEST(BoundaryTraction, PerMaterialRatios) {
  // Upper half "soft" with its own ratios (k0 = 0.5 and k_Hmax 1.4: k_hmin from k0 of the material),
  // lower half "rock" with the global ones; the azimuth (30 degrees) is global.
  Mesh mesh = box(1000, 1000, 2, 4, [](const Point3& c) { return c[2] > -500 ? std::string("soft") : std::string("rock"); });
  CaseFile cs = rollers_case();
  cs.initial_stress.surface_elevation = 50;
  cs.initial_stress.Hmax_azimuth_deg = 30;
  cs.initial_stress.k_Hmax = 1.3;
  cs.initial_stress.k_hmin = 0.9;
  cs.materials.push_back(linear_rock("rock"));
  MaterialSpec soft = linear_rock("soft", 2e9, 0.3);
  soft.biot = 0.8;
  soft.k_Hmax = 1.4;
  soft.k_hmin = 0.5;
  cs.materials.push_back(soft);
  mech::Model model = mech::build_model(mesh, cs);
  ASSERT_EQ(model.material_k.size(), 2u);
  mech::CellResults cells;
  const auto u = solve_zero_step(model, &cells);
  EXPECT_EQ(max_abs(u), 0.0);  // no load at all
  const double a = 30 * M_PI / 180, s[3] = {std::sin(a), std::cos(a), 0}, h[3] = {std::cos(a), -std::sin(a), 0};
  std::size_t seen[2] = {0, 0};
  double worst = 0;
  for (std::size_t e = 0; e < model.tets.size(); ++e) {
    double zc = 0;
    for (auto v : model.tets[e]) zc += 0.25 * model.x[v][2];
    const bool is_soft = model.materials[model.tet_material[e]].name == "soft";
    ++seen[is_soft];
    const double alpha = is_soft ? 0.8 : 1.0, kH = is_soft ? 1.4 : 1.3, kh = is_soft ? 0.5 : 0.9;
    const double sv = -(0.0226e6 - alpha * 0.0100e6) * (50 - zc);
    double S[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) S[i][j] = sv * (kH * s[i] * s[j] + kh * h[i] * h[j]);
    S[2][2] = sv;
    // Output order xx yy zz xy yz xz.
    const double want[6] = {S[0][0], S[1][1], S[2][2], S[0][1], S[1][2], S[0][2]};
    for (int k = 0; k < 6; ++k) worst = std::max(worst, std::abs(cells.stress[6 * e + k] - want[k]) / std::abs(sv));
  }
  std::printf("per-material ratios: %zu rock + %zu soft elements, worst relative error %.2e\n", seen[0], seen[1], worst);
  EXPECT_GT(seen[0], 0u);
  EXPECT_GT(seen[1], 0u);
  EXPECT_LT(worst, 1e-14);
}

TEST(BoundaryTraction, ForcesOfTheInsituAndOfATractionFreeFace) {
  const double L = 600, H = 900, kxx = 0.6, gl = 0.0226e6, gw = 0.0100e6, alpha = 0.9;
  Mesh mesh = box(L, H, 3, 5);
  CaseFile cs = rollers_case();
  cs.materials.push_back(linear_rock("rock"));
  cs.materials[0].biot = alpha;
  cs.tractions = {traction("north", true), traction("east", false)};
  const mech::Model model = mech::build_model(mesh, cs);
  double F[3] = {0, 0, 0};
  for (std::size_t v = 0; v < model.num_nodes(); ++v) {
    const bool east = model.x[v][0] == L, north = model.x[v][1] == L;
    for (int k = 0; k < 3; ++k) {
      if (!east) {  // the in-situ north face and the unloaded nodes
        EXPECT_EQ(model.traction_force[v][k], 0.0) << "node " << v << (north ? " (in-situ north face)" : "");
      }
      F[k] += model.traction_force[v][k];
    }
  }
  const double want = (kxx * (gl - alpha * gw) + alpha * gw) * L * H * H / 2;
  std::printf("traction-free east face: F = (%.6e, %.3e, %.3e) N, closed form F_x = %.6e N\n", F[0], F[1], F[2], want);
  EXPECT_NEAR(F[0] / want, 1.0, 1e-12);
  EXPECT_LT(std::abs(F[1]) + std::abs(F[2]), 1e-9 * want);
}

TEST(BoundaryTraction, InsituLoadKeepsTheInitialState) {
  const double L = 1000, H = 1000;
  Mesh mesh = box(L, H, 4, 4);
  CaseFile cs = rollers_case();
  cs.materials.push_back(linear_rock("rock"));
  cs.tractions = {traction("east", true), traction("north", true)};
  mech::Model in_situ = mech::build_model(mesh, cs);
  const auto u0 = solve_zero_step(in_situ);
  cs.tractions = {traction("east", false), traction("north", false)};  // traction-free: a wrong load
  mech::Model freed = mech::build_model(mesh, cs);
  const auto u1 = solve_zero_step(freed);
  std::printf("in-situ lateral load: max |u| %.3e m; the same box with traction-free sides: max |u| %.3e m\n", max_abs(u0),
              max_abs(u1));
  EXPECT_GT(max_abs(u1), 0.1);  // sigma'_h ~ 0.6 * 12.6 MPa at 1 km over E = 10 GPa: ~0.4 m at the east top
  EXPECT_LE(max_abs(u0), 1e-9 * max_abs(u1));
}

TEST(BoundaryTraction, ConstantTractionUniaxial) {
  const double L = 400, H = 300, E = 10e9, nu = 0.25, s = -5e6;
  Mesh mesh = box(L, H, 3, 3);
  // Distort interior nodes in x and y (the load and the rollers stay planar).
  for (auto& p : mesh.nodes)
    if (p[0] > 0 && p[0] < L && p[1] > 0 && p[1] < L && p[2] > -H && p[2] < 0) p = {p[0] + 23, p[1] - 17, p[2] + 11};
  CaseFile cs = rollers_case();
  cs.materials.push_back(linear_rock("rock", E, nu));
  cs.free_boundaries = {};
  cs.tractions = {traction("top", false, {0, 0, s})};
  mech::Model model = mech::build_model(mesh, cs);
  mech::CellResults cells;
  const auto u = solve_zero_step(model, &cells);
  double worst = 0;
  for (std::size_t v = 0; v < model.num_nodes(); ++v) {
    const auto& x = model.x[v];
    const double want[3] = {-nu * s * x[0] / E, -nu * s * x[1] / E, s * (x[2] + H) / E};
    for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(u[3 * v + k] - want[k]));
  }
  double worst_s = 0;
  for (std::size_t e = 0; e < model.tets.size(); ++e)
    for (int k = 0; k < 6; ++k) worst_s = std::max(worst_s, std::abs(cells.stress_change[6 * e + k] - (k == 2 ? s : 0.0)));
  const double top = std::abs(s * H / E);
  std::printf("uniaxial: top settlement %.6e m (closed form %.6e), worst |u - u_exact| %.2e m, worst stress error %.2e Pa\n",
              -u[3 * (model.num_nodes() - 1) + 2], top, worst, worst_s);
  EXPECT_LT(worst, 1e-10 * top);
  EXPECT_LT(worst_s, 1e-8 * std::abs(s));
}

// ugs-solve frees the matrix and preconditioner before the last step's output: the gathers give the
// same bits afterwards, and a further step is refused instead of solving with nothing.
TEST(MechanicsSolver, ReleasedLinearSystemKeepsTheGathersAndRefusesAStep) {
  Mesh mesh = box(400, 300, 3, 3);
  CaseFile cs = rollers_case();
  cs.materials.push_back(linear_rock("rock", 10e9, 0.25));
  cs.free_boundaries = {};
  cs.tractions = {traction("top", false, {0, 0, -5e6})};
  mech::Model model = mech::build_model(mesh, cs);
  mech::SolverOptions opt;
  opt.linear = mech::LinearSolver::CgHypre;  // hypre owns the matrix: the linear ugs-solve path
  mech::MechanicsSolver solver(MPI_COMM_WORLD, &model, opt);
  ASSERT_TRUE(solver.advance(std::vector<double>(model.tets.size(), 0.0), "step").converged);
  const auto u = solver.gather_displacement();
  const auto stress = solver.gather_cell_field(mech::CellField::Stress);
  const auto dsig = solver.gather_state_field(mech::StateField::Dsig);
  solver.release_linear_system();
  EXPECT_GT(max_abs(u), 1e-4);
  EXPECT_EQ(solver.gather_displacement(), u);
  EXPECT_EQ(solver.gather_cell_field(mech::CellField::Stress), stress);
  EXPECT_EQ(solver.gather_state_field(mech::StateField::Dsig), dsig);
  EXPECT_THROW(solver.advance(std::vector<double>(model.tets.size(), 0.0), "again"), std::logic_error);
}

TEST(BoundaryTraction, GroupNotInTheMeshIsNamedWithTheMeshGroups) {
  Mesh mesh = box(100, 100, 1, 1);
  CaseFile cs = rollers_case();
  cs.materials.push_back(linear_rock("rock"));
  cs.tractions = {traction("flank", false, {1e6, 0, 0})};
  try {
    mech::build_model(mesh, cs);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "bt.toml:9: boundary_traction: the mesh has no group bnd:flank (expected one of its "
                                     "boundary groups: west, east, south, north, bottom, top)");
  }
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ugs::mech::PetscSession petsc;
  return RUN_ALL_TESTS();
}
