// The layered model of the mechanics tests and the thesis-scale benchmark (tests/mechanics
// mech_make_case small, bench/solve make_thesis_case): elastic rock with two hypo-plastic pools, A
// and C, each inside a lagging aquifer ring; its case file and the pools' pressure-change series.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "case_toml.hpp"
#include "ugs/formats/mesh.hpp"

namespace ugs::testcase {

// The case file of the layered model (elastic rock, pools A and C with aquifers); a writer adds its
// own sections ([[pool]], [output]).
CaseToml layered_case();

// The layered model: pools as ellipses of semi-axes ra / rc in x (0.7 of that in y), aquifers to raq.
struct Layered {
  double lx, ly, ztop_a, zbot_a, ztop_c, zbot_c, ra, rc, raq;
};

std::string material_of(const Layered& L, const Point3& c);

// flow_pool_a.h5 and flow_pool_c.h5: primary production from year y0, then seasonal storage cycles,
// the aquifers lagging and decaying with distance from the pool's edge; p0 [Pa] the initial pressure.
void write_pools(const std::filesystem::path& dir, const Mesh& m, const Layered& L, const std::vector<std::string>& dates,
                 int y0, double p0);

}  // namespace ugs::testcase
