// make_thesis_case — the thesis-scale case of bench/solve: the layered box of the thesis (42 x 30 km,
// bottom -10 km, the surfaces of Table 4.1 with their 41 sub-layers, plan spacing 50 m over the
// reservoirs growing to ~2 km; ~500,000 nodes at scale 1), standing in for ugs-meshgen's output of the
// same size. Writes mesh.msh, case.toml and the pools' pressure-change fields into DIR.
//
//   make_thesis_case DIR --linear [--scale F]    one linear elastic step, Pool C depleted by 10 MPa;
//                                                also mesh_arrays.h5 for the FEniCSx peer
//   make_thesis_case DIR --history [--scale F]   the hypo-plastic 1950-2033 history, monthly fields
//   make_thesis_case DIR [--scale F]             the same model, 1950-1951 monthly
//
// (It was `mech_make_case thesis` of tests/mechanics; the cases are the same bytes.)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/box_mesh.hpp"
#include "dir_argument.hpp"
#include "layered_model.hpp"
#include "pressure_files.hpp"

using namespace ugs;
using namespace ugs::testcase;
namespace fs = std::filesystem;

namespace {

// Coordinates from lo to hi: spacing h inside [c - w, c + w], growing geometrically outside so
// that the total count is n intervals.
std::vector<double> focused(double lo, double hi, double c, double w, int n) {
  // Find the growth ratio giving n intervals.
  auto build = [&](double ratio) {
    const int ni = static_cast<int>(std::lround(2 * w / 50.0));
    std::vector<double> v = linspace(c - w, c + w, ni);
    double hgrow = 2 * w / ni;
    std::vector<double> left, right;
    double xl = c - w, xr = c + w, h = hgrow;
    while (xl > lo) {
      h *= ratio;
      xl -= h;
      left.push_back(std::max(xl, lo));
    }
    h = hgrow;
    while (xr < hi) {
      h *= ratio;
      xr += h;
      right.push_back(std::min(xr, hi));
    }
    std::vector<double> out(left.rbegin(), left.rend());
    out.insert(out.end(), v.begin(), v.end());
    out.insert(out.end(), right.begin(), right.end());
    // Merge a sliver at the ends.
    if (out.size() > 2 && out[1] - out[0] < 0.3 * (out[2] - out[1])) out.erase(out.begin() + 1);
    const std::size_t k = out.size();
    if (k > 2 && out[k - 1] - out[k - 2] < 0.3 * (out[k - 2] - out[k - 3])) out.erase(out.end() - 2);
    return out;
  };
  double lo_r = 1.0001, hi_r = 3.0;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo_r + hi_r);
    if (static_cast<int>(build(mid).size()) - 1 > n) lo_r = mid;
    else hi_r = mid;
  }
  return build(hi_r);
}

void make_thesis(const fs::path& dir, bool history, bool linear, double scale) {
  // Domain 42 x 30 km, bottom -10 km; the surfaces of Table 4.1 (flat) with their sub-layers.
  const double LX = 42000, LY = 30000;
  Layered L{LX, LY, -1410, -1476, -1498, -1515, 2200, 1800, 4000};
  const int nx = static_cast<int>(std::lround(130 * std::sqrt(scale))), ny = static_cast<int>(std::lround(94 * std::sqrt(scale)));
  BoxMeshSpec spec;
  spec.x = focused(0, LX, LX / 2, 1500 * std::sqrt(scale), nx);
  spec.y = focused(0, LY, LY / 2, 1100 * std::sqrt(scale), ny);
  const std::vector<std::pair<double, int>> surfaces{{50, 2},    {-346, 2},  {-1024, 2}, {-1152, 3}, {-1410, 5}, {-1476, 3},
                                                     {-1498, 8}, {-1515, 2}, {-1543, 10}, {-8655, 2}, {-10000, 0}};
  std::vector<double> z;
  for (std::size_t i = surfaces.size() - 1; i > 0; --i) {
    const auto seg = linspace(surfaces[i].first, surfaces[i - 1].first, surfaces[i - 1].second);
    for (double v : seg)
      if (z.empty() || v > z.back()) z.push_back(v);
  }
  spec.z = z;
  spec.material = [&](const Point3& c) {
    if (linear) return std::hypot(c[0] - LX / 2, (c[1] - LY / 2) / 0.7) < L.rc && c[2] < L.ztop_c && c[2] > L.zbot_c
                           ? std::string("pool_c")
                           : std::string("rock");
    return material_of(L, c);
  };
  const Mesh m = make_box_mesh(spec);
  write_msh(m, (dir / "mesh.msh").string());
  std::fprintf(stderr, "thesis: %zu x %zu x %zu nodes = %zu nodes, %zu tetrahedra\n", spec.x.size(), spec.y.size(),
               spec.z.size(), m.num_nodes(), m.count(ElementType::Tetrahedron));
  if (linear) {
    // One linear-elastic solve: depth-dependent elastic units everywhere, Pool C depleted by 10 MPa.
    CaseToml c(
        "# Thesis-scale linear elastic benchmark (bench/solve): elastic units with c_M from eq. 4.1\n"
        "# at the initial effective stress, isotropic nu = 0.3; Pool C depleted by 10 MPa.\n");
    c.initial_stress({.surface_elevation_m = 50, .k0 = 0.9}).material(elastic("rock", 0.3)).material(elastic("pool_c", 0.3));
    write_text(dir / "case.toml", c.table("output", "fields = [\"displacement\"]\n").str());
    write_pressure(dir / "flow.h5", submesh(m, {"pool_c"}), uniform_series({"2000-01-01"}, {-10e6}));
    // The same mesh for the FEniCSx peer: a field series holding coordinates, cells and the
    // pressure change of each cell (the Pool C cells of the case).
    FieldSeriesWriter w((dir / "mesh_arrays.h5").string(), m);
    Field dp{"dp", 1, {}};
    for_each_output_cell(m, default_output_cell_types(m), [&](const ElementBlock& b, std::size_t) {
      dp.values.push_back(m.physical_name_of(b.entity_dim, b.entity_tag) == "mat:pool_c" ? -10e6 : 0.0);
    });
    const Field cells[] = {dp};
    w.add_step("2000-01-01", static_cast<double>(*parse_iso_date("2000-01-01")), {}, cells);
    w.commit();
    return;
  }
  CaseToml c = layered_case();
  if (history) c.table("output", "dates = [\"2015-05-01\", \"2015-11-01\", \"2016-05-01\", \"2025-05-01\", \"2025-11-01\"]\n");
  write_text(dir / "case.toml", c.str());
  const auto dates = history ? monthly(1950, 1, 2033, 12) : monthly(1950, 1, 1951, 12);
  write_pools(dir, m, L, dates, 1950, 15.2e6);
}

}  // namespace

int main(int argc, char** argv) {
  if (const auto rc = refuse_dir_argument(argc, argv, "make_thesis_case DIR [--linear | --history] [--scale F]")) return *rc;
  const fs::path dir = argv[1];
  bool history = false, linear = false;
  double scale = 1.0;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--history") history = true;
    else if (a == "--linear") linear = true;
    else if (a == "--scale" && i + 1 < argc) {
      char* end = nullptr;
      scale = std::strtod(argv[++i], &end);
      if (*end != '\0' || !(scale > 0) || !std::isfinite(scale)) {
        std::fprintf(stderr, "make_thesis_case: error: --scale %s: expected a positive number\n", argv[i]);
        return 2;
      }
    } else {
      std::fprintf(stderr, "make_thesis_case: error: unknown argument '%s' (expected --linear, --history, --scale F)\n", a.c_str());
      return 2;
    }
  }
  try {
    fs::create_directories(dir);
    make_thesis(dir, history, linear, scale);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_thesis_case: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
