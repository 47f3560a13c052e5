// MSH 4.1 round trips: ASCII <-> binary <-> ASCII is exact, interface prisms and provenance
// survive, and the gmsh SDK reads what we write with the same counts and physical names.
#include <gmsh.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <regex>

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

// ---- issue 20: errors name the offending record: the byte offset of the element in binary input
// (not of the 64 k-element chunk read), "byte N" wording throughout binary input, lines for ASCII.
namespace {

std::string error_of(const std::string& bytes) {
  auto in = InputStream::from_string(bytes, "m.msh");
  try {
    read_msh(*in);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// Offset of the binary element record (tag, then its node tags) of `element` in `bytes`.
std::size_t record_offset(const std::string& bytes, const Mesh& m, std::uint64_t element) {
  for (const auto& b : m.blocks)
    for (std::size_t i = 0; i < b.size(); ++i)
      if (b.tags[i] == element) {
        std::string rec(reinterpret_cast<const char*>(&b.tags[i]), 8);
        for (auto n : b.element(i)) {
          const std::uint64_t t = m.node_tags[n];
          rec.append(reinterpret_cast<const char*>(&t), 8);
        }
        return bytes.find(rec);
      }
  return std::string::npos;
}

}  // namespace

TEST(MshErrors, BinaryElementErrorsNameTheElementsByteOffset) {
  const auto dir = test::temp_dir("msh-errors");
  const Mesh m = test::unit_cube_mesh();
  std::string bytes = write_to_string(m, MshEncoding::Binary, dir, "c.msh");
  const std::size_t at = record_offset(bytes, m, 4);
  ASSERT_NE(at, std::string::npos);
  const std::uint64_t missing = 99;
  std::string bad = bytes;
  bad.replace(at + 16, 8, std::string(reinterpret_cast<const char*>(&missing), 8));  // its second node
  EXPECT_EQ(error_of(bad), fmt::format("m.msh: byte {}: element 4 refers to missing node 99", at));
  const std::uint64_t zero = 0;
  bad = bytes;
  bad.replace(at, 8, std::string(reinterpret_cast<const char*>(&zero), 8));
  EXPECT_EQ(error_of(bad), fmt::format("m.msh: byte {}: element tag 0 is not allowed", at));
  // A node coordinate: the offset of that node's coordinates.
  const double x78[6] = {0, 1, 1, 1, 1, 1};  // nodes 7 and 8 of the cube
  const std::size_t c7 = bytes.find(std::string(reinterpret_cast<const char*>(x78), 48), bytes.find("$Nodes"));
  ASSERT_NE(c7, std::string::npos);
  const std::size_t c = c7 + 24;
  const double inf = std::numeric_limits<double>::infinity();
  bad = bytes;
  bad.replace(c + 8, 8, std::string(reinterpret_cast<const char*>(&inf), 8));
  EXPECT_EQ(error_of(bad), fmt::format("m.msh: byte {}: node 8 has a non-finite coordinate", c));
  fs::remove_all(dir);
}

TEST(MshErrors, BinaryHeadersUseByteWordingAndIndicesAreChecked) {
  const auto dir = test::temp_dir("msh-errors2");
  const Mesh m = test::unit_cube_mesh();
  const std::string bytes = write_to_string(m, MshEncoding::Binary, dir, "c.msh");
  // The element block header: an unsupported type, at the offset of the block header.
  const std::size_t els = bytes.find("$Elements\n") + 10 + 32;  // after the 4 size_t of the section header
  std::string bad = bytes;
  const int type = 99;
  bad.replace(els + 8, 4, std::string(reinterpret_cast<const char*>(&type), 4));
  const std::string e = error_of(bad);
  EXPECT_EQ(e.rfind(fmt::format("m.msh: byte {}: unsupported element type 99", els), 0), 0u) << e;
  // A section that does not end: "byte N", never a line number, in a binary file.
  const std::string cut = bytes.substr(0, bytes.find("$EndNodes")) + "$Junk\n";
  EXPECT_TRUE(std::regex_search(error_of(cut), std::regex("^m\\.msh: byte [0-9]+: "))) << error_of(cut);
  // ASCII: entity tags and physical tags are checked before use, with the line.
  const std::string ascii = write_to_string(m, MshEncoding::Ascii, dir, "a.msh");
  const auto ent = ascii.find("$Entities\n");
  const auto line_of = [&](std::size_t pos) { return std::count(ascii.begin(), ascii.begin() + pos, '\n') + 1; };
  const auto vol = ascii.find("\n", ascii.find("\n", ent) + 1) + 1;  // first entity line (the cube's volume)
  std::string a = ascii;
  a.replace(vol, 1, "0");  // entity tag 1 -> 0
  EXPECT_EQ(error_of(a).rfind(fmt::format("m.msh:{}: entity tag 0 must be positive", line_of(vol)), 0), 0u) << error_of(a);
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

// Entity boxes of a mesh large enough for the two-thread split (over 4 million node references):
// each entity's box equals the one met in element order, bit for bit (signed zeros too: bounds of
// +0 and -0 where the first met wins), with two blocks of one entity and an entity without elements.
TEST(EntityBoxes, LargeMeshEqualsTheElementOrderBox) {
  Mesh m;
  std::uint64_t state = 23;
  auto next = [&] {  // a fixed sequence (xorshift), no library generator: the same on every platform
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return state;
  };
  for (int i = 0; i < 200000; ++i) {
    Point3 x{static_cast<double>(next() % 100000) - 50000, static_cast<double>(next() % 100000),
             -static_cast<double>(next() % 5000)};
    if (i % 1000 == 7) x[1] = 0.0;    // y bounds of +0 ...
    if (i % 1000 == 501) x[1] = -0.0;  // ... and -0
    m.add_node(x);
  }
  for (int tag = 1; tag <= 4; ++tag) m.entities.push_back({3, tag, {}, {}});
  const int block_entity[5] = {1, 2, 3, 1, 2};  // entity 4 has none; 1 and 2 have two blocks each
  std::size_t refs = 0;
  for (int e : block_entity) {
    ElementBlock b;
    b.entity_dim = 3;
    b.entity_tag = e;
    b.type = ElementType::Tetrahedron;
    const std::size_t n = e == 3 ? 400000 : 200000;
    for (std::size_t i = 0; i < 4 * n; ++i) b.nodes.push_back(static_cast<std::uint32_t>(next() % (e == 2 ? 1000 : 200000)));
    b.tags.resize(n);
    refs += b.nodes.size();
    m.blocks.push_back(std::move(b));
  }
  ASSERT_GT(refs, std::size_t{1} << 22);
  m.update_entity_bboxes();
  for (int tag = 1; tag <= 4; ++tag) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    std::array<double, 6> want{inf, inf, inf, -inf, -inf, -inf};
    for (const auto& b : m.blocks)
      if (b.entity_tag == tag)
        for (auto n : b.nodes)
          for (int k = 0; k < 3; ++k) {
            want[k] = std::min(want[k], m.nodes[n][k]);
            want[k + 3] = std::max(want[k + 3], m.nodes[n][k]);
          }
    if (want[0] > want[3]) want = {};
    const auto& got = m.entities[static_cast<std::size_t>(tag - 1)].bbox;
    EXPECT_EQ(std::memcmp(got.data(), want.data(), sizeof want), 0)
        << "entity " << tag << ": " << fmt::format("{}", fmt::join(got, " ")) << " vs " << fmt::format("{}", fmt::join(want, " "));
  }
  EXPECT_EQ(m.entities[3].bbox, (std::array<double, 6>{}));
  EXPECT_EQ(m.entities[1].bbox[1], 0.0);  // entity 2's nodes 0 .. 999 hold the +0 (node 7) and -0 (node 501)
}
