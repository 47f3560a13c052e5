#include "ugs/meshing/mesh_quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <fmt/format.h>

#include "ugs/meshing/surface_stack.hpp"

namespace ugs {

namespace {

struct Partial {
  double vmin = std::numeric_limits<double>::infinity(), vmax = -std::numeric_limits<double>::infinity();
  double volume = 0, min_angle = 180;
  std::size_t inverted = 0, small = 0, degenerate = 0;
  std::size_t first_degenerate = std::numeric_limits<std::size_t>::max();  // its index in the block
  double max_cos = -1;  // the smallest angle's cosine; acos once per chunk, not per tetrahedron
};

// The cosine of the smallest dihedral angle (clamped to [-1, 1]); 1 for a flat or degenerate tetrahedron.
// Face i is the one opposite vertex i, spanned from its first vertex q0 = p[(i+1)%4] by q1 - q0 and
// q2 - q0 (q1 = p[(i+2)%4], q2 = p[(i+3)%4]); its normal cross(q1 - q0, q2 - q0) is turned away from
// vertex i (all outward or all inward) and made unit. The dihedral angle at an edge is pi minus the
// angle between the two normals. The loop over the faces this replaces took 400 instructions per
// tetrahedron (13 % of ugs-meshgen's thesis bench in the report alone, as much again in the cut's
// band); the same operations in the same order give the same bits, here two faces at a time in
// SSE2's two lanes (faces 0 and 1, then 2 and 3: q0 = (b, c) then (d, a), and so on).
#if defined(__SSE2__)
double worst_dihedral_cos_2(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  // Per coordinate k: the pairs (a, b), (b, c), (c, d), (d, a) of the four vertices.
  __m128d ab[3], bc[3], cd[3], da[3];
  for (int k = 0; k < 3; ++k) {
    ab[k] = _mm_set_pd(b[k], a[k]);  // lane 0 first: (a, b)
    bc[k] = _mm_set_pd(c[k], b[k]);
    cd[k] = _mm_set_pd(d[k], c[k]);
    da[k] = _mm_set_pd(a[k], d[k]);
  }
  const __m128d sign = _mm_set1_pd(-0.0), zero = _mm_setzero_pd();
  // Unit normals of two faces (q0, q1, q2 per lane, r the opposite vertex); false when one is degenerate.
  auto normals = [&](const __m128d* q0, const __m128d* q1, const __m128d* q2, const __m128d* r, __m128d* n) {
    __m128d u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
      u[k] = _mm_sub_pd(q1[k], q0[k]);
      v[k] = _mm_sub_pd(q2[k], q0[k]);
      w[k] = _mm_sub_pd(r[k], q0[k]);
    }
    n[0] = _mm_sub_pd(_mm_mul_pd(u[1], v[2]), _mm_mul_pd(u[2], v[1]));
    n[1] = _mm_sub_pd(_mm_mul_pd(u[2], v[0]), _mm_mul_pd(u[0], v[2]));
    n[2] = _mm_sub_pd(_mm_mul_pd(u[0], v[1]), _mm_mul_pd(u[1], v[0]));
    const __m128d towards = _mm_add_pd(_mm_add_pd(_mm_mul_pd(n[0], w[0]), _mm_mul_pd(n[1], w[1])), _mm_mul_pd(n[2], w[2]));
    const __m128d flip = _mm_and_pd(_mm_cmpgt_pd(towards, zero), sign);  // negate where it points towards r
    for (int k = 0; k < 3; ++k) n[k] = _mm_xor_pd(n[k], flip);
    const __m128d len =
        _mm_sqrt_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(n[0], n[0]), _mm_mul_pd(n[1], n[1])), _mm_mul_pd(n[2], n[2])));
    for (int k = 0; k < 3; ++k) n[k] = _mm_div_pd(n[k], len);
    return _mm_movemask_pd(_mm_cmpgt_pd(len, zero)) == 3;  // !(len > 0) in a lane: degenerate (or NaN)
  };
  __m128d n01[3], n23[3];
  const bool ok01 = normals(bc, cd, da, ab, n01);  // faces 0 (b, c, d; a) and 1 (c, d, a; b)
  const bool ok23 = normals(da, ab, bc, cd, n23);  // faces 2 (d, a, b; c) and 3 (a, b, c; d)
  if (!(ok01 && ok23)) return 1.0;
  auto dot = [](const __m128d* x, const __m128d* y) {
    return _mm_add_pd(_mm_add_pd(_mm_mul_pd(x[0], y[0]), _mm_mul_pd(x[1], y[1])), _mm_mul_pd(x[2], y[2]));
  };
  __m128d even[3], odd[3], n32[3];
  for (int k = 0; k < 3; ++k) {
    even[k] = _mm_unpacklo_pd(n01[k], n23[k]);  // (n0, n2)
    odd[k] = _mm_unpackhi_pd(n01[k], n23[k]);   // (n1, n3)
    n32[k] = _mm_shuffle_pd(n23[k], n23[k], 1);  // (n3, n2)
  }
  double p[6];  // n_i . n_j for (0,1), (2,3), (0,2), (1,3), (0,3), (1,2)
  _mm_storeu_pd(p, dot(even, odd));
  _mm_storeu_pd(p + 2, dot(n01, n23));
  _mm_storeu_pd(p + 4, dot(n01, n32));
  double worst = -1;
  for (int i : {0, 2, 4, 5, 3, 1}) worst = std::max(worst, -p[i]);  // in the pairs' order (0,1) .. (2,3)
  return std::clamp(worst, -1.0, 1.0);
}
#if defined(__x86_64__)
// The four faces at once in AVX's four lanes (face i in lane i: q0, q1, q2, r are the vertices
// rotated by 1, 2, 3 and 0), where the processor has AVX (no FMA: each product is rounded as the
// scalar code rounds it). The normals' dot products: with the normals rotated by one lane
// (0.1, 1.2, 2.3, 3.0) and by two (0.2, 1.3).
#define UGS_AVX __attribute__((target("avx"), always_inline)) inline
UGS_AVX __m256d rot1(__m256d x) { return _mm256_shuffle_pd(x, _mm256_permute2f128_pd(x, x, 1), 5); }  // (x1, x2, x3, x0)
UGS_AVX __m256d rot2(__m256d x) { return _mm256_permute2f128_pd(x, x, 1); }                           // (x2, x3, x0, x1)
UGS_AVX __m256d rot3(__m256d x) { return _mm256_shuffle_pd(_mm256_permute2f128_pd(x, x, 1), x, 5); }  // (x3, x0, x1, x2)
UGS_AVX __m256d dot4(const __m256d* x, const __m256d* y) {
  return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(x[0], y[0]), _mm256_mul_pd(x[1], y[1])), _mm256_mul_pd(x[2], y[2]));
}
#undef UGS_AVX

__attribute__((target("avx"))) double worst_dihedral_cos_4(const Point3& a, const Point3& b, const Point3& c,
                                                            const Point3& d) {
  __m256d r[3], q0[3], q1[3], q2[3];
  for (int k = 0; k < 3; ++k) {
    r[k] = _mm256_set_pd(d[k], c[k], b[k], a[k]);  // lane 0 last: (a, b, c, d)
    q0[k] = rot1(r[k]);
    q1[k] = rot2(r[k]);
    q2[k] = rot3(r[k]);
  }
  __m256d u[3], v[3], w[3], n[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = _mm256_sub_pd(q1[k], q0[k]);
    v[k] = _mm256_sub_pd(q2[k], q0[k]);
    w[k] = _mm256_sub_pd(r[k], q0[k]);
  }
  n[0] = _mm256_sub_pd(_mm256_mul_pd(u[1], v[2]), _mm256_mul_pd(u[2], v[1]));
  n[1] = _mm256_sub_pd(_mm256_mul_pd(u[2], v[0]), _mm256_mul_pd(u[0], v[2]));
  n[2] = _mm256_sub_pd(_mm256_mul_pd(u[0], v[1]), _mm256_mul_pd(u[1], v[0]));
  const __m256d zero = _mm256_setzero_pd();
  const __m256d flip = _mm256_and_pd(_mm256_cmp_pd(dot4(n, w), zero, _CMP_GT_OQ), _mm256_set1_pd(-0.0));
  for (int k = 0; k < 3; ++k) n[k] = _mm256_xor_pd(n[k], flip);
  const __m256d len = _mm256_sqrt_pd(dot4(n, n));
  if (_mm256_movemask_pd(_mm256_cmp_pd(len, zero, _CMP_GT_OQ)) != 15) return 1.0;  // !(len > 0) in a lane
  __m256d m1[3], m2[3];
  for (int k = 0; k < 3; ++k) {
    n[k] = _mm256_div_pd(n[k], len);
    m1[k] = rot1(n[k]);
    m2[k] = rot2(n[k]);
  }
  double p1[4], p2[4];  // n0.n1, n1.n2, n2.n3, n3.n0; n0.n2, n1.n3 (twice)
  _mm256_storeu_pd(p1, dot4(n, m1));
  _mm256_storeu_pd(p2, dot4(n, m2));
  double worst = -1;  // in the pairs' order (0,1), (0,2), (0,3), (1,2), (1,3), (2,3)
  for (double x : {p1[0], p2[0], p1[3], p1[1], p2[1], p1[2]}) worst = std::max(worst, -x);
  return std::clamp(worst, -1.0, 1.0);
}
#endif

#else  // no SSE2: the loop itself
using V3 = std::array<double, 3>;
V3 sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross(const V3& u, const V3& v) { return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]}; }
double dot(const V3& u, const V3& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }

double worst_dihedral_cos_2(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const Point3* p[4] = {&a, &b, &c, &d};
  V3 n[4];
  for (int i = 0; i < 4; ++i) {
    const Point3& q0 = *p[(i + 1) % 4];
    n[i] = cross(sub(*p[(i + 2) % 4], q0), sub(*p[(i + 3) % 4], q0));
    if (dot(n[i], sub(*p[i], q0)) > 0) n[i] = {-n[i][0], -n[i][1], -n[i][2]};
    const double len = std::sqrt(dot(n[i], n[i]));
    if (!(len > 0)) return 1.0;
    for (auto& x : n[i]) x /= len;
  }
  double worst = -1;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) worst = std::max(worst, -dot(n[i], n[j]));
  return std::clamp(worst, -1.0, 1.0);
}
#endif

double worst_dihedral_cos(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
#if defined(__x86_64__)
  static const bool avx = __builtin_cpu_supports("avx");
  if (avx) return worst_dihedral_cos_4(a, b, c, d);
#endif
  return worst_dihedral_cos_2(a, b, c, d);
}

double cos_to_deg(double c) { return std::acos(c) * 180.0 / M_PI; }

}  // namespace

// A flat tetrahedron's faces turn "away from" the opposite vertex by rounding only: their normals
// may all agree and give 180 deg. ugs-solve's test (tet_is_degenerate) tells it, and it is 0.
double min_dihedral_angle_deg(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  if (tet_is_degenerate(a, b, c, d)) return 0.0;
  return cos_to_deg(worst_dihedral_cos(a, b, c, d));
}

namespace detail {
double min_dihedral_angle_deg_lanes(int lanes, const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
#if defined(__x86_64__)
  if (lanes == 4 && __builtin_cpu_supports("avx")) return cos_to_deg(worst_dihedral_cos_4(a, b, c, d));
#endif
  return cos_to_deg(worst_dihedral_cos_2(a, b, c, d));
}
}  // namespace detail

QualityReport mesh_quality(const Mesh& mesh, double small_angle_deg) {
  QualityReport q;
  q.nodes = mesh.num_nodes();
  q.small_angle_deg = small_angle_deg;
  q.min_dihedral_deg = 180;
  q.min_volume = std::numeric_limits<double>::infinity();
  q.max_volume = -std::numeric_limits<double>::infinity();
  constexpr std::size_t chunk = 1 << 15;
  const unsigned nthreads = std::max(1u, std::min(8u, std::thread::hardware_concurrency()));
  for (const auto& b : mesh.blocks) {
    const std::string name = mesh.physical_name_of(b.entity_dim, b.entity_tag);
    if (b.type == ElementType::Triangle) {
      q.triangles += b.size();
      auto it = std::find_if(q.surfaces.begin(), q.surfaces.end(), [&](const auto& g) { return g.name == name; });
      if (it == q.surfaces.end()) q.surfaces.push_back({name, b.size()});
      else it->elements += b.size();
      continue;
    }
    if (b.type != ElementType::Tetrahedron) continue;
    const std::size_t first_tet = q.tetrahedra;  // the block's first tetrahedron's index among all
    q.tetrahedra += b.size();
    const std::size_t nchunks = (b.size() + chunk - 1) / chunk;
    std::vector<Partial> parts(nchunks);
    const double cos_small = std::cos(small_angle_deg * M_PI / 180.0);
    const double cos_lo = cos_small - 1e-9, cos_hi = cos_small + 1e-9;
    auto work = [&](unsigned t) {
      for (std::size_t k = t; k < nchunks; k += nthreads) {
        Partial& p = parts[k];
        const std::size_t end = std::min(b.size(), (k + 1) * chunk);
        for (std::size_t e = k * chunk; e < end; ++e) {
          const std::uint32_t* n = b.nodes.data() + 4 * e;  // element(e) looked up the type per element
          const auto &A = mesh.nodes[n[0]], &B = mesh.nodes[n[1]], &C = mesh.nodes[n[2]], &D = mesh.nodes[n[3]];
          const double v = tet_signed_volume(A, B, C, D);
          p.vmin = std::min(p.vmin, v);
          p.vmax = std::max(p.vmax, v);
          p.volume += v;
          p.inverted += v <= 0;
          const bool flat = tet_is_degenerate(A, B, C, D);
          if (flat) {
            p.first_degenerate = std::min(p.first_degenerate, e);
            ++p.degenerate;
          }
          // acos is decreasing: the smallest angle is acos of the largest cosine, and an angle is
          // below the bound when its cosine is above the bound's; acos only within rounding of it.
          // A flat one's is 1 (0 deg; min_dihedral_angle_deg).
          const double w = flat ? 1.0 : worst_dihedral_cos(A, B, C, D);
          p.max_cos = std::max(p.max_cos, w);
          if (w > cos_hi) ++p.small;
          else if (w >= cos_lo) p.small += cos_to_deg(w) < small_angle_deg;
        }
      }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < std::min<std::size_t>(nthreads, nchunks); ++t) pool.emplace_back(work, t);
    work(0);
    for (auto& th : pool) th.join();
    for (auto& p : parts) p.min_angle = cos_to_deg(p.max_cos);
    MaterialVolume* mv = nullptr;
    for (auto& m : q.materials)
      if (m.name == name) mv = &m;
    if (!mv) mv = &q.materials.emplace_back(MaterialVolume{name, 0, 0.0});
    mv->tetrahedra += b.size();
    for (const auto& p : parts) {  // in chunk order: the same sums whatever the thread count
      q.min_volume = std::min(q.min_volume, p.vmin);
      q.max_volume = std::max(q.max_volume, p.vmax);
      mv->volume += p.volume;
      q.total_volume += p.volume;
      q.inverted += p.inverted;
      if (p.degenerate > 0 && q.degenerate == 0) q.first_degenerate = first_tet + p.first_degenerate;
      q.degenerate += p.degenerate;
      q.small_angle += p.small;
      q.min_dihedral_deg = std::min(q.min_dihedral_deg, p.min_angle);
    }
  }
  if (q.tetrahedra == 0) q.min_volume = q.max_volume = q.min_dihedral_deg = 0;
  return q;
}

std::string format_quality(const QualityReport& q) {
  std::string s;
  s += fmt::format("nodes {}, tetrahedra {}, triangles {}\n", thousands(q.nodes), thousands(q.tetrahedra),
                   thousands(q.triangles));
  s += fmt::format("tetrahedron volume {:.4g} .. {:.4g} m3, {} inverted\n", q.min_volume, q.max_volume, q.inverted);
  s += fmt::format("smallest dihedral angle {:.2f} deg; {} tetrahedra ({:.2f}%) below {:g} deg\n", q.min_dihedral_deg,
                   thousands(q.small_angle), q.tetrahedra ? 100.0 * q.small_angle / q.tetrahedra : 0.0, q.small_angle_deg);
  for (const auto& m : q.materials)
    s += fmt::format("  {:<28} {:>10} tetrahedra {:>14.6g} m3 ({:.4f} km3)\n", m.name, thousands(m.tetrahedra), m.volume,
                     m.volume * 1e-9);
  s += fmt::format("  {:<28} {:>10} tetrahedra {:>14.6g} m3 ({:.4f} km3)\n", "total", thousands(q.tetrahedra),
                   q.total_volume, q.total_volume * 1e-9);
  for (const auto& g : q.surfaces) s += fmt::format("  {:<28} {:>10} triangles\n", g.name, thousands(g.elements));
  return s;
}

}  // namespace ugs
