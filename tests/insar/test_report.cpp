// ugs-report end to end on a synthetic result with known values: a displacement bump whose
// storage-phase uplift is exact at a node, stress changes confined to one layer of cells above
// Pool C, measured series at three PS points, chi on two faults. Checks the headline numbers, that
// every PNG exists with the requested size and is not blank, that every GeoTIFF opens in GDAL
// with the model CRS and holds the map, and that bad inputs fail with one line and exit code 2.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <unordered_map>

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "h5_poke.hpp"
#include "run_tool.hpp"
#include "solve_box.hpp"
#include "twin_data.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

const double kP0 = 15.2055e6;  // Pa, Pool C's reference pressure

// Uplift amplitude (m) at the centre at a date, and the bump's shape.
double amplitude(const std::string& date) {
  if (date == "2015-05-01") return -0.010;
  if (date == "2015-11-01") return -0.0062;  // storage: +3.8 mm at the centre
  return -0.0078;                            // 2016-05-01, production: -1.6 mm
}

struct Synthetic {
  fs::path dir;
  Mesh mesh;
};

Synthetic make_synthetic(const std::string& tag) {
  Synthetic s{test::temp_dir(tag), test::solve_box_mesh()};
  Mesh& m = s.mesh;
  // Two vertical faults as triangle groups (as ugs-faultinsert's input), for the fault results' names.
  for (const auto& [name, y] : {std::pair{"fault:north", 4956000.0}, std::pair{"fault:south", 4949000.0}}) {
    auto& b = m.block(2, m.entity_for_physical(2, name), ElementType::Triangle);
    for (int i = 0; i < 6; ++i)
      for (int k = 0; k < 4; ++k) {
        const double x0 = 677000 + i * 1500, z0 = -3000 + k * 600;
        const std::uint32_t a = m.add_node({x0, y, z0}), bb = m.add_node({x0 + 1500, y, z0}),
                            c = m.add_node({x0 + 1500, y, z0 + 600}), d = m.add_node({x0, y, z0 + 600});
        const std::uint32_t t1[3] = {a, bb, c}, t2[3] = {a, c, d};
        m.add_element(b, t1);
        m.add_element(b, t2);
      }
  }
  m.update_entity_bboxes();
  write_msh(m, (s.dir / "model.msh").string());
  // Pool schedules and the case.
  test::spit(s.dir / "pool_c.csv", "date,p_norm,p_MPa\n2010-01-01,0.70,10.64\n2015-05-01,0.60,9.12\n2015-11-01,0.85,12.92\n"
                                   "2016-05-01,0.62,9.43\n2017-01-01,0.70,10.64\n");
  test::spit(s.dir / "pool_a.csv", "date,p_norm,p_MPa\n2010-01-01,0.80,12.16\n2017-01-01,0.82,12.47\n");
  test::spit(s.dir / "case.toml", test::solve_box_case(3.0) + R"(
[[pool]]
name = "Pool A"
materials = ["pool_a"]
schedule = "pool_a.csv"
reference_pressure_MPa = 15.2055

[[pool]]
name = "Pool C"
materials = ["pool_c"]
schedule = "pool_c.csv"
reference_pressure_MPa = 15.2055
)");
  // Results: u = amplitude * bump (radial horizontal part), stress_change by layer.
  std::vector<std::int32_t> mat_of_tet;
  const PhysicalGroup* pool_c = m.find_physical(3, "mat:pool_c");
  std::vector<double> centroid_height;  // above Pool C's top (-1500) for cells over the pool, else -1
  for (const auto& b : m.blocks) {
    if (b.type != ElementType::Tetrahedron) continue;
    const bool pc = m.find_entity(3, b.entity_tag)->physicals.front() == pool_c->tag;
    for (std::size_t i = 0; i < b.size(); ++i) {
      double cx = 0, cy = 0, cz = 0;
      for (auto n : b.element(i)) cx += m.nodes[n][0] / 4, cy += m.nodes[n][1] / 4, cz += m.nodes[n][2] / 4;
      mat_of_tet.push_back(pc ? 1 : 0);
      const bool over = std::abs(cx - test::kPoolXc) < 1500 && std::abs(cy - test::kPoolYc) < 1500;
      centroid_height.push_back(over && cz > -1500 ? cz + 1500 : -1);
    }
  }
  FieldSeriesWriter w((s.dir / "solve.h5").string(), m);
  for (const std::string date : {"2015-05-01", "2015-11-01", "2016-05-01"}) {
    Field u{"u", 3, {}};
    for (const auto& p : m.nodes) {
      const double dx = p[0] - test::kPoolXc, dy = p[1] - test::kPoolYc;
      const double g = amplitude(date) * std::exp(-(dx * dx + dy * dy) / (2500.0 * 2500.0));
      u.values.insert(u.values.end(), {g * dx / 2500.0, g * dy / 2500.0, g});
    }
    const double level = date == "2015-11-01" ? 0.25 : 0.0;  // the storage phase raises sigma_z by 0.25 p0
    Field sc{"stress_change", 6, {}};
    for (std::size_t e = 0; e < mat_of_tet.size(); ++e) {
      double z = 0;
      if (mat_of_tet[e]) z = level * kP0;
      else if (centroid_height[e] > 0) z = level * kP0 * (centroid_height[e] < 25 ? 0.05 : 0.001);
      sc.values.insert(sc.values.end(), {0.33 * z, 0.33 * z, z, 0, 0, 0});
    }
    const Field nf[] = {u};
    const Field cf[] = {sc};
    w.add_step(date, double(*parse_iso_date(date)), nf, cf);
  }
  w.commit();
  // Fault results: the fault triangles only, chi growing with depth.
  Mesh fm = m;
  std::vector<ElementBlock> keep;
  for (const auto& b : fm.blocks)
    if (b.type == ElementType::Triangle && fm.physical_name_of(2, b.entity_tag).rfind("fault:", 0) == 0) keep.push_back(b);
  fm.blocks = keep;
  FieldSeriesOptions fo;
  fo.cell_types = {ElementType::Triangle};
  FieldSeriesWriter fw((s.dir / "faults.h5").string(), fm, fo);
  for (const std::string date : {"2015-05-01", "2015-11-01"}) {
    Field chi{"chi", 1, {}};
    for (const auto& b : fm.blocks)
      for (std::size_t i = 0; i < b.size(); ++i) {
        double z = 0;
        for (auto n : b.element(i)) z += fm.nodes[n][2] / 3;
        const bool north = fm.physical_name_of(2, b.entity_tag) == "fault:north";
        chi.values.push_back((date == "2015-05-01" ? 0.08 : 0.11) * (north ? 1.0 : 0.5) * (-z / 3000.0));
      }
    const Field cf[] = {chi};
    fw.add_step(date, double(*parse_iso_date(date)), {}, cf);
  }
  fw.commit();
  // Measured vertical series at three PS points, the trace and the sections.
  const auto dates = test::monthly_dates(2015, 5, 2016, 4);
  std::vector<double> x{681500, 682400, 684000}, y{4952500, 4952000, 4955000};
  std::vector<double> ex = x, ey = y;
  insar::CoordinateTransform ct(insar::any_crs_wkt("EPSG:32632", "t"), insar::any_crs_wkt("EPSG:3035", "t"), "t");
  ct.apply(ex, ey, {});
  std::string csv = "pid,easting,northing,height";
  for (auto t : dates) {
    const auto c = civil_from_days(t / 86400);
    csv += fmt::format(",{:04d}{:02d}{:02d}", c.year, c.month, c.day);
  }
  csv += "\n";
  for (int p = 0; p < 3; ++p) {
    // The second id differs from the first only in case: each still gets its own series picture.
    csv += fmt::format("{},{:.3f},{:.3f},40", p == 1 ? "p1" : fmt::format("P{}", p + 1), ex[p], ey[p]);
    for (std::size_t d = 0; d < dates.size(); ++d) csv += fmt::format(",{:.2f}", 0.2 * d * (p == 0 ? 1.0 : 0.3));
    csv += "\n";
  }
  test::spit(s.dir / "up.csv", csv);
  test::spit(s.dir / "trace.geojson", R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32632"}},
"features":[{"type":"Feature","properties":{"name":"Pool C"},"geometry":{"type":"Polygon","coordinates":[[[680000,4951000],[683000,4951000],[683000,4954000],[680000,4954000],[680000,4951000]]]}}]})");
  test::spit(s.dir / "sections.geojson", R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32632"}},
"features":[{"type":"Feature","properties":{"name":"A-A","from_label":"A","to_label":"A'"},"geometry":{"type":"LineString","coordinates":[[677000,4952500],[686000,4952500]]}},
{"type":"Feature","properties":{"name":"B-B","from_label":"B","to_label":"B'"},"geometry":{"type":"LineString","coordinates":[[681500,4956500],[681700,4948500]]}}]})");
  return s;
}

struct Image {
  int width = 0, height = 0, bands = 0;
  double variance = 0;
  std::string crs;
};

Image open_raster(const fs::path& p) {
  GDALAllRegister();
  CPLSetConfigOption("GDAL_PAM_ENABLED", "NO");  // statistics stay in memory: no .aux.xml beside the files
  Image im;
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen(p.c_str(), GA_ReadOnly));
  if (!ds) return im;
  im.width = ds->GetRasterXSize();
  im.height = ds->GetRasterYSize();
  im.bands = ds->GetRasterCount();
  if (const OGRSpatialReference* s = ds->GetSpatialRef()) {
    OGRSpatialReference c(*s);
    c.AutoIdentifyEPSG();
    if (c.GetAuthorityCode(nullptr)) im.crs = std::string("EPSG:") + c.GetAuthorityCode(nullptr);
  }
  double mn, mx, mean, sd;
  if (ds->GetRasterBand(1)->ComputeStatistics(false, &mn, &mx, &mean, &sd, nullptr, nullptr) == CE_None) im.variance = sd * sd;
  GDALClose(ds);
  return im;
}

std::string report_command(const Synthetic& s, const std::string& out, const std::string& extra = "") {
  const std::string d = s.dir.string() + "/";
  return test::tool("ugs-report") + " --thesis --results " + d + "solve.h5 --mesh " + d + "model.msh --case " + d + "case.toml" +
         " --measured " + d + "up.csv --trace " + d + "trace.geojson --sections " + d + "sections.geojson --faults " + d +
         "faults.h5 -o " + d + out + " " + extra;
}

}  // namespace

TEST(Report, PicturesGeoTiffsAndHeadlineNumbers) {
  const Synthetic s = make_synthetic("report");
  const auto r = test::run(report_command(s, "report"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path out = s.dir / "report";
  // Storage: +3.8 mm at the centre node; production: -1.6 mm.
  EXPECT_NE(r.out.find("storage 2015-05-01 to 2015-11-01: maximum uplift: 3.80 mm at x 681500, y 4952500"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("production 2015-11-01 to 2016-05-01: maximum settlement: 1.60 mm at x 681500, y 4952500"), std::string::npos) << r.out;
  // Stress change above 1 % of the peak only in the first cell layer over Pool C (centroids up to 22.5 m).
  EXPECT_NE(r.out.find("falls below 1 % of its peak (outside every pool and aquifer): 22.5 m"), std::string::npos) << r.out;
  // chi: north fault 0.08 x (2700/3000) ... deepest triangle centroid at z = -2800: 0.11 x 2800/3000 at maximum pressure.
  EXPECT_NE(r.out.find(fmt::format("maximum χ on north: {:.3f}", 0.11 * 2800.0 / 3000.0)), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(fmt::format("maximum χ on south: {:.3f}", 0.08 * 0.5 * 2800.0 / 3000.0)), std::string::npos) << r.out;
  // Every picture: the requested size, not blank.
  std::size_t pngs = 0;
  for (const auto& e : fs::directory_iterator(out)) {
    if (e.path().extension() != ".png") continue;
    ++pngs;
    const Image im = open_raster(e.path());
    EXPECT_EQ(im.width, 1600) << e.path();
    EXPECT_EQ(im.height, 1000) << e.path();
    EXPECT_GT(im.variance, 100.0) << e.path() << " looks blank";
  }
  // 2 phases x 3 maps, 2 x 2 sections x 3 components, 2 x 3 pool-top maps, 3 PS series, 2 fault scenarios.
  EXPECT_EQ(pngs, 6u + 12u + 6u + 3u + 2u);
  for (const char* name : {"uz_storage.png", "ux_production.png", "sec_a_a_storage_sz.png", "sec_b_b_production_sx.png",
                           "pooltop_storage_sz.png", "series_up_p1.png", "series_up_p1_2.png", "chi_minimum_pressure.png", "chi_maximum_pressure.png"})
    EXPECT_TRUE(fs::exists(out / name)) << name;
  // GeoTIFFs: open with the model CRS; the uplift map peaks at 3.8 mm.
  std::size_t tifs = 0;
  for (const auto& e : fs::directory_iterator(out)) {
    if (e.path().extension() != ".tif") continue;
    ++tifs;
    const Image im = open_raster(e.path());
    EXPECT_EQ(im.crs, "EPSG:32632") << e.path();
    EXPECT_GT(im.width, 100);
  }
  EXPECT_EQ(tifs, 6u);
  {
    GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen((out / "uz_storage.tif").c_str(), GA_ReadOnly));
    ASSERT_NE(ds, nullptr);
    double mn, mx, mean, sd;
    ds->GetRasterBand(1)->ComputeStatistics(false, &mn, &mx, &mean, &sd, nullptr, nullptr);
    EXPECT_NEAR(mx, 3.8, 0.05);  // the grid's cell centres miss the peak node by at most half a cell
    EXPECT_GT(mn, 0.0);
    GDALClose(ds);
  }
  // The summary page names the numbers next to the thesis'.
  const std::string html = test::slurp(out / "summary.html");
  EXPECT_NE(html.find("up to about 4 mm"), std::string::npos);
  EXPECT_NE(html.find("about 20 m above Pool C"), std::string::npos);
  EXPECT_NE(html.find("<img src=\"uz_storage.png\""), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "summary.md"));
  EXPECT_FALSE(fs::exists(out / "work"));
  if (!std::getenv("UGS_TEST_KEEP")) fs::remove_all(s.dir);
}

TEST(Report, WithoutFaultResultsTheChiPicturesAreSkippedWithANote) {
  const Synthetic s = make_synthetic("report-nofault");
  const std::string d = s.dir.string() + "/";
  const auto r = test::run(test::tool("ugs-report") + " --thesis --results " + d + "solve.h5 --mesh " + d + "model.msh --case " + d +
                           "case.toml --phase injection=2015-05-01/2015-11-01 -o " + d + "rep --width 800 --height 600");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("no fault results"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(s.dir / "rep" / "chi_minimum_pressure.png"));
  const Image im = open_raster(s.dir / "rep" / "uz_injection.png");
  EXPECT_EQ(im.width, 800);
  EXPECT_EQ(im.height, 600);
  EXPECT_NE(test::slurp(s.dir / "rep" / "summary.md").find("figures 4.43-4.44"), std::string::npos);
  if (!std::getenv("UGS_TEST_KEEP")) fs::remove_all(s.dir);
}

TEST(Report, BadInputsExitTwoWithOneLine) {
  const Synthetic s = make_synthetic("report-bad");
  const std::string d = s.dir.string() + "/";
  auto one_line_error = [](const test::RunResult& r) {
    return r.exit_code == 2 && r.err.rfind("ugs-report: error: ", 0) == 0 && r.err.find('\n') == r.err.size() - 1;
  };
  const std::string base = test::tool("ugs-report") + " --thesis --results " + d + "solve.h5 --mesh " + d + "model.msh --case " + d + "case.toml";
  auto r = test::run(base + " --phase storage=2015-11-01/2015-05-01 -o " + d + "x");
  EXPECT_TRUE(one_line_error(r)) << r.err;
  r = test::run(base + " --phase storage=2030-05-01/2030-11-01 -o " + d + "x");
  EXPECT_TRUE(one_line_error(r)) << r.err;
  EXPECT_NE(r.err.find("outside the results"), std::string::npos) << r.err;
  r = test::run(base + " --stress-pool 'Pool Z' -o " + d + "x");
  EXPECT_TRUE(one_line_error(r)) << r.err;
  test::spit(s.dir / "bad.csv", "pid,easting,northing,2015O501\nP,1,2,3\n");
  r = test::run(base + " --measured " + d + "bad.csv -o " + d + "x");
  EXPECT_TRUE(one_line_error(r)) << r.err;
  EXPECT_FALSE(fs::exists(s.dir / "x"));  // nothing left behind
  for (const auto& e : fs::directory_iterator(s.dir)) EXPECT_EQ(e.path().filename().string().find(".x.tmp"), std::string::npos);
  if (!std::getenv("UGS_TEST_KEEP")) fs::remove_all(s.dir);
}

// Issue 20: node indices out of range in the results' tetrahedra (read with --mesh for the stress
// pictures) or in the fault results' triangles, and non-finite coordinates, are refused with one
// line (they were read out of bounds: SIGSEGV, the temporary folder left behind); a plots.py that
// fails leaves no temporary folder either.
TEST(Report, OutOfRangeIndicesAndFailingPlotsLeaveNothing) {
  const Synthetic s = make_synthetic("report-index");
  const std::string d = s.dir.string() + "/";
  auto no_leftovers = [&] {
    std::string left;
    for (const auto& e : fs::directory_iterator(s.dir))
      if (e.path().filename().string().rfind(".x.tmp", 0) == 0 || e.path().filename() == "x") left += e.path().string() + " ";
    return left;
  };
  auto one_line = [](const test::RunResult& r, int code, const std::string& needle) {
    return r.exit_code == code && r.err.rfind("ugs-report: error: ", 0) == 0 && r.err.find('\n') == r.err.size() - 1 &&
           r.err.find(needle) != std::string::npos;
  };
  const std::string base = test::tool("ugs-report") + " --thesis --mesh " + d + "model.msh --case " + d + "case.toml";
  fs::copy_file(s.dir / "solve.h5", s.dir / "bad_tet.h5");
  test::h5_poke<std::uint32_t>(d + "bad_tet.h5", "/mesh/tetrahedra", 5 * 4 + 1, 4294967295u);
  auto r = test::run(base + " --results " + d + "bad_tet.h5 -o " + d + "x");
  EXPECT_TRUE(one_line(r, 2, "bad_tet.h5: /mesh/tetrahedra: cell 5 has node index 4294967295 (expected below the")) << r.err;
  EXPECT_EQ(no_leftovers(), "");
  // The same file without --mesh (top surface from the results' own cells): the same message.
  r = test::run(test::tool("ugs-report") + " --thesis --results " + d + "bad_tet.h5 -o " + d + "x");
  EXPECT_TRUE(one_line(r, 2, "bad_tet.h5: /mesh/tetrahedra: cell 5 has node index 4294967295")) << r.err;
  fs::copy_file(s.dir / "faults.h5", s.dir / "bad_faults.h5");
  test::h5_poke<std::uint32_t>(d + "bad_faults.h5", "/mesh/triangles", 2 * 3, 4294967295u);
  r = test::run(base + " --results " + d + "solve.h5 --faults " + d + "bad_faults.h5 -o " + d + "x");
  EXPECT_TRUE(one_line(r, 2, "bad_faults.h5: /mesh/triangles: cell 2 has node index 4294967295")) << r.err;
  EXPECT_EQ(no_leftovers(), "");
  fs::copy_file(s.dir / "solve.h5", s.dir / "nan_xyz.h5");
  test::h5_poke<double>(d + "nan_xyz.h5", "/mesh/coordinates", 3 * 3 + 1, std::nan(""));
  r = test::run(base + " --results " + d + "nan_xyz.h5 -o " + d + "x");
  EXPECT_TRUE(one_line(r, 2, "nan_xyz.h5: /mesh/coordinates: node 3 has y = nan (expected finite coordinates)")) << r.err;
  EXPECT_EQ(no_leftovers(), "");
  // plots.py raising an exception: exit 1 with its last line, nothing left.
  test::spit(s.dir / "broken_plots.py", "raise FileNotFoundError('work/missing.csv')\n");
  r = test::run("UGS_REPORT_PLOTS=" + d + "broken_plots.py " + base + " --results " + d + "solve.h5 -o " + d + "x");
  EXPECT_TRUE(one_line(r, 1, "plots.py failed (exit code 1): FileNotFoundError: work/missing.csv")) << r.err;
  EXPECT_EQ(no_leftovers(), "");
  if (!HasFailure() && !std::getenv("UGS_TEST_KEEP")) fs::remove_all(s.dir);
}

// Issue 20: measured series none of whose points lies on the model (plots.py died with
// FileNotFoundError, exit 1): refused as ugs-sample and ugs-calibrate refuse them, exit 2.
TEST(Report, EveryPsPointOffTheModelIsRefused) {
  const Synthetic s = make_synthetic("report-off");
  const std::string d = s.dir.string() + "/";
  test::spit(s.dir / "far.csv", "pid,x,y,20150601,20150701\nF1,600000,4900000,0,1\nF2,600500,4900000,0,2\n");
  const auto r = test::run(test::tool("ugs-report") + " --thesis --results " + d + "solve.h5 --mesh " + d + "model.msh --case " + d +
                           "case.toml --measured " + d + "far.csv -o " + d + "x");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("ugs-report: error: " + d + "far.csv: none of the 2 PS points lies on the model's top surface", 0), 0u)
      << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  EXPECT_FALSE(fs::exists(s.dir / "x"));
  for (const auto& e : fs::directory_iterator(s.dir)) EXPECT_NE(e.path().filename().string().rfind(".x.tmp", 0), 0u);
  if (!HasFailure() && !std::getenv("UGS_TEST_KEEP")) fs::remove_all(s.dir);
}

// Issue 20: numeric options finite and in range (a --raster-cell of 1e-300 overflowed the grid's
// int counts; inf and nan went through), exit 2 naming the option and the value.
TEST(Report, NumericOptionsMustBeFiniteAndInRange) {
  const Synthetic s = make_synthetic("report-numbers");
  const std::string d = s.dir.string() + "/";
  const std::string base = test::tool("ugs-report") + " --thesis --results " + d + "solve.h5 --mesh " + d + "model.msh --case " + d +
                           "case.toml -o " + d + "x ";
  auto one_line = [](const test::RunResult& r, const std::string& needle) {
    return r.exit_code == 2 && r.err.rfind("ugs-report: error: " + needle, 0) == 0 && r.err.find('\n') == r.err.size() - 1;
  };
  auto r = test::run(base + "--exaggeration inf");
  EXPECT_TRUE(one_line(r, "--exaggeration: inf (expected a finite number in (0, 1000000])")) << r.err;
  r = test::run(base + "--reference-pressure-MPa nan");
  EXPECT_TRUE(one_line(r, "--reference-pressure-MPa: nan (expected a finite number >= 0)")) << r.err;
  r = test::run(base + "--raster-cell 1e-300");
  EXPECT_TRUE(one_line(r, "--raster-cell: 1e-300 m gives")) << r.err;
  r = test::run(base + "--map-extent=-inf/inf/0/1");
  EXPECT_TRUE(one_line(r, "--map-extent: '-inf/inf/0/1' is not XMIN/XMAX/YMIN/YMAX (finite numbers)")) << r.err;
  r = test::run(base + "--section-zrange=-2000/-1000x");
  EXPECT_TRUE(one_line(r, "--section-zrange: '-2000/-1000x' is not ZMIN/ZMAX (finite numbers)")) << r.err;
  EXPECT_FALSE(fs::exists(s.dir / "x"));
  for (const auto& e : fs::directory_iterator(s.dir)) EXPECT_NE(e.path().filename().string().rfind(".x.tmp", 0), 0u);
  if (!HasFailure() && !std::getenv("UGS_TEST_KEEP")) fs::remove_all(s.dir);
}

// Issue 42: the safety answer as headlines — the safe scale, what limits it, the maximum safe
// pressure per pool from its schedule scaled about the reference (here the schedules' first date),
// and the seals' smallest margins.
TEST(Report, SafetyHeadlinesFromTheSearchAndTheCaprockTables) {
  const Synthetic s = make_synthetic("report-safety");
  const std::string d = s.dir.string() + "/";
  test::spit(s.dir / "scenario.csv",
             "# ugs-solve safe-scale search\n"
             "scale,max_chi,critical,fault,date,x_m,y_m,z_m,dp_max_MPa,dp_min_MPa,limiter,seal,min_tensile_margin_MPa,"
             "min_shear_margin_MPa,note\n"
             "1,0.4,0,,,0,0,0,1,0,,,3.1,4.2,\n2,0.6,0,,,0,0,0,2,0,,,1.2,3.9,\n"
             "4,0.9,1,,2015-11-01,1,2,3,4,0,caprock tensile failure,caprock,-2.5,3.1,\n"
             "3,0.8,1,,2015-11-01,1,2,3,3,0,caprock tensile failure,caprock,-0.4,3.5,\n2.5,0.7,0,,,0,0,0,2.5,0,,,0.3,3.7,\n");
  test::spit(s.dir / "caprock.csv",
             "date,seal,min_tensile_margin_MPa,tensile_x_m,tensile_y_m,tensile_z_m,pore_pressure_MPa,min_shear_margin_MPa,"
             "shear_x_m,shear_y_m,shear_z_m\n"
             "2015-05-01,caprock,4.5,0,0,0,9.1,6.0,0,0,0\n2015-11-01,caprock,1.25,0,0,0,12.9,5.5,0,0,0\n");
  const auto r = test::run(test::tool("ugs-report") + " --thesis --results " + d + "solve.h5 --mesh " + d + "model.msh --case " + d +
                           "case.toml --scenario " + d + "scenario.csv --caprock " + d + "caprock.csv -o " + d +
                           "rep --width 800 --height 600");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string md = test::slurp(s.dir / "rep" / "summary.md");
  EXPECT_NE(md.find("| safety | maximum safe scale of the swing | 2.5 (critical at 3) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| safety | what limits it | seal caprock: caprock tensile failure on 2015-11-01 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| safety | smallest seal margins at the maximum safe scale | tensile 0.30 MPa, shear 3.70 MPa |"),
            std::string::npos)
      << md;
  // Pool C: 0.70 p0 at the reference, its peak 0.85 p0: 0.70 p0 + 2.5 x 0.15 p0, p0 = 15.2055 MPa.
  EXPECT_NE(md.find(fmt::format("| safety | maximum safe pressure, Pool C | {:.2f} MPa (+{:.2f} MPa over its initial {:.2f} MPa) |",
                                (0.70 + 2.5 * 0.15) * 15.2055, 2.5 * 0.15 * 15.2055, 0.70 * 15.2055)),
            std::string::npos)
      << md;
  EXPECT_NE(md.find(fmt::format("| safety | maximum safe pressure, Pool A | {:.2f} MPa", (0.80 + 2.5 * 0.02) * 15.2055)),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("smallest tensile margin (fracture pressure - pore pressure) | 1.25 MPa (seal caprock, 2015-11-01, pore "
                    "pressure 12.90 MPa) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("smallest Mohr-Coulomb shear margin | 5.50 MPa (seal caprock, 2015-11-01) |"), std::string::npos) << md;

  // A fault that limits the scale: where, and how far from the reservoir trace (a square 0..1000 m:
  // the patch at x = 960 m is 40 m from its east side). Within --edge-distance the headline says the
  // answer sits at the reservoir's edge and depends on the mesh there; beyond it, only the distance.
  test::spit(s.dir / "fault_scenario.csv",
             "scale,max_chi,critical,fault,date,x_m,y_m,z_m,dp_max_MPa,dp_min_MPa,limiter,seal,min_tensile_margin_MPa,"
             "min_shear_margin_MPa,note\n"
             "1,0.4,0,,,0,0,0,1,0,,,,,\n2,1,1,local_2,2025-11-01,960,500,-1540,2,0,fault chi = 1,,,,\n");
  test::spit(s.dir / "trace.geojson",
             R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32632"}},)"
             R"( "features": [{"type": "Feature", "properties": {"name": "Pool C"},)"
             R"( "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [1000, 0], [1000, 1000], [0, 1000], [0, 0]]]}}]})");
  for (const auto& [edge, near] : {std::pair{"", true}, std::pair{" --edge-distance 30", false}}) {
    const auto rf = test::run(test::tool("ugs-report") + " --results " + d + "solve.h5 --mesh " + d + "model.msh --case " + d +
                              "case.toml --trace " + d + "trace.geojson --scenario " + d + "fault_scenario.csv -o " + d +
                              "repf --width 800 --height 600" + edge);
    ASSERT_EQ(rf.exit_code, 0) << rf.err;
    const std::string mf = test::slurp(s.dir / "repf" / "summary.md");
    EXPECT_NE(mf.find("| safety | where it is decided | fault local_2 at (960, 500, -1540), 40 m from the reservoir trace"),
              std::string::npos) << mf;
    EXPECT_EQ(mf.find("at the reservoir's edge") != std::string::npos, near) << mf;
    fs::remove_all(s.dir / "repf");
  }
  if (!std::getenv("UGS_TEST_KEEP")) fs::remove_all(s.dir);
}

// Issue 42: a report for the field — without --thesis the phases come from the case's [[report.phase]],
// the thesis column is gone, and the case's acceptance thresholds are stated as pass / FAIL.
TEST(Report, FieldReportTakesItsPhasesAndThresholdsFromTheCase) {
  const Synthetic s = make_synthetic("report-field");
  const std::string d = s.dir.string() + "/";
  test::spit(s.dir / "case.toml", test::slurp(s.dir / "case.toml") + R"(
[report]
stress_pool = "Pool C"
uplift_max_mm = 5
settlement_max_mm = 1
chi_max = 0.5
tensile_margin_min_MPa = 2

[[report.phase]]
name = "injection"
start = "2015-05-01"
end = "2015-11-01"

[[report.phase]]
name = "withdrawal"
start = "2015-11-01"
end = "2016-05-01"
)");
  const auto r = test::run(test::tool("ugs-report") + " --results " + d + "solve.h5 --mesh " + d + "model.msh --case " + d +
                           "case.toml --faults " + d + "faults.h5 -o " + d + "rep --width 800 --height 600");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string md = test::slurp(s.dir / "rep" / "summary.md");
  EXPECT_NE(md.find("- phases: injection 2015-05-01 to 2015-11-01; withdrawal 2015-11-01 to 2016-05-01"), std::string::npos) << md;
  EXPECT_NE(md.find("| | quantity | this run |\n|---|---|---|\n"), std::string::npos) << md;
  EXPECT_EQ(md.find("thesis"), std::string::npos) << md;
  // The synthetic run: +3.8 mm over the injection, -1.6 mm over the withdrawal, chi at most 0.11 x 2800 / 3000.
  EXPECT_NE(md.find("| acceptance | largest uplift over a phase <= 5 mm | 3.8 mm (injection 2015-05-01 to 2015-11-01 at x 681500, "
                    "y 4952500): pass |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| acceptance | largest settlement over a phase <= 1 mm | 1.6 mm (withdrawal 2015-11-01 to 2016-05-01 at x "
                    "681500, y 4952500): FAIL |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find(fmt::format("| acceptance | largest fault chi <= 0.5 | {:.3g} (fault north on", 0.11 * 2800.0 / 3000.0)),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| acceptance | smallest seal tensile margin >= 2 MPa | not checked: the inputs do not give it |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| acceptance | thresholds of the case | 1 of 3 FAIL |"), std::string::npos) << md;
  // A phase outside the results, an unknown pool, a threshold out of range: one line each, exit 2.
  const std::string good = test::slurp(s.dir / "case.toml");
  const std::pair<std::string, std::string> bad[] = {
      {"end = \"2016-05-01\"", "end = \"2040-05-01\""},
      {"stress_pool = \"Pool C\"", "stress_pool = \"Pool Z\""},
      {"chi_max = 0.5", "chi_max = 1.5"},
  };
  for (const auto& [from, to] : bad) {
    std::string text = good;
    text.replace(text.find(from), from.size(), to);
    test::spit(s.dir / "case.toml", text);
    const auto b = test::run(test::tool("ugs-report") + " --results " + d + "solve.h5 --mesh " + d + "model.msh --case " + d +
                             "case.toml -o " + d + "bad");
    EXPECT_EQ(b.exit_code, 2) << to << b.err;
    EXPECT_EQ(std::count(b.err.begin(), b.err.end(), '\n'), 1) << b.err;
    EXPECT_FALSE(fs::exists(s.dir / "bad"));
  }
  if (!std::getenv("UGS_TEST_KEEP")) fs::remove_all(s.dir);
}
