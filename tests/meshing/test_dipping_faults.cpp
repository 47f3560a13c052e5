// Dipping faults made of tetrahedron faces (issue 6, fault_cut.hpp): planar faults of dips 20-90
// degrees, a listric fault, two crossing faults and one ending against another, cut into a
// tetrahedral block. Each fault face lies on its plane within 1e-6 of the model size, its normal
// within 0.5 degree, the faces cover the fault's area inside the model (computed independently by
// clipping the fault polygon with the box), the mesh stays conforming with positive volumes, and
// ugs-faultinsert's library turns the faults into interface elements.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

#include "polygon_clip.hpp"
#include "meshing_checks.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/meshing/box_mesh.hpp"
#include "ugs/meshing/fault_cut.hpp"
#include "ugs/meshing/fault_insert.hpp"
#include "ugs/meshing/mesh_quality.hpp"

namespace ugs::test {
namespace {

constexpr double kPi = std::numbers::pi;
// The block: 4 x 3 km, 3 km deep, 250 m cells (Kuhn split), two materials (a layer boundary at -1,500 m).
constexpr double X1 = 4000, Y1 = 3000, Z0 = -3000;
constexpr double kSize = 5830.95;  // diagonal
// The smallest dihedral angle of the tetrahedra the cut makes (docs/dipping-faults.md, "Mesh
// quality": why 2 degrees).
constexpr double kBoundDeg = 2.0;

Mesh block() {
  BoxMeshSpec s;
  s.x = linspace(0, X1, 16);
  s.y = linspace(0, Y1, 12);
  s.z = linspace(Z0, 0, 12);
  s.material = [](const Point3& c) { return c[2] > -1500 ? std::string("upper") : std::string("lower"); };
  return make_box_mesh(s);
}

FaultTrace trace(const std::string& name, std::vector<std::array<double, 2>> line, double top, double bottom, double dip,
                 double dipdir) {
  FaultTrace t;
  t.name = name;
  t.where = "test";
  t.parts = {std::move(line)};
  t.top = t.trace_z = top;
  t.bottom = bottom;
  t.dip_deg = dip;
  t.dip_dir_deg = dipdir;
  check_fault_trace(t);
  return t;
}

Point3 sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The fault's area inside the box, independently of fault_cut: each (segment, piece) panel as the
// quadrilateral swept by the segment between the piece's depths, clipped by the box and by
// `extra` half-spaces.
double area_inside(const FaultTrace& tr, const std::vector<std::pair<Point3, double>>& extra = {}) {
  const double az = tr.dip_dir_deg * kPi / 180;
  const double dx = std::sin(az), dy = std::cos(az);
  double total = 0, above = tr.top;
  for (const auto& pc : tr.piece_list()) {
    const double o0 = tr.offset_at(above), o1 = tr.offset_at(pc.bottom);
    for (const auto& part : tr.parts)
      for (std::size_t i = 0; i + 1 < part.size(); ++i) {
        const auto &a = part[i], &b = part[i + 1];
        std::vector<Point3> q{{a[0] + o0 * dx, a[1] + o0 * dy, above},
                              {b[0] + o0 * dx, b[1] + o0 * dy, above},
                              {b[0] + o1 * dx, b[1] + o1 * dy, pc.bottom},
                              {a[0] + o1 * dx, a[1] + o1 * dy, pc.bottom}};
        q = clip_to_box(q, X1, Y1, Z0);
        for (const auto& [m, d] : extra) q = clip_polygon(q, m, d);
        if (q.size() >= 3) total += polygon_area(q);
      }
    above = pc.bottom;
  }
  return total;
}

struct FaceCheck {
  std::size_t faces = 0;
  double area = 0, max_distance = 0, max_angle_deg = 0;
};

// Every face of fault:<name> against the nearest of the fault's panels (planes from fault_cut's
// own geometry are not trusted: the plane of each piece is rebuilt from the trace).
FaceCheck check_faces(const Mesh& m, const FaultTrace& tr) {
  const double az = tr.dip_dir_deg * kPi / 180;
  const double dx = std::sin(az), dy = std::cos(az);
  struct Plane {
    Point3 n, a;
  };
  std::vector<Plane> planes;
  double above = tr.top;
  for (const auto& pc : tr.piece_list()) {
    const double dip = pc.dip_deg * kPi / 180, o = tr.offset_at(above);
    for (const auto& part : tr.parts)
      for (std::size_t i = 0; i + 1 < part.size(); ++i) {
        const Point3 e{part[i + 1][0] - part[i][0], part[i + 1][1] - part[i][1], 0};
        const Point3 w{dx * std::cos(dip), dy * std::cos(dip), -std::sin(dip)};
        Point3 n = cross(e, w);
        const double l = std::sqrt(dot(n, n));
        planes.push_back({{n[0] / l, n[1] / l, n[2] / l}, {part[i][0] + o * dx, part[i][1] + o * dy, above}});
      }
    above = pc.bottom;
  }
  FaceCheck c;
  const ElementBlock* b = triangle_group(m, "fault:" + tr.name);
  if (!b) return c;
  for (std::size_t i = 0; i < b->size(); ++i) {
    const auto e = b->element(i);
    const Point3 &p = m.nodes[e[0]], &q = m.nodes[e[1]], &r = m.nodes[e[2]];
    const Point3 n = cross(sub(q, p), sub(r, p));
    const double a = std::sqrt(dot(n, n));
    double best = 1e300, ang = 0;
    for (const auto& pl : planes) {
      double d = 0;
      for (const Point3* x : {&p, &q, &r}) d = std::max(d, std::abs(dot(pl.n, sub(*x, pl.a))));
      if (d < best) {
        best = d;
        ang = std::acos(std::min(1.0, std::abs(dot(n, pl.n)) / a)) * 180 / kPi;
      }
    }
    ++c.faces;
    c.area += 0.5 * a;
    c.max_distance = std::max(c.max_distance, best);
    c.max_angle_deg = std::max(c.max_angle_deg, ang);
  }
  return c;
}

double min_dihedral(const Mesh& m) {
  double a = 180;
  for (const auto& b : m.blocks)
    if (b.type == ElementType::Tetrahedron)
      for (std::size_t i = 0; i < b.size(); ++i) {
        const auto e = b.element(i);
        a = std::min(a, min_dihedral_angle_deg(m.nodes[e[0]], m.nodes[e[1]], m.nodes[e[2]], m.nodes[e[3]]));
      }
  return a;
}

void expect_sound(const Mesh& m, double volume) {
  const Conformity c = check_conformity(m);
  EXPECT_EQ(c.over_shared, 0u);
  EXPECT_EQ(c.untagged_outer, 0u);      // a hanging node would leave unmatched faces inside
  EXPECT_EQ(c.tagged_not_outer, 0u);
  EXPECT_EQ(c.fault_not_face, 0u);
  EXPECT_EQ(c.nonpositive, 0u);
  EXPECT_EQ(c.repeated_nodes, 0u);
  EXPECT_NEAR(c.volume, volume, 1e-9 * volume);
  // Material volumes are kept: only the free nodes inside a material move (the layer boundary at -1,500 m stays).
  EXPECT_NEAR(c.volume_of.at("mat:upper"), X1 * Y1 * 1500, 1e-9 * volume);
}

void expect_on_surface(const Mesh& m, const FaultTrace& tr, double area) {
  const FaceCheck f = check_faces(m, tr);
  ASSERT_GT(f.faces, 0u) << tr.name;
  EXPECT_LE(f.max_distance, 1e-6 * kSize) << tr.name;
  EXPECT_LE(f.max_angle_deg, 0.5) << tr.name;
  EXPECT_GE(f.area, 0.99 * area) << tr.name;
  EXPECT_LE(f.area, area * (1 + 1e-9)) << tr.name;  // and no more than the fault
}

class PlanarDip : public ::testing::TestWithParam<std::pair<double, double>> {};

TEST_P(PlanarDip, FacesOnThePlaneCoverTheFault) {
  const auto [dip, dipdir] = GetParam();
  Mesh m = block();
  const double volume = X1 * Y1 * -Z0;
  // A bent trace (two segments) across the block, -200 to -2,600 m.
  const FaultTrace tr = trace("f", {{600, 400}, {1900, 1500}, {2900, 2650}}, -200, -2600, dip, dipdir);
  const auto sum = cut_faults(m, {tr});
  ASSERT_EQ(sum.faults.size(), 1u);
  EXPECT_EQ(sum.faults[0].panels, 2u);
  expect_sound(m, volume);
  const double area = area_inside(tr);
  expect_on_surface(m, tr, area);
  EXPECT_NEAR(sum.faults[0].area, area, 1e-9 * area);
  const double a = min_dihedral(m);
  std::printf("dip %.0f toward %.0f: %zu -> %zu tetrahedra, %zu snapped, %zu collapsed, %zu smoothing moves, smallest "
              "dihedral angle %.3f deg\n",
              dip, dipdir, sum.tetrahedra_before, sum.tetrahedra_after, sum.snapped, sum.collapsed, sum.smoothed, a);
  EXPECT_GE(sum.band_min_dihedral_deg, kBoundDeg);
  EXPECT_EQ(sum.band_below_reference, 0u);  // the input's tetrahedra are better than the bound here
  EXPECT_EQ(a, std::min(sum.band_min_dihedral_deg, min_dihedral(block())));  // the band is the only change
  EXPECT_GT(sum.collapsed + sum.smoothed, 0u);
  // The fault becomes interface elements.
  FaultInsertOptions io;
  const auto rep = insert_faults(m, io);
  ASSERT_EQ(rep.faults.size(), 1u);
  EXPECT_EQ(rep.faults[0].triangles, sum.faults[0].triangles);
  EXPECT_GT(rep.faults[0].duplicated_nodes, 0u);
}

INSTANTIATE_TEST_SUITE_P(Dips, PlanarDip,
                         ::testing::Values(std::pair{20.0, 120.0}, std::pair{35.0, 195.0}, std::pair{45.0, 300.0},
                                           std::pair{60.0, 15.0}, std::pair{80.0, 135.0}, std::pair{90.0, 135.0}));

TEST(DippingFaults, ListricFault) {
  Mesh m = block();
  FaultTrace tr = trace("listric", {{500, 300}, {3500, 2700}}, -100, -2800, 60, 135);
  tr.pieces = {{-1000, 60}, {-2000, 40}, {-2800, 25}};
  check_fault_trace(tr);
  const auto sum = cut_faults(m, {tr});
  EXPECT_EQ(sum.faults[0].panels, 3u);
  expect_sound(m, X1 * Y1 * -Z0);
  std::printf("listric: smallest dihedral angle of the cut's tetrahedra %.3f deg\n", sum.band_min_dihedral_deg);
  EXPECT_GE(sum.band_min_dihedral_deg, kBoundDeg);
  expect_on_surface(m, tr, area_inside(tr));
  // The kinks are horizontal lines at the piece boundaries: faces are found on all three planes.
  const ElementBlock* b = triangle_group(m, "fault:listric");
  ASSERT_NE(b, nullptr);
  int in_piece[3] = {0, 0, 0};
  for (std::size_t i = 0; i < b->size(); ++i) {
    const auto e = b->element(i);
    const double zc = (m.nodes[e[0]][2] + m.nodes[e[1]][2] + m.nodes[e[2]][2]) / 3;
    ++in_piece[zc > -1000 ? 0 : (zc > -2000 ? 1 : 2)];
  }
  for (int k : in_piece) EXPECT_GT(k, 0);
}

TEST(DippingFaults, TwoCrossingFaults) {
  Mesh m = block();
  // Dipping toward each other: they meet 800 m below their traces, at -900 m.
  const FaultTrace a = trace("east_dipping", {{1200, 200}, {1200, 2800}}, -100, -2500, 45, 90);
  const FaultTrace b = trace("west_dipping", {{2800, 200}, {2800, 2800}}, -100, -2500, 45, 270);
  const auto sum = cut_faults(m, {a, b});
  expect_sound(m, X1 * Y1 * -Z0);
  expect_on_surface(m, a, area_inside(a));
  expect_on_surface(m, b, area_inside(b));
  std::printf("crossing: smallest dihedral angle of the cut's tetrahedra %.3f deg\n", sum.band_min_dihedral_deg);
  EXPECT_GE(sum.band_min_dihedral_deg, kBoundDeg);
  // The intersection line is made of mesh edges: both faults share nodes along it, all at x = 2000.
  std::set<std::uint32_t> na, nb;
  for (auto v : triangle_group(m, "fault:east_dipping")->nodes) na.insert(v);
  for (auto v : triangle_group(m, "fault:west_dipping")->nodes) nb.insert(v);
  std::size_t shared = 0;
  for (auto v : na)
    if (nb.count(v)) {
      ++shared;
      EXPECT_NEAR(m.nodes[v][0], 2000, 1e-6 * kSize);
      EXPECT_NEAR(m.nodes[v][2], -900, 1e-6 * kSize);
    }
  EXPECT_GT(shared, 10u);
  FaultInsertOptions io;
  const auto rep = insert_faults(m, io);
  ASSERT_EQ(rep.faults.size(), 2u);
  EXPECT_GT(rep.faults[0].meets.count("west_dipping"), 0u);
}

TEST(DippingFaults, FaultEndingAgainstAnother) {
  Mesh m = block();
  const FaultTrace a = trace("main", {{1200, 200}, {1200, 2800}}, -100, -2700, 45, 90);
  // A steep fault striking east-west, its trace ending 300 m short of the main fault's trace: it
  // is extended to the main fault and ends against it (on its hanging-wall side, x > the main fault).
  FaultTrace b = trace("splay", {{3700, 1500}, {1500, 1500}}, -300, -2000, 70, 0);
  b.ends_against = "main";
  const auto sum = cut_faults(m, {a, b});
  expect_sound(m, X1 * Y1 * -Z0);
  std::printf("ending against: smallest dihedral angle of the cut's tetrahedra %.3f deg\n", sum.band_min_dihedral_deg);
  EXPECT_GE(sum.band_min_dihedral_deg, kBoundDeg);
  expect_on_surface(m, a, area_inside(a));
  // The main fault's plane: x - 1200 = (-100 - z) (dip 45 toward east); the splay keeps x above it.
  const double s2 = std::sqrt(0.5);
  const std::vector<std::pair<Point3, double>> keep{{{-s2, 0, -s2}, -s2 * (1200 - 100)}};
  FaultTrace extended = b;
  extended.parts[0].back() = {0, 1500};  // long enough to reach the main fault at every depth
  const double area = area_inside(extended, keep);
  const FaceCheck f = check_faces(m, b);
  EXPECT_LE(f.max_distance, 1e-6 * kSize);
  EXPECT_LE(f.max_angle_deg, 0.5);
  EXPECT_GE(f.area, 0.99 * area);
  EXPECT_LE(f.area, area * (1 + 1e-9));
  // Every splay face lies on the hanging-wall side of the main fault.
  const ElementBlock* g = triangle_group(m, "fault:splay");
  for (auto v : g->nodes) EXPECT_GE(m.nodes[v][0] - 1200 - (-100 - m.nodes[v][2]), -1e-6 * kSize);
  FaultInsertOptions io;
  const auto rep = insert_faults(m, io);
  ASSERT_EQ(rep.faults.size(), 2u);
  (void)sum;
}

TEST(DippingFaults, BadInputNamesTheFault) {
  Mesh m = block();
  FaultTrace t = trace("x", {{500, 500}, {1500, 500}}, -100, -1000, 45, 0);
  t.ends_against = "nowhere";
  try {
    cut_faults(m, {t});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fault 'x'"), std::string::npos);
  }
  // A surface that misses the mesh.
  const FaultTrace far = trace("far", {{50000, 500}, {51000, 500}}, -100, -1000, 45, 0);
  EXPECT_THROW(cut_faults(m, {far}), InputError);
  FaultTrace bad = trace("d", {{500, 500}, {1500, 500}}, -100, -1000, 45, 0);
  bad.dip_deg = 0;
  EXPECT_THROW(check_fault_trace(bad), InputError);
  bad.dip_deg = 91;
  EXPECT_THROW(check_fault_trace(bad), InputError);
}

}  // namespace
}  // namespace ugs::test
