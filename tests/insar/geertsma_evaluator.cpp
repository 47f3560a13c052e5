// A stand-in solver for the calibration tests: the land displacement above two disk-shaped pools
// in a homogeneous half-space (Geertsma 1973, nucleus of strain, nu = 0.3) whose compaction
// follows the hypo-plastic law of the thesis in 1-D: dh/h = c dsigma', c = c_M(sigma') on virgin
// loading and c_M(sigma')/c_R on unloading/reloading, c_M = cm_a sigma'^-cm_b (eq. 4.1). c_R,
// cm_a, cm_b are read from the case file (materials pool_c and pool_a), so ugs-calibrate can
// drive it exactly like ugs-solve. Production starts in 1990; writes the top-surface displacement
// u (m) at monthly steps 2002-01 .. 2021-12 on a triangulated 15 x 15 km grid (EPSG:32632, node
// tags 1..N).
//
//   geertsma_evaluator --case case.toml -o result.h5
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <numbers>
#include <string>
#include <vector>

#include "ugs/formats/case_file.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/fields.hpp"

using namespace ugs;

namespace {

struct Pool {
  const char* material;
  double xc, yc, radius, depth, thickness;
  double sigma0_MPa;  // initial effective vertical stress magnitude
};

const Pool kPools[] = {{"pool_c", 681500, 4952300, 1600, 1500, 25, 20.0}, {"pool_a", 678000, 4953500, 1800, 1440, 40, 19.0}};

// Pressure change [MPa]: depletion to a minimum, then seasonal cycles (Pool A a third of a year later).
double dp_MPa(int pool, double years_since_1990) {
  const double t = years_since_1990;
  const double two_pi = 2 * std::numbers::pi;
  if (pool == 0) {
    if (t < 10) return -10.0 * t / 10;
    return -7.5 - 2.5 * std::cos(two_pi * (t - 10));
  }
  const double ta = 6.0 + 1.0 / 3.0;  // Pool A's cycles peak four months after Pool C's
  if (t < ta) return -7.0 * t / ta;
  return -5.0 - 2.0 * std::cos(two_pi * (t - ta));
}

}  // namespace

int main(int argc, char** argv) {
  std::string case_path, out;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == "--case") case_path = argv[++i];
    else if (std::string(argv[i]) == "-o") out = argv[++i];
  }
  if (case_path.empty() || out.empty()) {
    std::fprintf(stderr, "usage: geertsma_evaluator --case case.toml -o result.h5\n");
    return 2;
  }
  // Wall-clock start and end in the log, so tests can see evaluations overlap (ugs-calibrate -j).
  auto now_ms = [] {
    return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  };
  std::printf("start_ms %lld\n", static_cast<long long>(now_ms()));
  if (const char* s = std::getenv("UGS_TEST_EVALUATOR_SLEEP")) std::this_thread::sleep_for(std::chrono::duration<double>(std::atof(s)));
  try {
    const CaseFile cs = read_case_file(case_path);
    // Monthly steps from 1990; written from 2002.
    std::vector<std::int64_t> t;
    for (int y = 1990; y <= 2021; ++y)
      for (int m = 1; m <= 12; ++m) t.push_back(days_from_civil(y, m, 1) * 86400);
    const double t0 = double(t.front());
    // Compaction history of each pool: strain eps (shortening positive), 20 sub-steps per month.
    std::vector<std::vector<double>> eps(2, std::vector<double>(t.size(), 0.0));
    for (int p = 0; p < 2; ++p) {
      const MaterialSpec* m = cs.material(kPools[p].material);
      if (!m || !m->c_R) throw InputError(case_path, std::string("no hypoplastic material ") + kPools[p].material);
      double e = 0, sig = kPools[p].sigma0_MPa, sig_max = sig;
      for (std::size_t k = 1; k < t.size(); ++k) {
        const int sub = 20;
        for (int s = 1; s <= sub; ++s) {
          const double tb = (double(t[k - 1]) + s * double(t[k] - t[k - 1]) / sub - t0) / (365.25 * 86400);
          const double s_new = kPools[p].sigma0_MPa - (dp_MPa(p, tb));
          const double mid = 0.5 * (sig + s_new);
          double c = m->cm_a * std::pow(mid, -m->cm_b);
          if (s_new <= sig_max) c /= *m->c_R;
          e += c * (s_new - sig);
          sig = s_new;
          sig_max = std::max(sig_max, sig);
        }
        eps[p][k] = e;
      }
    }
    // Surface grid and the Green's functions of each pool (nuclei on a 100 m grid inside the disk).
    const int n = 31;
    const double x0 = 674000, y0 = 4945000, dx = 500;
    Mesh mesh;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) mesh.add_node({x0 + i * dx, y0 + j * dx, 0.0});
    auto& tri = mesh.block(2, mesh.entity_for_physical(2, "bnd:top"), ElementType::Triangle);
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i) {
        const std::uint32_t a = j * n + i, b = a + 1, c = a + n + 1, d = a + n;
        const std::uint32_t t1[3] = {a, b, c}, t2[3] = {a, c, d};
        mesh.add_element(tri, t1);
        mesh.add_element(tri, t2);
      }
    const double nu = 0.3, k = (1 - nu) / std::numbers::pi;
    std::vector<std::array<double, 3>> G[2];
    for (int p = 0; p < 2; ++p) {
      const Pool& P = kPools[p];
      G[p].assign(mesh.num_nodes(), {0, 0, 0});
      const double h = 100;
      for (double xn = P.xc - P.radius + h / 2; xn < P.xc + P.radius; xn += h)
        for (double yn = P.yc - P.radius + h / 2; yn < P.yc + P.radius; yn += h) {
          if (std::hypot(xn - P.xc, yn - P.yc) > P.radius) continue;
          const double vol = h * h * P.thickness;  // volume change per unit (-strain)
          for (std::size_t q = 0; q < mesh.num_nodes(); ++q) {
            const double rx = mesh.nodes[q][0] - xn, ry = mesh.nodes[q][1] - yn;
            const double f = k * vol / std::pow(rx * rx + ry * ry + P.depth * P.depth, 1.5);
            G[p][q][0] += f * rx;
            G[p][q][1] += f * ry;
            G[p][q][2] += f * P.depth;
          }
        }
    }
    FieldSeriesWriter w(out, mesh);
    const std::int64_t first_written = days_from_civil(2002, 1, 1) * 86400;
    for (std::size_t s = 0; s < t.size(); ++s) {
      if (t[s] < first_written) continue;
      Field u{"u", 3, std::vector<double>(3 * mesh.num_nodes(), 0.0)};
      for (std::size_t q = 0; q < mesh.num_nodes(); ++q)
        for (int p = 0; p < 2; ++p)
          for (int j = 0; j < 3; ++j) u.values[3 * q + j] += -eps[p][s] * G[p][q][j];  // compaction: volume loss
      const Field fs[] = {u};
      w.add_step(format_iso_date(t[s]), double(t[s]), fs);
    }
    w.commit();
    std::printf("geertsma_evaluator: c_R(pool_c) = %g, c_R(pool_a) = %g -> %s\n", *cs.material("pool_c")->c_R,
                *cs.material("pool_a")->c_R, out.c_str());
    std::printf("end_ms %lld\n", static_cast<long long>(now_ms()));
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "geertsma_evaluator: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "geertsma_evaluator: error: %s\n", e.what());
    return 1;
  }
}
