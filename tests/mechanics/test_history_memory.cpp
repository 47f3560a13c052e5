// Memory of a long hypo-plastic history (issue 23): what the solver allocates must stop growing once
// the Galerkin predictor's basis is full (48 step increments), and no step may hold a second copy
// of that basis (the re-orthonormalization at a preconditioner setup works in place). PETSc's own
// allocation tracking (-log_view_memory turns it on) counts the vectors; glibc's mallinfo2 the rest.
#include <malloc.h>
#include <petscsys.h>

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "ugs/mechanics/model.hpp"
#include "ugs/mechanics/petsc_session.hpp"
#include "ugs/mechanics/solver.hpp"
#include "ugs/meshing/box_mesh.hpp"

#include "case_builders.hpp"

using namespace ugs;

namespace {

constexpr int kBasis = 48;  // the predictor's directions (solver_impl.hpp, Predictor::kRecycle)

// A hypo-plastic block 2 km deep, its bottom fixed and sides on rollers.
mech::Model block_model(double L, int n) {
  BoxMeshSpec spec;
  spec.x = linspace(0, L, n);
  spec.y = linspace(0, L, n);
  spec.z = linspace(-2100, -1900, 5);
  const Mesh mesh = make_box_mesh(spec);
  CaseFile cs;
  cs.path = "test.toml";
  cs.materials.push_back(test::hypoplastic_material("rock", "test"));
  cs.fixed_boundaries = {"bottom"};
  cs.roller_boundaries = {"west", "east", "south", "north"};
  return mech::build_model(mesh, cs);
}

// Step k's pressure change per cell [Pa]: a depletion bowl whose centre circles the block, deeper
// each step and partly recovered every other one, so that elements go from virgin loading to
// unloading and back (preconditioner setups, and with them refreshes of the predictor's basis) and
// no two increments are alike (the basis fills).
std::vector<double> pressure(const mech::Model& model, double L, int k) {
  const double xc = L * (0.5 + 0.3 * std::cos(0.7 * k)), yc = L * (0.5 + 0.3 * std::sin(0.7 * k));
  const double amp = (k % 2 ? 1.0 : 3.0) + 0.1 * k, w = 0.35 * L;  // MPa
  std::vector<double> dp(model.tets.size());
  for (std::size_t c = 0; c < dp.size(); ++c) {
    double x = 0, y = 0;
    for (const auto v : model.tets[c]) x += 0.25 * model.x[v][0], y += 0.25 * model.x[v][1];
    const double r2 = ((x - xc) * (x - xc) + (y - yc) * (y - yc)) / (w * w);
    dp[c] = -1e6 * amp * (0.2 + std::exp(-r2));
  }
  return dp;
}

double petsc_bytes() {
  PetscLogDouble b = 0;
  PetscMallocGetCurrentUsage(&b);
  return b;
}

std::size_t heap_bytes() {
  const struct mallinfo2 mi = mallinfo2();
  return mi.uordblks + mi.hblkhd;
}

}  // namespace

TEST(HistoryMemory, FlatOnceThePredictorIsFullAndNoSecondBasis) {
  const double L = 1000;
  const int n = 11;
  const mech::Model model = block_model(L, n);
  const double vec_bytes = 3.0 * model.x.size() * sizeof(double);
  mech::SolverOptions opt;  // cg-hypre: GMRES + BoomerAMG on the hypo-plastic tangent
  mech::MechanicsSolver solver(MPI_COMM_WORLD, &model, opt);
  const int steps = kBasis + 14;
  std::vector<double> petsc_after(steps + 1), heap_after(steps + 1);
  double worst_transient = 0;  // bytes above both the start and the end of a step, at its peak
  int setups_when_full = 0;
  for (int k = 1; k <= steps; ++k) {
    const double before = petsc_bytes();
    PetscMallocPushMaximumUsage(k);
    const auto rep = solver.advance(pressure(model, L, k), "step " + std::to_string(k));
    PetscLogDouble peak = 0;
    PetscMallocPopMaximumUsage(k, &peak);
    ASSERT_TRUE(rep.converged) << rep.failure;
    EXPECT_EQ(rep.substeps, 1) << "step " << k;
    petsc_after[k] = petsc_bytes();
    heap_after[k] = static_cast<double>(heap_bytes());
    const double transient = peak - std::max(before, petsc_after[k]);
    if (k > kBasis) {
      worst_transient = std::max(worst_transient, transient);
      setups_when_full += rep.preconditioner_setups;
    }
    std::printf("step %2d: %d Newton, %3d linear, %d setups; PETSc %.0f kB, peak +%.0f kB (%.1f vectors); heap %.0f kB\n", k,
                rep.newton_iterations, rep.linear_iterations, rep.preconditioner_setups, petsc_after[k] / 1024,
                transient / 1024, transient / vec_bytes, heap_after[k] / 1024);
  }
  // The refresh of a full basis ran (a setup re-orthonormalizes the predictor's basis) ...
  ASSERT_GT(setups_when_full, 0);
  // ... with less than 3 vectors above the step's start and end (a second basis: 24), and the
  // headers of the refresh's sequential views on the blocks of the basis (48 of ~1.8 kB).
  EXPECT_LT(worst_transient, 3 * vec_bytes + 128 * 1024);
  // No growth once the basis is full: the vectors exactly, the whole heap within 64 kB.
  const int from = kBasis + 4;
  for (int k = from + 1; k <= steps; ++k) {
    EXPECT_EQ(petsc_after[k], petsc_after[from]) << "PETSc bytes after step " << k << " vs step " << from;
    EXPECT_NEAR(heap_after[k], heap_after[from], 64 * 1024) << "heap bytes after step " << k << " vs step " << from;
  }
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  // PETSc counts its allocations only with its tracing malloc (set up in PetscInitialize).
  ugs::mech::PetscSession petsc({"-log_view_memory"});
  return RUN_ALL_TESTS();
}
