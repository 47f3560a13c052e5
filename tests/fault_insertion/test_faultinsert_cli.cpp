// ugs-faultinsert end to end, and the faulted mesh through MSH 4.1 (ours and the gmsh SDK's):
// interface elements and twins survive a round trip, gmsh opens what we write, and bad input gives
// exit code 2, one line naming the fault, and no output file.
#include <gmsh.h>
#include <gtest/gtest.h>

#include <filesystem>

#include <fmt/format.h>

#include "fault_meshes.hpp"
#include "run_tool.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/fault_insert.hpp"

namespace ugs::test {
namespace {

namespace fs = std::filesystem;

// Box [0,6]^3 with a through-going fault A (x = 3) and a buried fault B (y = 3, x < 3) abutting it.
Mesh two_fault_box() {
  Mesh m = unit_box(6);
  add_fault_group(m, "A", [](const Point3& p) { return near(p[0], 3); });
  add_fault_group(m, "B", [](const Point3& p) { return near(p[1], 3) && p[0] < 3 + 1e-9 && p[2] > 1 - 1e-9 && p[2] < 5 + 1e-9; });
  return m;
}

std::map<std::uint64_t, std::vector<std::uint64_t>> prisms_by_tag(const Mesh& m) {
  std::map<std::uint64_t, std::vector<std::uint64_t>> r;
  for (const auto& b : m.blocks)
    if (b.type == ElementType::Prism)
      for (std::size_t e = 0; e < b.size(); ++e) {
        auto& v = r[b.tags[e]];
        for (auto n : b.element(e)) v.push_back(m.node_tags[n]);
      }
  return r;
}

class FaultMsh : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    gmsh::initialize();
    gmsh::option::setNumber("General.Terminal", 0);
  }
  static void TearDownTestSuite() { gmsh::finalize(); }
};

TEST_F(FaultMsh, RoundTripKeepsInterfaceElementsAndTwins) {
  Mesh m = two_fault_box();
  insert_faults(m);
  const auto dir = temp_dir("fault-msh");
  for (auto enc : {MshEncoding::Binary, MshEncoding::Ascii}) {
    const auto p = dir / (enc == MshEncoding::Binary ? "bin.msh" : "ascii.msh");
    write_msh(m, p.string(), enc);
    const Mesh r = read_msh(p.string());
    EXPECT_EQ(nodes_by_tag(r), nodes_by_tag(m));
    EXPECT_EQ(elements_by_tag(r, false), elements_by_tag(m, false));
    EXPECT_EQ(prisms_by_tag(r), prisms_by_tag(m));
    ASSERT_NE(r.find_physical(3, "fault:A"), nullptr);
    ASSERT_NE(r.find_physical(3, "fault:B"), nullptr);
    check_faulted(r);
  }
  std::filesystem::remove_all(dir);
}

TEST_F(FaultMsh, GmshOpensTheFaultedMesh) {
  Mesh m = two_fault_box();
  const auto before = m.num_nodes();
  const auto rep = insert_faults(m);
  const auto dir = temp_dir("fault-gmsh");
  const auto p = dir / "faulted.msh";
  write_msh(m, p.string());
  gmsh::clear();
  gmsh::open(p.string());
  std::vector<std::size_t> node_tags;
  std::vector<double> coord, param;
  gmsh::model::mesh::getNodes(node_tags, coord, param, -1, -1, false, false);
  EXPECT_EQ(node_tags.size(), before + rep.new_nodes);
  std::vector<std::size_t> et, en;
  gmsh::model::mesh::getElementsByType(6, et, en);
  EXPECT_EQ(et.size(), rep.faults[0].triangles + rep.faults[1].triangles);
  // gmsh sees the same prisms, node for node.
  const auto ours = prisms_by_tag(m);
  for (std::size_t i = 0; i < et.size(); ++i) {
    const auto& v = ours.at(et[i]);
    for (int k = 0; k < 6; ++k) EXPECT_EQ(en[6 * i + k], v[k]);
  }
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups);
  std::set<std::string> names;
  for (auto [dim, tag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(dim, tag, name);
    names.insert(std::to_string(dim) + " " + name);
  }
  EXPECT_TRUE(names.count("3 fault:A"));
  EXPECT_TRUE(names.count("3 fault:B"));
  EXPECT_FALSE(names.count("2 fault:A"));
  // And what gmsh writes back still holds them.
  const auto q = dir / "from-gmsh.msh";
  gmsh::option::setNumber("Mesh.Binary", 1);
  gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
  gmsh::option::setNumber("Mesh.SaveAll", 0);
  gmsh::write(q.string());
  const Mesh back = read_msh(q.string());
  EXPECT_EQ(prisms_by_tag(back), ours);
  check_faulted(back);
  std::filesystem::remove_all(dir);
}

// ---- the tool ----

struct FaultInsertTool : ::testing::Test {
  fs::path dir;
  void SetUp() override { dir = temp_dir(std::string("faultinsert-") + ::testing::UnitTest::GetInstance()->current_test_info()->name()); }
  void TearDown() override { fs::remove_all(dir); }
  std::string path(const std::string& n) const { return (dir / n).string(); }
  static std::string exe() { return tool("ugs-faultinsert"); }
};

TEST_F(FaultInsertTool, InsertsFromAFileAndReportsPerFault) {
  Mesh m = two_fault_box();
  write_msh(m, path("in.msh"));
  const auto r = run(exe() + " " + path("in.msh") + " -o " + path("out.msh"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  const Mesh out = read_msh(path("out.msh"));
  check_faulted(out);
  expect_glues_back(out, m);
  // Summary lines: name, source, triangles, area, nodes, duplicated, tips, intersections.
  EXPECT_NE(r.err.find(fmt::format("ugs-faultinsert: {:<24} {:<12} {:>10} {:>10} {:>8} {:>10} {:>6}  B (5)", "A", "mesh", 72,
                                   "3.6e-05", 49, 49, 0)),
            std::string::npos)
      << r.err;
  // B: 5 x 5 nodes (x 0..3 is 4 columns, z 1..5), buried except on the west boundary and on A.
  EXPECT_NE(r.err.find(fmt::format("{:<24} {:<12} {:>10} {:>10} {:>8} {:>10} {:>6}  A (5)", "B", "mesh", 24, "1.2e-05", 20,
                                   12, 8)),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("2 faults: "), std::string::npos) << r.err;
  EXPECT_EQ(out.provenance.back().rfind(exe(), 0), 0u);
}

TEST_F(FaultInsertTool, StreamsFromStdinToStdout) {
  Mesh m = two_fault_box();
  write_msh(m, path("in.msh"), MshEncoding::Ascii);
  const auto r = run("cat " + path("in.msh") + " | " + exe() + " -q --only B > " + path("out.msh"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const Mesh out = read_msh(path("out.msh"));
  EXPECT_NE(out.find_physical(3, "fault:B"), nullptr);
  EXPECT_NE(out.find_physical(2, "fault:A"), nullptr);  // not asked for: still triangles
  check_faulted(out);
  // Then A in a second run, through a pipe again.
  const auto r2 = run("cat " + path("out.msh") + " | " + exe() + " - -o " + path("out2.msh"));
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  check_faulted(read_msh(path("out2.msh")));
}

TEST_F(FaultInsertTool, TracesFromAVectorFile) {
  write_msh(unit_box(6), path("box.msh"));
  spit(dir / "faults.geojson", R"({"type":"FeatureCollection","features":[
{"type":"Feature","properties":{"name":"east","top_m":5,"bottom_m":1,"dip_deg":90,"dip_dir_deg":90},
 "geometry":{"type":"LineString","coordinates":[[3,1],[3,5]]}},
{"type":"Feature","properties":{"name":"dipping","top_m":6,"bottom_m":2,"dip_deg":45,"dip_dir_deg":270,"trace_z_m":6},
 "geometry":{"type":"LineString","coordinates":[[5,0],[5,6]]}}]})");
  const auto r = run(exe() + " " + path("box.msh") + " --faults " + path("faults.geojson") + " -o " + path("out.msh"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find(fmt::format("{:<24} {:<12} {:>10}", "east", "trace 100.0%", 32)), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(fmt::format("{:<24} {:<12} {:>10}", "dipping", "trace 100.0%", 48)), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("dipping (5)"), std::string::npos) << r.err;  // they cross along x = 3, z = 4
  const Mesh out = read_msh(path("out.msh"));
  EXPECT_EQ(out.count(ElementType::Prism), 80u);
  check_faulted(out);
  // --only picks one of them.
  const auto r2 = run(exe() + " " + path("box.msh") + " --faults " + path("faults.geojson") + " --only dipping -o " + path("one.msh"));
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  EXPECT_EQ(read_msh(path("one.msh")).count(ElementType::Prism), 48u);
}

TEST_F(FaultInsertTool, BadInputExitsTwoWithOneLineAndNoOutput) {
  Mesh m = two_fault_box();
  write_msh(m, path("in.msh"));
  auto expect_bad = [&](const std::string& args, const std::string& needle) {
    const auto r = run(exe() + " " + args + " -o " + path("bad.msh"));
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("ugs-faultinsert: error: ", 0), 0u) << r.err;
    EXPECT_FALSE(fs::exists(path("bad.msh")));
    for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos);
  };
  expect_bad(path("in.msh") + " --only nope", "unknown fault 'nope' (faults: A, B)");
  // Already faulted.
  ASSERT_EQ(run(exe() + " " + path("in.msh") + " -q -o " + path("faulted.msh")).exit_code, 0);
  expect_bad(path("faulted.msh"), "fault A, B already has interface elements");
  expect_bad(path("faulted.msh") + " --only A", "fault 'A' already has interface elements");
  // A trace the mesh does not follow.
  write_msh(unit_box(6), path("box.msh"));
  spit(dir / "off.geojson", R"({"type":"FeatureCollection","features":[
{"type":"Feature","properties":{"name":"off","top_m":5,"bottom_m":1,"dip_deg":90,"dip_dir_deg":90},
 "geometry":{"type":"LineString","coordinates":[[3.5,1],[3.5,5]]}}]})");
  expect_bad(path("box.msh") + " --faults " + path("off.geojson"), "fault 'off': mesh faces cover 0.0 %");
  spit(dir / "cross.geojson", R"({"type":"FeatureCollection","features":[
{"type":"Feature","properties":{"name":"bowtie","top_m":5,"bottom_m":1,"dip_deg":90,"dip_dir_deg":90},
 "geometry":{"type":"LineString","coordinates":[[1,1],[5,5],[5,1],[1,5]]}}]})");
  expect_bad(path("box.msh") + " --faults " + path("cross.geojson"), "fault 'bowtie': the trace crosses itself near (3.00, 3.00)");
  spit(dir / "deep.geojson", R"({"type":"FeatureCollection","features":[
{"type":"Feature","properties":{"name":"deep","top_m":-50,"bottom_m":-90,"dip_deg":90,"dip_dir_deg":90},
 "geometry":{"type":"LineString","coordinates":[[3,1],[3,5]]}}]})");
  expect_bad(path("box.msh") + " --faults " + path("deep.geojson"), "fault 'deep': its depth range");
  expect_bad(path("box.msh") + " --faults " + path("missing.geojson"), "missing.geojson");
  expect_bad(path("box.msh"), "no fault triangle groups");
  // A fault that does not follow mesh faces, given as a group.
  Mesh g = unit_box(4);
  const int e = g.entity_for_physical(2, "fault:skew");
  auto id = [](int i, int j, int k) { return static_cast<std::uint32_t>(i + 5 * (j + 5 * k)); };
  const std::uint32_t t[3] = {id(2, 1, 1), id(2, 2, 1), id(2, 1, 2)};
  g.add_element(g.block(2, e, ElementType::Triangle), t);
  write_msh(g, path("skew.msh"));
  expect_bad(path("skew.msh"), "fault 'skew': triangle");
}

// Issue 20: one faults file, one schema. A file that ugs-mesh2d and ugs-meshgen accept (names and
// depth ranges, no dip) was refused with "missing field 'dip_deg'" although the mesh holds the fault
// groups and the file then only gives the reference normal.
TEST_F(FaultInsertTool, FaultsFileWithoutDipsWhenTheMeshHasTheGroups) {
  Mesh m = two_fault_box();
  write_msh(m, path("in.msh"));
  spit(dir / "faults.geojson", R"({"type":"FeatureCollection","features":[
{"type":"Feature","properties":{"name":"A","top_m":6,"bottom_m":0},"geometry":{"type":"LineString","coordinates":[[3,0],[3,6]]}},
{"type":"Feature","properties":{"name":"B","dip_dir_deg":180},"geometry":{"type":"LineString","coordinates":[[0,3],[3,3]]}}]})");
  const auto r = run(exe() + " " + path("in.msh") + " --faults " + path("faults.geojson") + " -o " + path("out.msh"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Mesh out = read_msh(path("out.msh"));
  check_faulted(out);
  expect_glues_back(out, m);
  EXPECT_EQ(out.count(ElementType::Prism), 96u);  // A 72 + B 24, as from the mesh alone
  // B's reference normal from dip_dir_deg = 180 (dip 90): side 1 -> side 2 points north (+y), where
  // the mesh's own rule alone would point it south.
  for (const auto& b : out.blocks) {
    if (b.type != ElementType::Prism || out.physical_name_of(b.entity_dim, b.entity_tag) != "fault:B") continue;
    for (std::size_t e = 0; e < b.size(); ++e) {
      const auto& x1 = out.nodes[b.element(e)[0]];
      const auto& x2 = out.nodes[b.element(e)[1]];
      const auto& x3 = out.nodes[b.element(e)[2]];
      const double ny = (x2[2] - x1[2]) * (x3[0] - x1[0]) - (x2[0] - x1[0]) * (x3[2] - x1[2]);
      EXPECT_GT(ny, 0.0);
    }
  }
  // A fault the mesh lacks needs the whole trace: the message says which field and why.
  write_msh(unit_box(6), path("box.msh"));
  const auto bad = run(exe() + " " + path("box.msh") + " --faults " + path("faults.geojson") + " -o " + path("bad.msh"));
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_NE(bad.err.find("faults.geojson: feature 0: fault 'A': missing field 'dip_deg' (the mesh has no fault:A group to use, "
                         "so the file must give name, top_m, bottom_m, dip_deg, dip_dir_deg)"),
            std::string::npos)
      << bad.err;
  EXPECT_FALSE(fs::exists(path("bad.msh")));
}

// Issue 20: numeric options finite and in range, one readable line (CLI11's range check printed
// DBL_MAX in full).
TEST_F(FaultInsertTool, NonFiniteOptionsAreRefused) {
  write_msh(two_fault_box(), path("in.msh"));
  for (const char* v : {"inf", "nan", "-1"}) {
    const auto r = run(exe() + " " + path("in.msh") + " --tolerance " + v + " -o " + path("out.msh"));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err, fmt::format("ugs-faultinsert: error: --tolerance: {} (expected a finite number >= 0) (see --help)\n", v));
    EXPECT_FALSE(fs::exists(path("out.msh")));
  }
}

}  // namespace
}  // namespace ugs::test
