// Sections through tetrahedra and the top of a layer: the slice polygons of a box tile the section
// plane exactly (their areas add up to length x depth), also when the section runs along mesh
// lines; the top of a layer of cells and the cells just above it; the confinement height.
#include <gtest/gtest.h>

#include <cmath>

#include "ugs/insar/sections.hpp"
#include "ugs/meshing/box_mesh.hpp"

using namespace ugs;
using namespace ugs::insar;

namespace {

struct Box {
  Mesh mesh;
  std::vector<Tet> tets;
  std::vector<char> layer;  // cells with centroid z in (-60, -40)
};

Box make_box() {
  BoxMeshSpec s;
  s.x = linspace(0, 1000, 10);
  s.y = linspace(0, 800, 8);
  s.z = {-100, -80, -60, -40, -20, 0};
  s.material = [](const Point3& c) { return c[2] > -60 && c[2] < -40 ? std::string("layer") : std::string("rock"); };
  Box b{make_box_mesh(s), {}, {}};
  const PhysicalGroup* layer = b.mesh.find_physical(3, "mat:layer");
  for (const auto& blk : b.mesh.blocks) {
    if (blk.type != ElementType::Tetrahedron) continue;
    const bool in = b.mesh.find_entity(3, blk.entity_tag)->physicals.front() == layer->tag;
    for (std::size_t i = 0; i < blk.size(); ++i) {
      const auto e = blk.element(i);
      b.tets.push_back({e[0], e[1], e[2], e[3]});
      b.layer.push_back(in ? 1 : 0);
    }
  }
  return b;
}

double total_area(const SectionSlice& s) {
  double a = 0;
  for (std::size_t p = 0; p + 1 < s.offsets.size(); ++p) {
    double twice = 0;
    for (int i = s.offsets[p]; i < s.offsets[p + 1]; ++i) {
      const int j = i + 1 < s.offsets[p + 1] ? i + 1 : s.offsets[p];
      twice += s.sz[2 * i] * s.sz[2 * j + 1] - s.sz[2 * j] * s.sz[2 * i + 1];
    }
    a += std::abs(twice) / 2;
  }
  return a;
}

}  // namespace

TEST(Sections, SlicesTileTheSectionPlane) {
  const Box b = make_box();
  // Oblique, a polyline with a bend, and one along mesh lines (y = 400 is a node plane).
  const std::vector<std::vector<std::array<double, 2>>> lines = {
      {{50, 60}, {930, 710}}, {{100, 100}, {500, 700}, {900, 150}}, {{0, 400}, {1000, 400}}};
  for (const auto& l : lines) {
    const SectionSlice s = slice_tets(b.mesh.nodes, b.tets, "s", l, -1e9, 1e9);
    double len = 0;
    for (std::size_t k = 0; k + 1 < l.size(); ++k) len += std::hypot(l[k + 1][0] - l[k][0], l[k + 1][1] - l[k][1]);
    EXPECT_NEAR(s.length, len, 1e-9);
    EXPECT_NEAR(total_area(s), len * 100.0, 1e-6 * len * 100.0) << "polyline of " << l.size() << " points";
  }
  // A depth window clips the polygons to it: inside the one 20 m layer between -60 and -40 they tile
  // the 18 m of the window; across three layers, the 45 m from -75 to -30 (no blank wedges).
  const SectionSlice w = slice_tets(b.mesh.nodes, b.tets, "w", lines[0], -59, -41);
  EXPECT_NEAR(total_area(w), std::hypot(880, 650) * 18.0, 1e-6 * 1e5);
  const SectionSlice w3 = slice_tets(b.mesh.nodes, b.tets, "w3", lines[1], -75, -30);
  EXPECT_NEAR(total_area(w3), w3.length * 45.0, 1e-6 * w3.length * 45.0);
  for (std::size_t i = 0; i < w3.sz.size(); i += 2) {
    EXPECT_GE(w3.sz[i + 1], -75.0);
    EXPECT_LE(w3.sz[i + 1], -30.0);
  }
}

TEST(Sections, LayerTopAndConfinementHeight) {
  const Box b = make_box();
  const LayerTop top = layer_top(b.mesh.nodes, b.mesh.node_tags, b.tets, b.layer);
  // The top of the layer is the plane z = -40: 10 x 8 quads, two triangles each.
  ASSERT_EQ(top.surface.triangles.size(), 160u);
  for (const auto& p : top.surface.points) EXPECT_EQ(p[2], -40.0);
  for (auto a : top.above) {
    ASSERT_GE(a, 0);
    EXPECT_FALSE(b.layer[static_cast<std::size_t>(a)]);
  }
  // Values: 1 in the layer, 0.02 in the cells of the next layer up, 0.005 above.
  std::vector<double> v(b.tets.size());
  for (std::size_t e = 0; e < b.tets.size(); ++e) {
    double z = 0;
    for (auto n : b.tets[e]) z += b.mesh.nodes[n][2] / 4;
    v[e] = b.layer[e] ? -1.0 : (z > -40 && z < -20 ? 0.02 : 0.005);
  }
  const SurfaceLocator loc(top.surface);
  const auto h = confinement_height(b.mesh.nodes, b.tets, v, b.layer, loc, 0.01);
  EXPECT_EQ(h.peak, 1.0);
  EXPECT_NEAR(h.height, 15.0, 1e-9);  // Kuhn tetrahedra of a 20 m layer: centroids 5, 10, 15 m up
  EXPECT_EQ(h.cells_over, 10u * 8u * 6u);
  EXPECT_EQ(h.cells_above, 10u * 8u * 6u * 2u);
  // The next layer up under a pressure change of its own (another pool): left out, and nothing
  // above it reaches 1 % of the peak.
  std::vector<char> own(b.tets.size(), 0);
  for (std::size_t e = 0; e < b.tets.size(); ++e) {
    double z = 0;
    for (auto n : b.tets[e]) z += b.mesh.nodes[n][2] / 4;
    own[e] = !b.layer[e] && z > -40 && z < -20;
  }
  const auto rock = confinement_height(b.mesh.nodes, b.tets, v, b.layer, loc, 0.01, own);
  EXPECT_EQ(rock.peak, 1.0);
  EXPECT_EQ(rock.height, 0.0);
  EXPECT_EQ(rock.cells_over, 0u);
  EXPECT_EQ(rock.cells_above, 10u * 8u * 6u);
  // With the values above it raised to 0.02, they set the height: centroids up to 35 m.
  for (std::size_t e = 0; e < b.tets.size(); ++e)
    if (!b.layer[e] && !own[e]) v[e] = 0.02;
  const auto far = confinement_height(b.mesh.nodes, b.tets, v, b.layer, loc, 0.01, own);
  EXPECT_NEAR(far.height, 35.0, 1e-9);
  EXPECT_EQ(far.cells_over, 10u * 8u * 6u);
  EXPECT_THROW(confinement_height(b.mesh.nodes, b.tets, v, b.layer, loc, 0.01, std::vector<char>(3, 0)), std::logic_error);
}
