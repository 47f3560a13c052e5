// Sampling a known displacement field on the top surface: a field linear in x, y, z is linear on
// every (flat) surface triangle, so linear interpolation must reproduce it to rounding at any point.
#include <gtest/gtest.h>

#include <random>

#include "insar_fixtures.hpp"
#include "run_tool.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/insar/displacement.hpp"
#include "ugs/insar/sampling.hpp"
#include "ugs/insar/surface.hpp"

using namespace ugs;
using namespace ugs::insar;

namespace {

const test::LinearField kF1{{0.001, -0.002, 0.003}, {{1e-6, 2e-6, -3e-6}, {-2e-6, 5e-7, 1e-6}, {3e-6, -1e-6, 2e-6}}};
const test::LinearField kF2{{-0.004, 0.001, 0.002}, {{-2e-6, 1e-6, 4e-6}, {1e-6, -3e-6, 2e-6}, {-1e-6, 2e-6, -5e-6}}};

struct Model {
  std::filesystem::path dir;
  Mesh mesh;
  std::string h5;
};

Model write_model(const std::string& tag, bool surface_only) {
  Model m;
  m.dir = test::temp_dir(tag);
  m.mesh = test::undulating_box(680000, 4950000, 1000, 800, 500, 10, 8, 5, 20);
  m.h5 = (m.dir / "run.h5").string();
  // A surface output holds the bnd:top triangles and their nodes only, as ugs-solve's top file.
  Mesh out = m.mesh;
  if (surface_only) {
    const TopSurface top = surface_from_mesh(m.mesh, "bnd:top", "box");
    out = Mesh{};
    for (std::size_t i = 0; i < top.points.size(); ++i) out.add_node(top.points[i], top.node_tags[i]);
    auto& b = out.block(2, out.entity_for_physical(2, "bnd:top"), ElementType::Triangle);
    for (const auto& t : top.triangles) out.add_element(b, t);
  }
  FieldSeriesWriter w(m.h5, out);
  const Field f1[] = {kF1.field(out)};
  const Field f2[] = {kF2.field(out)};
  w.add_step("2015-05-01", double(*parse_iso_date("2015-05-01")), f1);
  w.add_step("2015-11-01", double(*parse_iso_date("2015-11-01")), f2);
  w.commit();
  return m;
}

}  // namespace

TEST(Sampling, LinearFieldIsReproducedAtRandomPoints) {
  const Model m = write_model("sample-linear", false);
  const TopSurface top = surface_from_mesh(m.mesh, "bnd:top", "box");
  const SurfaceLocator loc(top);
  SurfaceDisplacement res(m.h5, top);
  EXPECT_EQ(res.field(), "u");
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> ux(680000, 681000), uy(4950000, 4950800);
  std::vector<PsPoint> pts;
  for (int i = 0; i < 200; ++i) pts.push_back({std::to_string(i), ux(rng), uy(rng), {}, ""});
  const Located located = locate_points(loc, pts, false);
  ASSERT_EQ(located.sampled.size(), pts.size());
  const std::int64_t t1 = *parse_iso_date("2015-05-01"), t2 = *parse_iso_date("2015-11-01");
  const std::int64_t tm = t1 + (t2 - t1) / 4;
  const Samples s = sample_displacement(res, located.sampled, {t1, tm, t2}, std::nullopt);
  const double w = double(tm - t1) / double(t2 - t1);
  double worst = 0;
  for (std::size_t p = 0; p < pts.size(); ++p) {
    const auto& hit = located.sampled[p].hit;
    EXPECT_DOUBLE_EQ(hit.point[0], pts[p].x);
    EXPECT_DOUBLE_EQ(hit.point[1], pts[p].y);
    EXPECT_EQ(hit.distance, 0.0);
    EXPECT_GT(hit.point[2], -25.0);  // on the undulating top (within 20 m of 0), not on a face 100 m below
    const auto a = kF1.at(hit.point), b = kF2.at(hit.point);
    for (int j = 0; j < 3; ++j) {
      worst = std::max(worst, std::abs(s.at(p, 0)[j] - a[j]));
      worst = std::max(worst, std::abs(s.at(p, 2)[j] - b[j]));
      worst = std::max(worst, std::abs(s.at(p, 1)[j] - ((1 - w) * a[j] + w * b[j])));
    }
  }
  EXPECT_LT(worst, 1e-9) << "worst error in m";
  std::filesystem::remove_all(m.dir);
}

TEST(Sampling, ReferenceDateAndOutsidePoints) {
  const Model m = write_model("sample-ref", false);
  const TopSurface top = surface_from_mesh(m.mesh, "bnd:top", "box");
  const SurfaceLocator loc(top);
  SurfaceDisplacement res(m.h5, top);
  const std::vector<PsPoint> pts{{"in", 680500, 4950400, {}, ""}, {"out", 681100, 4950400, {}, ""}};
  const Located dropped = locate_points(loc, pts, false);
  ASSERT_EQ(dropped.sampled.size(), 1u);
  ASSERT_EQ(dropped.outside.size(), 1u);
  EXPECT_NEAR(dropped.outside[0].hit.distance, 100.0, 1e-9);
  const Located kept = locate_points(loc, pts, true);
  ASSERT_EQ(kept.sampled.size(), 2u);
  EXPECT_FALSE(kept.sampled[1].hit.inside);
  EXPECT_NEAR(kept.sampled[1].hit.point[0], 681000.0, 1e-9);
  EXPECT_NEAR(kept.sampled[1].hit.point[1], 4950400.0, 1e-9);
  const std::int64_t t1 = *parse_iso_date("2015-05-01");
  const Samples s = sample_displacement(res, kept.sampled, {}, t1);
  ASSERT_EQ(s.dates.size(), 2u);
  for (std::size_t p = 0; p < 2; ++p) {
    const auto& x = kept.sampled[p].hit.point;
    const auto a = kF1.at(x), b = kF2.at(x);
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(s.at(p, 0)[j], 0.0, 1e-12);
      EXPECT_NEAR(s.at(p, 1)[j], b[j] - a[j], 1e-9);
    }
  }
  EXPECT_THROW(sample_displacement(res, kept.sampled, {}, *parse_iso_date("2030-01-01")), InputError);
}

TEST(Sampling, SurfaceFromResultsMatchesMeshGroup) {
  // Tetrahedra only in the file: the top is their upward boundary; triangles only: the file's own.
  for (bool surface_only : {false, true}) {
    const Model m = write_model(surface_only ? "sample-tri" : "sample-tet", surface_only);
    const FieldSeriesReader r(m.h5);
    const TopSurface top = surface_from_results(r);
    const TopSurface ref = surface_from_mesh(m.mesh, "bnd:top", "box");
    EXPECT_EQ(top.triangles.size(), ref.triangles.size());
    const SurfaceLocator loc(top);
    SurfaceDisplacement res(m.h5, top);
    const auto hit = loc.locate(680321.5, 4950123.25);
    ASSERT_TRUE(hit.inside);
    const Samples s = sample_displacement(res, {{{"p", 680321.5, 4950123.25, {}, ""}, hit}}, {}, std::nullopt);
    const auto a = kF1.at(hit.point);
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(s.at(0, 0)[j], a[j], 1e-9);
  }
}

TEST(Sampling, MismatchedMeshIsAnInputError) {
  const Model m = write_model("sample-mismatch", false);
  Mesh other = m.mesh;
  for (auto& p : other.nodes) p[0] += 5;
  const TopSurface top = surface_from_mesh(other, "bnd:top", "other");
  EXPECT_THROW(SurfaceDisplacement(m.h5, top), InputError);
}
