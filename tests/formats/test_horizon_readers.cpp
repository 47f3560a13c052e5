// The horizon readers of formats/ (IRAP classic ASCII, CPS-3 ASCII, GOCAD TSurf) on hand-written
// files: node order and positions, undefined nodes, rotation, and the refusals that name the line:
// a header that disagrees with itself or with the count of values, a TRGL naming no vertex, ...
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "input_error.hpp"
#include "run_tool.hpp"
#include "ugs/formats/gocad_tsurf.hpp"
#include "ugs/formats/horizon_grid.hpp"

using namespace ugs;
using ugs::test::input_error_of;

namespace {

struct Files {
  ugs::test::TempDir dir{"horizon-readers"};
  std::string write(const std::string& name, const std::string& text) {
    const std::string p = (dir.path / name).string();
    std::ofstream(p) << text;
    return p;
  }
};

// 3 columns x 2 rows, x fastest from the origin's row; one undefined node.
const char* irap3x2 =
    "-996 2 50.000000 25.000000\n"
    "1000.000000 1100.000000 2000.000000 2025.000000\n"
    "3 0.000000 1000.000000 2000.000000\n"
    "0  0  0  0  0  0  0\n"
    " -1000.5 -1001.5 -1002.5 -1010.25\n"
    " 9999900.000000 -1012.25\n";

}  // namespace

TEST(IrapGrid, NodesXFastestFromTheOrigin) {
  Files f;
  const HorizonGrid g = read_irap_grid(f.write("a.irap", irap3x2));
  EXPECT_EQ(g.nx, 3u);
  EXPECT_EQ(g.ny, 2u);
  EXPECT_EQ(g.x0, 1000.0);
  EXPECT_EQ(g.y0, 2000.0);
  EXPECT_EQ(g.dx, 50.0);
  EXPECT_EQ(g.dy, 25.0);
  EXPECT_EQ(g.at(0, 0), -1000.5);
  EXPECT_EQ(g.at(2, 0), -1002.5);
  EXPECT_EQ(g.at(0, 1), -1010.25);
  EXPECT_TRUE(std::isnan(g.at(1, 1)));
  EXPECT_EQ(g.at(2, 1), -1012.25);
  EXPECT_EQ(g.undefined, 1u);
  EXPECT_EQ(detect_horizon_format(f.write("b.dat", irap3x2)), HorizonFormat::Irap);
}

TEST(IrapGrid, RotationIsCounterClockwiseAboutTheOrigin) {
  Files f;
  const HorizonGrid g = read_irap_grid(f.write("r.irap",
                                               "-996 2 100 100\n0 100 0 100\n2 90 0 0\n0 0 0 0 0 0 0\n1 2 3 4\n"));
  EXPECT_EQ(g.rotation_deg, 90.0);
  const auto p = g.node(1, 0);  // 100 m along the grid's x axis, turned 90 degrees: north
  EXPECT_NEAR(p[0], 0.0, 1e-9);
  EXPECT_NEAR(p[1], 100.0, 1e-9);
  const auto q = g.node(0, 1);
  EXPECT_NEAR(q[0], -100.0, 1e-9);
  EXPECT_NEAR(q[1], 0.0, 1e-9);
  EXPECT_NE(input_error_of([&] {
              read_irap_grid(f.write("r2.irap", "-996 2 100 100\n0 100 0 100\n2 90 5 0\n0 0 0 0 0 0 0\n1 2 3 4\n"));
            }).find("r2.irap:3: the grid is rotated about (5, 0), not about its origin"),
            std::string::npos);
}

TEST(IrapGrid, AHeaderThatDisagreesWithItsValuesIsRefusedNamingTheLine) {
  Files f;
  const std::string fewer = f.write("fewer.irap", std::string(irap3x2).substr(0, std::string(irap3x2).rfind(" -1012.25")) + "\n");
  EXPECT_NE(input_error_of([&] { read_irap_grid(fewer); })
                .find("fewer.irap:6: the file ends after 5 values, the header's NX x NY = 3 x 2 needs 6"),
            std::string::npos);
  const std::string more = f.write("more.irap", std::string(irap3x2) + "-1013\n");
  EXPECT_NE(input_error_of([&] { read_irap_grid(more); }).find("more.irap:7: value 7 '-1013' is one more than"),
            std::string::npos);
  const std::string xmax = f.write("xmax.irap", "-996 2 50 25\n1000 1150 2000 2025\n3 0 1000 2000\n0 0 0 0 0 0 0\n1 2 3 4 5 6\n");
  EXPECT_NE(input_error_of([&] { read_irap_grid(xmax); })
                .find("xmax.irap:2: XMAX 1150 disagrees with XORI + (NX - 1) XINC = 1000 + 2 x 50 = 1100"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { read_irap_grid(f.write("bad.irap", "-996 2 50 25\n1000 1100 abc 2025\n")); })
                .find("bad.irap:2: YORI: 'abc' is not a finite number"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { read_irap_grid(f.write("nx.irap", "-996 2 50 25\n1000 1100 2000 2025\n1 0 0 0\n")); })
                .find("nx.irap:3: NX: '1' is not a whole number from 2 to"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { read_irap_grid(f.write("nan.irap", std::string(irap3x2) + "nan\n")); }).find("nan.irap:7"),
            std::string::npos);
}

TEST(Cps3Grid, ColumnsFromTheWestEachFromTheNorth) {
  Files f;
  const std::string p = f.write("a.cps",
                                "FSASCI 0 1 COMPUTED 0 1.0000000E+30\nFSATTR 0 0\n"
                                "FSLIMI 1000.0 1100.0 2000.0 2025.0 -1013 -1000\nFSNROW 2 3\nFSXINC 50.0 25.0\n->top\n"
                                "-1010.25 -1000.5 0.1E+31 -1001.5 -1012.25\n-1002.5\n");
  EXPECT_EQ(detect_horizon_format(p), HorizonFormat::Cps3);
  const HorizonGrid g = read_cps3_grid(p);
  EXPECT_EQ(g.nx, 3u);
  EXPECT_EQ(g.ny, 2u);
  EXPECT_EQ(g.x0, 1000.0);
  EXPECT_EQ(g.y0, 2000.0);
  EXPECT_EQ(g.at(0, 0), -1000.5);
  EXPECT_EQ(g.at(0, 1), -1010.25);
  EXPECT_TRUE(std::isnan(g.at(1, 1)));
  EXPECT_EQ(g.at(1, 0), -1001.5);
  EXPECT_EQ(g.at(2, 1), -1012.25);
  EXPECT_EQ(g.at(2, 0), -1002.5);
  EXPECT_EQ(g.undefined, 1u);
}

TEST(Cps3Grid, AHeaderThatDisagreesWithItsValuesIsRefusedNamingTheLine) {
  Files f;
  const std::string head = "FSASCI 0 1 COMPUTED 0 1e30\nFSLIMI 0 100 0 25\nFSNROW 2 3\nFSXINC 50 25\n";
  EXPECT_NE(input_error_of([&] { read_cps3_grid(f.write("few.cps", head + "1 2 3 4 5\n")); })
                .find("few.cps:5: the file ends after 5 values, FSNROW 2 x 3 needs 6"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { read_cps3_grid(f.write("more.cps", head + "1 2 3 4 5\n6 7\n")); })
                .find("more.cps:6: value 7 '7' is one more than FSNROW's 2 x 3 = 6"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] {
              read_cps3_grid(f.write("lim.cps", "FSASCI 0 1 C 0 1e30\nFSLIMI 0 150 0 25\nFSNROW 2 3\nFSXINC 50 25\n1 2 3 4 5 6\n"));
            }).find("lim.cps:2: FSLIMI 0 150 0 25 disagrees with FSNROW 2 3 and FSXINC 50 25 (line 4)"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { read_cps3_grid(f.write("rot.cps", "FSASCI 0 1 C 0 1e30\nFSROTA 30\n")); })
                .find("rot.cps:2: unknown CPS-3 header keyword 'FSROTA'"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { read_cps3_grid(f.write("inc.cps", "FSASCI 0 1 C 0 1e30\nFSNROW 2 3\nFSXINC 50 25\n1\n")); })
                .find("inc.cps:4: no FSLIMI line before the values"),
            std::string::npos);
}

TEST(GocadTsurf, VerticesAtomsTrianglesAndDepth) {
  Files f;
  const std::string p = f.write("h.ts",
                                "GOCAD TSurf 1\nHEADER {\nname:top\n*solid*color:1 0 0 1\n}\n"
                                "GOCAD_ORIGINAL_COORDINATE_SYSTEM\nNAME Default\nAXIS_UNIT \"m\" \"m\" \"m\"\n"
                                "ZPOSITIVE Depth\nEND_ORIGINAL_COORDINATE_SYSTEM\nPROPERTIES a\nTFACE\n"
                                "VRTX 1 0 0 1000\nPVRTX 2 100 0 1010 7\nVRTX 3 0 100 1020\nTRGL 1 2 3\nTFACE\n"
                                "ATOM 4 2\nVRTX 5 100 100 1030\nVRTX 6 0 100 1020\nTRGL 4 5 6\nBSTONE 1\nBORDER 7 1 2\nEND\n");
  EXPECT_EQ(detect_horizon_format(p), HorizonFormat::Tsurf);
  const TriangulatedSurface s = read_gocad_tsurf(p);
  ASSERT_EQ(s.vertices.size(), 4u);  // vertex 6 is vertex 3 again: merged
  EXPECT_EQ(s.merged_vertices, 1u);
  EXPECT_TRUE(s.depth_positive);
  EXPECT_EQ(s.vertices[0][2], -1000.0);
  EXPECT_EQ(s.vertices[3][2], -1030.0);
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.triangles[1], (std::array<std::uint32_t, 3>{1, 3, 2}));
  EXPECT_EQ(s.triangle_line[1], 21u);
  EXPECT_EQ(s.faces, 2u);
}

TEST(GocadTsurf, RefusalsNameTheLine) {
  Files f;
  const std::string head = "GOCAD TSurf 1\nTFACE\nVRTX 1 0 0 0\nVRTX 2 1 0 0\nVRTX 3 0 1 0\n";
  EXPECT_NE(input_error_of([&] { read_gocad_tsurf(f.write("a.ts", head + "TRGL 1 2 9\nEND\n")); })
                .find("a.ts:6: TRGL 9 names no vertex of this TSurf"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { read_gocad_tsurf(f.write("b.ts", head + "TRGL 1 2 3\n")); })
                .find("b.ts:6: the TSurf object begun at line 1 has no END"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { read_gocad_tsurf(f.write("c.ts", head + "TRGL 1 2 2\nEND\n")); })
                .find("c.ts:6: TRGL 1 2 2 has two corners at one vertex"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { read_gocad_tsurf(f.write("d.ts", head + "SEG 1 2\nEND\n")); })
                .find("d.ts:6: unknown keyword 'SEG' inside a TFACE"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { read_gocad_tsurf(f.write("e.ts", head + "VRTX 2 5 5 5\nEND\n")); })
                .find("e.ts:6: vertex id 2 is given twice"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] {
              read_gocad_tsurf(f.write("f.ts", "GOCAD TSurf 1\nGOCAD_ORIGINAL_COORDINATE_SYSTEM\nAXIS_UNIT \"ft\" \"ft\" \"ft\"\n"));
            }).find("f.ts:3: AXIS_UNIT \"ft\": ugs reads coordinates in metres"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { read_gocad_tsurf(f.write("g.ts", "GOCAD PLine 1\nEND\n")); })
                .find("g.ts:1: a GOCAD PLine object, not a TSurf"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { read_gocad_tsurf(f.write("h.ts", head + "END\n")); }).find("h.ts:6: the TSurf has no triangle"),
            std::string::npos);
}
