#include "ugs/meshing/mesh_quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#include <fmt/format.h>

#include "ugs/meshing/surface_stack.hpp"

namespace ugs {

namespace {

using V3 = std::array<double, 3>;
V3 sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross(const V3& u, const V3& v) { return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]}; }
double dot(const V3& u, const V3& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }

struct Partial {
  double vmin = std::numeric_limits<double>::infinity(), vmax = -std::numeric_limits<double>::infinity();
  double volume = 0, min_angle = 180;
  std::size_t inverted = 0, small = 0;
  double max_cos = -1;  // the smallest angle's cosine; acos once per chunk, not per tetrahedron
};

// The cosine of the smallest dihedral angle (clamped to [-1, 1]); 1 for a flat or degenerate tetrahedron.
double worst_dihedral_cos(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const Point3* p[4] = {&a, &b, &c, &d};
  // Normal of the face opposite each vertex, pointing away from that vertex (all outward or all inward).
  V3 n[4];
  for (int i = 0; i < 4; ++i) {
    const Point3& q0 = *p[(i + 1) % 4];
    const Point3& q1 = *p[(i + 2) % 4];
    const Point3& q2 = *p[(i + 3) % 4];
    n[i] = cross(sub(q1, q0), sub(q2, q0));
    if (dot(n[i], sub(*p[i], q0)) > 0) n[i] = {-n[i][0], -n[i][1], -n[i][2]};
    const double len = std::sqrt(dot(n[i], n[i]));
    if (!(len > 0)) return 1.0;
    for (auto& x : n[i]) x /= len;
  }
  double worst = -1;  // the dihedral angle is pi minus the angle between two outward normals
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) worst = std::max(worst, -dot(n[i], n[j]));
  return std::clamp(worst, -1.0, 1.0);
}

double cos_to_deg(double c) { return std::acos(c) * 180.0 / M_PI; }

}  // namespace

double min_dihedral_angle_deg(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return cos_to_deg(worst_dihedral_cos(a, b, c, d));
}

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
          const auto n = b.element(e);
          const auto &A = mesh.nodes[n[0]], &B = mesh.nodes[n[1]], &C = mesh.nodes[n[2]], &D = mesh.nodes[n[3]];
          const double v = tet_signed_volume(A, B, C, D);
          p.vmin = std::min(p.vmin, v);
          p.vmax = std::max(p.vmax, v);
          p.volume += v;
          p.inverted += v <= 0;
          // acos is decreasing: the smallest angle is acos of the largest cosine, and an angle is
          // below the bound when its cosine is above the bound's; acos only within rounding of it.
          const double w = worst_dihedral_cos(A, B, C, D);
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
