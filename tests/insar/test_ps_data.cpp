// PS points and series: the EGMS ortho layout (EPSG:3035 coordinates reprojected to the model
// CRS), generic CSV and OGR files, and the bad inputs the tools must refuse with a file:line error.
#include <gtest/gtest.h>

#include <cmath>

#include "run_tool.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/insar/crs.hpp"
#include "ugs/insar/ps_data.hpp"

using namespace ugs;
using namespace ugs::insar;

namespace {
const std::string kSample = std::string(UGS_SOURCE_DIR) + "/data-samples/po-plain/";

std::string error_of(const std::string& path, const PsReadOptions& o) {
  try {
    read_ps(path, o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(PsData, EgmsSampleMatchesThePointFileAfterReprojection) {
  PsReadOptions o;
  o.model_crs = any_crs_wkt("EPSG:32632", "test");
  const PsData up = read_ps(kSample + "insar_vertical.csv", o);
  EXPECT_EQ(up.layout, "EGMS");
  EXPECT_TRUE(up.reprojected);
  EXPECT_EQ(crs_name(up.source_crs), "EPSG:3035");
  ASSERT_EQ(up.points.size(), 6u);
  EXPECT_EQ(up.dates.size(), 485u);
  EXPECT_EQ(up.dates.front(), *parse_iso_date("2003-10-11"));
  EXPECT_EQ(up.value_mm(0, 0), 0.0);  // EGMS series start at 0
  const PsData geo = read_ps(kSample + "ps_points.geojson", o);
  EXPECT_EQ(geo.layout, "OGR");
  ASSERT_EQ(geo.points.size(), 6u);
  for (const auto& p : geo.points) {
    const auto i = up.find(p.id);
    ASSERT_TRUE(i) << p.id;
    EXPECT_NEAR(up.points[*i].x, p.x, 0.01) << p.id;  // README: they match to 4 mm
    EXPECT_NEAR(up.points[*i].y, p.y, 0.01) << p.id;
    ASSERT_TRUE(p.height);
  }
  // The Table 4.1 point.
  const auto vjp = geo.find("A016VJP");
  ASSERT_TRUE(vjp);
  EXPECT_NEAR(geo.points[*vjp].x, 681763.4, 0.01);
  EXPECT_NEAR(geo.points[*vjp].y, 4952171.8, 0.01);
}

TEST(PsData, GenericCsvInModelCrsAndLonLat) {
  const auto dir = test::temp_dir("ps-generic");
  test::spit(dir / "xy.csv", "name,x,y,2015-05-01,2015-11-01\nP1,681000,4952000,0,3.5\nP2,682000,4953000,,1.0\n");
  PsReadOptions o;
  const PsData xy = read_ps((dir / "xy.csv").string(), o);
  EXPECT_EQ(xy.layout, "CSV");
  EXPECT_FALSE(xy.reprojected);
  ASSERT_EQ(xy.points.size(), 2u);
  EXPECT_EQ(xy.points[1].id, "P2");
  EXPECT_TRUE(std::isnan(xy.value_mm(1, 0)));
  EXPECT_EQ(xy.value_mm(0, 1), 3.5);
  // lon/lat: EPSG:4326 by default; reference values from GDAL's Python bindings (osr).
  test::spit(dir / "ll.csv", "id,lon,lat\nc,11.29,44.70\n");
  o.model_crs = any_crs_wkt("EPSG:32632", "test");
  const PsData ll = read_ps((dir / "ll.csv").string(), o);
  ASSERT_EQ(ll.points.size(), 1u);
  EXPECT_TRUE(ll.reprojected);
  EXPECT_NEAR(ll.points[0].x, 681426.965, 0.01);
  EXPECT_NEAR(ll.points[0].y, 4952176.025, 0.01);
  // ... and refused without a model CRS.
  o.model_crs.clear();
  EXPECT_NE(error_of((dir / "ll.csv").string(), o).find("model CRS"), std::string::npos);
}

TEST(PsData, BadInputsNameFileAndLine) {
  const auto dir = test::temp_dir("ps-bad");
  PsReadOptions o;
  o.model_crs = any_crs_wkt("EPSG:32632", "test");
  auto write = [&](const std::string& name, const std::string& text) {
    test::spit(dir / name, text);
    return (dir / name).string();
  };
  // Missing columns: EGMS without northing; no coordinates at all; EGMS without pid.
  EXPECT_NE(error_of(write("a.csv", "pid,easting,height,20150101\nA,4400000,10,0\n"), o).find("no column 'northing'"),
            std::string::npos);
  EXPECT_NE(error_of(write("b.csv", "pid,foo,bar\nA,1,2\n"), o).find("no coordinate columns"), std::string::npos);
  EXPECT_NE(error_of(write("c.csv", "easting,northing,20150101\n4400000,2400000,0\n"), o).find("no column 'pid'"),
            std::string::npos);
  // Dates that do not parse, or go backwards.
  EXPECT_NE(error_of(write("d.csv", "pid,easting,northing,20150101,20151341\nA,4400000,2400000,0,1\n"), o)
                .find("d.csv:1: column '20151341' is not a date"),
            std::string::npos);
  EXPECT_NE(error_of(write("e.csv", "pid,easting,northing,20150201,20150101\nA,4400000,2400000,0,1\n"), o)
                .find("is not after"),
            std::string::npos);
  // A point with no data, a non-numeric value, duplicate ids.
  EXPECT_NE(error_of(write("f.csv", "pid,easting,northing,20150101,20150201\nA,4400000,2400000,0,1\nB,4400010,2400000,,\n"), o)
                .find("f.csv:3: point 'B' has no data"),
            std::string::npos);
  EXPECT_NE(error_of(write("g.csv", "pid,easting,northing,20150101\nA,4400000,2400000,x1\n"), o).find("g.csv:2"),
            std::string::npos);
  EXPECT_NE(error_of(write("h.csv", "pid,x,y\nA,1,2\nA,3,4\n"), o).find("also used"), std::string::npos);
  // A displacement of a kilometre or more (-1e308 mm squared to inf in the misfit, written with exit 0).
  EXPECT_NE(error_of(write("l.csv", "pid,easting,northing,20150101,20150201\nA,4400000,2400000,0,-1e308\n"), o)
                .find("l.csv:2: column '20150201': displacement -1e+308 mm (expected at most 1e+06 mm"),
            std::string::npos);
  EXPECT_NE(error_of(write("m.csv", "pid,easting,northing,20150101\nA,4400000,2400000,1000000.5\n"), o).find("m.csv:2"),
            std::string::npos);
  EXPECT_EQ(read_ps(write("n.csv", "pid,easting,northing,20150101\nA,4400000,2400000,-1000000\n"), o).values_mm[0], -1e6);
  EXPECT_NE(error_of(write("i.csv", "pid,x,y\n"), o).find("no points"), std::string::npos);
  // A series required but absent.
  PsReadOptions series = o;
  series.require_series = true;
  EXPECT_NE(error_of(write("j.csv", "pid,x,y\nA,1,2\n"), series).find("no date columns"), std::string::npos);
  // Not a point geometry.
  const std::string line = write("k.geojson", R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"pid":"L"},
    "geometry":{"type":"LineString","coordinates":[[0,0],[1,1]]}}]})");
  EXPECT_NE(error_of(line, o).find("not a point"), std::string::npos);
}

TEST(PsData, SelectPoints) {
  PsReadOptions o;
  o.model_crs = any_crs_wkt("EPSG:32632", "test");
  const PsData up = read_ps(kSample + "insar_vertical.csv", o);
  const PsData two = select_points(up, {"A016VNW", "A00LFZ4"});
  ASSERT_EQ(two.points.size(), 2u);
  EXPECT_EQ(two.points[0].id, "A016VNW");
  EXPECT_EQ(two.value_mm(1, 100), up.value_mm(*up.find("A00LFZ4"), 100));
  EXPECT_THROW(select_points(up, {"NOPE"}), InputError);
}
