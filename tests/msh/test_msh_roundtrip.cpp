// MSH 4.1 round trips: ASCII <-> binary <-> ASCII is exact, interface prisms and provenance
// survive, and the gmsh SDK reads what we write with the same counts and physical names.
#include <gmsh.h>
#include <gtest/gtest.h>

#include "run_tool.hpp"
#include "ugs/formats/msh.hpp"

namespace fs = std::filesystem;
using namespace ugs;

namespace {

Mesh cube_with_interface() {
  Mesh m = test::unit_cube_mesh();
  // A zero-thickness interface prism on twins of the top face nodes (topology only for I/O).
  std::uint32_t twins[3];
  const std::uint32_t side1[3] = {4, 5, 7};
  for (int k = 0; k < 3; ++k) twins[k] = m.add_node(m.nodes[side1[k]]);
  const int f = m.entity_for_physical(3, "fault:F1");
  auto& b = m.block(3, f, ElementType::Prism);
  const std::uint32_t prism[6] = {side1[0], side1[1], side1[2], twins[0], twins[1], twins[2]};
  m.add_element(b, prism);
  m.update_entity_bboxes();
  return m;
}

std::string write_to_string(const Mesh& m, MshEncoding enc, const fs::path& dir, const std::string& name) {
  const auto p = dir / name;
  write_msh(m, p.string(), enc);
  return test::slurp(p);
}

}  // namespace

TEST(MshRoundTrip, AsciiBinaryAsciiIsExact) {
  const auto dir = test::temp_dir("msh-rt");
  Mesh m = cube_with_interface();
  m.nodes[3] = {0.1, 1.0 / 3.0, 1e-300};  // values that need all 17 digits
  const std::string a1 = write_to_string(m, MshEncoding::Ascii, dir, "a1.msh");
  const Mesh ma = read_msh((dir / "a1.msh").string());
  const std::string b1 = write_to_string(ma, MshEncoding::Binary, dir, "b1.msh");
  const Mesh mb = read_msh((dir / "b1.msh").string());
  const std::string a2 = write_to_string(mb, MshEncoding::Ascii, dir, "a2.msh");
  const std::string b2 = write_to_string(read_msh((dir / "a2.msh").string()), MshEncoding::Binary, dir, "b2.msh");
  EXPECT_EQ(a1, a2);
  EXPECT_EQ(b1, b2);
  ASSERT_EQ(mb.num_nodes(), m.num_nodes());
  for (std::size_t i = 0; i < m.num_nodes(); ++i) {
    EXPECT_EQ(mb.node_tags[i], m.node_tags[i]);
    EXPECT_EQ(mb.nodes[i], m.nodes[i]);  // bit-exact doubles
  }
  EXPECT_EQ(mb.count(ElementType::Tetrahedron), 6u);
  EXPECT_EQ(mb.count(ElementType::Triangle), 2u);
  EXPECT_EQ(mb.count(ElementType::Prism), 1u);
  ASSERT_EQ(mb.provenance.size(), 1u);
  EXPECT_EQ(mb.provenance[0], "unit_cube_mesh (test)");
  ASSERT_NE(mb.find_physical(3, "fault:F1"), nullptr);
  fs::remove_all(dir);
}

TEST(MshRoundTrip, KeepsSparseTagsAndMaterials) {
  const auto dir = test::temp_dir("msh-tags");
  Mesh m = test::unit_cube_mesh();
  for (auto& t : m.node_tags) t = t * 1000 + 7;  // sparse, non-contiguous tags
  for (auto& b : m.blocks)
    for (auto& t : b.tags) t += 500000;
  write_msh(m, (dir / "s.msh").string());
  const Mesh r = read_msh((dir / "s.msh").string());
  EXPECT_EQ(r.node_tags, m.node_tags);
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    EXPECT_EQ(r.blocks[b].tags, m.blocks[b].tags);
    EXPECT_EQ(r.blocks[b].nodes, m.blocks[b].nodes);
    EXPECT_EQ(r.physical_name_of(r.blocks[b].entity_dim, r.blocks[b].entity_tag),
              m.physical_name_of(m.blocks[b].entity_dim, m.blocks[b].entity_tag));
  }
  fs::remove_all(dir);
}

TEST(MshRoundTrip, ReadsFromAnInMemoryStreamWithoutSize) {
  // The reader must not depend on seeking: parse from a stream object.
  const auto dir = test::temp_dir("msh-stream");
  write_msh(test::unit_cube_mesh(), (dir / "c.msh").string(), MshEncoding::Binary);
  auto in = InputStream::from_string(test::slurp(dir / "c.msh"), "mem");
  const Mesh m = read_msh(*in);
  EXPECT_EQ(m.count(ElementType::Tetrahedron), 6u);
  fs::remove_all(dir);
}

class GmshSdk : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    gmsh::initialize();
    gmsh::option::setNumber("General.Terminal", 0);
  }
  static void TearDownTestSuite() { gmsh::finalize(); }
};

TEST_F(GmshSdk, OpensWhatWeWriteWithSameCountsAndNames) {
  const auto dir = test::temp_dir("msh-gmsh");
  const Mesh m = cube_with_interface();
  for (auto enc : {MshEncoding::Binary, MshEncoding::Ascii}) {
    const auto p = dir / (enc == MshEncoding::Binary ? "b.msh" : "a.msh");
    write_msh(m, p.string(), enc);
    gmsh::clear();
    gmsh::open(p.string());
    std::vector<std::size_t> node_tags;
    std::vector<double> coord, param;
    gmsh::model::mesh::getNodes(node_tags, coord, param, -1, -1, false, false);
    EXPECT_EQ(node_tags.size(), m.num_nodes());
    for (auto [type, expected] : {std::pair{4, 6u}, std::pair{2, 2u}, std::pair{6, 1u}}) {
      std::vector<std::size_t> et, en;
      gmsh::model::mesh::getElementsByType(type, et, en);
      EXPECT_EQ(et.size(), expected) << "gmsh type " << type;
    }
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups);
    EXPECT_EQ(groups.size(), m.physicals.size());
    for (const auto& [dim, tag] : groups) {
      std::string name;
      gmsh::model::getPhysicalName(dim, tag, name);
      const PhysicalGroup* p = m.find_physical_tag(dim, tag);
      ASSERT_NE(p, nullptr);
      EXPECT_EQ(name, p->name);
    }
  }
  fs::remove_all(dir);
}

TEST_F(GmshSdk, WeReadWhatGmshWrites) {
  const auto dir = test::temp_dir("msh-fromgmsh");
  gmsh::clear();
  gmsh::model::add("box");
  gmsh::model::occ::addBox(0, 0, 0, 1, 2, 3);
  gmsh::model::occ::synchronize();
  gmsh::model::addPhysicalGroup(3, {1}, 7);
  gmsh::model::setPhysicalName(3, 7, "mat:rock");
  gmsh::option::setNumber("Mesh.MeshSizeMax", 0.5);
  gmsh::model::mesh::generate(3);
  std::vector<std::size_t> et, en;
  gmsh::model::mesh::getElementsByType(4, et, en);
  for (int binary : {0, 1}) {
    gmsh::option::setNumber("Mesh.Binary", binary);
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::option::setNumber("Mesh.SaveAll", 0);
    const auto p = dir / (binary ? "g-bin.msh" : "g-asc.msh");
    gmsh::write(p.string());
    const Mesh m = read_msh(p.string());
    EXPECT_EQ(m.count(ElementType::Tetrahedron), et.size());
    ASSERT_NE(m.find_physical(3, "mat:rock"), nullptr);
    double vol = 0;
    for (const auto& b : m.blocks)
      if (b.type == ElementType::Tetrahedron)
        for (std::size_t i = 0; i < b.size(); ++i) {
          auto n = b.element(i);
          vol += tet_signed_volume(m.nodes[n[0]], m.nodes[n[1]], m.nodes[n[2]], m.nodes[n[3]]);
        }
    EXPECT_NEAR(vol, 6.0, 1e-9);
  }
  fs::remove_all(dir);
}
