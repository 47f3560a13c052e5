// The layered mesh of ugs-meshgen as worked examples: random plans with shuffled node numbers
// extruded through curved surfaces must give conforming meshes (every interior face in exactly two
// tetrahedra, every outer face tagged once), unit volumes equal to the integral of the thickness,
// merged nodes at pinch-outs, fault triangles that are faces of the mesh; plus the order rule,
// the plan checks and the quality measures.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <set>

#include <fmt/format.h>

#include "meshing_checks.hpp"
#include "run_tool.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/meshing/layered_mesh.hpp"
#include "ugs/meshing/mesh_quality.hpp"
#include "ugs/meshing/natural_neighbour.hpp"
#include "ugs/meshing/plan.hpp"
#include "ugs/meshing/surface_stack.hpp"

using namespace ugs;

namespace {

// Three units between four curved surfaces; the middle unit pinches out where `pinch` < 0.
struct Model {
  Plan plan;
  std::vector<std::vector<double>> z;
  LayeredMeshInput in;
};

Model make_model(const Mesh& plan_mesh, std::vector<int> layers, double pinch_shift, std::vector<double> bias = {}) {
  Model m;
  m.plan = plan_from_mesh(plan_mesh, "plan");
  const std::size_t nc = m.plan.num_columns();
  m.z.assign(4, std::vector<double>(nc));
  for (std::size_t c = 0; c < nc; ++c) {
    const double x = m.plan.xy[c][0], y = m.plan.xy[c][1];
    m.z[0][c] = 50 + 10 * std::sin(x / 900.0) + 5 * std::cos(y / 700.0);
    m.z[1][c] = -300 + 40 * std::sin((x + y) / 1500.0);
    // The middle unit thins towards -x and vanishes where x < pinch_shift (150 m at most).
    m.z[2][c] = m.z[1][c] - std::clamp(0.02 * (x - pinch_shift), 0.0, 150.0);
    m.z[3][c] = -2000 + 100 * std::cos(x / 2000.0);
  }
  std::vector<StackSurface> s = {{"top", "t:1"}, {"a", "t:2"}, {"b", "t:3"}, {"bottom", "t:4"}};
  apply_stack_rules(m.z, s, m.plan, {1.0, 0.0});
  m.in.plan = &m.plan;
  m.in.surfaces = m.z;
  const char* names[] = {"upper", "middle", "lower"};
  for (int u = 0; u < 3; ++u) m.in.units.push_back({names[u], layers[u], bias.empty() ? 1.0 : bias[u]});
  m.in.materials = {"upper", "middle", "lower"};
  for (std::uint32_t u = 0; u < 3; ++u) m.in.material_of.push_back(std::vector<std::uint32_t>(m.plan.triangles.size(), u));
  return m;
}

// Exact integral over the plan of a field linear on each triangle.
double integral(const Plan& p, const std::vector<double>& f) {
  double s = 0;
  for (std::size_t t = 0; t < p.triangles.size(); ++t) {
    const auto& [a, b, c] = p.triangles[t];
    s += p.area(t) * (f[a] + f[b] + f[c]) / 3.0;
  }
  return s;
}

std::vector<double> minus(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> r(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) r[i] = a[i] - b[i];
  return r;
}

}  // namespace

TEST(SublayerFractions, UniformAndBiased) {
  const auto u = sublayer_fractions(4, 1.0);
  ASSERT_EQ(u.size(), 5u);
  for (int k = 0; k <= 4; ++k) EXPECT_NEAR(u[k], k / 4.0, 1e-15);
  const auto b = sublayer_fractions(3, 2.0);  // thicknesses 1 : 2 : 4
  EXPECT_NEAR(b[1], 1.0 / 7.0, 1e-15);
  EXPECT_NEAR(b[2], 3.0 / 7.0, 1e-15);
  EXPECT_EQ(b[3], 1.0);
  EXPECT_THROW(sublayer_fractions(0, 1.0), std::invalid_argument);
  EXPECT_THROW(sublayer_fractions(2, 0.0), std::invalid_argument);
}

TEST(LayeredMesh, RandomPlansGiveConformingTaggedMeshes) {
  std::mt19937 rng(2024);
  for (unsigned seed = 0; seed < 25; ++seed) {
    const int nx = 3 + static_cast<int>(rng() % 6), ny = 3 + static_cast<int>(rng() % 6);
    const Mesh pm = test::random_plan_mesh(nx, ny, 6000, 5000, seed);
    Model m = make_model(pm, {1 + static_cast<int>(seed % 3), 2 + static_cast<int>(seed % 4), 2}, 1000.0 + 150.0 * seed);
    LayeredMeshStats st;
    const Mesh mesh = build_layered_mesh(m.in, &st);
    const auto c = test::check_conformity(mesh);
    SCOPED_TRACE("seed " + std::to_string(seed));
    EXPECT_EQ(c.over_shared, 0u);
    EXPECT_EQ(c.untagged_outer, 0u);
    EXPECT_EQ(c.tagged_not_outer, 0u);
    EXPECT_EQ(c.doubly_tagged, 0u);
    EXPECT_EQ(c.repeated_nodes, 0u);
    EXPECT_EQ(c.nonpositive, 0u);
    EXPECT_EQ(c.tets, st.tetrahedra);
    // No overlap: the tetrahedra fill exactly the volume between top and bottom.
    const double domain = integral(m.plan, minus(m.z[0], m.z[3]));
    EXPECT_NEAR(c.volume, domain, 1e-11 * domain);
  }
}

TEST(LayeredMesh, PrismSplitIsTheGlobalOrderRule) {
  // One triangle, one layer: the side diagonals join bottom(min) to top(max) for every numbering.
  for (auto tags : std::vector<std::array<std::uint64_t, 3>>{{1, 2, 3}, {3, 1, 2}, {2, 3, 1}, {1, 3, 2}, {3, 2, 1}}) {
    Mesh pm;
    pm.add_node({0, 0, 0}, tags[0]);
    pm.add_node({100, 0, 0}, tags[1]);
    pm.add_node({0, 100, 0}, tags[2]);
    auto& b = pm.block(2, pm.entity_for_physical(2, "region:d"), ElementType::Triangle);
    const std::uint32_t t[3] = {0, 1, 2};
    pm.add_element(b, t);
    const Plan plan = plan_from_mesh(pm, "p");
    LayeredMeshInput in;
    in.plan = &plan;
    in.surfaces = {{0, 0, 0}, {-10, -10, -10}};
    in.units = {{"u", 1, 1.0}};
    in.materials = {"m"};
    in.material_of = {{0}};
    const Mesh mesh = build_layered_mesh(in);
    ASSERT_EQ(mesh.count(ElementType::Tetrahedron), 3u);
    // Columns are numbered by tag; node of column c at level l is 2c + l (top first).
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const auto& blk : mesh.blocks) {
      if (blk.type != ElementType::Tetrahedron) continue;
      for (std::size_t e = 0; e < blk.size(); ++e) {
        auto n = blk.element(e);
        for (int i = 0; i < 4; ++i)
          for (int j = 0; j < 4; ++j) edges.insert({n[i], n[j]});
      }
    }
    for (std::uint32_t a = 0; a < 3; ++a)
      for (std::uint32_t c = a + 1; c < 3; ++c) {
        const std::uint32_t bottom_min = 2 * a + 1, top_max = 2 * c, top_min = 2 * a, bottom_max = 2 * c + 1;
        EXPECT_TRUE(edges.count({bottom_min, top_max})) << a << " " << c;
        EXPECT_FALSE(edges.count({top_min, bottom_max})) << a << " " << c;
      }
  }
}

TEST(LayeredMesh, UnitVolumeIsTheIntegralOfItsThickness) {
  const Mesh pm = test::random_plan_mesh(9, 7, 9000, 7000, 7);
  Model m = make_model(pm, {2, 5, 3}, 3000.0, {1.0, 1.4, 0.7});
  const Mesh mesh = build_layered_mesh(m.in);
  const auto c = test::check_conformity(mesh);
  const char* names[] = {"upper", "middle", "lower"};
  for (int u = 0; u < 3; ++u) {
    const double expected = integral(m.plan, minus(m.z[u], m.z[u + 1]));
    const double got = c.volume_of.at(std::string("mat:") + names[u]);
    EXPECT_NEAR(got, expected, 1e-9 * expected) << names[u];
  }
}

TEST(LayeredMesh, PinchOutMergesNodesAndDropsOnlyDegenerateTetrahedra) {
  const Mesh pm = test::random_plan_mesh(10, 6, 6000, 4000, 11);
  const int layers_middle = 4;
  Model m = make_model(pm, {2, layers_middle, 3}, 2500.0);
  std::size_t zero_columns = 0;
  for (std::size_t c = 0; c < m.plan.num_columns(); ++c) zero_columns += m.z[1][c] == m.z[2][c];
  ASSERT_GT(zero_columns, 10u);
  ASSERT_LT(zero_columns, m.plan.num_columns());
  LayeredMeshStats st;
  const Mesh mesh = build_layered_mesh(m.in, &st);
  const std::size_t levels = 1 + 2 + layers_middle + 3;
  EXPECT_EQ(mesh.num_nodes(), m.plan.num_columns() * levels - zero_columns * layers_middle);
  EXPECT_EQ(st.merged_nodes, zero_columns * layers_middle);
  EXPECT_EQ(st.pinched_columns[1], zero_columns);
  // One tetrahedron per collapsed prism edge disappears.
  std::size_t collapsed_edges = 0;
  for (const auto& t : m.plan.triangles)
    for (auto c : t) collapsed_edges += m.z[1][c] == m.z[2][c];
  EXPECT_EQ(st.dropped_tetrahedra, collapsed_edges * layers_middle);
  EXPECT_EQ(st.tetrahedra, 3 * m.plan.triangles.size() * (levels - 1) - st.dropped_tetrahedra);
  const auto c = test::check_conformity(mesh);
  EXPECT_EQ(c.nonpositive, 0u);
  EXPECT_EQ(c.repeated_nodes, 0u);
  EXPECT_EQ(c.over_shared, 0u);
  EXPECT_EQ(c.untagged_outer, 0u);
  const auto q = mesh_quality(mesh);
  EXPECT_GT(q.min_volume, 0.0);
  EXPECT_EQ(q.inverted, 0u);
}

TEST(LayeredMesh, BoundaryGroupsFaceOutwards) {
  const Mesh pm = test::random_plan_mesh(5, 4, 5000, 4000, 3);
  Model m = make_model(pm, {1, 2, 1}, -1e9);
  const Mesh mesh = build_layered_mesh(m.in);
  const std::map<std::string, std::array<double, 3>> outward = {
      {"bnd:top", {0, 0, 1}},  {"bnd:bottom", {0, 0, -1}}, {"bnd:west", {-1, 0, 0}},
      {"bnd:east", {1, 0, 0}}, {"bnd:south", {0, -1, 0}},  {"bnd:north", {0, 1, 0}}};
  std::map<std::string, std::size_t> seen;
  for (const auto& b : mesh.blocks) {
    if (b.type != ElementType::Triangle) continue;
    const std::string name = mesh.physical_name_of(b.entity_dim, b.entity_tag);
    ASSERT_TRUE(outward.count(name)) << name;
    const auto& o = outward.at(name);
    for (std::size_t i = 0; i < b.size(); ++i) {
      auto n = b.element(i);
      const auto &A = mesh.nodes[n[0]], &B = mesh.nodes[n[1]], &C = mesh.nodes[n[2]];
      const double u[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]}, v[3] = {C[0] - A[0], C[1] - A[1], C[2] - A[2]};
      const double nrm[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
      const double len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
      EXPECT_GT((nrm[0] * o[0] + nrm[1] * o[1] + nrm[2] * o[2]) / len, 0.9) << name;
      ++seen[name];
    }
  }
  EXPECT_EQ(seen.size(), 6u);
  EXPECT_EQ(seen["bnd:west"], 4u * 4 * 2);   // 4 plan edges x 4 sub-layers x 2 triangles
  EXPECT_EQ(seen["bnd:south"], 5u * 4 * 2);
}

TEST(LayeredMesh, FaultTrianglesOverTheDepthRange) {
  const Mesh pm = test::random_plan_mesh(8, 6, 8000, 6000, 5);
  Model m = make_model(pm, {2, 3, 4}, -1e9);
  // The grid line y = 3000 (j = 3) is made of plan edges whatever the diagonals.
  VerticalFault f;
  f.name = "f1";
  f.top = -100;
  f.bottom = -1200;
  for (int i = 0; i < 8; ++i) {
    auto col = [&](int ii) {
      const auto tag = pm.node_tags[3 * 9 + ii];
      return static_cast<std::uint32_t>(std::lower_bound(m.plan.node_tags.begin(), m.plan.node_tags.end(), tag) -
                                        m.plan.node_tags.begin());
    };
    f.edges.push_back({col(i), col(i + 1)});  // trace towards +x: right-hand side is -y
  }
  m.in.faults = {f};
  const Mesh mesh = build_layered_mesh(m.in);
  // Expected faces: sub-layers whose mid-depth lies in [-1200, -100].
  std::size_t expected = 0;
  const auto fr = std::vector<std::vector<double>>{sublayer_fractions(2, 1), sublayer_fractions(3, 1), sublayer_fractions(4, 1)};
  for (const auto& [a, b] : f.edges)
    for (int u = 0; u < 3; ++u)
      for (std::size_t k = 0; k + 1 < fr[u].size(); ++k) {
        auto zl = [&](std::uint32_t c, double t) { return m.z[u][c] - t * (m.z[u][c] - m.z[u + 1][c]); };
        const double mid = 0.25 * (zl(a, fr[u][k]) + zl(b, fr[u][k]) + zl(a, fr[u][k + 1]) + zl(b, fr[u][k + 1]));
        expected += (mid <= -100 && mid >= -1200) ? 2 : 0;
      }
  ASSERT_GT(expected, 0u);
  const auto* g = mesh.find_physical(2, "fault:f1");
  ASSERT_NE(g, nullptr);
  std::size_t got = 0;
  for (const auto& b : mesh.blocks) {
    if (mesh.physical_name_of(b.entity_dim, b.entity_tag) != "fault:f1") continue;
    got += b.size();
    for (std::size_t i = 0; i < b.size(); ++i) {
      auto n = b.element(i);
      const auto &A = mesh.nodes[n[0]], &B = mesh.nodes[n[1]], &C = mesh.nodes[n[2]];
      const double ny = (C[0] - A[0]) * (B[2] - A[2]) - (B[0] - A[0]) * (C[2] - A[2]);
      EXPECT_LT(ny, 0.0);  // normal to the right of the trace direction (+x): -y
      EXPECT_LE(std::max({A[2], B[2], C[2]}), -100 + 200.0);
    }
  }
  EXPECT_EQ(got, expected);
  EXPECT_EQ(test::check_conformity(mesh).fault_not_face, 0u);

  // A fault segment that is not a plan edge is bad input.
  m.in.faults[0].edges.push_back({0, static_cast<std::uint32_t>(m.plan.num_columns() - 1)});
  EXPECT_THROW(build_layered_mesh(m.in), InputError);
}

TEST(SurfaceStack, OrderRuleClampsWithinToleranceAndRejectsBeyond) {
  const Mesh pm = test::random_plan_mesh(3, 3, 300, 300, 1, false);
  const Plan plan = plan_from_mesh(pm, "p");
  const std::size_t nc = plan.num_columns();
  std::vector<StackSurface> s = {{"DEM", "s.toml:3"}, {"Base", "s.toml:7"}, {"Bottom", "s.toml:11"}};
  std::vector<std::vector<double>> z = {std::vector<double>(nc, 0.0), std::vector<double>(nc, -10.0),
                                        std::vector<double>(nc, -20.0)};
  z[1][2] = 0.6;  // above the DEM by 0.6 m: lowered onto it
  auto r = apply_stack_rules(z, s, plan, {1.0, 0.5});
  EXPECT_EQ(z[1][2], 0.0);
  EXPECT_EQ(r.clamped[1], 1u);
  EXPECT_EQ(r.collapsed[0], 1u);

  z[1][5] = 3.0;
  z[1][7] = 2.0;
  try {
    apply_stack_rules(z, s, plan, {1.0, 0.5});
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string w = e.what();
    EXPECT_EQ(e.where(), "s.toml:7");
    EXPECT_NE(w.find("surface 'Base' lies above 'DEM' at 2 columns, by up to 3.00 m"), std::string::npos) << w;
    EXPECT_NE(w.find(fmt::format("x={:.2f}, y={:.2f}", plan.xy[5][0], plan.xy[5][1])), std::string::npos) << w;
  }
  // An unconformity truncates every surface below it, by any amount.
  s[0].unconformity = true;
  r = apply_stack_rules(z, s, plan, {1.0, 0.5});
  EXPECT_EQ(z[1][5], 0.0);
  EXPECT_EQ(r.truncated[1], 2u);  // 5 and 7; column 2 was already on the DEM
}

TEST(SurfaceStack, ThinUnitsCollapseOntoTheirTop) {
  const Mesh pm = test::random_plan_mesh(2, 2, 200, 200, 1, false);
  const Plan plan = plan_from_mesh(pm, "p");
  const std::size_t nc = plan.num_columns();
  std::vector<std::vector<double>> z = {std::vector<double>(nc, 0.0), std::vector<double>(nc, -0.3),
                                        std::vector<double>(nc, -5.0)};
  z[1][0] = -2.0;
  const auto r = apply_stack_rules(z, {{"a", ""}, {"b", ""}, {"c", ""}}, plan, {0.0, 0.5});
  EXPECT_EQ(r.collapsed[0], nc - 1);
  for (std::size_t c = 1; c < nc; ++c) EXPECT_EQ(z[1][c], 0.0);
  EXPECT_EQ(z[1][0], -2.0);
  EXPECT_EQ(thousands(1532), "1,532");
  EXPECT_EQ(thousands(1234567), "1,234,567");
  EXPECT_EQ(thousands(12), "12");
}

namespace {
Mesh plan_of(const std::vector<std::array<double, 2>>& pts, const std::vector<std::array<std::uint32_t, 3>>& tris) {
  Mesh m;
  for (const auto& p : pts) m.add_node({p[0], p[1], 0});
  auto& b = m.block(2, m.entity_for_physical(2, "region:d"), ElementType::Triangle);
  for (const auto& t : tris) m.add_element(b, t);
  return m;
}
void expect_plan_error(const Mesh& m, const std::string& fragment) {
  try {
    plan_from_mesh(m, "plan.msh");
    FAIL() << "no error for " << fragment;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("plan.msh: ", 0), 0u) << e.what();
  }
}
}  // namespace

TEST(Plan, RejectsInvertedDuplicateDegenerateAndOverlappingTriangles) {
  const std::vector<std::array<double, 2>> sq = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {2, 0}, {2, 1}};
  EXPECT_NO_THROW(plan_from_mesh(plan_of(sq, {{0, 1, 2}, {0, 2, 3}, {1, 4, 5}, {1, 5, 2}}), "p"));
  // All clockwise is fine (gmsh may write a -z normal); the plan is turned counter-clockwise.
  const Plan cw = plan_from_mesh(plan_of(sq, {{0, 2, 1}, {0, 3, 2}, {1, 5, 4}, {1, 2, 5}}), "p");
  for (std::size_t t = 0; t < cw.triangles.size(); ++t) EXPECT_GT(cw.area(t), 0);
  expect_plan_error(plan_of(sq, {{0, 1, 2}, {0, 2, 3}, {1, 4, 5}, {1, 2, 5}}), "inverted triangle 4 (nodes 2, 3, 6) at x=");
  expect_plan_error(plan_of(sq, {{0, 1, 2}, {0, 2, 3}, {2, 0, 1}}), "duplicate triangles 1 and 3");
  expect_plan_error(plan_of({{0, 0}, {1, 0}, {2, 0}, {0, 1}}, {{0, 1, 2}, {0, 1, 3}}), "degenerate triangle 1");
  // Two triangles on the same side of their common edge overlap.
  expect_plan_error(plan_of({{0, 0}, {1, 0}, {0, 1}, {0.2, 0.5}}, {{0, 1, 2}, {0, 1, 3}}), "overlap");
  // Two nodes at the same place.
  expect_plan_error(plan_of({{0, 0}, {1, 0}, {0, 1}, {1, 0}, {1, 1}}, {{0, 1, 2}, {3, 4, 2}}), "same place");
  Mesh tet = test::unit_cube_mesh();
  expect_plan_error(tet, "3D mesh");
}

TEST(Quality, DihedralAnglesAndVolumes) {
  const Point3 a{1, 1, 1}, b{1, -1, -1}, c{-1, 1, -1}, d{-1, -1, 1};
  EXPECT_NEAR(min_dihedral_angle_deg(a, b, c, d), std::acos(1.0 / 3.0) * 180 / M_PI, 1e-9);
  EXPECT_NEAR(min_dihedral_angle_deg({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), 54.7356103172, 1e-6);
  EXPECT_EQ(min_dihedral_angle_deg({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}), 0.0);
}

// The smallest dihedral angle as the loop over the faces wrote it before it was written out
// (mesh_quality.cpp): the reference for the bit-for-bit test below.
double loop_min_dihedral_deg(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  using V = std::array<double, 3>;
  auto sub = [](const Point3& x, const Point3& y) { return V{x[0] - y[0], x[1] - y[1], x[2] - y[2]}; };
  auto cross = [](const V& u, const V& v) {
    return V{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  };
  auto dot = [](const V& u, const V& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  const Point3* p[4] = {&a, &b, &c, &d};
  V n[4];
  for (int i = 0; i < 4; ++i) {
    const Point3& q0 = *p[(i + 1) % 4];
    n[i] = cross(sub(*p[(i + 2) % 4], q0), sub(*p[(i + 3) % 4], q0));
    if (dot(n[i], sub(*p[i], q0)) > 0) n[i] = {-n[i][0], -n[i][1], -n[i][2]};
    const double len = std::sqrt(dot(n[i], n[i]));
    if (!(len > 0)) return std::acos(1.0) * 180.0 / M_PI;
    for (auto& x : n[i]) x /= len;
  }
  double worst = -1;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) worst = std::max(worst, -dot(n[i], n[j]));
  return std::acos(std::clamp(worst, -1.0, 1.0)) * 180.0 / M_PI;
}

// Random tetrahedra of both orientations at the thesis' coordinates (UTM metres, 1e-3 .. 1e4 m
// apart, slivers, flat and repeated nodes): the angle (four faces at a time with AVX, two with
// SSE2) equals the loop's bit for bit.
TEST(Quality, DihedralAngleBitForBitAsTheLoop) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> scale_exp(-3, 4), kind(0, 9);
  std::size_t checked = 0, slivers = 0, degenerate = 0;
  for (int k = 0; k < 200000; ++k) {
    const Point3 o{700000 + 20000 * unit(rng), 4.9e6 + 20000 * unit(rng), -3000 + 3000 * unit(rng)};
    const double s = std::pow(10.0, scale_exp(rng));
    Point3 x[4];
    for (auto& q : x) q = {o[0] + s * unit(rng), o[1] + s * unit(rng), o[2] + s * unit(rng)};
    const int what = kind(rng);
    if (what == 0) x[3] = x[1];  // repeated node
    if (what == 1) x[3] = {x[0][0] + 0.5 * (x[1][0] - x[0][0]), x[0][1] + 0.5 * (x[1][1] - x[0][1]), x[0][2]};  // near flat
    if (what == 2) x[3][2] = x[0][2] + 1e-9 * s * unit(rng);                                                // sliver
    if (what == 3) x[3] = {x[0][0] + x[1][0] - x[2][0], x[0][1] + x[1][1] - x[2][1], x[0][2] + x[1][2] - x[2][2]};  // flat
    const double got = min_dihedral_angle_deg(x[0], x[1], x[2], x[3]);
    const double loop = loop_min_dihedral_deg(x[0], x[1], x[2], x[3]);
    // Flat by ugs-solve's test: 0 whatever the faces' rounding says (issue 43: it said 180).
    const double want = ugs::tet_is_degenerate(x[0], x[1], x[2], x[3]) ? 0.0 : loop;
    ASSERT_EQ(std::memcmp(&got, &want, sizeof got), 0) << "tetrahedron " << k << ": " << got << " vs " << want;
    for (int lanes : {2, 4}) {  // both kernels, whichever the processor makes the default: the loop's bits
      const double other = detail::min_dihedral_angle_deg_lanes(lanes, x[0], x[1], x[2], x[3]);
      ASSERT_EQ(std::memcmp(&other, &loop, sizeof other), 0) << lanes << " lanes, tetrahedron " << k;
    }
    ++checked;
    slivers += got > 0 && got < 1;
    degenerate += got == 0;
  }
  EXPECT_EQ(checked, 200000u);
  EXPECT_GT(slivers, 1000u);     // the near-flat cases were met
  EXPECT_GT(degenerate, 10000u);  // and the flat and repeated ones
}

TEST(NaturalNeighbour, ReproducesLinearFieldsInsideTheHull) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0, 1000);
  std::vector<std::array<double, 3>> picks;
  auto f = [](double x, double y) { return -1500 + 0.03 * x - 0.02 * y; };
  for (double x : {0.0, 1000.0})
    for (double y : {0.0, 1000.0}) picks.push_back({x, y, f(x, y)});
  for (int i = 0; i < 40; ++i) {
    const double x = u(rng), y = u(rng);
    picks.push_back({x, y, f(x, y)});
  }
  const NaturalNeighbourSurface s(picks);
  for (int i = 0; i < 200; ++i) {
    const double x = u(rng), y = u(rng);
    const auto v = s.at(x, y);
    ASSERT_TRUE(v.has_value());
    EXPECT_NEAR(*v, f(x, y), 1e-8);
  }
  EXPECT_NEAR(*s.at(picks[7][0], picks[7][1]), picks[7][2], 1e-12);
  // On the hull's edges (plan nodes on the domain boundary with picks at its corners).
  EXPECT_NEAR(*s.at(500, 1000), f(500, 1000), 1e-8);
  EXPECT_NEAR(*s.at(0, 321), f(0, 321), 1e-8);
  EXPECT_FALSE(s.at(-1, 500).has_value());
  EXPECT_FALSE(s.at(500, 1000.5).has_value());
  picks.push_back({picks[3][0], picks[3][1], picks[3][2] + 1});
  EXPECT_THROW(NaturalNeighbourSurface{picks}, std::invalid_argument);
  EXPECT_THROW(NaturalNeighbourSurface({{0, 0, 0}, {1, 1, 0}, {2, 2, 0}}), std::invalid_argument);
}
