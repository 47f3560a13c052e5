// Faults as surfaces (issue 40, items 3, 4 and 6; docs/faults.md, "Faults as surfaces"): GOCAD
// TSurf and fault sticks cut into a tetrahedral block exactly. Against known geometry: a planar
// TSurf against the dip-and-trace definition of the same plane; a cylindrical (listric) and a
// conical surface, whose triangles' normals have closed forms; a branch ending on another fault
// (the Y junction, its junction line known) and dying out inside the model (its tip lines). Every
// fault node lies on its triangle's plane, every face's normal is its triangle's, the group's area
// is the surface's area inside the model (triangles clipped by the box, independently of the cut).
// Bad input: non-manifold, self-intersecting or inconsistently oriented TSurfs, sticks that cross,
// a surface outside the model: InputError naming file and line.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <set>

#include <fmt/format.h>
#include <unistd.h>

#include "polygon_clip.hpp"
#include "meshing_checks.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/meshing/box_mesh.hpp"
#include "ugs/meshing/fault_cut.hpp"
#include "ugs/meshing/fault_insert.hpp"
#include "ugs/meshing/fault_surface_input.hpp"
#include "ugs/meshing/mesh_quality.hpp"

namespace ugs::test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double deg = kPi / 180;
// The block of test_dipping_faults: 4 x 3 km, 3 km deep, 250 m cells, a layer boundary at -1,500 m.
constexpr double X1 = 4000, Y1 = 3000, Z0 = -3000;

Mesh block() {
  BoxMeshSpec s;
  s.x = linspace(0, X1, 16);
  s.y = linspace(0, Y1, 12);
  s.z = linspace(Z0, 0, 12);
  s.material = [](const Point3& c) { return c[2] > -1500 ? std::string("upper") : std::string("lower"); };
  return make_box_mesh(s);
}

Point3 sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Point3& a) { return std::sqrt(dot(a, a)); }
Point3 unit(const Point3& a) {
  const double l = norm(a);
  return {a[0] / l, a[1] / l, a[2] / l};
}

// The angle between two lines (degrees), from the cross and dot products: acos near 1 would
// floor at 1e-6 degree (sqrt of the rounding), atan2 resolves 1e-14.
double angle_deg(const Point3& a, const Point3& b) {
  return std::atan2(norm(cross(a, b)), std::abs(dot(a, b))) / deg;
}

// A surface of rows x cols vertices (grid(i, j)), each quad split into two triangles.
TriangulatedSurface grid_surface(std::size_t rows, std::size_t cols, const std::function<Point3(std::size_t, std::size_t)>& at) {
  TriangulatedSurface s;
  s.path = "test.ts";
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t j = 0; j < cols; ++j) {
      s.vertices.push_back(at(i, j));
      s.vertex_line.push_back(s.vertices.size());
    }
  auto id = [&](std::size_t i, std::size_t j) { return static_cast<std::uint32_t>(i * cols + j); };
  for (std::size_t i = 0; i + 1 < rows; ++i)
    for (std::size_t j = 0; j + 1 < cols; ++j) {
      s.triangles.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
      s.triangle_line.push_back(1000 + s.triangles.size() - 1);
      s.triangle_line.push_back(1000 + s.triangles.size());
    }
  s.objects = s.faces = 1;
  return s;
}

FaultTrace surface_fault(const std::string& name, TriangulatedSurface s) {
  check_fault_surface(s);
  auto in = std::make_shared<FaultSurfaceInput>();
  in->mesh = std::move(s);
  in->format = "GOCAD TSurf";
  FaultTrace t;
  t.name = name;
  t.where = "test";
  t.top = -1e300;
  t.bottom = 1e300;
  for (const auto& p : in->mesh.vertices) t.top = std::max(t.top, p[2]), t.bottom = std::min(t.bottom, p[2]);
  t.trace_z = t.top;
  t.parts = {{{0, 0}, {1, 1}}};
  t.surface = std::move(in);
  check_fault_trace(t);
  return t;
}

// The surface's area inside the box: each triangle clipped by the box's six planes.
double area_inside(const TriangulatedSurface& s) {
  double total = 0;
  for (const auto& t : s.triangles) {
    std::vector<Point3> q{s.vertices[t[0]], s.vertices[t[1]], s.vertices[t[2]]};
    q = clip_to_box(q, X1, Y1, Z0);
    if (q.size() >= 3) total += polygon_area(q);
  }
  return total;
}

// Is x in triangle t of s (its plane within `tol`, and inside its edges by `tol`)?
double outside_triangle(const TriangulatedSurface& s, std::size_t t, const Point3& x) {
  const auto& tri = s.triangles[t];
  const Point3 n = unit(cross(sub(s.vertices[tri[1]], s.vertices[tri[0]]), sub(s.vertices[tri[2]], s.vertices[tri[0]])));
  double out = 0;
  for (int k = 0; k < 3; ++k) {
    const Point3 &a = s.vertices[tri[k]], &b = s.vertices[tri[(k + 1) % 3]];
    const Point3 o = unit(cross(sub(b, a), n));  // outward for counter-clockwise corners about n
    out = std::max(out, dot(o, sub(x, a)));
  }
  return out;
}

struct FaceCheck {
  std::size_t faces = 0;
  double area = 0, max_distance = 0, max_angle_deg = 0;  // of nodes from, and normals to, the triangle holding the face
  std::vector<std::size_t> triangle;                      // per face: the surface triangle holding it
};

// Every face of fault:<name> against the surface triangle holding its centroid (the nearest one
// whose edges hold it): its nodes' distance to the triangle's plane, its normal's angle to the
// triangle's normal (either sign: the orientation is checked separately).
FaceCheck check_faces(const Mesh& m, const std::string& name, const TriangulatedSurface& s) {
  FaceCheck c;
  const ElementBlock* b = triangle_group(m, "fault:" + name);
  if (!b) return c;
  for (std::size_t i = 0; i < b->size(); ++i) {
    const auto e = b->element(i);
    const Point3 &p = m.nodes[e[0]], &q = m.nodes[e[1]], &r = m.nodes[e[2]];
    const Point3 cen{(p[0] + q[0] + r[0]) / 3, (p[1] + q[1] + r[1]) / 3, (p[2] + q[2] + r[2]) / 3};
    const Point3 n = cross(sub(q, p), sub(r, p));
    double best = 1e300, ang = 0;
    std::size_t which = 0;
    for (std::size_t t = 0; t < s.triangles.size(); ++t) {
      if (outside_triangle(s, t, cen) > 1e-3) continue;
      const auto& tri = s.triangles[t];
      const Point3 tn = unit(cross(sub(s.vertices[tri[1]], s.vertices[tri[0]]), sub(s.vertices[tri[2]], s.vertices[tri[0]])));
      double d = 0;
      for (const Point3* x : {&p, &q, &r}) d = std::max(d, std::abs(dot(tn, sub(*x, s.vertices[tri[0]]))));
      if (d < best) {
        best = d;
        which = t;
        ang = angle_deg(n, tn);
      }
    }
    ++c.faces;
    c.area += 0.5 * norm(n);
    c.max_distance = std::max(c.max_distance, best);
    c.max_angle_deg = std::max(c.max_angle_deg, ang);
    c.triangle.push_back(which);
  }
  return c;
}

void expect_sound(const Mesh& m) {
  const Conformity c = check_conformity(m);
  EXPECT_EQ(c.over_shared, 0u);
  EXPECT_EQ(c.untagged_outer, 0u);
  EXPECT_EQ(c.tagged_not_outer, 0u);
  EXPECT_EQ(c.fault_not_face, 0u);
  EXPECT_EQ(c.nonpositive, 0u);
  EXPECT_EQ(c.repeated_nodes, 0u);
  const double volume = X1 * Y1 * -Z0;
  EXPECT_NEAR(c.volume, volume, 1e-9 * volume);
}

// The checks every surface fault passes; returns the face check for more.
FaceCheck expect_exact(const Mesh& m, const FaultTrace& f, const FaultCutSummary& sum, std::size_t k) {
  const FaceCheck c = check_faces(m, f.name, f.surface->mesh);
  const double area = area_inside(f.surface->mesh);
  EXPECT_GT(c.faces, 0u) << f.name;
  EXPECT_LE(c.max_distance, 1e-6) << f.name;      // every fault node on its triangle within 1e-6 m
  EXPECT_LE(c.max_angle_deg, 1e-6) << f.name;     // every face's normal its triangle's within 1e-6 degree
  EXPECT_NEAR(c.area, area, 1e-3 * area) << f.name;  // the faces tile the surface's part inside the model
  EXPECT_NEAR(sum.faults[k].area, c.area, 1e-9 * area) << f.name;
  std::printf("%s: %zu triangles -> %zu panels, %zu faces, area %.6f of %.6f m2 (%.2e), nodes off their triangle <= %.2e m, "
              "normals <= %.2e deg; band: %zu tetrahedra, smallest dihedral angle %.3f deg (%zu below the reference)\n",
              f.name.c_str(), f.surface->mesh.triangles.size(), sum.faults[k].panels, c.faces, c.area, area,
              std::abs(c.area - area) / area, c.max_distance, c.max_angle_deg, sum.band_tetrahedra,
              sum.band_min_dihedral_deg, sum.band_below_reference);
  return c;
}

// ---- the planar case ----------------------------------------------------------------------------

FaultTrace dip_trace() {
  FaultTrace t;
  t.name = "f";
  t.where = "test";
  t.parts = {{{600, 400}, {1900, 1500}, {2900, 2650}}};
  t.top = t.trace_z = -200;
  t.bottom = -2600;
  t.dip_deg = 45;
  t.dip_dir_deg = 300;
  check_fault_trace(t);
  return t;
}

// The trace's panels as a TSurf: each segment's quad between top and bottom, two triangles.
TriangulatedSurface trace_as_tsurf(const FaultTrace& t) {
  const double az = t.dip_dir_deg * deg, dx = std::sin(az), dy = std::cos(az);
  const auto& line = t.parts[0];
  return grid_surface(2, line.size(), [&](std::size_t i, std::size_t j) {
    const double z = i == 0 ? t.top : t.bottom, o = t.offset_at(z);
    return Point3{line[j][0] + o * dx, line[j][1] + o * dy, z};
  });
}

TEST(SurfaceFaults, PlanarTSurfGivesTheDipAndTraceMesh) {
  const FaultTrace tr = dip_trace();
  Mesh a = block();
  const auto sa = cut_faults(a, {tr});
  FaultTrace ts = surface_fault("f", trace_as_tsurf(tr));
  Mesh b = block();
  const auto sb = cut_faults(b, {ts});
  EXPECT_EQ(sb.faults[0].panels, 2u);  // each segment's two coplanar triangles are one panel
  expect_sound(b);
  expect_exact(b, ts, sb, 0);
  // The same mesh: node count, and each node of one at a node of the other.
  std::printf("planar: dip and trace %zu nodes, %zu tetrahedra; TSurf %zu nodes, %zu tetrahedra\n", a.nodes.size(),
              sa.tetrahedra_after, b.nodes.size(), sb.tetrahedra_after);
  EXPECT_NEAR(static_cast<double>(a.nodes.size()), static_cast<double>(b.nodes.size()), 0.01 * a.nodes.size());
  // Each node of the TSurf's mesh against the nearest node of the trace's.
  double worst = 0;
  std::size_t matched = 0;
  for (const auto& x : b.nodes) {
    double best = 1e300;
    for (const auto& y : a.nodes) best = std::min(best, norm(sub(x, y)));
    worst = std::max(worst, best);
    matched += best <= 1e-9;
  }
  std::printf("planar: %zu of %zu nodes at a node of the trace's mesh within 1e-9 m, the others up to %.3f m; fault faces "
              "%zu and %zu, areas %.6f and %.6f m2\n",
              matched, b.nodes.size(), worst, sa.faults[0].triangles, sb.faults[0].triangles, sa.faults[0].area,
              sb.faults[0].area);
  // The documented difference (docs/faults.md, "Faults as surfaces"): the panels are the same
  // polygons, but their bounds are other planes through the same lines (the trace's are vertical
  // or horizontal, the surface's lie across the surface) and are cut in another order, so a few
  // snaps and bisections near the panels' edges differ. Both tile the same area exactly.
  EXPECT_GE(matched, b.nodes.size() * 95 / 100);
  EXPECT_NEAR(sb.faults[0].area, sa.faults[0].area, 1e-9 * sa.faults[0].area);
}

// ---- curved surfaces ----------------------------------------------------------------------------

// Listric: a cylinder about the horizontal axis x = 3000, z = 0 (along y), radius 2,800 m, from
// vertical at the top (phi = 0) to 20 degrees at phi = 70 degrees; begun at phi = -5 degrees above
// the model and run past both ends in y. Its triangles' normals: the chord plane of the strip
// [phi_i, phi_i+1] has the cylinder's normal at the mid-angle, (cos phi_m, 0, sin phi_m) up to sign.
constexpr double kR = 2800, kXc = 3000;
constexpr std::size_t kRows = 13, kCols = 7;
double phi_of(std::size_t i) { return (-5.0 + 75.0 * static_cast<double>(i) / (kRows - 1)) * deg; }

TriangulatedSurface cylinder() {
  return grid_surface(kRows, kCols, [](std::size_t i, std::size_t j) {
    const double phi = phi_of(i), y = -300 + 3600.0 * static_cast<double>(j) / (kCols - 1);
    return Point3{kXc - kR * std::cos(phi), y, -kR * std::sin(phi)};
  });
}

TEST(SurfaceFaults, ListricCylinder) {
  FaultTrace f = surface_fault("listric", cylinder());
  Mesh m = block();
  const auto t0 = std::chrono::steady_clock::now();
  const auto sum = cut_faults(m, {f});
  std::printf("listric cut: %.2f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  expect_sound(m);
  const FaceCheck c = expect_exact(m, f, sum, 0);
  // Closed form: each face's normal is the cylinder's at its strip's mid-angle.
  const ElementBlock* b = triangle_group(m, "fault:listric");
  ASSERT_NE(b, nullptr);
  double worst = 0;
  for (std::size_t i = 0; i < b->size(); ++i) {
    const auto e = b->element(i);
    const Point3 n = unit(cross(sub(m.nodes[e[1]], m.nodes[e[0]]), sub(m.nodes[e[2]], m.nodes[e[0]])));
    const double phim = 0.5 * (phi_of(c.triangle[i] / (2 * (kCols - 1))) + phi_of(c.triangle[i] / (2 * (kCols - 1)) + 1));
    const Point3 exact{std::cos(phim), 0, std::sin(phim)};
    worst = std::max(worst, angle_deg(n, exact));
    // One orientation, the surface's: its mean normal points down, so every face's is -exact.
    EXPECT_LT(dot(n, exact), 0);
  }
  std::printf("listric: face normals against the closed form: %.3e deg at most\n", worst);
  EXPECT_LE(worst, 1e-6);
  EXPECT_GE(sum.band_min_dihedral_deg, 0.1 * 2.0);
  FaultInsertOptions io;
  const auto rep = insert_faults(m, io);
  ASSERT_EQ(rep.faults.size(), 1u);
  EXPECT_EQ(rep.faults[0].triangles, sum.faults[0].triangles);
  EXPECT_GT(rep.faults[0].duplicated_nodes, 0u);
}

// A cone about the vertical axis through (2000, 1500), apex at z = 500, half-angle 30 degrees
// (a fault dipping 60 degrees outward, around a salt dome), theta from 20 to 200 degrees. The chord
// plane of the generators theta_m -/+ delta has the normal (cos a cos theta_m, cos a sin theta_m,
// sin a cos delta) up to sign and length (a = the half-angle).
constexpr double kAlpha = 30 * deg, kApex = 500;
constexpr std::size_t kRings = 7, kSectors = 13;
double theta_of(std::size_t j) { return (20.0 + 180.0 * static_cast<double>(j) / (kSectors - 1)) * deg; }

TriangulatedSurface cone() {
  return grid_surface(kRings, kSectors, [](std::size_t i, std::size_t j) {
    const double z = 100 - 3000.0 * static_cast<double>(i) / (kRings - 1), r = (kApex - z) * std::tan(kAlpha);
    return Point3{2000 + r * std::cos(theta_of(j)), 1500 + r * std::sin(theta_of(j)), z};
  });
}

TEST(SurfaceFaults, Cone) {
  FaultTrace f = surface_fault("cone", cone());
  Mesh m = block();
  const auto sum = cut_faults(m, {f});
  expect_sound(m);
  const FaceCheck c = expect_exact(m, f, sum, 0);
  const ElementBlock* b = triangle_group(m, "fault:cone");
  ASSERT_NE(b, nullptr);
  double worst = 0;
  const double delta = 0.5 * (theta_of(1) - theta_of(0));
  for (std::size_t i = 0; i < b->size(); ++i) {
    const auto e = b->element(i);
    const Point3 n = unit(cross(sub(m.nodes[e[1]], m.nodes[e[0]]), sub(m.nodes[e[2]], m.nodes[e[0]])));
    const std::size_t j = (c.triangle[i] / 2) % (kSectors - 1);
    const double thm = 0.5 * (theta_of(j) + theta_of(j + 1));
    const Point3 exact = unit({std::cos(kAlpha) * std::cos(thm), std::cos(kAlpha) * std::sin(thm), std::sin(kAlpha) * std::cos(delta)});
    worst = std::max(worst, angle_deg(n, exact));
  }
  std::printf("cone: face normals against the closed form: %.3e deg at most\n", worst);
  EXPECT_LE(worst, 1e-6);
  FaultInsertOptions io;
  const auto rep = insert_faults(m, io);
  ASSERT_EQ(rep.faults.size(), 1u);
  EXPECT_GT(rep.faults[0].duplicated_nodes, 0u);
}

// A surface that curves in both directions (a listric fault whose trace curves in plan):
// x = 1000 + 0.25 (-z) + 1.2e-4 z^2 + 1.5e-4 (y - 1500)^2 - 1e-4 (y - 1500) z, dipping about 45 to
// 80 degrees, sampled every 400 m down and 425 m along strike past the model. The twist term makes
// every quad of the grid non-planar: each triangle is a panel of its own.
TEST(SurfaceFaults, CurvedInBothDirections) {
  FaultTrace f = surface_fault("bowl", grid_surface(9, 9, [](std::size_t i, std::size_t j) {
                                 const double z = 100 - 400.0 * static_cast<double>(i);
                                 const double y = -200 + 425.0 * static_cast<double>(j);
                                 return Point3{1000 + 0.25 * -z + 1.2e-4 * z * z + 1.5e-4 * (y - 1500) * (y - 1500) - 1e-4 * (y - 1500) * z, y, z};
                               }));
  Mesh m = block();
  const auto t0 = std::chrono::steady_clock::now();
  const auto sum = cut_faults(m, {f});
  std::printf("doubly curved cut: %.2f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  EXPECT_EQ(sum.faults[0].panels, 128u);
  expect_sound(m);
  expect_exact(m, f, sum, 0);
  // 128 panels meeting at angles of a few degrees, each cutting 250 m cells at its own angle: the
  // cut's slivers are worse than a planar fault's (docs/faults.md, "Faults as surfaces"): measured
  // 1 tetrahedron of 22,047 below a tenth of the 2-degree bound (0.109 deg), 316 below the bound.
  EXPECT_GT(sum.band_min_dihedral_deg, 0.1);
  EXPECT_LE(sum.band_below_bound * 1000, sum.band_tetrahedra);
  FaultInsertOptions io;
  const auto rep = insert_faults(m, io);
  ASSERT_EQ(rep.faults.size(), 1u);
  EXPECT_EQ(rep.faults[0].triangles, sum.faults[0].triangles);
}

// ---- a branch ending on another fault, dying out inside the model ---------------------------------

// The main fault: the plane x = 1500 + (-z) / tan 60 (dipping 60 degrees east), over the whole
// box. The branch: the vertical plane y = 1500, from the main fault east to x = 3600, between
// -400 and -2400 m: it ends on the main fault along the junction line y = 1500, x = 1500 - z / tan 60,
// and dies out inside the model along its three other edges (tip lines).
double main_x(double z) { return 1500 - z / std::tan(60 * deg); }

TEST(SurfaceFaults, BranchEndingOnAnotherAndDyingOut) {
  FaultTrace main = surface_fault("main", grid_surface(2, 2, [](std::size_t i, std::size_t j) {
                                    const double z = i == 0 ? 200 : -3200;
                                    return Point3{main_x(z), j == 0 ? -200.0 : 3200.0, z};
                                  }));
  FaultTrace branch = surface_fault("branch", grid_surface(2, 2, [](std::size_t i, std::size_t j) {
                                      const double z = i == 0 ? -400 : -2400;
                                      return Point3{j == 0 ? main_x(z) : 3600.0, 1500, z};
                                    }));
  Mesh m = block();
  const auto sum = cut_faults(m, {main, branch});
  expect_sound(m);
  expect_exact(m, main, sum, 0);
  expect_exact(m, branch, sum, 1);
  // The junction: nodes of both faults lie on the junction line, and the edges of branch faces
  // along it run its whole length (2,000 m / sin 60).
  std::set<std::uint32_t> nm(triangle_group(m, "fault:main")->nodes.begin(), triangle_group(m, "fault:main")->nodes.end());
  double worst = 0, zlo = 0, zhi = -1e300;
  zlo = 1e300;
  std::size_t shared = 0;
  for (auto v : triangle_group(m, "fault:branch")->nodes)
    if (nm.count(v)) {
      ++shared;
      const Point3& x = m.nodes[v];
      worst = std::max({worst, std::abs(x[1] - 1500), std::abs(x[0] - main_x(x[2]))});
      zlo = std::min(zlo, x[2]);
      zhi = std::max(zhi, x[2]);
    }
  std::printf("junction: %zu nodes shared, off the junction line by %.2e m at most, z from %.3f to %.3f\n", shared, worst, zlo, zhi);
  EXPECT_GT(shared, 5u);
  EXPECT_LE(worst, 1e-6);
  EXPECT_NEAR(zhi, -400, 1e-6);
  EXPECT_NEAR(zlo, -2400, 1e-6);
  // Every branch node lies on the hanging-wall side of the main fault (x >= main_x(z)).
  for (auto v : triangle_group(m, "fault:branch")->nodes) EXPECT_GE(m.nodes[v][0] - main_x(m.nodes[v][2]), -1e-6);
  FaultInsertOptions io;
  const auto rep = insert_faults(m, io);
  ASSERT_EQ(rep.faults.size(), 2u);
  std::size_t meets = 0;
  for (const auto& f : rep.faults) meets += f.meets.size();
  EXPECT_GT(meets, 0u);
}

// ---- fault sticks ------------------------------------------------------------------------------

// The files the tests write, in one folder removed when the program ends.
std::filesystem::path scratch(const std::string& name) {
  struct Folder {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / ("ugs_surface_faults_" + std::to_string(::getpid()));
    ~Folder() {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  };
  static const Folder folder;
  std::filesystem::create_directories(folder.dir);
  return folder.dir / name;
}

void write(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SurfaceFaults, SticksMakeTheCylinder) {
  // The cylinder's rows as sticks (one per y, down the fault), the middle one given upward.
  std::string text = "# listric fault, sticks from west to east\n";
  for (std::size_t j = 0; j < kCols; ++j) {
    const double y = -300 + 3600.0 * static_cast<double>(j) / (kCols - 1);
    for (std::size_t k = 0; k < kRows; ++k) {
      const std::size_t i = j == 3 ? kRows - 1 - k : k;
      text += fmt::format("{:.9f} {:.9f} {:.9f}\n", kXc - kR * std::cos(phi_of(i)), y, -kR * std::sin(phi_of(i)));
    }
    text += "999.000000 999.000000 999.000000\n";
  }
  const auto path = scratch("listric.sticks");
  write(path, text);
  const FaultSurfaceInput s = read_fault_surface(path.string());
  EXPECT_EQ(s.format, "fault sticks");
  EXPECT_EQ(s.mesh.vertices.size(), kRows * kCols);
  EXPECT_EQ(s.mesh.triangles.size(), 2 * (kRows - 1) * (kCols - 1));
  EXPECT_TRUE(s.cleaned.empty());
  EXPECT_NEAR(area_inside(s.mesh), area_inside(cylinder()), 1e-9 * area_inside(cylinder()));
  // Crossing sticks: the third one swapped with the fifth.
  std::string crossed;
  std::size_t stick = 0;
  std::vector<std::string> sticks(1);
  for (std::size_t i = 0, b = 0; i < text.size(); ++i)
    if (text[i] == '\n') {
      sticks.back() += text.substr(b, i + 1 - b);
      if (text.compare(b, 3, "999") == 0) sticks.emplace_back();
      b = i + 1;
    }
  std::swap(sticks[3], sticks[5]);
  for (const auto& s2 : sticks) crossed += s2;
  (void)stick;
  write(path, crossed);
  const std::string e = error_of([&] { read_fault_surface(path.string()); });
  EXPECT_NE(e.find("listric.sticks:"), std::string::npos) << e;
  EXPECT_NE(e.find("crosses the stick of line"), std::string::npos) << e;
}

// ---- cost ---------------------------------------------------------------------------------------

// What a surface's cut costs against today's planar faults, on finer blocks (run by hand:
// --gtest_also_run_disabled_tests --gtest_filter=*Cost*; docs/faults.md gives the numbers).
TEST(SurfaceFaults, DISABLED_CostAgainstPlanarFaults) {
  for (int n : {16, 32, 48}) {
    BoxMeshSpec spec;
    spec.x = linspace(0, X1, n);
    spec.y = linspace(0, Y1, n * 3 / 4);
    spec.z = linspace(Z0, 0, n * 3 / 4);
    spec.material = [](const Point3& c) { return c[2] > -1500 ? std::string("upper") : std::string("lower"); };
    const Mesh base = make_box_mesh(spec);
    const FaultTrace tr = dip_trace();
    const std::vector<std::pair<std::string, FaultTrace>> cases{
        {"dip and trace (2 panels)", tr},
        {"planar TSurf (4 triangles)", surface_fault("f", trace_as_tsurf(tr))},
        {"listric cylinder (144 triangles)", surface_fault("listric", cylinder())},
        {"doubly curved (128 triangles)", surface_fault("bowl", grid_surface(9, 9, [](std::size_t i, std::size_t j) {
                                                           const double z = 100 - 400.0 * static_cast<double>(i);
                                                           const double y = -200 + 425.0 * static_cast<double>(j);
                                                           return Point3{1000 + 0.25 * -z + 1.2e-4 * z * z +
                                                                             1.5e-4 * (y - 1500) * (y - 1500) - 1e-4 * (y - 1500) * z,
                                                                         y, z};
                                                         }))}};
    for (const auto& [what, f] : cases) {
      Mesh m = base;
      const auto t0 = std::chrono::steady_clock::now();
      const auto sum = cut_faults(m, {f});
      const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::printf("cost: %zu tetrahedra, %-34s %zu panels: %.3f s, %zu -> %zu tetrahedra, smallest dihedral %.3f deg, "
                  "%zu of %zu below the reference, %zu below the bound\n",
                  sum.tetrahedra_before, what.c_str(), sum.faults[0].panels, sec, sum.tetrahedra_before, sum.tetrahedra_after,
                  sum.band_min_dihedral_deg, sum.band_below_reference, sum.band_tetrahedra, sum.band_below_bound);
    }
  }
}

// ---- bad input ---------------------------------------------------------------------------------

std::string tsurf(const std::vector<Point3>& v, const std::vector<std::array<int, 3>>& t) {
  std::string s = "GOCAD TSurf 1\nHEADER {\nname: f\n}\nPROPERTIES throw\nTFACE\n";  // line 6 is TFACE
  for (std::size_t i = 0; i < v.size(); ++i) s += fmt::format("PVRTX {} {} {} {} 7.5\n", i + 1, v[i][0], v[i][1], v[i][2]);
  for (const auto& tri : t) s += fmt::format("TRGL {} {} {}\n", tri[0], tri[1], tri[2]);
  return s + "END\n";
}

TEST(SurfaceFaults, BadSurfacesNameFileAndLine) {
  const std::vector<Point3> sq{{0, 0, 0}, {100, 0, 0}, {100, 0, -100}, {0, 0, -100}, {50, 50, -50}, {50, -50, -50}};
  const auto path = scratch("bad.ts");
  auto err = [&](const std::vector<Point3>& v, const std::vector<std::array<int, 3>>& t) {
    write(path, tsurf(v, t));
    return error_of([&] { read_fault_surface(path.string()); });
  };
  // Vertices on lines 7.. (6 of them: 7-12), triangles from line 13.
  EXPECT_NE(err(sq, {{1, 2, 3}, {1, 3, 4}, {1, 3, 5}}).find("bad.ts:15: non-manifold edge"), std::string::npos);
  EXPECT_NE(err(sq, {{1, 2, 3}, {1, 4, 3}}).find("bad.ts:14: inconsistent orientation"), std::string::npos);
  // Two sheets crossing: the square and a triangle through it.
  const std::vector<Point3> x{{0, 0, 0}, {100, 0, 0}, {100, 0, -100}, {0, 0, -100}, {50, 50, -20}, {50, -50, -20}, {50, 0, -90}};
  EXPECT_NE(err(x, {{1, 2, 3}, {1, 3, 4}, {5, 6, 7}}).find("self-intersection"), std::string::npos) << err(x, {{1, 2, 3}, {1, 3, 4}, {5, 6, 7}});
  // Duplicate vertices are merged, and said.
  std::string two = tsurf(sq, {{1, 2, 3}, {1, 3, 4}});
  two.insert(two.find("TRGL"), "VRTX 7 100 0 -100\n");
  two.replace(two.find("TRGL 1 3 4"), 10, "TRGL 1 7 4");
  write(path, two);
  const FaultSurfaceInput ok = read_fault_surface(path.string());
  ASSERT_EQ(ok.cleaned.size(), 1u);
  EXPECT_NE(ok.cleaned[0].find("1 vertices at the same x, y, z"), std::string::npos) << ok.cleaned[0];
  // Sticks files: a stick of one point, a line of four values, a last stick without its 999 line.
  const auto sticks = scratch("bad.sticks");
  auto sticks_err = [&](const std::string& text) {
    write(sticks, text);
    return error_of([&] { read_fault_surface(sticks.string()); });
  };
  const std::string sep = "999 999 999\n";
  EXPECT_NE(sticks_err("0 0 0\n0 0 -100\n" + sep + "100 0 0\n" + sep).find("bad.sticks:4: a stick of one point"),
            std::string::npos);
  EXPECT_NE(sticks_err("0 0 0\n0 0 -100 5\n" + sep).find("bad.sticks:2: 4 values"), std::string::npos);
  EXPECT_NE(sticks_err("0 0 0\n0 0 -100\n" + sep + "100 0 0\n100 0 -100\n").find("bad.sticks:4: the last stick has no 999"),
            std::string::npos);
  // A surface entirely outside the model.
  FaultTrace far = surface_fault("far", grid_surface(2, 2, [](std::size_t i, std::size_t j) {
                                   return Point3{9000.0 + 500 * j, 500, i == 0 ? -100.0 : -1000.0};
                                 }));
  Mesh m = block();
  EXPECT_NE(error_of([&] { cut_faults(m, {far}); }).find("fault 'far': its surface does not cross the mesh"), std::string::npos);
}

}  // namespace
}  // namespace ugs::test
