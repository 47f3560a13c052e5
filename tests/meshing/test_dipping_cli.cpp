// Dipping faults through the tools (issue 6): ugs-mesh2d --box | ugs-meshgen with a faults file of
// a 35-degree thrust, a listric fault and a steep fault ending against the thrust; then
// ugs-faultinsert. The faces lie on the dipping planes, the mesh conforms, faultinsert inserts the
// faults without a distance warning; bad input (dip outside (0, 90], depth range outside the model,
// trace leaving the plan) exits 2 with one line naming the fault and writes nothing.
#include <gtest/gtest.h>

#include <regex>

#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "meshing_checks.hpp"
#include "run_tool.hpp"
#include "strata_toml.hpp"
#include "ugs/formats/msh.hpp"

namespace fs = std::filesystem;
using namespace ugs;
using namespace ugs::test;

namespace {

const std::string kStrata = testcase::StrataToml("crs = \"EPSG:32632\"\nfaults = \"faults.geojson\"\n", testcase::Layout::Compact)
                                .surface({.name = "Ground", .constant = 0})
                                .surface({.name = "Top B", .constant = -800})
                                .surface({.name = "Bottom", .constant = -3000})
                                .unit({.name = "A", .layers = 4})
                                .unit({.name = "B", .layers = 6})
                                .material({.name = "rock", .units = {"A", "B"}})
                                .str();

std::string feature(const std::string& props, const std::string& coords) {
  return fmt::format(R"({{ "type": "Feature", "properties": {{ {} }}, "geometry": {{ "type": "LineString", "coordinates": {} }} }})",
                     props, coords);
}

void write_faults(const fs::path& dir, const std::vector<std::string>& features) {
  std::ofstream f(dir / "faults.geojson");
  f << R"({"type": "FeatureCollection", "crs": { "type": "name", "properties": { "name": "urn:ogc:def:crs:EPSG::32632" } }, "features": [)";
  for (std::size_t i = 0; i < features.size(); ++i) f << (i ? ",\n" : "\n") << features[i];
  f << "]}\n";
}

const std::string kThrust = feature(R"("name": "thrust", "top_m": -200, "bottom_m": -2600, "dip_deg": 35, "dip_dir_deg": 195)",
                                    "[[1000, 3400], [3000, 3000], [5000, 2900]]");
const std::string kListric = feature(
    R"("name": "growth", "top_m": -100, "bottom_m": -2500, "dip_dir_deg": 300, "listric_bottom_m": [-900, -2500], "listric_dip_deg": [70, 40])",
    "[[4200, 500], [5600, 2000]]");
const std::string kSplay = feature(
    R"("name": "splay", "top_m": -400, "bottom_m": -1800, "dip_deg": 75, "dip_dir_deg": 90, "ends_against": "thrust")",
    "[[2500, 600], [2500, 2400]]");

struct Case {
  fs::path dir;
  RunResult run_meshgen() {
    const std::string cd = "cd " + dir.string() + " && ";
    auto r = run(cd + tool("ugs-mesh2d") + " --box 0/6000/0/4000 --hmax 400 -q -o plan.msh");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return run(cd + tool("ugs-meshgen") + " plan.msh --strata strata.toml -o model.msh");
  }
};

Case make_case(const std::string& tag, const std::vector<std::string>& faults) {
  Case c{temp_dir("dipping-" + tag)};
  std::ofstream(c.dir / "strata.toml") << kStrata;
  write_faults(c.dir, faults);
  return c;
}

// Distance from x to the plane swept by the trace segment a-b moved down-dip (the surface of
// docs/dipping-faults.md: the trace translated along the dip direction by dz / tan(dip)).
double plane_distance(const Point3& x, double dip, double dipdir, const Point3& a, const Point3& b) {
  const double d = dip * M_PI / 180, az = dipdir * M_PI / 180;
  const Point3 w{std::sin(az) * std::cos(d), std::cos(az) * std::cos(d), -std::sin(d)};
  const Point3 e{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  Point3 n{e[1] * w[2] - e[2] * w[1], e[2] * w[0] - e[0] * w[2], e[0] * w[1] - e[1] * w[0]};
  const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  return std::abs(n[0] * (x[0] - a[0]) + n[1] * (x[1] - a[1]) + n[2] * (x[2] - a[2])) / l;
}

TEST(DippingFaultsCli, ThrustListricAndSplayThroughTheTools) {
  Case c = make_case("good", {kThrust, kListric, kSplay});
  auto r = c.run_meshgen();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("fault:thrust"), std::string::npos) << r.err;
  const Mesh m = read_msh((c.dir / "model.msh").string());
  const Conformity k = check_conformity(m);
  EXPECT_EQ(k.over_shared, 0u);
  EXPECT_EQ(k.untagged_outer, 0u);
  EXPECT_EQ(k.tagged_not_outer, 0u);
  EXPECT_EQ(k.fault_not_face, 0u);
  EXPECT_EQ(k.nonpositive, 0u);
  EXPECT_NEAR(k.volume, 6000.0 * 4000 * 3000, 1e-6 * 6000.0 * 4000 * 3000);
  // Thrust faces: on the plane through (1000, 3400, -200) (first segment) or (3000, 3000, -200).
  const double size = std::sqrt(6000.0 * 6000 + 4000.0 * 4000 + 3000.0 * 3000);
  for (const auto& b : m.blocks) {
    if (m.physical_name_of(b.entity_dim, b.entity_tag) != "fault:thrust") continue;
    ASSERT_GT(b.size(), 100u);
    for (auto v : b.nodes) {
      const Point3& x = m.nodes[v];
      const double d = std::min(plane_distance(x, 35, 195, {1000, 3400, -200}, {3000, 3000, -200}),
                                plane_distance(x, 35, 195, {3000, 3000, -200}, {5000, 2900, -200}));
      // Two panels with the same dip and dip direction meet along a down-dip line: one plane each side.
      EXPECT_LE(d, 1e-6 * size) << x[0] << " " << x[1] << " " << x[2];
      EXPECT_GE(x[2], -2600 - 1e-6 * size);
      EXPECT_LE(x[2], -200 + 1e-6 * size);
    }
  }
  r = run("cd " + c.dir.string() + " && " + tool("ugs-faultinsert") + " model.msh --faults faults.geojson -o faulted.msh");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("triangles are used; they"), std::string::npos) << r.err;  // groups on the file's surfaces
  EXPECT_NE(r.err.find("3 faults"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("thrust (") , std::string::npos) << r.err;  // the splay meets the thrust
}

void expect_bad(const std::string& tag, const std::string& fault, const std::string& what) {
  Case c = make_case(tag, {fault});
  const auto r = c.run_meshgen();
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("fault 'bad'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(c.dir / "model.msh"));
}

TEST(DippingFaultsCli, BadInputExitsTwoNamingTheFault) {
  expect_bad("dip0", feature(R"("name": "bad", "top_m": -200, "bottom_m": -900, "dip_deg": 0, "dip_dir_deg": 10)",
                             "[[1000, 1000], [2000, 1000]]"),
             "outside (0, 90]");
  expect_bad("dip95", feature(R"("name": "bad", "top_m": -200, "bottom_m": -900, "dip_deg": 95, "dip_dir_deg": 10)",
                              "[[1000, 1000], [2000, 1000]]"),
             "outside (0, 90]");
  expect_bad("deep", feature(R"("name": "bad", "top_m": -200, "bottom_m": -5000, "dip_deg": 45, "dip_dir_deg": 10)",
                             "[[1000, 1000], [2000, 1000]]"),
             "outside the model");
  expect_bad("high", feature(R"("name": "bad", "top_m": 300, "bottom_m": -900, "dip_deg": 45, "dip_dir_deg": 10)",
                             "[[1000, 1000], [2000, 1000]]"),
             "outside the model");
  expect_bad("leaves", feature(R"("name": "bad", "top_m": -200, "bottom_m": -900, "dip_deg": 45, "dip_dir_deg": 10)",
                               "[[1000, 1000], [7000, 1000]]"),
             "leaves the plan");
}

// Regression: the sample's faults cut into its layered mesh (pinch-outs, two nearly collinear
// segments of the back-thrust whose panels meet at an angle of 1e-6 rad). With an on-plane
// tolerance at rounding level, nodes of one panel lying 1e-4 m off the next one had every edge
// split 1e-4 m from them: tetrahedra with coincident nodes that ugs-flow rejects as degenerate.
TEST(DippingFaultsCli, SampleCutHasNoDegenerateTetrahedra) {
  const fs::path src = fs::path(UGS_SOURCE_DIR) / "data-samples/po-plain";
  ASSERT_TRUE(fs::exists(src / "strata.toml")) << src;
  const fs::path dir = temp_dir("dipping-sample");
  const fs::path plan = dir / "plan.msh", model = dir / "model.msh";
  auto r = run("cd " + src.string() + " && " + tool("ugs-mesh2d") +
               " --domain domain.geojson --refine refinement.geojson --size-field none --refine-size 600 --trace "
               "reservoir_traces.geojson --fault faults.geojson --section sections.geojson --hmax 5000 --grading 0.3 -q -o " +
               plan.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run("cd " + src.string() + " && " + tool("ugs-meshgen") + " " + plan.string() + " --strata strata.toml -o " +
          model.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The quality bound of the cut (docs/dipping-faults.md, "Mesh quality"): the tetrahedra holding
  // a node the cut made keep a tenth of min(2 deg, their input tetrahedron's smallest dihedral
  // angle) but for a few where no node may move (measured: 16 of 64,039), and most keep all of it.
  std::smatch mq;
  ASSERT_TRUE(std::regex_search(r.err, mq, std::regex(R"(fault cut: (\d+) tetrahedra hold a node the cut made: smallest dihedral angle [0-9.]+ deg; (\d+) below min\(2 deg, their input tetrahedron's\), (\d+) below a tenth of it)")))
      << r.err;
  const double band = std::stod(mq[1]), below_reference = std::stod(mq[2]), below_bound = std::stod(mq[3]);
  EXPECT_GT(band, 10000);
  EXPECT_LE(below_bound, 1e-3 * band);
  EXPECT_LE(below_reference, 0.1 * band);
  const Mesh m = read_msh(model.string());
  std::size_t coincident = 0, degenerate = 0, fault_faces = 0;
  for (const auto& b : m.blocks) {
    if (b.type == ElementType::Triangle && m.physical_name_of(b.entity_dim, b.entity_tag).rfind("fault:", 0) == 0)
      fault_faces += b.size();
    if (b.type != ElementType::Tetrahedron) continue;
    for (std::size_t i = 0; i < b.size(); ++i) {
      const auto e = b.element(i);
      bool same = false;
      for (int a = 0; a < 4; ++a)
        for (int c = a + 1; c < 4; ++c) {
          const Point3 &p = m.nodes[e[a]], &q = m.nodes[e[c]];
          same = same || std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]) < 1e-6;
        }
      coincident += same;
      // ugs-flow's test (solver/flow/src/flow_model.cpp): volume against the cube of the Jacobian's size.
      const Point3 &x0 = m.nodes[e[0]], &x1 = m.nodes[e[1]], &x2 = m.nodes[e[2]], &x3 = m.nodes[e[3]];
      const double scale = std::abs(x1[0] - x0[0]) + std::abs(x2[1] - x0[1]) + std::abs(x3[2] - x0[2]) +
                           std::abs(x2[0] - x0[0]) + std::abs(x3[1] - x0[1]) + std::abs(x1[2] - x0[2]);
      degenerate += !(tet_signed_volume(x0, x1, x2, x3) > 1e-14 * scale * scale * scale);
    }
  }
  EXPECT_EQ(coincident, 0u);
  EXPECT_EQ(degenerate, 0u);
  // Six faults, the layering's resolution kept (their areas: FaultInsertTwin): 8,827 faces since the
  // regional faults moved outside the depleted volume, away from the reservoir refinement (was
  // 15,000+ with the faults through the refined aquifers).
  EXPECT_GT(fault_faces, 7500u);
  const Conformity k = check_conformity(m);
  EXPECT_EQ(k.over_shared, 0u);
  EXPECT_EQ(k.untagged_outer, 0u);
  EXPECT_EQ(k.tagged_not_outer, 0u);
  EXPECT_EQ(k.fault_not_face, 0u);
  EXPECT_EQ(k.nonpositive, 0u);
  EXPECT_EQ(k.repeated_nodes, 0u);
}

}  // namespace
