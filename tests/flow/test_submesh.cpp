// Sub-mesh extraction (meshing/submesh.hpp): materials, polygon clipping, parent tags, and faults —
// barriers given as triangles (nodes duplicated, flow stops), interface prisms of a faulted mesh
// (ties: flow crosses as in the continuous mesh; as barriers: flow stops).
#include <gtest/gtest.h>

#include <set>

#include "flow_cases.hpp"
#include "ugs/flow/transient.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/meshing/box_mesh.hpp"
#include "ugs/meshing/submesh.hpp"

using namespace ugs;

namespace {

// 6 x 2 x 2 cells of 1 m: "pool" in the first cell column, "aquifer" elsewhere, "cap" on top.
BoxMeshSpec bar_spec() {
  BoxMeshSpec s;
  s.x = linspace(0, 6, 6);
  s.y = linspace(0, 2, 2);
  s.z = linspace(-1003, -1000, 3);
  s.material = [](const Point3& c) {
    if (c[2] > -1001) return std::string("cap");
    return std::string(c[0] < 1 ? "pool" : "aquifer");
  };
  return s;
}

std::uint32_t node_at(const Mesh& m, double x, double y, double z) {
  for (std::uint32_t n = 0; n < m.num_nodes(); ++n)
    if (std::abs(m.nodes[n][0] - x) < 1e-9 && std::abs(m.nodes[n][1] - y) < 1e-9 && std::abs(m.nodes[n][2] - z) < 1e-9) return n;
  return UINT32_MAX;
}

// Triangles of the plane x = x0 for z in [z0, z1], split as the Kuhn tetrahedra are (diagonal from
// the lower-index corner), in the group fault:<name>.
void add_fault_plane(Mesh& m, const BoxMeshSpec& s, double x0, double z_top, const std::string& name) {
  const int e = m.entity_for_physical(2, "fault:" + name);
  for (std::size_t j = 0; j + 1 < s.y.size(); ++j)
    for (std::size_t k = 0; k + 1 < s.z.size(); ++k) {
      if (s.z[k + 1] > z_top + 1e-9) continue;
      const std::uint32_t a = node_at(m, x0, s.y[j], s.z[k]), b = node_at(m, x0, s.y[j + 1], s.z[k]),
                          c = node_at(m, x0, s.y[j + 1], s.z[k + 1]), d = node_at(m, x0, s.y[j], s.z[k + 1]);
      const std::uint32_t t1[3] = {a, b, c}, t2[3] = {a, c, d};
      m.add_element(m.block(2, e, ElementType::Triangle), t1);
      m.add_element(m.block(2, e, ElementType::Triangle), t2);
    }
}

// Pressure change at the end of a short depletion of the pool, per sub-mesh node.
std::vector<double> deplete(const Mesh& sub) {
  test::AquiferParams a;
  CaseFile c = test::aquifer_case(a);
  const flow::FlowModel fm = flow::build_flow_model(sub, c);
  const flow::TimeGrid g = test::step_grid(test::uniform_dates(100, 2000), -1e6);
  const flow::TransientResult r = flow::run_transient(fm, g);
  std::vector<double> dp(sub.num_nodes());
  for (std::size_t n = 0; n < sub.num_nodes(); ++n) dp[n] = r.dp[fm.dof_of_node[n]];
  return dp;
}

}  // namespace

TEST(Submesh, MaterialsByNameAndIdKeepParentTags) {
  const BoxMeshSpec s = bar_spec();
  const Mesh parent = make_box_mesh(s);
  const int pool_id = parent.find_physical(3, "mat:pool")->tag;
  SubmeshReport r;
  const Mesh sub = extract_submesh(parent, {{std::to_string(pool_id), "mat:aquifer"}, {}, {}}, &r);
  EXPECT_EQ(r.tetrahedra, 6u * 2u * 2u * 6u);   // 6 x 2 x 2 cells below the cap, 6 tets each
  EXPECT_EQ(sub.num_nodes(), 7u * 3u * 3u);     // the cap's top nodes are gone
  EXPECT_EQ(r.materials, (std::vector<std::string>{"pool", "aquifer"}));
  EXPECT_EQ(sub.find_physical(3, "mat:pool")->tag, pool_id);
  // Every sub-mesh node keeps its parent tag and position.
  const auto by_tag = parent.node_index_by_tag();
  for (std::size_t n = 0; n < sub.num_nodes(); ++n) {
    const auto p = by_tag.at(sub.node_tags[n]);
    EXPECT_EQ(sub.nodes[n], parent.nodes[p]);
  }
  // Element tags are the parent's; boundary triangles kept only where they are faces of kept cells.
  std::set<std::uint64_t> parent_tets;
  for (const auto& b : parent.blocks)
    if (b.type == ElementType::Tetrahedron) parent_tets.insert(b.tags.begin(), b.tags.end());
  for (const auto& b : sub.blocks)
    if (b.type == ElementType::Tetrahedron) {
      for (auto t : b.tags) EXPECT_TRUE(parent_tets.count(t));
    }
  EXPECT_FALSE(sub.find_physical(2, "bnd:top"));   // the top belongs to the cap
  EXPECT_TRUE(sub.find_physical(2, "bnd:bottom"));
  EXPECT_EQ(r.triangles, 2u * (6 * 2) + 2u * (6 * 2) * 2 + 2u * (2 * 2) * 2);  // bottom, south+north, west+east

  EXPECT_THROW(extract_submesh(parent, {{"nope"}, {}, {}}), InputError);
  EXPECT_THROW(extract_submesh(parent, {{"aquifer"}, {}, {"F9"}}), InputError);
}

TEST(Submesh, PolygonClipsByCentroid) {
  const Mesh parent = make_box_mesh(bar_spec());
  SubmeshSpec spec{{"aquifer", "pool"}, {{{-1, -1}, {2.1, -1}, {2.1, 5}, {-1, 5}}}, {}};
  SubmeshReport r;
  const Mesh sub = extract_submesh(parent, spec, &r);
  EXPECT_EQ(r.tetrahedra, 2u * 2u * 2u * 6u);  // the cells in x < 2, below the cap
  for (const auto& n : sub.nodes) EXPECT_LE(n[0], 2.0 + 1e-12);
  // A hole removes what it covers (even-odd rule over the rings).
  spec.rings.push_back({{1, -1}, {2, -1}, {2, 5}, {1, 5}});
  const Mesh holed = extract_submesh(parent, spec, &r);
  EXPECT_EQ(r.tetrahedra, 2u * 6u * 2u);
  EXPECT_THROW(extract_submesh(parent, {{"aquifer"}, {{{10, 10}, {11, 10}, {11, 11}}}, {}}), InputError);
  EXPECT_TRUE(inside_rings({{{0, 0}, {1, 0}, {1, 1}, {0, 1}}}, 0.5, 0.5));
  EXPECT_FALSE(inside_rings({{{0, 0}, {1, 0}, {1, 1}, {0, 1}}}, 1.5, 0.5));
}

TEST(Submesh, BarrierTrianglesCutTheFlow) {
  const BoxMeshSpec s = bar_spec();
  Mesh parent = make_box_mesh(s);
  add_fault_plane(parent, s, 3.0, -1001, "F");  // the full cross-section below the cap
  SubmeshReport r;
  const Mesh sub = extract_submesh(parent, {{"pool", "aquifer"}, {}, {"fault:F"}}, &r);
  EXPECT_EQ(r.duplicated_nodes, 3u * 3u);  // every node of the plane x = 3 below the cap (3 in y x 3 in z)
  const PhysicalGroup* twin = sub.find_physical(1, "twin:F");
  ASSERT_TRUE(twin);
  std::size_t lines = 0;
  for (const auto& b : sub.blocks)
    if (b.type == ElementType::Line) {
      lines += b.size();
      for (std::size_t i = 0; i < b.size(); ++i) {
        const auto e = b.element(i);
        EXPECT_EQ(sub.nodes[e[0]], sub.nodes[e[1]]);             // same place
        EXPECT_LE(sub.node_tags[e[0]], parent.max_node_tag());  // node 1: the parent node
        EXPECT_GT(sub.node_tags[e[1]], parent.max_node_tag());  // node 2: its duplicate, a new tag
      }
    }
  EXPECT_EQ(lines, 9u);
  // Flow stops at the barrier: beyond it the pressure does not change at all.
  const auto dp = deplete(sub);
  double left = 0;
  for (std::size_t n = 0; n < sub.num_nodes(); ++n) {
    const bool beyond = sub.nodes[n][0] > 3 + 1e-9 || (sub.node_tags[n] > parent.max_node_tag());
    if (beyond) {
      EXPECT_EQ(dp[n], 0.0) << "node " << sub.node_tags[n];
    }
    if (sub.nodes[n][0] > 1.5 && sub.nodes[n][0] < 2.5) left = std::min(left, dp[n]);
  }
  EXPECT_LT(left, -1e3);  // the near side did see the depletion
}

TEST(Submesh, PartialBarrierLetsFlowAroundItsEdge) {
  BoxMeshSpec s = bar_spec();
  s.z = linspace(-1004, -1000, 4);
  s.material = [](const Point3& c) { return std::string(c[0] < 1 ? "pool" : "aquifer"); };
  Mesh parent = make_box_mesh(s);
  add_fault_plane(parent, s, 3.0, -1002, "F");  // lower half only: its upper edge is inside
  SubmeshReport r;
  const Mesh sub = extract_submesh(parent, {{}, {}, {"F"}}, &r);
  EXPECT_EQ(r.duplicated_nodes, 3u * 2u);  // z = -1004 and -1003; the edge nodes at -1002 stay shared
  const auto dp = deplete(sub);
  const auto far = node_at(sub, 5, 0, -1004);
  EXPECT_LT(dp[far], -1.0);  // water reached the far side around the fault's edge
}

// A faulted parent as ugs-faultinsert makes it: the plane x = 3 split, the tetrahedra beyond it on
// twin nodes, interface prisms (nodes 1-3 near side, 4-6 twins) in fault:F.
TEST(Submesh, InterfacePrismsTiedUnlessBarrier) {
  const BoxMeshSpec s = bar_spec();
  const Mesh continuous = make_box_mesh(s);
  Mesh faulted = continuous;
  std::map<std::uint32_t, std::uint32_t> twin;
  for (std::uint32_t n = 0; n < continuous.num_nodes(); ++n)
    if (std::abs(continuous.nodes[n][0] - 3) < 1e-9) twin[n] = faulted.add_node(continuous.nodes[n]);
  for (auto& b : faulted.blocks) {
    if (b.type != ElementType::Tetrahedron) continue;
    for (std::size_t i = 0; i < b.size(); ++i) {
      double cx = 0;
      for (auto n : b.element(i)) cx += 0.25 * continuous.nodes[n][0];
      if (cx > 3)
        for (int k = 0; k < 4; ++k)
          if (twin.count(b.nodes[i * 4 + k])) b.nodes[i * 4 + k] = twin[b.nodes[i * 4 + k]];
    }
  }
  Mesh with_faces = continuous;
  add_fault_plane(with_faces, s, 3.0, -1000, "F");
  const int e = faulted.entity_for_physical(3, "fault:F");
  for (const auto& b : with_faces.blocks)
    if (b.type == ElementType::Triangle && with_faces.physical_name_of(2, b.entity_tag) == "fault:F")
      for (std::size_t i = 0; i < b.size(); ++i) {
        const auto t = b.element(i);
        const std::uint32_t p[6] = {t[0], t[1], t[2], twin[t[0]], twin[t[1]], twin[t[2]]};
        faulted.add_element(faulted.block(3, e, ElementType::Prism), p);
      }
  SubmeshReport r;
  const Mesh tied = extract_submesh(faulted, {{"pool", "aquifer"}, {}, {}}, &r);
  EXPECT_EQ(r.dropped_interface_elements, 2u * 2u * 3u);
  EXPECT_EQ(r.tied_pairs, 3u * 3u);  // the plane's nodes below the cap
  EXPECT_EQ(faulted.count(ElementType::Prism), 12u);
  EXPECT_EQ(tied.count(ElementType::Prism), 0u);
  // Tied: the same pressures as the continuous mesh (node by node, through the parent tags).
  const Mesh cont_sub = extract_submesh(continuous, {{"pool", "aquifer"}, {}, {}});
  const auto dp_c = deplete(cont_sub), dp_t = deplete(tied);
  const auto by_tag = cont_sub.node_index_by_tag();
  for (std::size_t n = 0; n < tied.num_nodes(); ++n) {
    auto it = by_tag.find(tied.node_tags[n]);
    const std::size_t c = it != by_tag.end() ? it->second : node_at(cont_sub, tied.nodes[n][0], tied.nodes[n][1], tied.nodes[n][2]);
    EXPECT_NEAR(dp_t[n], dp_c[c], 1e-9 * 1e6);
  }
  // As a barrier: nothing tied, nothing crosses.
  const Mesh cut = extract_submesh(faulted, {{"pool", "aquifer"}, {}, {"F"}}, &r);
  EXPECT_EQ(r.tied_pairs, 0u);
  const auto dp_cut = deplete(cut);
  for (std::size_t n = 0; n < cut.num_nodes(); ++n)
    if (cut.nodes[n][0] > 3 + 1e-9) {
      EXPECT_EQ(dp_cut[n], 0.0);
    }
}
