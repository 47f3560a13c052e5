// ugs-meshgen as users run it, on a small synthetic model written by the test (GeoTIFF planes,
// picks, a reservoir polygon, a fault): `ugs-mesh2d ... | ugs-meshgen --strata strata.toml`.
// The mesh must conform, carry every group, hold the volume of each material computed here from
// the planes, open in the gmsh SDK, show no inverted element in ugs-meshinfo, and be the same
// bytes on every run. Every bad-input case of the issue exits 2 with one line naming the surface
// or rule, the column and its coordinates, and leaves no output behind.
#include <gtest/gtest.h>

#include <gmsh.h>

#include <cmath>
#include <regex>

#include <fmt/format.h>

#include "geo_fixtures.hpp"
#include "meshing_checks.hpp"
#include "run_tool.hpp"
#include "strata_toml.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/layered_mesh.hpp"
#include "ugs/meshing/plan.hpp"

namespace fs = std::filesystem;
using namespace ugs;

namespace {

constexpr double X0 = 680000, Y0 = 4950000;
double dem(double x, double y) { return 50 + 0.001 * (x - X0); }
double base_a(double x, double y) { return -300 - 0.01 * (y - Y0); }
double top_c(double x, double y) { return -600 + 0.02 * (x - X0); }
double base_c_raw(double x, double y) { return top_c(x, y) - 0.05 * (x - 683000); }  // above top_c west of 683 km
constexpr double BOTTOM = -3000;

const std::string kStrata = testcase::StrataToml("crs = \"EPSG:32632\"\nmin_thickness = 0.5\nfaults = \"faults.geojson\"\n\n")
                                .surface({.name = "DEM", .raster = "dem.tif"})
                                .surface({.name = "Base A", .raster = "base_a.tif"})
                                .surface({.name = "Top C", .picks = "top_c.csv", .unconformity = true})
                                .surface({.name = "Base C", .raster = "base_c.tif"})
                                .surface({.name = "Bottom", .constant = BOTTOM})
                                .unit({.name = "Cover", .layers = 2})
                                .unit({.name = "Shale", .layers = 3, .bias = 1.5})
                                .unit({.name = "Sand C", .layers = 4})
                                .unit({.name = "Basement", .layers = 2})
                                .material({.name = "reservoir", .units = {"Sand C"}, .polygon = "reservoir.geojson", .where = "name = 'res'"})
                                .material({.name = "aquifer", .units = {"Sand C"}})
                                .material({.name = "rock", .units = {"Cover", "Shale", "Basement"}})
                                .str();

std::string strata_text() { return kStrata; }

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  if (p == std::string::npos) throw std::runtime_error("not found: " + from);
  return s.replace(p, from.size(), to);
}

class MeshgenCli : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(test::temp_dir("meshgen"));
    const fs::path& d = *dir_;
    const test::Grid g{X0 - 200, Y0 + 4200, 100, 64, 44};
    test::write_raster((d / "dem.tif").string(), g, dem);
    test::write_raster((d / "base_a.tif").string(), g, base_a);
    test::write_raster((d / "base_c.tif").string(), g, base_c_raw);
    // A raster that misses the east of the plan, and one with a no-data pixel.
    test::write_raster((d / "short.tif").string(), {X0 - 200, Y0 + 4200, 100, 50, 44}, base_a);
    test::write_raster((d / "holes.tif").string(), g, base_a, 32632, [](int i, int j) { return i >= 28 && i <= 33 && j >= 18 && j <= 23; });
    std::string csv = "x,y,z\n";
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 6; ++j) {
        const double x = X0 - 1000 + 1000 * i, y = Y0 - 1000 + 1000 * j;
        csv += fmt::format("{},{},{:.17g}\n", x, y, top_c(x, y));
      }
    test::spit(d / "top_c.csv", csv);
    test::spit(d / "few.csv", "x,y,z\n680000,4950000,-600\n683000,4950000,-540\n680000,4952000,-600\n");
    test::write_vector((d / "reservoir.geojson").string(),
                       {{"res", "POLYGON ((682000 4951000, 685000 4951000, 685000 4953000, 682000 4953000, 682000 4951000))", {}},
                        {"other", "POLYGON ((681000 4950500, 683500 4950500, 683500 4951800, 681000 4951800, 681000 4950500))", {}}});
    test::write_vector((d / "faults.geojson").string(),
                       {{"f1", "LINESTRING (681000 4951000, 685000 4953000)", {{"top_m", -100}, {"bottom_m", -1000}}}});
    test::spit(d / "strata.toml", strata_text());
    plan_cmd_ = new std::string(test::tool("ugs-mesh2d") + " --box 680000/686000/4950000/4954000 --hmax 400 --fault " +
                                (d / "faults.geojson").string());
    const auto r = test::run(*plan_cmd_ + " -o " + (d / "plan.msh").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete plan_cmd_;
  }

  static std::string meshgen() { return test::tool("ugs-meshgen"); }
  static fs::path path(const std::string& f) { return *dir_ / f; }

  // Runs ugs-meshgen on the plan with strata text `strata` and checks the bad-input contract.
  void expect_bad(const std::string& strata, const std::vector<std::string>& fragments, const std::string& plan = "plan.msh") {
    test::spit(path("bad.toml"), strata);
    const auto out = path("bad-out.msh");
    fs::remove(out);
    const auto r = test::run(meshgen() + " " + path(plan).string() + " --strata " + path("bad.toml").string() + " -o " +
                             out.string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(std::regex_match(r.err, std::regex("^ugs-meshgen: error: [^\n]+\n$"))) << r.err;
    for (const auto& f : fragments) EXPECT_NE(r.err.find(f), std::string::npos) << "missing '" << f << "' in: " << r.err;
    EXPECT_FALSE(fs::exists(out));
    for (const auto& e : fs::directory_iterator(*dir_))
      EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
  }

  static fs::path* dir_;
  static std::string* plan_cmd_;
};
fs::path* MeshgenCli::dir_ = nullptr;
std::string* MeshgenCli::plan_cmd_ = nullptr;

}  // namespace

TEST_F(MeshgenCli, PipelineGivesAConformingMeshWithTheExpectedVolumesAndCounts) {
  const auto out = path("model.msh");
  const auto r = test::run(*plan_cmd_ + " | " + meshgen() + " --strata " + path("strata.toml").string() + " > " +
                           out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("smallest dihedral angle"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("mat:reservoir"), std::string::npos) << r.err;
  const Mesh mesh = read_msh(out.string());
  const Plan plan = plan_from_mesh(read_msh(path("plan.msh").string()), "plan");

  // Independent expectation from the planes at the plan nodes: the order rule (Top C truncates
  // Base C) and the pinch-out (Sand C thinner than 0.5 m collapses onto its top).
  const std::size_t nc = plan.num_columns();
  std::vector<std::array<double, 5>> z(nc);
  std::vector<std::array<bool, 4>> alive(nc);
  for (std::size_t c = 0; c < nc; ++c) {
    const double x = plan.xy[c][0], y = plan.xy[c][1];
    z[c] = {dem(x, y), base_a(x, y), top_c(x, y), std::min(base_c_raw(x, y), top_c(x, y)), BOTTOM};
    if (z[c][2] - z[c][3] < 0.5) z[c][3] = z[c][2];
    for (int u = 0; u < 4; ++u) alive[c][u] = z[c][u] > z[c][u + 1];
  }
  const int layers[4] = {2, 3, 4, 2};
  std::size_t nodes = 0, tets = 0, pinched = 0;
  for (std::size_t c = 0; c < nc; ++c) {
    nodes += 1;
    for (int u = 0; u < 4; ++u) nodes += alive[c][u] ? layers[u] : 0;
    pinched += !alive[c][2];
  }
  ASSERT_GT(pinched, 5u);
  ASSERT_LT(pinched, nc);
  std::map<std::string, double> volume;
  for (std::size_t t = 0; t < plan.triangles.size(); ++t) {
    const auto& tri = plan.triangles[t];
    const XY m = plan.centroid(t);
    const bool in_res = m[0] > 682000 && m[0] < 685000 && m[1] > 4951000 && m[1] < 4953000;
    for (int u = 0; u < 4; ++u) {
      double sum = 0;
      for (auto c : tri) {
        sum += z[c][u] - z[c][u + 1];
        tets += alive[c][u] ? layers[u] : 0;
      }
      volume[u == 2 ? (in_res ? "mat:reservoir" : "mat:aquifer") : "mat:rock"] += plan.area(t) * sum / 3.0;
    }
  }
  EXPECT_EQ(mesh.num_nodes(), nodes);
  EXPECT_EQ(mesh.count(ElementType::Tetrahedron), tets);
  const auto c = test::check_conformity(mesh);
  EXPECT_EQ(c.over_shared, 0u);
  EXPECT_EQ(c.untagged_outer, 0u);
  EXPECT_EQ(c.tagged_not_outer, 0u);
  EXPECT_EQ(c.nonpositive, 0u);
  EXPECT_EQ(c.fault_not_face, 0u);
  for (const auto& [name, v] : volume) EXPECT_NEAR(c.volume_of.at(name), v, 1e-9 * v) << name;
  for (const char* g : {"bnd:top", "bnd:bottom", "bnd:west", "bnd:east", "bnd:south", "bnd:north", "fault:f1"})
    EXPECT_NE(mesh.find_physical(2, g), nullptr) << g;
  // The fault spans -100 .. -1000 m only.
  for (const auto& b : mesh.blocks)
    if (mesh.physical_name_of(b.entity_dim, b.entity_tag) == "fault:f1")
      for (auto n : b.nodes) {
        EXPECT_LT(mesh.nodes[n][2], 0.0);
        EXPECT_GT(mesh.nodes[n][2], -1400.0);
      }
  // Provenance: the plan's command, then meshgen's.
  ASSERT_EQ(mesh.provenance.size(), 2u);
  EXPECT_NE(mesh.provenance[0].find("ugs-mesh2d"), std::string::npos);
  EXPECT_NE(mesh.provenance[1].find("ugs-meshgen"), std::string::npos);
}

TEST_F(MeshgenCli, SameInputSameBytes) {
  // The same command line (it is recorded in the mesh), run twice.
  const std::string cmd = meshgen() + " " + path("plan.msh").string() + " --strata " + path("strata.toml").string() + " -q";
  ASSERT_EQ(test::run(cmd + " > " + path("a.msh").string()).exit_code, 0);
  ASSERT_EQ(test::run(cmd + " > " + path("b.msh").string()).exit_code, 0);
  const std::string a = test::slurp(path("a.msh")), b = test::slurp(path("b.msh"));
  EXPECT_GT(a.size(), 10000u);
  EXPECT_TRUE(a == b);
}

TEST_F(MeshgenCli, GmshOpensTheMeshAndMeshinfoFindsNoInvertedElement) {
  const auto out = path("for-gmsh.msh");
  ASSERT_EQ(test::run(meshgen() + " " + path("plan.msh").string() + " --strata " + path("strata.toml").string() +
                      " -q -o " + out.string())
                .exit_code,
            0);
  const Mesh ours = read_msh(out.string());
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::open(out.string());
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> tags, nodes;
  gmsh::model::mesh::getElements(types, tags, nodes, 3);
  std::size_t tets = 0;
  for (std::size_t k = 0; k < types.size(); ++k)
    if (types[k] == 4) tets += tags[k].size();
  EXPECT_EQ(tets, ours.count(ElementType::Tetrahedron));
  std::vector<std::size_t> ntags;
  std::vector<double> xyz, par;
  gmsh::model::mesh::getNodes(ntags, xyz, par);
  EXPECT_EQ(ntags.size(), ours.num_nodes());
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups);
  std::set<std::string> names;
  for (const auto& [d, t] : groups) {
    std::string n;
    gmsh::model::getPhysicalName(d, t, n);
    names.insert(n);
  }
  gmsh::finalize();
  for (const char* g : {"mat:rock", "mat:reservoir", "mat:aquifer", "bnd:top", "bnd:north", "fault:f1"})
    EXPECT_TRUE(names.count(g)) << g;

  const auto r = test::run(test::tool("ugs-meshinfo") + " --fail-on-inverted " + out.string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("inverted elements: 0"), std::string::npos) << r.out;
}

TEST_F(MeshgenCli, BadSurfaces) {
  const std::string s = strata_text();
  expect_bad(replace(s, "raster = \"base_a.tif\"", "raster = \"missing.tif\""),
             {"bad.toml:", "surface 'Base A'", "missing.tif", "cannot open"});
  expect_bad(replace(s, "raster = \"base_a.tif\"", "raster = \"short.tif\""),
             {"surface 'Base A'", "does not cover", "plan columns, within x", "(first: plan node", "x=", "y="});
  expect_bad(replace(s, "raster = \"base_a.tif\"", "raster = \"holes.tif\""),
             {"surface 'Base A'", "no-data", "x=", "y="});
  // Base C above Top C with no unconformity: beyond the 1 m the order rule fixes.
  expect_bad(replace(s, "unconformity = true\n", ""),
             {"bad.toml:", "surface 'Base C' lies above 'Top C' at", "columns, by up to", "x=", "y="});
  expect_bad(replace(s, "picks = \"top_c.csv\"", "picks = \"few.csv\""),
             {"surface 'Top C'", "do not cover", "convex hull", "x="});
  expect_bad(replace(s, "picks = \"top_c.csv\"", "picks = \"top_c.csv\"\nconstant = 3.0"),
             {"surface 'Top C'", "exactly one of raster, grid, constant or picks"});
  // Two bad surfaces (sampled on different threads): the first in the file is the one reported.
  for (const auto& [first, second] : {std::pair{"Base A", "Top C"}, std::pair{"Top C", "Base C"}}) {
    std::string two = s;
    for (const char* name : {first, second}) {
      if (std::string(name) == "Base A") two = replace(two, "raster = \"base_a.tif\"", "raster = \"missing.tif\"");
      if (std::string(name) == "Top C") two = replace(two, "picks = \"top_c.csv\"", "picks = \"few.csv\"");
      if (std::string(name) == "Base C") two = replace(two, "raster = \"base_c.tif\"", "raster = \"short.tif\"");
    }
    expect_bad(two, {fmt::format("surface '{}'", first)});  // writes bad.toml
    const auto r = test::run(meshgen() + " " + path("plan.msh").string() + " --strata " + path("bad.toml").string() + " -o " +
                             path("bad-out.msh").string());
    EXPECT_EQ(r.err.find(fmt::format("surface '{}'", second)), std::string::npos) << r.err;
  }
}

TEST_F(MeshgenCli, BadUnitsAndMaterials) {
  const std::string s = strata_text();
  expect_bad(replace(s, "layers = 3\n", "layers = 0\n"), {"bad.toml:", "unit 'Shale' needs at least one sub-layer (got 0)"});
  expect_bad(replace(s, "layers = 3\n", "layers = -2\n"), {"unit 'Shale' needs at least one sub-layer (got -2)"});
  expect_bad(replace(s, "bias = 1.5", "bias = -1"), {"unit 'Shale'", "> 0"});
  expect_bad(replace(s, "layers = 3\n", "layres = 3\n"), {"unknown key"});
  // A second reservoir rule whose polygon crosses the first one's.
  expect_bad(replace(s, "[[material]]\nname = \"aquifer\"",
                     "[[material]]\nname = \"other\"\nunits = [\"Sand C\"]\npolygon = \"reservoir.geojson\"\n"
                     "where = \"name = 'other'\"\n\n[[material]]\nname = \"aquifer\""),
             {"material rules 'reservoir'", "'other'", "overlap partly in unit 'Sand C'", "x=", "y="});
  // Without the default rule, Sand C outside the polygon has no material.
  expect_bad(replace(s, "[[material]]\nname = \"aquifer\"\nunits = [\"Sand C\"]\n", ""),
             {"unit 'Sand C' has no material at plan triangle", "x="});
  expect_bad(replace(s, "units = [\"Cover\", \"Shale\", \"Basement\"]", "units = [\"Cover\", \"Shales\"]"),
             {"no unit named 'Shales'"});
  expect_bad(replace(s, "where = \"name = 'res'\"", "where = \"name = 'nothing'\""), {"selects no feature"});
}

TEST_F(MeshgenCli, OverlapCanBeResolvedByOrderWhenAsked) {
  std::string s = replace(strata_text(), "[[material]]\nname = \"aquifer\"",
                          "[[material]]\nname = \"other\"\nunits = [\"Sand C\"]\npolygon = \"reservoir.geojson\"\n"
                          "where = \"name = 'other'\"\n\n[[material]]\nname = \"aquifer\"");
  test::spit(path("first.toml"), "material_overlap = \"first\"\n" + s);
  const auto r = test::run(meshgen() + " " + path("plan.msh").string() + " --strata " + path("first.toml").string() +
                           " -o " + path("first.msh").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(MeshgenCli, BadPlans) {
  const std::string s = strata_text();
  // Triangles of the real plan, one turned over; then one repeated.
  Mesh plan = read_msh(path("plan.msh").string());
  for (auto& b : plan.blocks)
    if (b.type == ElementType::Triangle) {
      std::swap(b.nodes[3 * 5 + 1], b.nodes[3 * 5 + 2]);
      break;
    }
  write_msh(plan, path("inverted.msh").string());
  expect_bad(s, {"inverted.msh", "inverted triangle", "x=", "y="}, "inverted.msh");
  plan = read_msh(path("plan.msh").string());
  for (auto& b : plan.blocks)
    if (b.type == ElementType::Triangle) {
      std::vector<std::uint32_t> n(b.nodes.begin() + 6, b.nodes.begin() + 9);
      plan.add_element(b, n);
      break;
    }
  write_msh(plan, path("duplicate.msh").string());
  expect_bad(s, {"duplicate.msh", "duplicate triangles", "x=", "y="}, "duplicate.msh");
  test::spit(path("garbage.msh"), "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 1 2\n");
  expect_bad(s, {"garbage.msh"}, "garbage.msh");
}

TEST_F(MeshgenCli, FaultsNeedADepthRangeWhenRangesAreGiven) {
  const std::string s = replace(strata_text(), "faults = \"faults.geojson\"\n", "");
  test::spit(path("f.toml"), s + "\n[[fault]]\nname = \"f9\"\ntop_m = -10.0\nbottom_m = -20.0\n");
  const auto r = test::run(meshgen() + " " + path("plan.msh").string() + " --strata " + path("f.toml").string() +
                           " -o " + path("f.msh").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("fault line 'f1'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("f.msh")));
}

TEST_F(MeshgenCli, HelpAndMissingFiles) {
  auto r = test::run(meshgen() + " --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("Example:"), std::string::npos);
  r = test::run(meshgen() + " " + path("plan.msh").string() + " --strata " + path("nope.toml").string() + " -o x.msh");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nope.toml: cannot open"), std::string::npos) << r.err;
  r = test::run(meshgen() + " " + path("plan.msh").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--strata"), std::string::npos) << r.err;
}

// Issue 20: sub-layer counts are estimated before building: 3 tetrahedra per plan triangle and
// sub-layer above --max-elements is refused (exit 2, the estimate in the message); raising the
// limit lets the same input through.
TEST_F(MeshgenCli, ElementEstimateAboveTheLimitIsRefused) {
  const auto plan = read_msh(path("plan.msh").string());
  const std::size_t triangles = plan.count(ElementType::Triangle);
  const auto out = path("big.msh");
  const std::string cmd = meshgen() + " " + path("plan.msh").string() + " --strata " + path("strata.toml").string();
  const auto r = test::run(cmd + " --max-elements 1000 -o " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(fmt::format("ugs-meshgen: error: --max-elements: {} plan triangles x ", triangles)), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("more than the limit of 1000"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  ASSERT_EQ(test::run(cmd + " -q --max-elements 1e7 -o " + out.string()).exit_code, 0);
  EXPECT_GT(read_msh(out.string()).count(ElementType::Tetrahedron), 1000u);
}
