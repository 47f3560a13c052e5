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
#include <unordered_map>
#include <vector>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/box_mesh.hpp"

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

inline std::string toml_number(double v) { return v == std::floor(v) ? fmt::format("{:.1f}", v) : fmt::format("{}", v); }

inline std::string solve_box_case(double c_R, double c_R_a = 5.0) {
  return fmt::format(R"(# box twin for ugs-calibrate with ugs-solve
crs = "EPSG:32632"

[initial_stress]
surface_elevation_m = 0.0
lithostatic_gradient_MPa_per_m = 0.0226
hydrostatic_gradient_MPa_per_m = 0.0100
k0 = 0.9

[[material]]
name = "surrounding_rock"
law = "elastic"
nu_z = 0.3

[[material]]
name = "pool_c"
law = "hypoplastic"
nu_z = 0.3
Eh_over_Ez = 3.0
nuh_over_nuz = 0.2
c_R = {}

[[material]]
name = "pool_a"
law = "hypoplastic"
nu_z = 0.3
Eh_over_Ez = 3.0
nuh_over_nuz = 0.2
c_R = {}

[boundary]
fixed = ["bottom", "west", "east", "south", "north"]

[output]
dates = ["2013-05-01", "2013-11-01", "2014-05-01"]
)",
                     toml_number(c_R), toml_number(c_R_a));
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
  Mesh sub;
  std::unordered_map<std::uint32_t, std::uint32_t> local;
  const PhysicalGroup* pool = mesh.find_physical(3, "mat:" + material);
  for (const auto& b : mesh.blocks) {
    if (b.type != ElementType::Tetrahedron) continue;
    const Entity* e = mesh.find_entity(3, b.entity_tag);
    if (!e || e->physicals.empty() || e->physicals.front() != pool->tag) continue;
    auto& sb = sub.block(3, sub.entity_for_physical(3, "mat:" + material), ElementType::Tetrahedron);
    for (std::size_t i = 0; i < b.size(); ++i) {
      std::uint32_t n[4];
      for (int k = 0; k < 4; ++k) {
        const auto g = b.element(i)[k];
        auto [it, fresh] = local.emplace(g, 0);
        if (fresh) it->second = sub.add_node(mesh.nodes[g], mesh.node_tags[g]);
        n[k] = it->second;
      }
      sub.add_element(sb, n, b.tags[i]);
    }
  }
  FieldSeriesWriter w(path, sub);
  for (auto t : solve_box_dates()) {
    const Field dp{"dp", 1, std::vector<double>(sub.num_nodes(), solve_box_dp_MPa(pool_index, t) * 1e6)};
    const Field fs[] = {dp};
    w.add_step(format_iso_date(t), double(t), fs);
  }
  w.commit();
}

// Writes model.msh, case.toml (c_R of Pool C and Pool A), dp_c.h5 and dp_a.h5 into `dir`.
inline void write_solve_box(const std::filesystem::path& dir, double c_R, double c_R_a = 5.0) {
  const Mesh mesh = solve_box_mesh();
  write_msh(mesh, (dir / "model.msh").string());
  {
    std::FILE* f = std::fopen((dir / "case.toml").c_str(), "w");
    const std::string t = solve_box_case(c_R, c_R_a);
    std::fwrite(t.data(), 1, t.size(), f);
    std::fclose(f);
  }
  write_pool_dp(mesh, "pool_c", 0, (dir / "dp_c.h5").string());
  write_pool_dp(mesh, "pool_a", 1, (dir / "dp_a.h5").string());
}

}  // namespace ugs::test
