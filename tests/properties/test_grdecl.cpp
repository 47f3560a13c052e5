// GRDECL reading (formats/grdecl.hpp) and the corner-point grid it gives (corner_point_grid.hpp):
// repeat counts, comments, INCLUDE, keywords of records, the cells' corners by hand, MAPAXES and
// GRIDUNIT, and the one-line errors.
#include <gtest/gtest.h>

#include <functional>

#include "input_error.hpp"
#include "run_tool.hpp"
#include "ugs/formats/corner_point_grid.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/grdecl.hpp"

using namespace ugs;

namespace {

// 2 x 1 x 1 cells of 10 x 20 m, 5 m thick at depth 1000 (cell 2 dipping 1 m east), vertical pillars.
const char* kGrid = R"(-- two cells
SPECGRID
 2 1 1 1 F /
COORD
 0 0 900  0 0 1100   10 0 900 10 0 1100   20 0 900 20 0 1100
 0 20 900 0 20 1100  10 20 900 10 20 1100 20 20 900 20 20 1100 /
ZCORN
 1000 1000 1000 1001  1000 1000 1000 1001   -- top, j = 0 (west, east of each cell), then j = 1
 1005 1005 1005 1006  1005 1005 1005 1006 /
FAULTS
 'F1' 2 2 1 1 1 1 'X' /
/
PORO
 0.1 2*0.25/
)";


}  // namespace

TEST(Grdecl, ReadsRepeatsCommentsIncludesAndRecords) {
  test::TempDir d("grdecl-read");
  test::spit(d / "grid.grdecl", kGrid);
  test::spit(d / "main.grdecl", "INCLUDE\n 'grid.grdecl' /\nNTG -- net to gross\n 3*0.5 /\n");
  const GrdeclFile f = read_grdecl(d / "main.grdecl");
  ASSERT_NE(f.find("PORO"), nullptr);
  EXPECT_EQ(f.find("PORO")->values, (std::vector<double>{0.1, 0.25, 0.25}));
  EXPECT_EQ(f.find("PORO")->where, d / "grid.grdecl" + ":13");  // the keyword's line
  EXPECT_EQ(f.find("NTG")->values, (std::vector<double>{0.5, 0.5, 0.5}));
  EXPECT_EQ(f.find("SPECGRID")->words, (std::vector<std::string>{"F"}));
  EXPECT_EQ(f.find("FAULTS"), nullptr);  // records skipped
  EXPECT_EQ(f.find("ZCORN")->values.size(), 16u);
  // Only the keywords asked for keep their values.
  const GrdeclFile only = read_grdecl(d / "main.grdecl", {"NTG"});
  EXPECT_EQ(only.find("PORO"), nullptr);
  EXPECT_NE(only.find("NTG"), nullptr);
}

TEST(Grdecl, CornersOnThePillarsAtTheirDepths) {
  test::TempDir d("grdecl-corners");
  test::spit(d / "grid.grdecl", kGrid);
  const CornerPointGrid g = corner_point_grid(read_grdecl(d / "grid.grdecl"));
  EXPECT_EQ(g.dims, (std::array<int, 3>{2, 1, 1}));
  ASSERT_EQ(g.num_active(), 2u);
  // Cell 2 (i = 1): top face (10,0) (20,0) (10,20) (20,20) at depths 1000 1001 1000 1001, z = -depth.
  EXPECT_EQ(g.corners[1][0], (Point3{10, 0, -1000}));
  EXPECT_EQ(g.corners[1][1], (Point3{20, 0, -1001}));
  EXPECT_EQ(g.corners[1][3], (Point3{20, 20, -1001}));
  EXPECT_EQ(g.corners[1][7], (Point3{20, 20, -1006}));
  EXPECT_EQ(g.corners[0][4], (Point3{0, 0, -1005}));
}

TEST(Grdecl, LeaningPillarsMapaxesFeetAndActnum) {
  test::TempDir d("grdecl-map");
  // One cell, pillars leaning 10 ft east over 100 ft, in feet, MAPAXES in metres turning the grid
  // by 90 degrees (local x along map y) about (1000, 2000); ACTNUM 1.
  test::spit(d / "g.grdecl", R"(SPECGRID
 1 1 1 1 F /
GRIDUNIT
 'FEET' /
MAPUNITS
 'METRES' /
MAPAXES
 900 2000 1000 2000 1000 2100 /
COORD
 0 0 0 10 0 100   100 0 0 110 0 100
 0 100 0 10 100 100   100 100 0 110 100 100 /
ZCORN
 4*50 4*100 /
ACTNUM
 1 /
)");
  const CornerPointGrid g = corner_point_grid(read_grdecl(d / "g.grdecl"));
  ASSERT_EQ(g.num_active(), 1u);
  EXPECT_TRUE(g.mapaxes);
  // Corner 0: on pillar (0,0) at depth 50 ft: local x = 5 ft, y = 0 -> map (1000 - 0, 2000 + 5 ft).
  const double ft = 0.3048;
  const Point3 c0 = g.corners[0][0];
  EXPECT_NEAR(c0[0], 1000.0, 1e-9);
  EXPECT_NEAR(c0[1], 2000.0 + 5 * ft, 1e-9);
  EXPECT_NEAR(c0[2], -50 * ft, 1e-9);
  // Corner 3 ((1,1) top): local (105, 100) ft -> map x = 1000 - 100 ft, y = 2000 + 105 ft.
  EXPECT_NEAR(g.corners[0][3][0], 1000.0 - 100 * ft, 1e-9);
  EXPECT_NEAR(g.corners[0][3][1], 2000.0 + 105 * ft, 1e-9);
}

TEST(Grdecl, BadFilesAreOneLineErrors) {
  test::TempDir d("grdecl-bad");
  EXPECT_NE(test::input_error_of([&] { read_grdecl(d / "none.grdecl"); }).find("no such file"), std::string::npos);
  test::spit(d / "open.grdecl", "PORO\n 0.1 0.2\n");
  EXPECT_EQ(test::input_error_of([&] { read_grdecl(d / "open.grdecl"); }), d / "open.grdecl" + ":1: PORO has no closing '/' before the end of the file");
  test::spit(d / "rep.grdecl", "PORO\n x*0.1 /\n");
  EXPECT_NE(test::input_error_of([&] { read_grdecl(d / "rep.grdecl"); }).find(":2: 'x*0.1' in PORO: the repeat count"), std::string::npos);
  test::spit(d / "eq.grdecl", "EQUALS\n 'PORO' 0.2 /\n/\n");
  EXPECT_NE(test::input_error_of([&] { read_grdecl(d / "eq.grdecl"); }).find(":1: EQUALS computes arrays"), std::string::npos);
  test::spit(d / "short.grdecl", std::string(kGrid).replace(std::string(kGrid).find("1005 1005 1005 1006  1005"), 4, ""));
  EXPECT_NE(test::input_error_of([&] { corner_point_grid(read_grdecl(d / "short.grdecl")); }).find("ZCORN has 15 values, expected 16"),
            std::string::npos);
  test::spit(d / "nogrid.grdecl", "PORO\n 1 /\n");
  EXPECT_NE(test::input_error_of([&] { corner_point_grid(read_grdecl(d / "nogrid.grdecl")); }).find("no SPECGRID or DIMENS keyword"),
            std::string::npos);
}
