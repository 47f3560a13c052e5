// Faults from traces on box meshes [0,6]^3 (unit cells, Kuhn-split): the tetrahedron faces on the
// trace surface are selected with the expected count and area, coverage is measured against the
// exact section of the model, and bad traces are refused with the fault's name. Kuhn faces tile the
// planes x = c, y = c, z = c and the diagonal planes x - y = c, x - z = c, y - z = c, so vertical,
// oblique and 45-degree dipping faults all follow mesh faces here.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "input_error.hpp"
#include "fault_meshes.hpp"
#include "run_tool.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/meshing/fault_insert.hpp"
#include "ugs/meshing/fault_select.hpp"
#include "ugs/meshing/fault_traces.hpp"

namespace ugs::test {
namespace {

FaultTrace trace(std::string name, std::vector<std::array<double, 2>> line, double top, double bottom, double dip,
                 double dip_dir) {
  FaultTrace t;
  t.name = std::move(name);
  t.where = "traces";
  t.parts = {std::move(line)};
  t.top = top;
  t.bottom = bottom;
  t.trace_z = top;
  t.dip_deg = dip;
  t.dip_dir_deg = dip_dir;
  check_fault_trace(t);
  return t;
}


TEST(FaultSelect, VerticalBuriedTrace) {
  Mesh m = unit_box(6);
  const auto sel = select_fault_faces(m, {trace("F", {{3, 1}, {3, 5}}, 5, 1, 90, 90)});
  ASSERT_EQ(sel.size(), 1u);
  EXPECT_FALSE(sel[0].from_mesh);
  EXPECT_EQ(sel[0].triangles, 32u);
  EXPECT_NEAR(sel[0].area_inside, 16.0, 1e-9);
  EXPECT_NEAR(sel[0].covered, 16.0, 1e-9);
  EXPECT_DOUBLE_EQ(sel[0].coverage, 1.0);
  ASSERT_NE(m.find_physical(2, "fault:F"), nullptr);
  // Same result as the hand-made group of test_fault_insert.
  FaultInsertOptions o;
  o.reference_normals["F"] = FaultSurface(trace("F", {{3, 1}, {3, 5}}, 5, 1, 90, 90)).reference_normal();
  const Mesh input = m;
  const auto r = insert_faults(m, o);
  EXPECT_EQ(r.new_nodes, 9u);
  EXPECT_EQ(r.faults[0].tip_nodes, 16u);
  // Dip direction east: side 1 (hanging wall side) is east, the normal points west.
  EXPECT_NEAR(r.faults[0].normal[0], -1.0, 1e-12);
  check_faulted(m);
  expect_glues_back(m, input);
}

TEST(FaultSelect, DippingTraceFollowsTheDiagonalPlane) {
  // Dip 45 deg towards the west from the trace x = 5 at the top (z = 6) down to z = 2: the plane
  // x - z = -1, tiled by the Kuhn faces of the cells with i - k = -1.
  Mesh m = unit_box(6);
  const FaultTrace t = trace("D", {{5, 0}, {5, 6}}, 6, 2, 45, 270);
  const auto sel = select_fault_faces(m, {t});
  EXPECT_EQ(sel[0].triangles, 48u);
  EXPECT_NEAR(sel[0].area_inside, 24 * std::sqrt(2.0), 1e-9);
  EXPECT_DOUBLE_EQ(sel[0].coverage, 1.0);
  const Point3 n = FaultSurface(t).reference_normal();
  EXPECT_NEAR(n[0], std::sqrt(0.5), 1e-12);  // down and east: from the hanging wall (west, above) to the footwall
  EXPECT_NEAR(n[2], -std::sqrt(0.5), 1e-12);
  FaultInsertOptions o;
  o.reference_normals["D"] = n;
  const Mesh input = m;
  const auto r = insert_faults(m, o);
  EXPECT_EQ(r.faults[0].nodes, 35u);
  EXPECT_EQ(r.faults[0].tip_nodes, 7u);  // the buried bottom edge; the top and the sides split through
  EXPECT_EQ(r.new_nodes, 28u);
  EXPECT_NEAR(r.faults[0].normal[0], std::sqrt(0.5), 1e-12);
  check_faulted(m);
  expect_glues_back(m, input);
}

TEST(FaultSelect, ObliqueTraceWithABend) {
  // x = 3 for y in [0, 3], then along x = y to (6, 6): both vertical planes follow Kuhn faces.
  Mesh m = unit_box(6);
  const auto sel = select_fault_faces(m, {trace("B", {{3, 0}, {3, 3}, {6, 6}}, 6, 0, 90, 0)});
  EXPECT_NEAR(sel[0].area_inside, 6 * (3 + 3 * std::sqrt(2.0)), 1e-9);
  EXPECT_DOUBLE_EQ(sel[0].coverage, 1.0);
  EXPECT_EQ(sel[0].triangles, 2u * 6u * 6u);
  const Mesh input = m;
  insert_faults(m);
  check_faulted(m);
  expect_glues_back(m, input);
}

TEST(FaultSelect, DepthLimitsBetweenLevelsFollowTheMidDepthRule) {
  // Top 4.6 and bottom 1.4: the face rows with centroids inside (1.4, 4.6) are kept; the trace
  // surface is covered by the faces lying on it, which reach beyond both limits.
  Mesh m = unit_box(6);
  const auto sel = select_fault_faces(m, {trace("F", {{3, 1}, {3, 5}}, 4.6, 1.4, 90, 90)});
  EXPECT_NEAR(sel[0].area_inside, 4 * 3.2, 1e-9);
  EXPECT_DOUBLE_EQ(sel[0].coverage, 1.0);
  // Rows z 1-2 and 4-5 straddle: in each quad one triangle's centroid (at 1/3 or 2/3 of the row)
  // falls inside; rows 2-3 and 3-4 are kept whole.
  EXPECT_EQ(sel[0].triangles, 4u * 2u * 2u + 4u * 2u);
}

TEST(FaultSelect, CoverageTooLowSaysHowMuchAndWhatToDo) {
  Mesh m = unit_box(6);
  // Off the grid planes: no face lies on it.
  auto e = test::input_error_of([&] { select_fault_faces(m, {trace("off", {{3.5, 1}, {3.5, 5}}, 5, 1, 90, 90)}); });
  EXPECT_NE(e.find("traces: fault 'off': mesh faces cover 0.0 % of its"), std::string::npos) << e;
  EXPECT_NE(e.find("embed the trace in the plan"), std::string::npos) << e;
  // Half on the grid: x = 3 up to y = 3, then off the planes to (4, 6).
  e = test::input_error_of([&] { select_fault_faces(m, {trace("half", {{3, 0}, {3, 3}, {4, 6}}, 6, 0, 90, 90)}); });
  EXPECT_NE(e.find("fault 'half': mesh faces cover 48.7 %"), std::string::npos) << e;
  EXPECT_EQ(m.find_physical(2, "fault:half"), nullptr);  // nothing added on error
  // A lower threshold lets it through.
  FaultSelectOptions o;
  o.min_coverage = 0.4;
  EXPECT_NO_THROW(select_fault_faces(m, {trace("half", {{3, 0}, {3, 3}, {4, 6}}, 6, 0, 90, 90)}, o));
}

TEST(FaultSelect, DepthRangeOutsideTheMesh) {
  Mesh m = unit_box(6);
  const auto e = test::input_error_of([&] { select_fault_faces(m, {trace("deep", {{3, 1}, {3, 5}}, -10, -20, 90, 90)}); });
  EXPECT_NE(e.find("fault 'deep': its depth range, top_m -10.0 to bottom_m -20.0, lies outside the mesh"), std::string::npos) << e;
  const auto e2 = test::input_error_of([&] { select_fault_faces(m, {trace("away", {{30, 1}, {30, 5}}, 5, 1, 90, 90)}); });
  EXPECT_NE(e2.find("fault 'away': its surface does not cross the mesh"), std::string::npos) << e2;
}

TEST(FaultSelect, MeshGroupWinsAndItsDeviationIsMeasured) {
  Mesh m = unit_box(6);
  add_fault_group(m, "F", [](const Point3& p) { return near(p[0], 3); });
  // The file says 45 deg: the mesh's vertical group is kept, 3 m away at the bottom (z = 0, 6 m below the trace).
  const auto sel = select_fault_faces(m, {trace("F", {{3, 0}, {3, 6}}, 6, 0, 45, 270)});
  EXPECT_TRUE(sel[0].from_mesh);
  EXPECT_EQ(sel[0].triangles, 72u);
  EXPECT_NEAR(sel[0].max_deviation, 6 * std::sqrt(0.5), 1e-9);
  EXPECT_EQ(sel[0].beyond_depth, 0u);
  // A file range of 2 to 4 m: the rows 5-6 and 0-1 lie wholly outside it (4-5 and 1-2 touch it).
  const auto sel2 = select_fault_faces(m, {trace("F", {{3, 0}, {3, 6}}, 4, 2, 90, 90)});
  EXPECT_NEAR(sel2[0].max_deviation, 0, 1e-12);
  EXPECT_EQ(sel2[0].beyond_depth, 24u);
  EXPECT_DOUBLE_EQ(sel2[0].zmin, 0);
  EXPECT_DOUBLE_EQ(sel2[0].zmax, 6);
}

TEST(FaultSelect, AlreadyInsertedIsRefused) {
  Mesh m = unit_box(4);
  add_fault_group(m, "F", [](const Point3& p) { return near(p[0], 2); });
  insert_faults(m);
  const auto e = test::input_error_of([&] { select_fault_faces(m, {trace("F", {{2, 0}, {2, 4}}, 4, 0, 90, 90)}); });
  EXPECT_NE(e.find("fault 'F' already has interface elements"), std::string::npos) << e;
}

TEST(FaultTraces, BadTraces) {
  auto bad = [](FaultTrace t) { return test::input_error_of([&] { check_fault_trace(t); }); };
  FaultTrace t;
  t.name = "x";
  t.where = "f.geojson: feature 2";
  t.top = 0;
  t.bottom = -100;
  t.trace_z = 0;
  t.dip_deg = 60;
  t.parts = {{{0, 0}, {10, 10}, {10, 0}, {0, 10}}};  // a bow tie
  EXPECT_EQ(bad(t), "f.geojson: feature 2: fault 'x': the trace crosses itself near (5.00, 5.00): the fault surface would intersect itself");
  t.parts = {{{0, 0}, {10, 0}, {5, 0}}};  // runs back over itself
  EXPECT_NE(bad(t).find("crosses itself near (10.00, 0.00)"), std::string::npos);
  t.parts = {{{0, 0}, {10, 0}}, {{5, -5}, {5, 5}}};
  EXPECT_NE(bad(t).find("touches another of its parts near (5.00, 0.00)"), std::string::npos) << bad(t);
  t.parts = {{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}}};  // closed ring: fine
  EXPECT_EQ(bad(t), "(no InputError)");
  t.parts = {{{0, 0}, {0, 0}}};
  EXPECT_NE(bad(t).find("fewer than two distinct points"), std::string::npos);
  t.parts = {{{0, 0}, {1, 0}}};
  t.bottom = 10;
  EXPECT_NE(bad(t).find("fault 'x': top_m (0.0) must lie above bottom_m (10.0)"), std::string::npos);
  t.bottom = -10;
  t.dip_deg = 0;
  EXPECT_NE(bad(t).find("dip_deg 0 is outside (0, 90]"), std::string::npos);
  t.dip_deg = 90;
  t.dip_dir_deg = -90;
  FaultTrace ok = t;
  check_fault_trace(ok);
  EXPECT_DOUBLE_EQ(ok.dip_dir_deg, 270);
}

TEST(FaultTraces, ReadsTheSampleTwin) {
  const auto traces = read_fault_traces(std::string(UGS_SOURCE_DIR) + "/data-samples/po-plain/faults.geojson");
  ASSERT_EQ(traces.size(), 6u);
  EXPECT_EQ(traces[0].name, "overthrust_north");
  EXPECT_DOUBLE_EQ(traces[0].top, -500);
  EXPECT_DOUBLE_EQ(traces[0].bottom, -5000);
  EXPECT_DOUBLE_EQ(traces[0].dip_deg, 35);
  EXPECT_DOUBLE_EQ(traces[0].dip_dir_deg, 195);
  EXPECT_DOUBLE_EQ(traces[0].trace_z, -1500);  // given at the pools' level (docs/fault-convergence.md)
  EXPECT_EQ(traces[0].parts.at(0).size(), 5u);
  EXPECT_EQ(traces[5].name, "local_4");
}

TEST(FaultTraces, FileErrorsNameTheFeatureAndTheFault) {
  const auto dir = temp_dir("fault-traces");
  auto write = [&](const std::string& props, const std::string& geom = R"({"type":"LineString","coordinates":[[0,0],[1,1]]})") {
    const auto p = dir / "t.geojson";
    spit(p, R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":)" + props +
                R"(,"geometry":)" + geom + "}]}");
    return p.string();
  };
  auto err = [&](const std::string& path) { return test::input_error_of([&] { read_fault_traces(path); }); };
  EXPECT_NE(err(write(R"({"name":"a","top_m":0,"bottom_m":-10,"dip_deg":60})")).find("feature 0: fault 'a': missing field 'dip_dir_deg'"),
            std::string::npos);
  EXPECT_NE(err(write(R"({"name":"a","top_m":0,"bottom_m":-10,"dip_deg":"steep","dip_dir_deg":0})")).find("field 'dip_deg' is not a number"),
            std::string::npos);
  EXPECT_NE(err(write(R"({"name":"a","top_m":0,"bottom_m":-10,"dip_deg":60,"dip_dir_deg":0})",
                      R"({"type":"Point","coordinates":[0,0]})"))
                .find("fault 'a': the feature is not a line"),
            std::string::npos);
  const auto good = read_fault_traces(write(R"({"name":"fault:a","top_m":0,"bottom_m":-10,"dip_deg":"60","dip_dir_deg":0})"));
  EXPECT_EQ(good.at(0).name, "a");
  EXPECT_DOUBLE_EQ(good.at(0).dip_deg, 60);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ugs::test
