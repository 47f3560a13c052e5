// The po-plain sample twin (small variant, generated here by data-samples/po-plain/generate.py) at
// a coarse setting: ugs-mesh2d | ugs-meshgen with the sample's strata.toml, checked against counts
// and material volumes computed independently in this test: surfaces sampled with our own
// bilinear code on GDAL's pixels, the order and pinch-out rules re-applied, materials found with
// GEOS (OGR Contains) on the triangle centroids, volumes as area x mean thickness.
#include <gtest/gtest.h>

#include <regex>

#include <cmath>
#include <map>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include <toml.hpp>

#include "meshing_checks.hpp"
#include "run_tool.hpp"
#include "ugs/formats/msh.hpp"

namespace fs = std::filesystem;
using namespace ugs;

namespace {

struct Raster {
  int nx = 0, ny = 0;
  double gt[6];
  std::vector<double> v;
  explicit Raster(const std::string& path) {
    GDALAllRegister();
    GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_ReadOnly));
    if (!ds) throw std::runtime_error("cannot open " + path);
    nx = ds->GetRasterXSize();
    ny = ds->GetRasterYSize();
    ds->GetGeoTransform(gt);
    v.resize(static_cast<std::size_t>(nx) * ny);
    if (ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, nx, ny, v.data(), nx, ny, GDT_Float64, 0, 0) != CE_None)
      throw std::runtime_error("cannot read " + path);
    GDALClose(ds);
  }
  // North-up rasters only (what the sample writes).
  double at(double x, double y) const {
    const double u = (x - gt[0]) / gt[1] - 0.5, w = (y - gt[3]) / gt[5] - 0.5;
    const int i = std::min(static_cast<int>(std::floor(u)), nx - 2), j = std::min(static_cast<int>(std::floor(w)), ny - 2);
    if (i < 0 || j < 0) throw std::runtime_error("point outside the raster");
    const double fx = u - i, fy = w - j;
    auto p = [&](int a, int b) { return v[static_cast<std::size_t>(b) * nx + a]; };
    return (1 - fx) * (1 - fy) * p(i, j) + fx * (1 - fy) * p(i + 1, j) + (1 - fx) * fy * p(i, j + 1) + fx * fy * p(i + 1, j + 1);
  }
};

std::vector<std::unique_ptr<OGRGeometry>> polygons(const std::string& path, const std::string& where) {
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpenEx(path.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  if (!ds) throw std::runtime_error("cannot open " + path);
  std::vector<std::unique_ptr<OGRGeometry>> out;
  OGRLayer* l = ds->GetLayer(0);
  if (!where.empty()) l->SetAttributeFilter(where.c_str());
  while (OGRFeature* f = l->GetNextFeature()) {
    out.emplace_back(f->GetGeometryRef()->clone());
    OGRFeature::DestroyFeature(f);
  }
  GDALClose(ds);
  return out;
}

}  // namespace

TEST(SampleTwin, CoarseMeshMatchesIndependentCountsAndVolumes) {
  const fs::path dir = test::temp_dir("sample-twin");
  const std::string gen = std::string(UGS_SOURCE_DIR) + "/data-samples/po-plain/generate.py";
  ASSERT_TRUE(fs::exists(gen)) << gen;
  auto r = test::run("/usr/bin/python3 " + gen + " --out " + dir.string() + " --small -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;

  // The sample's strata; the faults' depth ranges come from faults.geojson.
  std::string strata = test::slurp(dir / "strata.toml");
  if (strata.find("\nfaults =") == std::string::npos) strata = "faults = \"faults.geojson\"\n" + strata;
  test::spit(dir / "strata-faults.toml", strata);
  const fs::path plan_file = dir / "plan.msh", model_file = dir / "model.msh";
  r = test::run(test::tool("ugs-mesh2d") + " --domain " + (dir / "domain.geojson").string() + " --fault " +
                (dir / "faults.geojson").string() + " --hmax 1000 -q -o " + plan_file.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run(test::tool("ugs-meshgen") + " " + plan_file.string() + " --strata " + (dir / "strata-faults.toml").string() +
                " -v -o " + model_file.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The sample's faults dip: ugs-meshgen cuts them into the layered mesh (docs/dipping-faults.md)
  // and says how many tetrahedra the layered mesh had and how many nodes the cut added.
  const std::smatch cut = [&] {
    std::smatch m;
    static const std::regex re(R"(dipping faults cut in [0-9.]+ s: ([0-9]+) -> ([0-9]+) tetrahedra, ([0-9]+) new nodes)");
    std::regex_search(r.err, m, re);
    return m;
  }();
  ASSERT_EQ(cut.size(), 4u) << r.err;
  const std::size_t layered_tets = std::stoul(cut[1]), cut_tets = std::stoul(cut[2]), cut_nodes = std::stoul(cut[3]);
  const Mesh mesh = read_msh(model_file.string());
  const Mesh plan = read_msh(plan_file.string());

  // The stratigraphy, read with toml11 directly.
  const auto doc = toml::parse(dir / "strata.toml");
  const double min_thickness = toml::find<double>(doc, "min_thickness");
  std::vector<std::function<double(double, double)>> surface;
  std::vector<std::unique_ptr<Raster>> rasters;
  for (const auto& s : toml::find<toml::array>(doc, "surface")) {
    if (s.contains("raster")) {
      rasters.push_back(std::make_unique<Raster>((dir / toml::find<std::string>(s, "raster")).string()));
      const Raster* ras = rasters.back().get();
      surface.push_back([ras](double x, double y) { return ras->at(x, y); });
    } else {
      const double c = toml::find<double>(s, "constant");
      surface.push_back([c](double, double) { return c; });
    }
  }
  std::vector<std::string> units;
  std::vector<int> layers;
  for (const auto& u : toml::find<toml::array>(doc, "unit")) {
    units.push_back(toml::find<std::string>(u, "name"));
    layers.push_back(toml::find<int>(u, "layers"));
  }
  ASSERT_EQ(surface.size(), 12u);
  ASSERT_EQ(units.size(), 11u);
  struct Rule {
    std::string name;
    std::vector<std::string> units;
    std::vector<std::unique_ptr<OGRGeometry>> polys;
    bool any = false;
  };
  std::vector<Rule> rules;
  for (const auto& m : toml::find<toml::array>(doc, "material")) {
    Rule rule;
    rule.name = toml::find<std::string>(m, "name");
    rule.units = toml::find<std::vector<std::string>>(m, "units");
    if (m.contains("polygon"))
      rule.polys = polygons((dir / toml::find<std::string>(m, "polygon")).string(),
                            m.contains("where") ? toml::find<std::string>(m, "where") : "");
    else
      rule.any = true;
    rules.push_back(std::move(rule));
  }

  // Columns: nodes of the plan's triangles.
  std::map<std::uint32_t, std::vector<double>> z;  // plan node index -> surface elevations
  std::vector<std::array<std::uint32_t, 3>> tris;
  for (const auto& b : plan.blocks)
    if (b.type == ElementType::Triangle)
      for (std::size_t i = 0; i < b.size(); ++i) {
        auto n = b.element(i);
        tris.push_back({n[0], n[1], n[2]});
        for (auto c : n) z[c];
      }
  std::size_t nodes = 0;
  for (auto& [c, zs] : z) {
    const auto& p = plan.nodes[c];
    for (const auto& f : surface) zs.push_back(f(p[0], p[1]));
    for (std::size_t i = 1; i < zs.size(); ++i)
      if (zs[i] > zs[i - 1]) {
        ASSERT_LE(zs[i] - zs[i - 1], 1.0) << "the sample's surfaces cross";
        zs[i] = zs[i - 1];
      }
    for (std::size_t u = 0; u + 1 < zs.size(); ++u)
      if (zs[u] - zs[u + 1] < min_thickness) zs[u + 1] = zs[u];
    nodes += 1;
    for (std::size_t u = 0; u < units.size(); ++u) nodes += zs[u] > zs[u + 1] ? layers[u] : 0;
  }
  std::size_t tets = 0;
  std::map<std::string, double> volume;
  for (const auto& t : tris) {
    const auto &A = plan.nodes[t[0]], &B = plan.nodes[t[1]], &C = plan.nodes[t[2]];
    const double area = 0.5 * std::abs((B[0] - A[0]) * (C[1] - A[1]) - (B[1] - A[1]) * (C[0] - A[0]));
    OGRPoint centroid((A[0] + B[0] + C[0]) / 3, (A[1] + B[1] + C[1]) / 3);
    for (std::size_t u = 0; u < units.size(); ++u) {
      double sum = 0;
      for (auto c : t) {
        sum += z[c][u] - z[c][u + 1];
        tets += z[c][u] > z[c][u + 1] ? layers[u] : 0;
      }
      std::string mat;
      for (const auto& rule : rules) {
        if (std::find(rule.units.begin(), rule.units.end(), units[u]) == rule.units.end()) continue;
        bool hit = rule.any;
        for (const auto& g : rule.polys) hit = hit || g->Contains(&centroid);
        if (hit) {
          mat = rule.name;
          break;
        }
      }
      ASSERT_FALSE(mat.empty()) << units[u];
      volume["mat:" + mat] += area * sum / 3.0;
    }
  }

  EXPECT_EQ(mesh.num_nodes(), nodes + cut_nodes);
  EXPECT_EQ(layered_tets, tets);
  EXPECT_EQ(mesh.count(ElementType::Tetrahedron), cut_tets);
  const auto c = test::check_conformity(mesh);
  EXPECT_EQ(c.over_shared, 0u);
  EXPECT_EQ(c.untagged_outer, 0u);
  EXPECT_EQ(c.nonpositive, 0u);
  EXPECT_EQ(c.fault_not_face, 0u);
  for (const auto& [name, v] : volume) {
    if (v == 0) continue;
    ASSERT_TRUE(c.volume_of.count(name)) << name;
    EXPECT_NEAR(c.volume_of.at(name), v, 1e-9 * v) << name;
  }
  EXPECT_GE(c.volume_of.size(), 5u);
  for (const char* f : {"fault:overthrust_north", "fault:backthrust_south"}) EXPECT_NE(mesh.find_physical(2, f), nullptr) << f;
  fs::remove_all(dir);
}
