// V8 (VERIFICATION.md): the stress change on a locked fault offsetting a depleted reservoir against
// the closed form of Jansen, Singhal & Vossepoel (2019) (jansen_offset_fault.hpp), through the
// library calls of ugs-solve. Plane strain: the section is the (x, z) plane, a slab one element thick
// in y with u_y = 0 on front and back (as V4, V5), rollers on the outer sides 30 h away, E = 10 GPa,
// nu = 0.25, alpha = 1. Reservoir height h = 100 m, throw h/3, a normal fault dipping atan(2)
// (63.4 degrees: the diagonal plane of cells hz = 2 hx), the blocks 5 h wide on either side,
// dp = -10 MPa on the reservoir's tetrahedra only, cohesion 1e12 Pa (locked). The fault runs h/2
// beyond the corners and ends in the rock (tips).
//
// Checks, on the node pairs at least 0.1 h (along the fault) from the four corners:
//  - error: max |d lambda - closed form| of the normal and the dip shear traction change, relative
//    to the peak shear change of the closed form over the same points;
//  - roughness: max |e_i - (e_{i-1} + e_{i+1}) / 2| of the error e = computed - closed form over
//    consecutive pairs along the dip line (front side, the three in one stretch between corners),
//    relative to the same peak (docs/fault-mechanics.md; the same on the computed profile, which
//    includes the closed form's curvature, is printed too), and the front/back half-difference;
//  - the same roughness against the closed form averaged over each pair's hat function along the
//    dip (1D, Gauss on the two intervals): what a dual-mortar multiplier represents, so that the
//    first-order offset of the hat's centroid from the node on irregular spacing drops out;
//  - irregular meshes: nodes moved by up to a quarter cell, off the fault only or along it too;
//  - the fast case (12 cells per h) in CI, the three refinements (6, 12, 24) in test_offset_fault_long (bench-long).
// The profiles go to <build>/tests/fault_mechanics/v8_profile_<n>.csv (plot_offset_fault.py).
#include <algorithm>
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "case_builders.hpp"
#include "cell_values.hpp"
#include "fault_meshes.hpp"
#include "jansen_offset_fault.hpp"
#include "ugs/contact/contact.hpp"
#include "ugs/contact/fault_model.hpp"
#include "ugs/mechanics/model.hpp"
#include "ugs/mechanics/petsc_session.hpp"
#include "ugs/mechanics/solver.hpp"
#include "ugs/meshing/box_mesh.hpp"

using namespace ugs;
namespace jansen = ugs::test::jansen;

namespace {

// Every measure relative to the peak shear change of the closed form over the checked pairs.
struct V8Result {
  double err_n = 0, err_s = 0;          // max |error| of the normal and the dip shear traction change
  double rough_n = 0, rough_s = 0;      // roughness of the computed profiles (includes the closed form's curvature)
  double rough_err_n = 0, rough_err_s = 0;  // roughness of the errors: the pair-to-pair oscillation
  double rough_hat_n = 0, rough_hat_s = 0;  // the same against the closed form averaged over each pair's hat function (1D, along the dip)
  double front_back = 0;                // max |front - back| / 2 at the same height (plane strain: 0 exactly)
  double peak = 0;                      // [Pa]
  int checked = 0, pairs = 0, not_sticking = 0, newton = 0;
};

struct V8Options {
  int n = 12;                  // cells per reservoir height
  double jitter = 0;           // random displacement of the nodes in the fault's band (fraction of a cell)
  bool jitter_fault = false;   // the fault's nodes too (along the fault): irregular spacing along the dip
  bool write_profile = true;
};

V8Result run_v8(const V8Options& o) {
  jansen::OffsetReservoir r;
  r.theta = std::atan(2.0);
  const double h = r.h, hz = h / o.n, hx = hz / std::tan(r.theta);
  const double Zf = (r.h + r.t) / 2 + h / 2;  // the fault's half extent in z
  const int nu = static_cast<int>(std::lround(1.5 * o.n));
  const double Zu = nu * hz, Xu = nu * hx, L = 30 * h;
  auto axis = [&](double hu, double U) {
    std::vector<double> right = graded(U, L, hu * 1.15, 1.15), v;
    for (auto it = right.rbegin(); it != right.rend(); ++it) v.push_back(-*it);
    v.pop_back();
    for (double x : linspace(-U, U, 2 * nu)) v.push_back(x);
    v.pop_back();
    for (double x : right) v.push_back(x);
    return v;
  };
  BoxMeshSpec spec;
  spec.x = axis(hx, Xu);
  spec.z = axis(hz, Zu);
  spec.y = {0.0, hx};
  // The blocks' lateral ends: the grid line nearest to 5 h.
  double W = spec.x.back();
  for (double x : spec.x)
    if (std::abs(x - 5 * h) < std::abs(W - 5 * h)) W = x;
  r.W_left = r.W_right = W;
  Mesh mesh = make_box_mesh(spec);
  const double sn = std::sin(r.theta), cs_ = std::cos(r.theta);
  const auto cz = r.corners();
  if (o.jitter > 0) {
    // Irregular tetrahedra: the nodes of the uniform band move by up to `jitter` cells, those on the
    // fault's plane along it, those on the reservoir's top and base along x, the corners not at all.
    // A hash of the node's (x, z) grid position: front and back nodes move alike (a prismatic slab).
    auto rnd = [](std::uint64_t seed) {
      seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
      seed ^= seed >> 29;
      seed *= 0xbf58476d1ce4e5b9ULL;
      seed ^= seed >> 32;
      return static_cast<double>(seed >> 11) / 9007199254740992.0 * 2 - 1;
    };
    for (auto& x : mesh.nodes) {
      const auto key = static_cast<std::uint64_t>(std::llround(x[0] / hx + 1e6)) * 4000037ULL +
                       static_cast<std::uint64_t>(std::llround(x[2] / hz + 1e6));
      const double a = rnd(key) * o.jitter, b = rnd(key ^ 0x9e3779b97f4a7c15ULL) * o.jitter;
      if (std::abs(x[0]) >= Xu - 1e-9 * h || std::abs(x[2]) >= Zu - 1e-9 * h) continue;
      bool level = false;
      for (double c : cz) level = level || std::abs(x[2] - c) < 1e-9 * h;
      const bool on_fault = std::abs(x[2] * cs_ - x[0] * sn) < 1e-9 * h;
      if (on_fault && (level || !o.jitter_fault)) continue;
      if (on_fault) {
        x[0] += a * hx, x[2] += a * hz;  // along the plane (hx, hz) is its direction
      } else if (level) {
        x[0] += a * hx;
      } else {
        x[0] += a * hx, x[2] += b * hz;
      }
    }
  }
  test::add_planar_fault(
      mesh, "F", {0, 0, 0}, {-sn, 0, cs_}, [&](const Point3& c) { return std::abs(c[2]) < Zf; }, 1e-9 * h);
  test::insert_all_faults(mesh);

  CaseFile cs;
  cs.path = "v8.toml";
  cs.materials.push_back(test::linear_material("rock", "v8.toml:1", r.E, r.nu));
  cs.fixed_boundaries.clear();
  cs.roller_boundaries = {"west", "east", "south", "north", "bottom", "top"};
  cs.faults.push_back(test::fault_spec("F", "v8.toml:2", 1e12, 30));

  mech::Model model = mech::build_model(mesh, cs, true);
  const fem::Vec6 sigma0{-50e6, -50e6, -50e6, 0, 0, 0};
  contact::InitialFaultState init;
  init.total_stress = [&](const Point3&, double, const std::array<double, 2>&, const GasColumn&) { return sigma0; };
  init.pressure = [](const Point3&, const GasColumn&) { return 0.0; };
  const contact::FaultModel fm = contact::build_fault_model(mesh, cs, model, init);
  const std::vector<double> dp = test::cell_values_in(
      model,
      [&](const Point3& c) {
        const bool hanging = c[0] < r.fault_x(c[2]) && c[0] > -W && c[2] > cz[0] && c[2] < cz[2];
        const bool foot = c[0] > r.fault_x(c[2]) && c[0] < W && c[2] > cz[1] && c[2] < cz[3];
        return hanging || foot;
      },
      r.dp);

  contact::ContactOptions copt;
  copt.solver = contact::SaddleSolver::Mumps;
  contact::FaultContact fc(MPI_COMM_WORLD, &fm, copt);
  mech::SolverOptions opt;
  opt.linear = mech::LinearSolver::Mumps;
  opt.tolerance = 1e-10;
  opt.max_substeps = 1;
  mech::MechanicsSolver solver(MPI_COMM_WORLD, &model, opt);
  solver.set_coupling(fc);
  fc.set_pressure_change(std::vector<double>(fm.pairs.size(), 0.0));
  const auto rep = solver.advance(dp, "v8");
  EXPECT_TRUE(rep.converged) << rep.failure;
  const auto res = fc.gather();

  V8Result out;
  out.pairs = static_cast<int>(fm.pairs.size());
  out.newton = rep.newton_iterations;
  struct Row {
    double s, z, tn, ts, en, es, an = 0, as = 0, nx = 0, nz = 0, dx = 0, dz = 0;
    bool checked;
    int segment;
  };
  std::vector<Row> front, back;
  for (std::size_t q = 0; q < fm.pairs.size(); ++q) {
    const auto& p = fm.pairs[q];
    out.not_sticking += res.state[q] != 0;
    const double nx = p.R[2], nz = p.R[8];
    const auto T = jansen::fault_traction_change(r, p.x[2], nx, nz);
    Row w;
    w.z = p.x[2];
    w.s = p.x[2] / sn;  // along the dip line
    w.tn = res.lambda[3 * q + 2] - p.lambda0[2];
    w.ts = res.lambda[3 * q + 1] - p.lambda0[1];
    w.en = T[0] * nx + T[1] * nz;
    w.es = T[0] * p.R[1] + T[1] * p.R[7];
    w.nx = nx;
    w.nz = nz;
    w.dx = p.R[1];
    w.dz = p.R[7];
    double dmin = 1e300;
    w.segment = 0;
    for (double c : cz) {
      dmin = std::min(dmin, std::abs(p.x[2] - c) / sn);
      w.segment += p.x[2] > c;
    }
    w.checked = dmin >= 0.1 * h - 1e-9 * h && std::abs(p.x[2]) < Zf - 0.1 * h;  // away from corners and tips
    (p.x[1] < 0.5 * hx ? front : back).push_back(w);
  }
  auto by_s = [](const Row& a, const Row& b) { return a.s < b.s; };
  std::sort(front.begin(), front.end(), by_s);
  std::sort(back.begin(), back.end(), by_s);
  EXPECT_EQ(front.size(), back.size());
  for (const Row& w : front)
    if (w.checked) out.peak = std::max(out.peak, std::abs(w.es));
  for (std::size_t i = 0; i < std::min(front.size(), back.size()); ++i)
    if (front[i].checked)
      out.front_back = std::max({out.front_back, 0.5 * std::abs(front[i].tn - back[i].tn) / out.peak,
                                 0.5 * std::abs(front[i].ts - back[i].ts) / out.peak});
  // The closed form weighted by the 1D hat function of each pair along the dip line (what a dual
  // mortar multiplier represents): separates the reading position from the discretisation.
  {
    const double gx[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
    const double gw[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
    for (std::size_t i = 1; i + 1 < front.size(); ++i) {
      double wn = 0, ws = 0, wt = 0;
      for (int side = 0; side < 2; ++side) {
        const double a = side ? front[i].s : front[i - 1].s, b = side ? front[i + 1].s : front[i].s;
        for (int sub = 0; sub < 8; ++sub) {
          const double a2 = a + (b - a) * sub / 8, b2 = a + (b - a) * (sub + 1) / 8;
          for (int g = 0; g < 4; ++g) {
            const double sg = 0.5 * (a2 + b2) + 0.5 * (b2 - a2) * gx[g], wg = 0.5 * (b2 - a2) * gw[g];
            const double phi = side ? (b - sg) / (b - a) : (sg - a) / (b - a);
            const double nx = front[i].nx, nz = front[i].nz, dx = front[i].dx, dz = front[i].dz;
            const auto T = jansen::fault_traction_change(r, sg * sn, nx, nz);
            wn += phi * wg * (T[0] * nx + T[1] * nz);
            ws += phi * wg * (T[0] * dx + T[1] * dz);
            wt += phi * wg;
          }
        }
      }
      front[i].an = wn / wt;
      front[i].as = ws / wt;
    }
  }
  for (std::size_t i = 0; i < front.size(); ++i) {
    const Row& w = front[i];
    if (!w.checked) continue;
    ++out.checked;
    out.err_n = std::max(out.err_n, std::abs(w.tn - w.en) / out.peak);
    out.err_s = std::max(out.err_s, std::abs(w.ts - w.es) / out.peak);
    if (i == 0 || i + 1 == front.size()) continue;
    const Row &a = front[i - 1], &b = front[i + 1];
    if (!a.checked || !b.checked || a.segment != w.segment || b.segment != w.segment) continue;
    out.rough_n = std::max(out.rough_n, std::abs(w.tn - 0.5 * (a.tn + b.tn)) / out.peak);
    out.rough_s = std::max(out.rough_s, std::abs(w.ts - 0.5 * (a.ts + b.ts)) / out.peak);
    out.rough_err_n = std::max(out.rough_err_n, std::abs(w.tn - w.en - 0.5 * (a.tn - a.en + b.tn - b.en)) / out.peak);
    out.rough_err_s = std::max(out.rough_err_s, std::abs(w.ts - w.es - 0.5 * (a.ts - a.es + b.ts - b.es)) / out.peak);
    if (i >= 2 && i + 2 < front.size()) {
      out.rough_hat_n = std::max(out.rough_hat_n, std::abs(w.tn - w.an - 0.5 * (a.tn - a.an + b.tn - b.an)) / out.peak);
      out.rough_hat_s = std::max(out.rough_hat_s, std::abs(w.ts - w.as - 0.5 * (a.ts - a.as + b.ts - b.as)) / out.peak);
    }
  }
  if (o.write_profile) {
    std::ofstream csv(std::string(UGS_BINARY_DIR) + "/tests/fault_mechanics/v8_profile_" + std::to_string(o.n) + ".csv");
    csv << "side,z_m,s_m,dsigma_n_MPa,dtau_dip_MPa,exact_dsigma_n_MPa,exact_dtau_dip_MPa,checked\n";
    for (const Row& w : front)
      csv << 0 << ',' << w.z << ',' << w.s << ',' << w.tn * 1e-6 << ',' << w.ts * 1e-6 << ',' << w.en * 1e-6 << ',' << w.es * 1e-6 << ','
          << (w.checked ? 1 : 0) << '\n';
    for (const Row& w : back)
      csv << 1 << ',' << w.z << ',' << w.s << ',' << w.tn * 1e-6 << ',' << w.ts * 1e-6 << ',' << w.en * 1e-6 << ',' << w.es * 1e-6 << ','
          << (w.checked ? 1 : 0) << '\n';
  }
  std::printf("V8 n = %d%s: %zu nodes, %zu pairs, %d Newton; peak shear change %.3f MPa over %d pairs; of it: errors normal "
              "%.2f %%, shear %.2f %%; roughness of the errors normal %.3f %%, shear %.3f %% (of the profiles %.2f %%, %.2f %%); "
              "front/back %.2f %%; roughness against the hat-weighted closed form normal %.3f %%, shear %.3f %%\n",
              o.n, o.jitter > 0 ? (o.jitter_fault ? " (jittered, fault nodes too)" : " (jittered off the fault)") : "",
              mesh.num_nodes(), fm.pairs.size(), out.newton, out.peak * 1e-6, out.checked, 100 * out.err_n, 100 * out.err_s,
              100 * out.rough_err_n, 100 * out.rough_err_s, 100 * out.rough_n, 100 * out.rough_s, 100 * out.front_back, 100 * out.rough_hat_n, 100 * out.rough_hat_s);
  return out;
}

}  // namespace

// The closed form itself: a uniform layer (blocks much wider than h, no throw) gives the oedometric
// horizontal stress change -alpha dp (1 - 2 nu) / (1 - nu) inside and nothing far outside, and the
// fault tractions are continuous across the fault away from the corners.
#ifndef UGS_V8_LONG
TEST(V8, ClosedFormLimits) {
  jansen::OffsetReservoir r;
  r.theta = std::atan(2.0);
  r.t = 0;
  r.W_left = r.W_right = 1e7;
  const auto in = jansen::stress_change(r, 20 * r.h, 0.1 * r.h);
  EXPECT_NEAR(in[0], -r.alpha * r.dp * (1 - 2 * r.nu) / (1 - r.nu), 1e-5 * std::abs(r.dp));
  EXPECT_NEAR(in[1], 0, 1e-5 * std::abs(r.dp));
  EXPECT_NEAR(in[2], 0, 1e-5 * std::abs(r.dp));
  const auto outside = jansen::stress_change(r, 20 * r.h, 3 * r.h);
  for (double s : outside) EXPECT_NEAR(s, 0, 1e-5 * std::abs(r.dp));
  // With the throw: sigma n equal on both sides of the fault to 1e-5 of dp (0.05 h or more from the corners).
  jansen::OffsetReservoir o;
  o.theta = std::atan(2.0);
  const double nx = -std::sin(o.theta), nz = std::cos(o.theta);
  const auto c = o.corners();
  for (double z = c[0] - 0.5 * o.h; z <= c[3] + 0.5 * o.h; z += 0.013 * o.h) {
    bool near = false;
    for (double zc : c) near = near || std::abs(z - zc) < 0.05 * o.h;
    if (near) continue;
    const double x = o.fault_x(z), e = 1e-7 * o.h;
    const auto A = jansen::stress_change(o, x - e * nx, z - e * nz), B = jansen::stress_change(o, x + e * nx, z + e * nz);
    EXPECT_NEAR(A[0] * nx + A[2] * nz, B[0] * nx + B[2] * nz, 1e-5 * std::abs(o.dp)) << "z = " << z;
    EXPECT_NEAR(A[2] * nx + A[1] * nz, B[2] * nx + B[1] * nz, 1e-5 * std::abs(o.dp)) << "z = " << z;
  }
}

// n = 12 cells per h (errors measured 2.5 % normal, 0.4 % shear; roughness of the errors 0.03 %).
TEST(V8, OffsetFaultTractions) {
  const V8Result r = run_v8({});
  EXPECT_EQ(r.not_sticking, 0);
  EXPECT_GE(r.checked, 12);
  EXPECT_GT(r.peak, 3e6);
  EXPECT_LT(r.err_n, 0.04);
  EXPECT_LT(r.err_s, 0.01);
  EXPECT_LT(r.rough_err_n, 0.01);
  EXPECT_LT(r.rough_err_s, 0.01);
  EXPECT_LT(std::max(r.rough_hat_n, r.rough_hat_s), 0.01);  // 0.09 %
  EXPECT_LT(r.front_back, 0.03);  // 1.9 %: the one-sided hat functions of the Kuhn split, first order (long test)
}

// Irregular tetrahedra (nodes off the fault moved by up to a quarter cell), regular spacing along the
// fault: still smooth (roughness of the errors 0.25 %).
TEST(V8, IrregularTetrahedra) {
  const V8Result r = run_v8({12, 0.25, false, false});
  EXPECT_EQ(r.not_sticking, 0);
  EXPECT_LT(r.err_n, 0.05);
  EXPECT_LT(r.err_s, 0.02);
  EXPECT_LT(r.rough_err_n, 0.01);
  EXPECT_LT(r.rough_err_s, 0.01);
}

// The fault's nodes moved along it too (irregular spacing along the dip): the roughness the issue
// saw, 2.8 % of the peak shear change (docs/fault-mechanics.md: the multiplier of a pair is the
// traction weighted by its hat function, whose centroid is off the node). Bounds, not the goal.
TEST(V8, IrregularFaultNodes) {
  const V8Result r = run_v8({12, 0.25, true, false});
  EXPECT_EQ(r.not_sticking, 0);
  EXPECT_LT(r.err_n, 0.06);
  EXPECT_LT(r.err_s, 0.04);
  EXPECT_LT(std::max(r.rough_err_n, r.rough_err_s), 0.04);  // 2.3 / 2.8 %
  // Against the closed form weighted by each pair's hat function (what the multiplier represents)
  // half of it goes: 1.2 / 1.5 %, the distortion of the rock's elements (1.0 % with the fault's
  // nodes regular and the others moved, IrregularTetrahedra).
  EXPECT_LT(std::max(r.rough_hat_n, r.rough_hat_s), 0.02);
}

#else
// Three refinements (6, 12, 24 cells per h): the errors decrease, the roughness of the errors stays
// below 1 %, the front/back difference decreases (first order).
TEST(V8Long, OffsetFaultConvergence) {
  std::vector<V8Result> runs;
  for (int n : {6, 12, 24}) runs.push_back(run_v8({n}));
  for (std::size_t i = 1; i < runs.size(); ++i) {
    EXPECT_LT(runs[i].err_n, runs[i - 1].err_n);
    EXPECT_LT(runs[i].err_s, runs[i - 1].err_s);
    EXPECT_LT(runs[i].front_back, runs[i - 1].front_back);
  }
  for (const auto& r : runs) {
    EXPECT_EQ(r.not_sticking, 0);
    EXPECT_LT(r.rough_err_n, 0.01);
    EXPECT_LT(r.rough_err_s, 0.01);
  }
  // Irregular spacing along the fault, for the record (not asserted: docs/fault-mechanics.md).
  for (int n : {6, 12, 24}) run_v8({n, 0.25, true, false});
}

#endif

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ugs::mech::PetscSession petsc;
  return RUN_ALL_TESTS();
}
