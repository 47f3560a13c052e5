// Dipping faults through the tools (issue 6): ugs-mesh2d --box | ugs-meshgen with a faults file of
// a 35-degree thrust, a listric fault and a steep fault ending against the thrust; then
// ugs-faultinsert. The faces lie on the dipping planes, the mesh conforms, faultinsert inserts the
// faults without a distance warning; bad input (dip outside (0, 90], depth range outside the model,
// trace leaving the plan) exits 2 with one line naming the fault and writes nothing. Faults as
// surfaces (issue 40): a listric GOCAD TSurf of two TFACEs and a fault given by sticks, dying out
// inside the model, cut across both units and inserted; bad surfaces exit 2 naming file and line.
#include <gtest/gtest.h>

#include <regex>

#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "meshing_checks.hpp"
#include "run_tool.hpp"
#include "strata_toml.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/fault_surface_input.hpp"

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

namespace {

// A GOCAD TSurf of a grid of points, rows split into two TFACEs at row `split` (the shared row is
// given again as VRTX in the second: merged by coordinates, and said). PVRTX carry a property.
std::string tsurf_grid(const std::vector<std::vector<Point3>>& rows, std::size_t split) {
  std::string s = "GOCAD TSurf 1\nHEADER {\nname: listric\n}\nPROPERTIES throw\nGOCAD_ORIGINAL_COORDINATE_SYSTEM\n"
                  "NAME Default\nAXIS_UNIT \"m\" \"m\" \"m\"\nZPOSITIVE Elevation\nEND_ORIGINAL_COORDINATE_SYSTEM\n";
  long id = 1;
  for (auto [r0, r1] : {std::pair{std::size_t{0}, split}, std::pair{split, rows.size() - 1}}) {
    s += "TFACE\n";
    const long first = id;
    for (std::size_t i = r0; i <= r1; ++i)
      for (const auto& p : rows[i]) s += fmt::format("PVRTX {} {:.6f} {:.6f} {:.6f} 0.25\n", id++, p[0], p[1], p[2]);
    const std::size_t nc = rows[0].size();
    auto at = [&](std::size_t i, std::size_t j) { return first + static_cast<long>((i - r0) * nc + j); };
    for (std::size_t i = r0; i < r1; ++i)
      for (std::size_t j = 0; j + 1 < nc; ++j) {
        s += fmt::format("TRGL {} {} {}\n", at(i, j), at(i, j + 1), at(i + 1, j + 1));
        s += fmt::format("TRGL {} {} {}\n", at(i, j), at(i + 1, j + 1), at(i + 1, j));
      }
  }
  return s + "END\n";
}

// Listric: a cylinder about the axis x = 5000, z = 0 (along y), radius 3,000 m, vertical at the top
// (phi 0) to 15 degrees at phi 75, begun above the ground and run past the plan's ends in y.
std::vector<std::vector<Point3>> listric_rows() {
  std::vector<std::vector<Point3>> rows;
  for (int i = 0; i <= 10; ++i) {
    const double phi = (-5.0 + 8.0 * i) * M_PI / 180;
    rows.emplace_back();
    for (int j = 0; j <= 4; ++j) rows.back().push_back({5000 - 3000 * std::cos(phi), -200 + 1100.0 * j, -3000 * std::sin(phi)});
  }
  return rows;
}

// Sticks of a fault dipping 60 degrees west, from -100 to -2,000 m, between y = 500 and 3,500 m:
// it dies out inside the model on every side.
std::string sticks_text() {
  std::string s = "# fault sticks, IRAP classic lines\n";
  for (int k = 0; k < 4; ++k) {
    for (double z : {-100.0, -1000.0, -2000.0})
      s += fmt::format("{:.6f} {:.6f} {:.6f}\n", 1500 + z / std::tan(M_PI / 3), 500.0 + 1000 * k, z);
    s += "999.000000 999.000000 999.000000\n";
  }
  return s;
}

// Distance from x to a triangulated surface: to the nearest triangle's plane where x projects
// inside it (within 1 mm), else the distance outside.
double surface_distance(const TriangulatedSurface& s, const Point3& x) {
  double best = 1e300;
  for (const auto& t : s.triangles) {
    const Point3 &a = s.vertices[t[0]], &b = s.vertices[t[1]], &c = s.vertices[t[2]];
    auto sub = [](const Point3& p, const Point3& q) { return Point3{p[0] - q[0], p[1] - q[1], p[2] - q[2]}; };
    auto cross = [](const Point3& p, const Point3& q) {
      return Point3{p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]};
    };
    auto dot = [](const Point3& p, const Point3& q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; };
    Point3 n = cross(sub(b, a), sub(c, a));
    const double l = std::sqrt(dot(n, n));
    n = {n[0] / l, n[1] / l, n[2] / l};
    double out = 0;
    for (const auto& [p, q] : {std::pair{&a, &b}, std::pair{&b, &c}, std::pair{&c, &a}}) {
      Point3 o = cross(sub(*q, *p), n);
      const double lo = std::sqrt(dot(o, o));
      out = std::max(out, dot(o, sub(x, *p)) / lo);
    }
    best = std::min(best, std::max(std::abs(dot(n, sub(x, a))), out > 1e-3 ? out : 0.0));
  }
  return best;
}

}  // namespace

TEST(SurfaceFaultsCli, TSurfAndSticksThroughTheTools) {
  Case c = make_case("surfaces", {feature(R"("name": "listric", "surface": "listric.ts", "size_m": 300)", "[[2000, 0], [2000, 4000]]"),
                                   feature(R"("name": "sticks", "surface": "sticks.txt")", "[[1440, 500], [1440, 3500]]")});
  std::ofstream(c.dir / "listric.ts") << tsurf_grid(listric_rows(), 5);
  std::ofstream(c.dir / "sticks.txt") << sticks_text();
  auto r = c.run_meshgen();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The second TFACE repeats the shared row's 5 vertices: merged, and said.
  EXPECT_NE(r.err.find("listric.ts: 5 vertices at the same x, y, z as an earlier one merged into it"), std::string::npos) << r.err;
  // The cut's line per fault says it came from a surface: 10 strips of coplanar triangles, 10 panels.
  EXPECT_NE(r.err.find("fault:listric              surface, 10 panel(s)"), std::string::npos) << r.err;
  const Mesh m = read_msh((c.dir / "model.msh").string());
  const Conformity k = check_conformity(m);
  EXPECT_EQ(k.over_shared, 0u);
  EXPECT_EQ(k.untagged_outer, 0u);
  EXPECT_EQ(k.fault_not_face, 0u);
  EXPECT_EQ(k.nonpositive, 0u);
  EXPECT_NEAR(k.volume, 6000.0 * 4000 * 3000, 1e-6 * 6000.0 * 4000 * 3000);
  for (const auto& [name, file] : {std::pair{"listric", "listric.ts"}, std::pair{"sticks", "sticks.txt"}}) {
    const auto surface = read_fault_surface((c.dir / file).string());
    std::size_t faces = 0;
    double worst = 0;
    for (const auto& b : m.blocks) {
      if (m.physical_name_of(b.entity_dim, b.entity_tag) != std::string("fault:") + name) continue;
      faces += b.size();
      for (auto v : b.nodes) worst = std::max(worst, surface_distance(surface.mesh, m.nodes[v]));
    }
    std::printf("%s: %zu faces, nodes within %.2e m of the surface\n", name, faces, worst);
    EXPECT_GT(faces, 50u) << name;
    EXPECT_LE(worst, 1e-6) << name;  // the model's coordinates are 6 km: 1e-6 m is 1.7e-10 of it
  }
  r = run("cd " + c.dir.string() + " && " + tool("ugs-faultinsert") + " model.msh --faults faults.geojson -o faulted.msh");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("2 faults"), std::string::npos) << r.err;
}

TEST(SurfaceFaultsCli, BadSurfacesExitTwoNamingFileAndLine) {
  auto bad = [](const std::string& tag, const std::string& file, const std::string& text, const std::string& what) {
    Case c = make_case(tag, {feature(R"("name": "bad", "surface": ")" + file + R"(")", "[[1000, 1000], [2000, 1000]]")});
    std::ofstream(c.dir / file) << text;
    const auto r = c.run_meshgen();
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(c.dir / "model.msh"));
  };
  auto rows = listric_rows();
  std::string ts = tsurf_grid(rows, 5);
  // A third triangle on the edge from vertex 1 to 7 (non-manifold), at the end of the first TFACE.
  std::string nm = ts;
  nm.insert(nm.find("TFACE", nm.find("TFACE") + 5), "TRGL 1 7 13\n");
  bad("nonmanifold", "bad.ts", nm, "non-manifold edge");
  // Inconsistent orientation: one triangle's corners reversed.
  std::string flip = ts;
  const auto t1 = flip.find("TRGL 1 2 7");
  flip.replace(t1, 10, "TRGL 2 1 7");
  bad("orientation", "bad.ts", flip, "inconsistent orientation");
  // A surface entirely below the model.
  for (auto& row : rows)
    for (auto& p : row) p[2] -= 10000;
  bad("below", "bad.ts", tsurf_grid(rows, 5), "lies outside the model");
  // Crossing sticks: the second stick given twice as far along the strike as the third.
  std::string st = sticks_text();
  const auto s1 = st.find("999.000000 999.000000 999.000000\n") + 33;
  const auto s2 = st.find("999.000000 999.000000 999.000000\n", s1) + 33;
  const auto s3 = st.find("999.000000 999.000000 999.000000\n", s2) + 33;
  st = st.substr(0, s1) + st.substr(s2, s3 - s2) + st.substr(s1, s2 - s1) + st.substr(s3);
  bad("crossing", "bad.sticks", st, "crosses the stick of line");
  // Fields that contradict the surface.
  Case c = make_case("both", {feature(R"("name": "bad", "surface": "x.ts", "dip_deg": 45)", "[[1000, 1000], [2000, 1000]]")});
  const auto r = c.run_meshgen();
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("dip_deg and surface exclude each other"), std::string::npos) << r.err;
}
