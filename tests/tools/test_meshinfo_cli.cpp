// ugs-meshinfo as users run it: counts from a file and through a real pipe, --help/--version,
// and every bad-input case of the foundation issue: exit code 2, a one-line error naming the
// file and the line or byte offset, and no output file left behind.
#include <gtest/gtest.h>

#include <cstring>
#include <regex>

#include "run_tool.hpp"
#include "ugs/formats/msh.hpp"

namespace fs = std::filesystem;
using namespace ugs;

namespace {

class MeshinfoCli : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = test::temp_dir("meshinfo");
    write_msh(test::unit_cube_mesh(), (dir_ / "cube.msh").string(), MshEncoding::Ascii);
    write_msh(test::unit_cube_mesh(), (dir_ / "cube-bin.msh").string(), MshEncoding::Binary);
    ascii_ = test::slurp(dir_ / "cube.msh");
    binary_ = test::slurp(dir_ / "cube-bin.msh");
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Writes `content` as bad.msh, runs the tool with --convert and checks the error contract.
  void expect_bad(const std::string& content, const std::string& expected_fragment) {
    const auto bad = dir_ / "bad.msh";
    const auto out = dir_ / "out.vtu";
    test::spit(bad, content);
    const auto r = test::run(test::tool("ugs-meshinfo") + " " + bad.string() + " --convert " + out.string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    // One line: "ugs-meshinfo: error: <file>:<line>: ..." or "<file>: byte N: ...".
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    const std::regex where("^ugs-meshinfo: error: " + bad.string() + "(:[0-9]+| byte [0-9]+|): .*\n$");
    EXPECT_TRUE(std::regex_match(r.err, where)) << r.err;
    EXPECT_NE(r.err.find(expected_fragment), std::string::npos) << "stderr: " << r.err;
    EXPECT_FALSE(fs::exists(out));
    for (const auto& e : fs::directory_iterator(dir_))
      EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
  }

  static std::string replace(std::string s, const std::string& from, const std::string& to) {
    const auto pos = s.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    return s.replace(pos, from.size(), to);
  }

  fs::path dir_;
  std::string ascii_, binary_;
};

}  // namespace

TEST_F(MeshinfoCli, ReportsCountsGroupsAndVolume) {
  const auto r = test::run(test::tool("ugs-meshinfo") + " " + (dir_ / "cube.msh").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("nodes: 8\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("tetrahedra: 6\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("triangles: 2\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("total 1 m3"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("inverted elements: 0"), std::string::npos) << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("3D +1 \"mat:rock\" +6 tetrahedra\n"))) << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("2D +2 \"bnd:top\" +2 triangles\n"))) << r.out;
}

TEST_F(MeshinfoCli, StreamsThroughARealPipe) {
  for (auto f : {"cube.msh", "cube-bin.msh"}) {
    const auto r = test::run("cat " + (dir_ / f).string() + " | " + test::tool("ugs-meshinfo") + " -");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("tetrahedra: 6\n"), std::string::npos) << r.out;
  }
  // No file argument means stdin too.
  const auto r = test::run(test::tool("ugs-meshinfo") + " < " + (dir_ / "cube-bin.msh").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(MeshinfoCli, CountsInvertedTetrahedra) {
  Mesh m = test::unit_cube_mesh();
  for (auto& b : m.blocks)
    if (b.type == ElementType::Tetrahedron) std::swap(b.nodes[0], b.nodes[1]);  // invert the first tet
  write_msh(m, (dir_ / "inv.msh").string());
  const auto r = test::run(test::tool("ugs-meshinfo") + " " + (dir_ / "inv.msh").string() + " --fail-on-inverted");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("inverted elements: 1"), std::string::npos) << r.out;
}

TEST_F(MeshinfoCli, HelpShowsAWorkedExampleAndVersionWorks) {
  auto r = test::run(test::tool("ugs-meshinfo") + " --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("Example:\n  ugs-meshinfo model.msh"), std::string::npos) << r.out;
  r = test::run(test::tool("ugs-meshinfo") + " --version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("ugs-meshinfo (ugs) "), std::string::npos);
  r = test::run(test::tool("ugs-meshinfo") + " --no-such-option");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.rfind("ugs-meshinfo: error: ", 0), 0u) << r.err;
}

TEST_F(MeshinfoCli, MissingFile) {
  const auto r = test::run(test::tool("ugs-meshinfo") + " " + (dir_ / "nope.msh").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nope.msh: cannot open"), std::string::npos) << r.err;
}

TEST_F(MeshinfoCli, EmptyInput) { expect_bad("", "empty input"); }

TEST_F(MeshinfoCli, NotAMeshFile) { expect_bad("hello\nworld\n", "expected a section header"); }

TEST_F(MeshinfoCli, UnsupportedVersion) {
  expect_bad(replace(ascii_, "4.1 0 8", "2.2 0 8"), "MSH version 2.2 is not supported");
}

TEST_F(MeshinfoCli, TruncatedAsciiFile) { expect_bad(ascii_.substr(0, ascii_.find("$Elements") + 30), "truncated file?"); }

TEST_F(MeshinfoCli, TruncatedBinaryFile) {
  expect_bad(binary_.substr(0, binary_.find("$Nodes") + 60), "truncated file?");
}

TEST_F(MeshinfoCli, WrongNodeCount) {
  // Header says 9 nodes, the block holds 8.
  expect_bad(replace(ascii_, "$Nodes\n1 8 1 8\n", "$Nodes\n1 9 1 8\n"), "announces 9 nodes");
}

TEST_F(MeshinfoCli, CountLargerThanTheFileCanHold) {
  expect_bad(replace(ascii_, "$Nodes\n1 8 1 8\n", "$Nodes\n1 800000000000 1 8\n"), "larger than the file can hold");
}

TEST_F(MeshinfoCli, HugeElementCountInBinaryRefusedBeforeAllocating) {
  std::string b = binary_;
  const auto pos = b.find("$Elements\n") + 10 + 8;  // second size_t: number of elements
  const std::uint64_t huge = 1ull << 40;
  std::memcpy(b.data() + pos, &huge, 8);
  expect_bad(b, "larger than the file can hold");
}

TEST_F(MeshinfoCli, NanCoordinate) { expect_bad(replace(ascii_, "\n1 1 1\n", "\nnan 1 1\n"), "non-finite coordinate"); }

TEST_F(MeshinfoCli, InfCoordinate) { expect_bad(replace(ascii_, "\n1 1 1\n", "\n1 inf 1\n"), "non-finite coordinate"); }

// A finite but absurd coordinate (damage: 8 bytes of 0xff across two doubles gave -1.6e305) made the
// tetrahedron volumes overflow: "min -inf max inf total -nan" with exit 0 (found by mutation_tools).
TEST_F(MeshinfoCli, HugeCoordinate) {
  expect_bad(replace(ascii_, "\n1 1 1\n", "\n1 -1.6e305 1\n"), "beyond +-1e+09 m (expected metres in a projected CRS)");
}

TEST_F(MeshinfoCli, ElementReferringToMissingNode) {
  const auto pos = ascii_.find("$Elements");
  std::string s = ascii_;
  const auto line = s.find("\n1 1 ", pos);  // first element line "1 1 2 4 8"
  ASSERT_NE(line, std::string::npos);
  s.replace(line + 1, 4, "1 99");
  expect_bad(s, "refers to missing node 99");
}

TEST_F(MeshinfoCli, UnsupportedElementType) {
  std::string s = ascii_;
  const auto pos = s.find(" 4 6\n", s.find("$Elements"));  // block header: dim tag type=4 count=6
  ASSERT_NE(pos, std::string::npos);
  s.replace(pos, 5, " 11 6\n");
  expect_bad(s, "unsupported element type 11");
}

TEST_F(MeshinfoCli, TextWhereNumbersBelong) { expect_bad(replace(ascii_, "\n1 1 1\n", "\n1 one 1\n"), "expected a number"); }

TEST_F(MeshinfoCli, BinaryOfTheWrongEndianness) {
  std::string b = binary_;
  const auto pos = b.find("4.1 1 8\n") + 8;
  const std::uint32_t swapped = 0x01000000u;
  std::memcpy(b.data() + pos, &swapped, 4);
  expect_bad(b, "wrong endianness");
}
