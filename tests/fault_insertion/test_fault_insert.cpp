// Fault insertion on box meshes [0,6]^3 (unit cells, Kuhn-split): counts of duplicated and tip
// nodes that follow from the splitting rule, junction copy counts, orientation, gluing back, and
// the refusals. Every faulted mesh also passes check_faulted (fault_meshes.hpp).
#include <gtest/gtest.h>

#include "fault_meshes.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/meshing/fault_insert.hpp"

namespace ugs::test {
namespace {

// Plane x = 3 inside y in [y0, y1], z in [z0, z1].
NodePredicate on_x3(double y0, double y1, double z0, double z1) {
  return [=](const Point3& p) { return near(p[0], 3) && p[1] > y0 - 1e-9 && p[1] < y1 + 1e-9 && p[2] > z0 - 1e-9 && p[2] < z1 + 1e-9; };
}

double total_volume(const Mesh& m) {
  double v = 0;
  for (const auto& b : m.blocks)
    if (b.type == ElementType::Tetrahedron)
      for (std::size_t e = 0; e < b.size(); ++e) {
        const auto c = b.element(e);
        v += tet_signed_volume(m.nodes[c[0]], m.nodes[c[1]], m.nodes[c[2]], m.nodes[c[3]]);
      }
  return v;
}

// Connected pieces of the tetrahedra through shared nodes.
int pieces(const Mesh& m) {
  std::vector<std::uint32_t> parent(m.num_nodes());
  std::iota(parent.begin(), parent.end(), 0u);
  std::function<std::uint32_t(std::uint32_t)> find = [&](std::uint32_t x) { return parent[x] == x ? x : parent[x] = find(parent[x]); };
  std::vector<bool> used(m.num_nodes(), false);
  for (const auto& b : m.blocks)
    if (b.type == ElementType::Tetrahedron)
      for (std::size_t e = 0; e < b.size(); ++e) {
        const auto c = b.element(e);
        for (int k = 0; k < 4; ++k) used[c[k]] = true;
        for (int k = 1; k < 4; ++k) parent[find(c[k])] = find(c[0]);
      }
  int n = 0;
  for (std::uint32_t v = 0; v < m.num_nodes(); ++v) n += used[v] && find(v) == v;
  return n;
}

TEST(FaultInsert, BuriedFaultSplitsInteriorNodesOnly) {
  Mesh m = unit_box(6);
  ASSERT_EQ(add_fault_group(m, "F", on_x3(1, 5, 1, 5)), 32u);  // 4 x 4 quads
  const Mesh input = m;
  const auto r = insert_faults(m);
  ASSERT_EQ(r.faults.size(), 1u);
  const auto& f = r.faults[0];
  EXPECT_EQ(f.triangles, 32u);
  EXPECT_NEAR(f.area, 16.0, 1e-12);
  EXPECT_EQ(f.nodes, 25u);
  EXPECT_EQ(f.tip_nodes, 16u);            // the buried edge: 4 x 4 perimeter
  EXPECT_EQ(f.duplicated_nodes, 9u);      // = fault nodes - tip nodes
  EXPECT_EQ(f.duplicated_nodes, f.nodes - f.tip_nodes);
  EXPECT_EQ(r.new_nodes, 9u);
  EXPECT_EQ(f.parts, 1u);
  EXPECT_EQ(f.junction_nodes, 0u);
  EXPECT_EQ(f.unsplit_triangles, 2u);     // two corners whose three nodes all lie on the buried edge
  EXPECT_EQ(m.num_nodes(), input.num_nodes() + 9);
  // New tags above the largest, consecutive.
  for (std::size_t i = input.num_nodes(); i < m.num_nodes(); ++i) EXPECT_EQ(m.node_tags[i], 343 + (i - input.num_nodes()) + 1);
  // Vertical fault striking north: normal points west (side 1 = east).
  EXPECT_NEAR(f.normal[0], -1.0, 1e-12);
  // The triangles are gone, the prisms carry their tags in a dim-3 group.
  EXPECT_EQ(m.find_physical(2, "fault:F"), nullptr);
  ASSERT_NE(m.find_physical(3, "fault:F"), nullptr);
  const ElementBlock* p = find_block(m, 3, "fault:F", ElementType::Prism);
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->size(), 32u);
  EXPECT_EQ(m.count(ElementType::Triangle), input.count(ElementType::Triangle) - 32);
  EXPECT_EQ(copies_at(m, {3, 3, 3}), 2);
  EXPECT_EQ(copies_at(m, {3, 1, 3}), 1);  // tip
  EXPECT_NEAR(total_volume(m), 216.0, 1e-9);
  check_faulted(m);
  expect_glues_back(m, input);
}

TEST(FaultInsert, FaultReachingTheTopSplitsItsSurfaceNodes) {
  Mesh m = unit_box(6);
  add_fault_group(m, "F", on_x3(1, 5, 2, 6));  // 4 x 4 quads up to z = 6
  const Mesh input = m;
  const auto r = insert_faults(m);
  const auto& f = r.faults[0];
  EXPECT_EQ(f.nodes, 25u);
  EXPECT_EQ(f.tip_nodes, 5 + 5 + 3u);     // y = 1 and y = 5 columns (z 2..6) and the bottom row
  EXPECT_EQ(f.duplicated_nodes, 12u);     // 9 interior + 3 on the ground
  for (double y : {2.0, 3.0, 4.0}) EXPECT_EQ(copies_at(m, {3, y, 6}), 2) << y;
  EXPECT_EQ(copies_at(m, {3, 1, 6}), 1);
  // The ground triangles next to the fault moved to the copies of their tetrahedra.
  EXPECT_GT(r.renumbered_elements, 0u);
  EXPECT_EQ(r.unattached_elements, 0u);
  check_faulted(m);  // includes: every boundary triangle is a face of exactly one tetrahedron
  expect_glues_back(m, input);
}

TEST(FaultInsert, ThroughGoingFaultCutsTheModelInTwo) {
  Mesh m = unit_box(6);
  add_fault_group(m, "F", on_x3(0, 6, 0, 6));
  const Mesh input = m;
  const auto r = insert_faults(m);
  EXPECT_EQ(r.faults[0].nodes, 49u);
  EXPECT_EQ(r.faults[0].tip_nodes, 0u);
  EXPECT_EQ(r.new_nodes, 49u);
  EXPECT_EQ(pieces(input), 1);
  EXPECT_EQ(pieces(m), 2);
  check_faulted(m);
  expect_glues_back(m, input);
}

TEST(FaultInsert, TJunctionGivesThreeCopies) {
  Mesh m = unit_box(6);
  add_fault_group(m, "A", on_x3(0, 6, 0, 6));
  add_fault_group(m, "B", [](const Point3& p) { return near(p[1], 3) && p[0] < 3 + 1e-9; });  // abuts A from the west
  const Mesh input = m;
  const auto r = insert_faults(m);
  ASSERT_EQ(r.faults.size(), 2u);
  const auto& a = r.faults[0];
  const auto& b = r.faults[1];
  EXPECT_EQ(a.nodes, 49u);
  EXPECT_EQ(b.nodes, 28u);
  EXPECT_EQ(a.junction_nodes, 7u);
  EXPECT_EQ(b.junction_nodes, 7u);
  EXPECT_EQ(a.meets.at("B"), 7u);
  EXPECT_EQ(b.tip_nodes, 0u);             // its edge on A is not a tip: A separates it
  EXPECT_EQ(r.new_nodes, 42u + 21u + 7u * 2u);
  for (int z = 0; z <= 6; ++z) EXPECT_EQ(copies_at(m, {3, 3, double(z)}), 3) << z;
  EXPECT_EQ(copies_at(m, {1, 3, 2}), 2);
  EXPECT_EQ(copies_at(m, {3, 5, 2}), 2);
  check_faulted(m);
  expect_glues_back(m, input);
}

TEST(FaultInsert, XJunctionGivesFourCopies) {
  Mesh m = unit_box(6);
  add_fault_group(m, "A", on_x3(0, 6, 0, 6));
  add_fault_group(m, "B", [](const Point3& p) { return near(p[1], 3); });
  const Mesh input = m;
  const auto r = insert_faults(m);
  EXPECT_EQ(r.new_nodes, 42u + 42u + 7u * 3u);
  EXPECT_NEAR(r.faults[0].normal[0], -1.0, 1e-12);  // vertical, striking north: points west
  EXPECT_NEAR(r.faults[1].normal[1], -1.0, 1e-12);  // vertical, striking east: points south
  for (int z = 0; z <= 6; ++z) EXPECT_EQ(copies_at(m, {3, 3, double(z)}), 4) << z;
  EXPECT_EQ(pieces(m), 4);
  check_faulted(m);
  expect_glues_back(m, input);
}

TEST(FaultInsert, BuriedXJunctionEndsInTips) {
  // Two buried faults crossing: the junction line's ends lie on both faults' buried edges.
  Mesh m = unit_box(6);
  add_fault_group(m, "A", on_x3(1, 5, 1, 5));
  add_fault_group(m, "B", [](const Point3& p) { return near(p[1], 3) && p[0] > 1 - 1e-9 && p[0] < 5 + 1e-9 && p[2] > 1 - 1e-9 && p[2] < 5 + 1e-9; });
  const Mesh input = m;
  const auto r = insert_faults(m);
  for (int z = 2; z <= 4; ++z) EXPECT_EQ(copies_at(m, {3, 3, double(z)}), 4) << z;
  // At z = 1 and z = 5 the junction node is on both buried edges: the four sectors still meet below.
  EXPECT_EQ(copies_at(m, {3, 3, 1}), 1);
  EXPECT_EQ(r.faults[0].junction_nodes, 5u);
  check_faulted(m);
  expect_glues_back(m, input);
}

TEST(FaultInsert, InsertingOneAtATimeEqualsAllAtOnce) {
  Mesh m = unit_box(6);
  add_fault_group(m, "A", on_x3(0, 6, 0, 6));
  add_fault_group(m, "B", [](const Point3& p) { return near(p[1], 3); });
  const Mesh input = m;
  Mesh once = m;
  insert_faults(once);
  FaultInsertOptions only_a;
  only_a.only = {"A"};
  insert_faults(m, only_a);
  EXPECT_NE(m.find_physical(2, "fault:B"), nullptr);
  check_faulted(m);
  FaultInsertOptions only_b;
  only_b.only = {"fault:B"};
  const auto r = insert_faults(m, only_b);
  EXPECT_EQ(m.num_nodes(), once.num_nodes());
  for (int z = 0; z <= 6; ++z) EXPECT_EQ(copies_at(m, {3, 3, double(z)}), 4) << z;
  EXPECT_GT(r.renumbered_elements, 0u);  // A's prisms moved to B's copies
  check_faulted(m);
  expect_glues_back(m, input);
}

TEST(FaultInsert, SameInputSameOutput) {
  Mesh a = unit_box(4), b;
  add_fault_group(a, "F", [](const Point3& p) { return near(p[0], 2); });
  b = a;
  insert_faults(a);
  insert_faults(b);
  EXPECT_EQ(a.node_tags, b.node_tags);
  ASSERT_EQ(a.blocks.size(), b.blocks.size());
  for (std::size_t i = 0; i < a.blocks.size(); ++i) {
    EXPECT_EQ(a.blocks[i].nodes, b.blocks[i].nodes);
    EXPECT_EQ(a.blocks[i].tags, b.blocks[i].tags);
  }
}

TEST(FaultInsert, ReferenceNormalChoosesTheSides) {
  Mesh m = unit_box(4);
  add_fault_group(m, "F", [](const Point3& p) { return near(p[0], 2); });
  FaultInsertOptions o;
  o.reference_normals["F"] = {1, 0, 0};
  const auto r = insert_faults(m, o);
  EXPECT_NEAR(r.faults[0].normal[0], 1.0, 1e-12);
  check_faulted(m);
}

TEST(FaultInsert, HorizontalFaultNormalPointsDown) {
  Mesh m = unit_box(4);
  add_fault_group(m, "H", [](const Point3& p) { return near(p[2], 2) && p[0] > 1 - 1e-9 && p[0] < 3 + 1e-9; });
  const auto r = insert_faults(m);
  EXPECT_NEAR(r.faults[0].normal[2], -1.0, 1e-12);
  check_faulted(m);
}

// ---- refusals: InputError naming the fault ----

void expect_error(Mesh m, const FaultInsertOptions& o, const std::string& needle) {
  const Mesh before = m;
  try {
    insert_faults(m, o);
    ADD_FAILURE() << "no error, expected: " << needle;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
  EXPECT_EQ(m.num_nodes(), before.num_nodes());  // unchanged on error
  EXPECT_EQ(m.blocks.size(), before.blocks.size());
}

TEST(FaultInsertErrors, TriangleNotAMeshFace) {
  Mesh m = unit_box(4);
  // The other diagonal of the quad at x = 2: not a face of the Kuhn tetrahedra.
  const int e = m.entity_for_physical(2, "fault:G");
  auto id = [](int i, int j, int k) { return static_cast<std::uint32_t>(i + 5 * (j + 5 * k)); };
  const std::uint32_t t[3] = {id(2, 1, 1), id(2, 2, 1), id(2, 1, 2)};
  const std::uint32_t t2[3] = {id(2, 2, 1), id(2, 2, 2), id(2, 1, 2)};
  m.add_element(m.block(2, e, ElementType::Triangle), t);
  m.add_element(m.block(2, e, ElementType::Triangle), t2);
  FaultInsertOptions named;
  named.source = "box.msh";
  expect_error(m, named, "box.msh: fault 'G': triangle");
  expect_error(m, {}, "does not follow mesh faces");
}

TEST(FaultInsertErrors, NonManifoldEdge) {
  Mesh m = unit_box(6);
  // Three sheets meet along x = y = 3: one fault cannot hold them (two faults can: T-junction).
  auto x3 = [](const Point3& p) { return near(p[0], 3); };
  auto y3 = [](const Point3& p) { return near(p[1], 3) && p[0] < 3 + 1e-9; };
  add_fault_faces(m, "T", [&](const Point3& a, const Point3& b, const Point3& c) {
    return (x3(a) && x3(b) && x3(c)) || (y3(a) && y3(b) && y3(c));
  });
  expect_error(m, {}, "fault 'T' has a non-manifold edge");
}

TEST(FaultInsertErrors, CellWithFourNodesOnTheFault) {
  Mesh m = unit_box(6);
  // An L-shaped fault bending around an edge: corner tetrahedra have all four nodes on it.
  auto vertical = [](const Point3& p) { return near(p[0], 3) && p[2] < 3 + 1e-9; };
  auto flat = [](const Point3& p) { return near(p[2], 3) && p[0] > 3 - 1e-9; };
  add_fault_faces(m, "L", [&](const Point3& a, const Point3& b, const Point3& c) {
    return (vertical(a) && vertical(b) && vertical(c)) || (flat(a) && flat(b) && flat(c));
  });
  expect_error(m, {}, "all four nodes on the fault");
}

TEST(FaultInsertErrors, FaultOnTheModelBoundary) {
  Mesh m = unit_box(3);
  add_fault_group(m, "W", [](const Point3& p) { return near(p[0], 0); });
  expect_error(m, {}, "fault 'W'");
  expect_error(m, {}, "model boundary");
}

TEST(FaultInsertErrors, UnknownAndAlreadyInserted) {
  Mesh m = unit_box(4);
  add_fault_group(m, "F", [](const Point3& p) { return near(p[0], 2); });
  FaultInsertOptions o;
  o.only = {"nope"};
  expect_error(m, o, "unknown fault 'nope' (fault groups in the mesh: F)");
  insert_faults(m);
  expect_error(m, {}, "fault F already has interface elements");
  o.only = {"F"};
  expect_error(m, o, "fault 'F' already has interface elements");
  Mesh plain = unit_box(2);
  expect_error(plain, {}, "no fault triangle groups");
}

TEST(FaultInsertErrors, TwoFaultsShareATriangle) {
  Mesh m = unit_box(4);
  add_fault_group(m, "A", [](const Point3& p) { return near(p[0], 2); });
  add_fault_group(m, "B", [](const Point3& p) { return near(p[0], 2) && p[1] < 2 + 1e-9; });
  expect_error(m, {}, "faults 'A' and 'B' share triangle");
}

}  // namespace
}  // namespace ugs::test
