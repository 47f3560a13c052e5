// Material constants that vary in space (meshing/properties): each source sampled at tetrahedra
// (a table by elevation and by depth, a map, a cell field by element tag, a GRDECL array through
// the corner-point grid of the ECLIPSE tests' deck), the per-tetrahedron copies of a material, and
// the bad input: a tetrahedron the source does not cover, a value the key does not allow, a
// keyword or file that is not there, a key that cannot vary.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "input_error.hpp"
#include "case_toml.hpp"
#include "run_tool.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/meshing/box_mesh.hpp"
#include "ugs/meshing/field_sources.hpp"
#include "ugs/meshing/material_fields.hpp"

using namespace ugs;

namespace {


// A mesh of one small tetrahedron (edge 2 m) per point, centroid exactly there, material `mat`.
Mesh tets_at(const std::vector<Point3>& points, const std::string& mat = "rock") {
  Mesh m;
  const int e = m.entity_for_physical(3, "mat:" + mat);
  for (const Point3& p : points) {
    // Corners (0,0,0) (2,0,0) (0,2,0) (0,0,2) about their centroid (0.5, 0.5, 0.5).
    const Point3 c[4] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
    std::uint32_t n[4];
    for (int k = 0; k < 4; ++k) n[k] = m.add_node({p[0] + c[k][0] - 0.5, p[1] + c[k][1] - 0.5, p[2] + c[k][2] - 0.5});
    m.add_element(m.block(3, e, ElementType::Tetrahedron), n);
  }
  return m;
}

// A case with one material "rock" whose lines are `lines` (besides its name).
CaseFile case_with(const test::TempDir& d, const std::string& lines, const std::string& head = "") {
  testcase::CaseToml c(head);
  c.material({.name = "rock", .more = lines});
  testcase::write_text(d / "case.toml", c.str());
  return read_case_file(d / "case.toml");
}

std::vector<double> values_of(const MaterialFieldValues& v, double (*get)(const MaterialSpec&)) {
  std::vector<double> out;
  for (std::size_t t = 0; t < v.instance.size(); ++t) out.push_back(get(v.specs.at(static_cast<std::size_t>(v.instance[t]))));
  return out;
}

double c_R_of(const MaterialSpec& m) { return *m.c_R; }
double porosity_of(const MaterialSpec& m) { return *m.porosity; }

}  // namespace

TEST(MaterialFields, TableByElevationAndByDepth) {
  test::TempDir d("mf-table");
  // Elevation rows -1000 -> 2, -900 -> 4: linear between, the rows' values at them.
  const CaseFile c = case_with(d, "c_R = { elevation_table = [[-1000, 2.0], [-900, 4.0]] }\n"
                                  "porosity = { depth_table = [[900, 0.1], [1010, 0.32]], scale = 0.5 }\n",
                               "[initial_stress]\nsurface_elevation_m = 10.0\n\n");
  const Mesh m = tets_at({{0, 0, -1000}, {5, 0, -950}, {0, 9, -900}, {1, 1, -975}});
  const MaterialFieldValues v = material_field_values(m, c);
  EXPECT_EQ(values_of(v, c_R_of), (std::vector<double>{2.0, 3.0, 4.0, 2.5}));
  // Depth below surface_elevation_m = 10: 1010, 960, 910, 985 m; 0.5 x (0.1 + 0.22 (d - 900) / 110).
  const std::vector<double> n = values_of(v, porosity_of);
  const double want[4] = {0.16, 0.5 * (0.1 + 0.22 * 60 / 110), 0.5 * (0.1 + 0.22 * 10 / 110), 0.5 * (0.1 + 0.22 * 85 / 110)};
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(n[static_cast<std::size_t>(k)], want[k], 1e-14) << k;
  EXPECT_EQ(v.specs.size(), 4u);
  EXPECT_TRUE(v.specs[0].fields.empty());
  EXPECT_EQ(v.specs[0].cm_a, c.materials[0].cm_a);  // the other constants are the material's
}

TEST(MaterialFields, EqualValuesShareOneCopyAndOtherMaterialsNone) {
  test::TempDir d("mf-share");
  testcase::CaseToml t;
  t.material({.name = "rock", .more = "biot = { elevation_table = [[-2000, 0.8], [-1000, 0.8]] }\n"});
  t.material({.name = "cap", .more = "biot = 0.5\n"});
  testcase::write_text(d / "case.toml", t.str());
  const CaseFile c = read_case_file(d / "case.toml");
  BoxMeshSpec s;
  s.x = linspace(0, 100, 2);
  s.y = linspace(0, 100, 1);
  s.z = linspace(-1500, -1400, 2);
  s.material = [](const Point3& p) { return std::string(p[2] > -1450 ? "cap" : "rock"); };
  const Mesh m = make_box_mesh(s);
  const MaterialFieldValues v = material_field_values(m, c);
  ASSERT_EQ(v.specs.size(), 1u);
  EXPECT_EQ(v.specs[0].biot, 0.8);
  std::size_t rock = 0, own = 0;
  for (const auto i : v.instance) (i == 0 ? rock : own) += 1;
  EXPECT_EQ(rock, 12u);
  EXPECT_EQ(own, 12u);
  // No field in the case: nothing is read, no copy.
  testcase::CaseToml plain;
  plain.material({.name = "rock"});
  plain.material({.name = "cap"});
  testcase::write_text(d / "plain.toml", plain.str());
  EXPECT_TRUE(material_field_values(m, read_case_file(d / "plain.toml")).instance.empty());
}

TEST(MaterialFields, MapBilinearAtTheCentroid) {
  test::TempDir d("mf-map");
  // IRAP classic: 3 x 2 nodes from (1000, 2000), 50 x 25 m; one node undefined (9999900).
  test::spit(d / "e.irap", "-996 2 50.000000 25.000000\n1000.0 1100.0 2000.0 2025.0\n3 0.0 1000.0 2000.0\n0 0 0 0 0 0 0\n"
                           " 10 20 30 40\n 50 9999900\n");
  const CaseFile c = case_with(d, "E_MPa = { map = \"e.irap\" }\nlaw = \"linear\"\n");
  const MaterialFieldValues v = material_field_values(tets_at({{1025, 2012.5, -5}, {1000, 2025, -700}}), c);
  // (1025, 2012.5): the middle of the cell 10 20 / 40 50 -> 30 MPa; the node (1000, 2025) -> 40 MPa.
  EXPECT_DOUBLE_EQ(*v.specs[0].E_Pa, 30e6);
  EXPECT_DOUBLE_EQ(*v.specs[1].E_Pa, 40e6);
  // Next to the undefined node, or off the map: not covered.
  const std::string e = test::input_error_of([&] { material_field_values(tets_at({{1075, 2012.5, -5}}), c); });
  EXPECT_NE(e.find(d / "case.toml:3: material 'rock' E_MPa: tetrahedron 1 (centroid 1075.00, 2012.50, -5.00) of the material lies "
                       "outside the field's source"), std::string::npos) << e;
  EXPECT_NE(test::input_error_of([&] { material_field_values(tets_at({{990, 2010, -5}}), c); }).find("outside the map"), std::string::npos);
}

TEST(MaterialFields, CellFieldByElementTag) {
  test::TempDir d("mf-cells");
  BoxMeshSpec s;
  s.x = linspace(0, 10, 1);
  s.y = linspace(0, 10, 1);
  s.z = linspace(-10, 0, 1);
  const Mesh m = make_box_mesh(s);
  Field f{"cr", 1, {}}, six{"six", 6, {}};
  for (std::size_t t = 0; t < 6; ++t) f.values.push_back(1.5 + static_cast<double>(t)), six.values.resize(six.values.size() + 6, 1.0);
  {
    FieldSeriesWriter w(d / "cr.h5", m, {{ElementType::Tetrahedron}});
    const Field cells[2] = {f, six};
    w.add_step("2020-01-01", 0, {}, cells);
    w.commit();
  }
  const CaseFile c = case_with(d, "c_R = { cells = \"cr.h5\", field = \"cr\", date = \"2020-01-01\" }\n");
  const MaterialFieldValues v = material_field_values(m, c);
  EXPECT_EQ(values_of(v, c_R_of), (std::vector<double>{1.5, 2.5, 3.5, 4.5, 5.5, 6.5}));
  // A mesh whose tags the file lacks; a field of 6 components; a field not there.
  Mesh other = m;
  for (auto& b : other.blocks)
    if (b.type == ElementType::Tetrahedron) b.tags.back() = 999;
  EXPECT_NE(test::input_error_of([&] { material_field_values(other, c); }).find("tetrahedron 999 (centroid"), std::string::npos);
  const CaseFile c6 = case_with(d, "c_R = { cells = \"cr.h5\", field = \"six\" }\n");
  EXPECT_NE(test::input_error_of([&] { material_field_values(m, c6); }).find("cell field 'six' at 2020-01-01 has 36 values of 6 components for 6 cells"),
            std::string::npos);
  const CaseFile cx = case_with(d, "c_R = { cells = \"cr.h5\", field = \"nothing\" }\n");
  EXPECT_NE(test::input_error_of([&] { material_field_values(m, cx); }).find(d / "case.toml:3: 'c_R': "), std::string::npos);
}

// The ECLIPSE tests' deck (tests/eclipse/make_deck.py): leaning pillars, a twisted top, a faulted
// pillar row (15 m throw east of i = 4), an inactive cell, MAPAXES turning the grid 36.87 degrees.
// UGSCELL = 1 + the cell's natural index: a tetrahedron at the centre of cell (i, j, k) gets it.
namespace deck {
constexpr int NX = 8, NY = 6;
double top(int i, int j) { return 1000.0 + 4.0 * i + 3.0 * j + 0.6 * i * j; }
double thickness(int k, int i, int j) { return 10.0 + 0.5 * std::sin(i + 2 * j + k); }
double depth(int k, int i, int j, bool east) {
  double d = top(i, j);
  for (int m = 0; m < k; ++m) d += thickness(m, i, j);
  return d + (east ? 15.0 : 0.0);
}
// The mean of the cell's 8 corners in map coordinates (pillars lean 2 m east over 900 .. 1200 m).
Point3 centre(int i, int j, int k) {
  Point3 c{0, 0, 0};
  for (int q = 0; q < 8; ++q) {
    const int di = q & 1, dj = (q >> 1) & 1, dk = q >> 2;
    const double z = depth(k + dk, i + di, j + dj, i >= 4);
    const double x = (i + di) * 100.0 + 2.0 * (z - 900.0) / 300.0, y = (j + dj) * 100.0;
    c[0] += (600000.0 + 0.8 * x - 0.6 * y) / 8, c[1] += (5000000.0 + 0.6 * x + 0.8 * y) / 8, c[2] -= z / 8;
  }
  return c;
}
}  // namespace deck

TEST(MaterialFields, GrdeclOfTheEclipseTestDeckLandsOnItsCells) {
  test::TempDir d("mf-deck");
  ASSERT_EQ(test::run(std::string(UGS_PYTHON) + " " + UGS_SOURCE_DIR + "/tests/eclipse/make_deck.py " + d / "T.DATA" + " --grdecl " +
                      d / "T.GRDECL").exit_code, 0);
  const CaseFile c = case_with(d, "c_R = { grdecl = \"T.GRDECL\", keyword = \"UGSCELL\", scale = 0.5 }\n");
  // Cells (i, j, k) 0-based on both sides of the fault and in every layer.
  const std::vector<std::array<int, 3>> cells = {{0, 0, 0}, {3, 2, 1}, {4, 2, 1}, {7, 5, 3}, {5, 1, 2}, {2, 4, 3}};
  std::vector<Point3> at;
  // Off the centre a little (the centre is a corner of the locator's tetrahedra).
  for (const auto& [i, j, k] : cells) {
    const Point3 p = deck::centre(i, j, k);
    at.push_back({p[0] + 0.3, p[1] + 0.2, p[2] - 0.1});
  }
  const MaterialFieldValues v = material_field_values(tets_at(at), c);
  const std::vector<double> got = values_of(v, c_R_of);
  for (std::size_t n = 0; n < cells.size(); ++n) {
    const auto [i, j, k] = cells[n];
    EXPECT_EQ(got[n], 0.5 * (1 + i + deck::NX * (j + deck::NY * k))) << i << " " << j << " " << k;
  }
  // The inactive cell (3,3,2) 1-based, and a point above the grid: no value.
  const Point3 inactive = deck::centre(2, 2, 1);
  const std::string e = test::input_error_of([&] { material_field_values(tets_at({inactive}), c); });
  EXPECT_NE(e.find(d / "case.toml:3: material 'rock' c_R: tetrahedron 1 (centroid"), std::string::npos) << e;
  EXPECT_NE(e.find("in no active cell of the grid"), std::string::npos) << e;
  EXPECT_NE(test::input_error_of([&] { material_field_values(tets_at({{600100, 5000100, -500}}), c); }).find("in no active cell"), std::string::npos);
  // A keyword the file lacks; a value the key does not allow (UGSCELL 1 as a porosity).
  const CaseFile k = case_with(d, "c_R = { grdecl = \"T.GRDECL\", keyword = \"CR\" }\n");
  EXPECT_NE(test::input_error_of([&] { material_field_values(tets_at(at), k); }).find(d / "case.toml:3: 'c_R': " + d / "T.GRDECL: no keyword CR (keywords: SPECGRID"),
            std::string::npos);
  const CaseFile big = case_with(d, "porosity = { grdecl = \"T.GRDECL\", keyword = \"UGSCELL\" }\n");
  const std::string p = test::input_error_of([&] { material_field_values(tets_at(at), big); });
  EXPECT_NE(p.find(d / "case.toml:3: material 'rock': at tetrahedron 1 (centroid"), std::string::npos) << p;
  EXPECT_NE(p.find("porosity = 1 outside (0, 1)"), std::string::npos) << p;
}

TEST(MaterialFields, CaseFileRefusesWhatCannotBeAField) {
  test::TempDir d("mf-case");
  const auto err = [&](const std::string& lines) {
    testcase::CaseToml c;
    c.material({.name = "rock", .more = lines});
    testcase::write_text(d / "case.toml", c.str());
    return test::input_error_of([&] { read_case_file(d / "case.toml"); });
  };
  EXPECT_NE(err("k0 = { elevation_table = [[0, 1], [1, 1]] }\n").find(":3: 'material[0].k0': cannot vary in space"), std::string::npos);
  EXPECT_NE(err("sigma_z_min_MPa = { map = \"x\" }\n").find("cannot vary in space"), std::string::npos);
  EXPECT_NE(err("c_R = { grdecl = \"none.GRDECL\", keyword = \"CR\" }\n").find(":3: 'material[0].c_R.grdecl': no such file: "),
            std::string::npos);
  EXPECT_NE(err("c_R = { keyword = \"CR\" }\n").find("a field needs its source"), std::string::npos);
  EXPECT_NE(err("c_R = { elevation_table = [[0, 1]], map = \"x\" }\n").find("two sources"), std::string::npos);
  EXPECT_NE(err("c_R = { grdecl = \"case.toml\" }\n").find("'material[0].c_R.keyword': is required with grdecl"), std::string::npos);
  EXPECT_NE(err("c_R = { elevation_table = [[0, 1], [-5, 2]] }\n").find("(expected rows in increasing elevation)"), std::string::npos);
  EXPECT_NE(err("porosity = { elevation_table = [[0, 0.1], [5, 1.2]] }\n").find("row 2: porosity = 1.2 outside (0, 1)"), std::string::npos);
  EXPECT_NE(err("c_R = { elevation_table = [[0, 1]], scale = -2 }\n").find("'material[0].c_R.scale': must be positive"), std::string::npos);
  EXPECT_NE(err("K_m_per_s = [1e-6, { elevation_table = [[0, 1]] }]\n").find("expected [Kx, Ky, Kz]"), std::string::npos);
  EXPECT_EQ(err("K_m_per_s = [1e-6, { elevation_table = [[0, 1e-7]] }, 2e-7]\nE_MPa = { elevation_table = [[0, 10]] }\n"), "(no InputError)");
}

// The deck run by OPM Flow: its INIT's DEPTH (the cell centre's depth, the mean of its 8 corners',
// float32) at tetrahedra in chosen cells, located through the EGRID beside it.
TEST(MaterialFields, InitArrayThroughTheEgrid) {
  test::TempDir d("mf-init");
  ASSERT_EQ(test::run(std::string(UGS_PYTHON) + " " + UGS_SOURCE_DIR + "/tests/eclipse/make_deck.py " + d / "T.DATA").exit_code, 0);
  // INIT in the GRID section: the simulator writes T.INIT.
  std::string deck = test::slurp(d / "T.DATA");
  deck.replace(deck.find("\nGRID\n"), 6, "\nGRID\nINIT\n");
  test::spit(d / "T.DATA", deck);
  const auto r = test::run("cd " + d.path.string() + " && " + UGS_FLOW + " T.DATA --output-dir=. > flow.log 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CaseFile c = case_with(d, "E_MPa = { init = \"T.INIT\", keyword = \"DEPTH\" }\n");
  const std::vector<std::array<int, 3>> cells = {{0, 0, 0}, {3, 2, 1}, {4, 2, 1}, {7, 5, 3}};
  std::vector<Point3> at;
  for (const auto& [i, j, k] : cells) {
    const Point3 p = deck::centre(i, j, k);
    at.push_back({p[0] + 0.3, p[1] + 0.2, p[2] - 0.1});
  }
  const MaterialFieldValues v = material_field_values(tets_at(at), c);
  for (std::size_t n = 0; n < cells.size(); ++n) {
    const auto [i, j, k] = cells[n];
    EXPECT_NEAR(*v.specs.at(static_cast<std::size_t>(v.instance[n])).E_Pa / 1e6, -deck::centre(i, j, k)[2], 1e-3) << i << j << k;
  }
  const CaseFile none = case_with(d, "E_MPa = { init = \"T.INIT\", keyword = \"NOPE\" }\n");
  EXPECT_NE(test::input_error_of([&] { material_field_values(tets_at(at), none); }).find("T.INIT: no array NOPE (arrays: "), std::string::npos);
}
