// A small reservoir model for ugs-solve, built as ugs-meshgen and ugs-flow would: a box mesh
// (11 x 11 km, 3 km deep, EPSG:32632 coordinates) with a 20 m thick Pool C (3 x 3 km) at -1500 m
// and a 30 m thick Pool A (3 x 3 km, north-west of it) at -1440 m, the case file, and each pool's
// pressure change as a field series on its sub-mesh (node field dp in Pa, parent tags, as
// ugs-flow writes): Pool C depleted by 8 MPa over 1990-2000, then seasonal cycles of 6 MPa
// (lowest on 1 May, highest on 1 November); Pool A depleted by 6 MPa over 1990-1996, then cycles of
// 4 MPa three months later; steps in 1990, 1995, 2000, then quarterly from 2009-02 to 2014-11.
#pragma once
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/box_mesh.hpp"
#include "case_toml.hpp"
#include "pressure_files.hpp"

namespace ugs::test {

constexpr double kBoxX0 = 676000, kBoxY0 = 4947000, kPoolXc = 681500, kPoolYc = 4952500;
constexpr double kPoolAXc = 678500, kPoolAYc = 4954500;

inline Mesh solve_box_mesh() {
  BoxMeshSpec s;
  s.x = linspace(kBoxX0, kBoxX0 + 11000, 12);
  s.y = linspace(kBoxY0, kBoxY0 + 11000, 12);
  s.z = {-3000, -2200, -1700, -1560, -1520, -1510, -1500, -1470, -1440, -1400, -1200, -800, -400, 0};
  s.material = [](const Point3& c) {
    if (std::abs(c[0] - kPoolXc) < 1500 && std::abs(c[1] - kPoolYc) < 1500 && c[2] > -1520 && c[2] < -1500) return std::string("pool_c");
    if (std::abs(c[0] - kPoolAXc) < 1500 && std::abs(c[1] - kPoolAYc) < 1500 && c[2] > -1470 && c[2] < -1440) return std::string("pool_a");
    return std::string("surrounding_rock");
  };
  return make_box_mesh(s);
}

inline std::string solve_box_case(double c_R, double c_R_a = 5.0) {
  testcase::CaseToml c("# box twin for ugs-calibrate with ugs-solve\ncrs = \"EPSG:32632\"\n\n", testcase::Numbers::Decimal);
  c.initial_stress({.surface_elevation_m = 0, .k0 = 0.9});
  c.material({.name = "surrounding_rock", .law = "elastic", .nu_z = 0.3});
  c.material(testcase::hypoplastic("pool_c", c_R)).material(testcase::hypoplastic("pool_a", c_R_a));
  c.boundary(testcase::fixed_sides()).table("output", "dates = [\"2013-05-01\", \"2013-11-01\", \"2014-05-01\"]\n");
  return c.str();
}

// A pool's pressure change [MPa] at a date (pool 0: Pool C, 1: Pool A).
inline double solve_box_dp_MPa(int pool, std::int64_t t) {
  const double years = double(t - days_from_civil(1990, 1, 1) * 86400) / (365.25 * 86400);
  const auto c = civil_from_days(t / 86400);
  const double month = c.month - 1 + (c.day - 1) / 30.0;  // 0 = 1 January
  const double pi = 3.141592653589793;
  if (pool == 0) {
    if (years <= 10) return -8.0 * years / 10;
    return -5.0 + 3.0 * std::cos(2 * pi * (month - 10) / 12);  // -2 on 1 Nov, -8 on 1 May
  }
  if (years <= 6) return -6.0 * years / 6;
  return -4.0 + 2.0 * std::cos(2 * pi * (month - 7) / 12);  // -2 on 1 Aug, -6 on 1 Feb
}

inline std::vector<std::int64_t> solve_box_dates() {
  std::vector<std::int64_t> d{days_from_civil(1990, 1, 1) * 86400, days_from_civil(1995, 1, 1) * 86400,
                              days_from_civil(2000, 1, 1) * 86400};
  for (int y = 2009; y <= 2014; ++y)
    for (int m : {2, 5, 8, 11}) d.push_back(days_from_civil(y, m, 1) * 86400);
  return d;
}

// The sub-mesh of a material with its pressure history, parent node and element tags kept.
inline void write_pool_dp(const Mesh& mesh, const std::string& material, int pool_index, const std::string& path) {
  testcase::Series s;
  std::vector<double> dp_Pa;
  for (auto t : solve_box_dates()) {
    s.dates.push_back(format_iso_date(t));
    dp_Pa.push_back(solve_box_dp_MPa(pool_index, t) * 1e6);
  }
  testcase::write_pressure(path, testcase::submesh(mesh, {material}), testcase::uniform_series(s.dates, dp_Pa));
}

// Writes model.msh, case.toml (c_R of Pool C and Pool A), dp_c.h5 and dp_a.h5 into `dir`.
inline void write_solve_box(const std::filesystem::path& dir, double c_R, double c_R_a = 5.0) {
  const Mesh mesh = solve_box_mesh();
  write_msh(mesh, (dir / "model.msh").string());
  testcase::write_text(dir / "case.toml", solve_box_case(c_R, c_R_a));
  write_pool_dp(mesh, "pool_c", 0, (dir / "dp_c.h5").string());
  write_pool_dp(mesh, "pool_a", 1, (dir / "dp_a.h5").string());
}

}  // namespace ugs::test
