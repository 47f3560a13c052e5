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
// Face i is the one opposite vertex i, spanned from its first vertex q0 = p[(i+1)%4] by q1 - q0 and
// q2 - q0 (q1 = p[(i+2)%4], q2 = p[(i+3)%4]); its normal is turned away from vertex i (all outward
// or all inward) and made unit. The dihedral angle at an edge is pi minus the angle between the two
// normals. Written out for the four faces (a loop over pointers with indices mod 4 took 400
// instructions per tetrahedron, 13 % of ugs-meshgen's thesis bench in the report alone): the same
// operations in the same order, so the same bits. A flip is kept as a sign, not applied: negation is
// exact and rounding symmetric, so -dot(s_i n_i, s_j n_j) = -(s_i s_j) dot(n_i, n_j) bit for bit.
double worst_dihedral_cos(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  struct Normal {
    double x, y, z;
    bool flip;
  };
  // cross(q1 - q0, q2 - q0), turned away from r (flip when it points towards r), unit.
  auto face = [](const Point3& q0, const Point3& q1, const Point3& q2, const Point3& r, Normal& n) {
    const double ux = q1[0] - q0[0], uy = q1[1] - q0[1], uz = q1[2] - q0[2];
    const double vx = q2[0] - q0[0], vy = q2[1] - q0[1], vz = q2[2] - q0[2];
    const double x = uy * vz - uz * vy, y = uz * vx - ux * vz, z = ux * vy - uy * vx;
    const double rx = r[0] - q0[0], ry = r[1] - q0[1], rz = r[2] - q0[2];
    n.flip = x * rx + y * ry + z * rz > 0;
    const double len = std::sqrt(x * x + y * y + z * z);
    n.x = x / len;
    n.y = y / len;
    n.z = z / len;
    return len > 0;
  };
  Normal n[4];
  const bool ok0 = face(b, c, d, a, n[0]), ok1 = face(c, d, a, b, n[1]);
  const bool ok2 = face(d, a, b, c, n[2]), ok3 = face(a, b, c, d, n[3]);
  if (!(ok0 && ok1 && ok2 && ok3)) return 1.0;
  auto minus_dot = [&](int i, int j) {
    const double p = n[i].x * n[j].x + n[i].y * n[j].y + n[i].z * n[j].z;
    return n[i].flip == n[j].flip ? -p : p;
  };
  double worst = -1;
  worst = std::max(worst, minus_dot(0, 1));
  worst = std::max(worst, minus_dot(0, 2));
  worst = std::max(worst, minus_dot(0, 3));
  worst = std::max(worst, minus_dot(1, 2));
  worst = std::max(worst, minus_dot(1, 3));
  worst = std::max(worst, minus_dot(2, 3));
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
          const std::uint32_t* n = b.nodes.data() + 4 * e;  // element(e) looked up the type per element
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
