// Faulted test meshes: structured box meshes (meshing/box_mesh.hpp) with planar faults along
// mesh faces, inserted by the ugs-faultinsert library. A plane through grid nodes is a union of
// Kuhn-split faces when it is a grid plane (x, y or z = const) or a cell-diagonal plane
// x_loc = y_loc, x_loc = z_loc or y_loc = z_loc of the cells it crosses: with spacings dx and dz,
// the plane through the grid nodes (x_i, z_i) dips atan(dz / dx).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <set>
#include <string>

#include "ugs/formats/mesh.hpp"
#include "ugs/meshing/box_mesh.hpp"
#include "ugs/meshing/fault_cut.hpp"
#include "ugs/meshing/fault_insert.hpp"

namespace ugs::test {

// Adds the faces of tetrahedra lying on the plane (within tol) whose centroid passes `keep` as a
// fault:<name> triangle group. Returns the number of triangles.
inline std::size_t add_planar_fault(Mesh& mesh, const std::string& name, const Point3& point, const Point3& normal,
                                    const std::function<bool(const Point3&)>& keep, double tol) {
  const double ln = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  auto dist = [&](const Point3& p) {
    return ((p[0] - point[0]) * normal[0] + (p[1] - point[1]) * normal[1] + (p[2] - point[2]) * normal[2]) / ln;
  };
  std::set<std::array<std::uint32_t, 3>> faces;
  static const int kFaces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  for (const auto& b : mesh.blocks) {
    if (b.type != ElementType::Tetrahedron) continue;
    for (std::size_t i = 0; i < b.size(); ++i) {
      const auto t = b.element(i);
      for (const auto& f : kFaces) {
        std::array<std::uint32_t, 3> k{t[f[0]], t[f[1]], t[f[2]]};
        bool on = true;
        Point3 c{0, 0, 0};
        for (auto v : k) {
          on = on && std::abs(dist(mesh.nodes[v])) < tol;
          for (int d = 0; d < 3; ++d) c[d] += mesh.nodes[v][d] / 3;
        }
        if (!on || !keep(c)) continue;
        std::sort(k.begin(), k.end());
        faces.insert(k);
      }
    }
  }
  const int e = mesh.entity_for_physical(2, "fault:" + name);
  auto& blk = mesh.block(2, e, ElementType::Triangle);
  for (const auto& k : faces) mesh.add_element(blk, k);
  mesh.update_entity_bboxes();
  return faces.size();
}

// Inserts every fault group (ugs-faultinsert's library call).
inline FaultInsertReport insert_all_faults(Mesh& mesh) {
  FaultInsertOptions o;
  o.source = "test";
  return insert_faults(mesh, o);
}

// Box of lx x ly m in cells of 50 m, nine layers of thickness dz below z = 0: the bed of a planar
// fault through grid nodes dipping atan(dz / 50 m) (see above).
inline Mesh nine_layer_box(double lx, double ly, double dz) {
  BoxMeshSpec spec;
  spec.x = linspace(0, lx, static_cast<int>(std::lround(lx / 50)));
  spec.y = linspace(0, ly, static_cast<int>(std::lround(ly / 50)));
  spec.z = linspace(-9 * dz, 0, 9);
  return make_box_mesh(spec);
}

// Box 1000 x 600 x 1000 m (z from -1000 to 0) of cells of size h with a fault "F" dipping 45
// degrees through the line x = 300, z = -1000, for y in (100, 500) and z in (-800, -300): buried on
// three sides, it reaches the east side (x = 1000) along z = -300.
inline Mesh dipping_fault_box(double h = 50) {
  BoxMeshSpec spec;
  spec.x = linspace(0, 1000, static_cast<int>(std::lround(1000 / h)));
  spec.y = linspace(0, 600, static_cast<int>(std::lround(600 / h)));
  spec.z = linspace(-1000, 0, static_cast<int>(std::lround(1000 / h)));
  Mesh m = make_box_mesh(spec);
  add_planar_fault(
      m, "F", {300, 0, -1000}, {-1, 0, 1}, [](const Point3& c) { return c[1] > 100 && c[1] < 500 && c[2] > -800 && c[2] < -200; },
      1e-6 * h);
  return m;
}

// Plane-strain slab for the crack benchmarks V4 and V5 (VERIFICATION.md): the square
// [-L/2, L/2]^2 one element thick (z in [0, h]), a straight crack "crack" of half-length b through
// the origin at psi from the x axis, split into 2 n_half segments of equal length. Along the crack
// the cells are uniform, hx = b cos(psi) / n_half and hy = hx tan(psi) (psi > 0: the crack is the
// diagonal plane of the cells it crosses; psi = 0: the grid plane y = 0 with hy = hx), for
// n_extra cells beyond the tips, then grow by `ratio` to the sides.
inline Mesh crack_slab_mesh(double psi, double b, int n_half, int n_extra, double L, double ratio) {
  const double hx = b * std::cos(psi) / n_half, hy = psi > 0 ? hx * std::tan(psi) : hx;
  const double X1 = b * std::cos(psi) + n_extra * hx, Y1 = b * std::sin(psi) + n_extra * hy;
  auto axis = [&](double h, double w, int n) {
    std::vector<double> right = graded(w, L / 2, h * ratio, ratio), v;
    for (auto it = right.rbegin(); it != right.rend(); ++it) v.push_back(-*it);
    v.pop_back();
    for (double x : linspace(-w, w, n)) v.push_back(x);
    v.pop_back();
    for (double x : right) v.push_back(x);
    return v;
  };
  BoxMeshSpec spec;
  spec.x = axis(hx, X1, 2 * (n_half + n_extra));
  spec.y = axis(hy, Y1, psi > 0 ? 2 * (n_half + n_extra) : 2 * n_extra);
  spec.z = {0.0, hx};
  Mesh m = make_box_mesh(spec);
  const double c = std::cos(psi), sn = std::sin(psi);
  add_planar_fault(
      m, "crack", {0, 0, 0}, {-sn, c, 0}, [&](const Point3& p) { return std::abs(p[0] * c + p[1] * sn) < b; }, 1e-9 * b);
  insert_all_faults(m);
  return m;
}

// Plane-strain slab in the x-z plane for faults reaching boundaries (test_fault_boundaries): x in
// [0, 600] m (12 cells of 50 m), one 50 m cell in y, z from -16 dz to 0 with dz = 50 tan(60 deg),
// and a fault "F" dipping 60 degrees (the cell-diagonal plane through x = 0, z = -14 dz, normal
// (-dz, 0, dx)). Through: the fault runs from the west side (z = -14 dz) to the east side
// (z = -2 dz); buried: only its part with 100 < x < 500. The group is added on the exact grid, then
// every node moves by x += tilt * y: the faces' normals leave the x-z plane by atan(tilt) (meshgen's
// faces are tilted ~1e-4 degrees by rounding) while every side stays within rounding of its plane.
inline constexpr double kSlabDz = 86.60254037844386;  // 50 tan(60 deg)
// With `crossing`, a vertical fault "G" (the plane x = 300, top to bottom) crosses F at z = -8 dz:
// an X-junction whose pairs all have y prescribed, and G's pairs on the bottom have only x free.
inline Mesh dipping_slab(bool buried, double tilt, bool crossing = false) {
  BoxMeshSpec spec;
  spec.x = linspace(0, 600, 12);
  spec.y = {0.0, 50.0};
  spec.z = linspace(-16 * kSlabDz, 0, 16);
  Mesh m = make_box_mesh(spec);
  add_planar_fault(
      m, "F", {0, 0, -14 * kSlabDz}, {-kSlabDz, 0, 50}, [&](const Point3& c) { return !buried || (c[0] > 100 && c[0] < 500); },
      1e-6);
  if (crossing) add_planar_fault(m, "G", {300, 0, 0}, {1, 0, 0}, [](const Point3&) { return true; }, 1e-6);
  for (auto& p : m.nodes) p[0] += tilt * p[1];
  m.update_entity_bboxes();
  return m;
}

// A 3D block 2000 x 1500 x 1500 m (250 m cells) cut by a planar fault "F" of oblique strike (trace
// from (-300, -200) to (2300, 1700) at z = -200, dipping 60 degrees to the south-east, down to
// -1300 m) with ugs's conforming cut (fault_cut.hpp): it meets the west, south, east and north sides;
// its faces' normals scatter by rounding as meshgen's do.
inline Mesh oblique_fault_block() {
  BoxMeshSpec spec;
  spec.x = linspace(0, 2000, 8);
  spec.y = linspace(0, 1500, 6);
  spec.z = linspace(-1500, 0, 6);
  Mesh m = make_box_mesh(spec);
  FaultTrace t;
  t.name = "F";
  t.where = "test";
  t.parts = {{{-300.0, -200.0}, {2300.0, 1700.0}}};
  t.top = t.trace_z = -200;
  t.bottom = -1300;
  t.dip_deg = 60;
  t.dip_dir_deg = 143.84;  // normal to the trace, to its right (the trace runs at azimuth 53.84 deg)
  check_fault_trace(t);
  cut_faults(m, {t});
  return m;
}

}  // namespace ugs::test
