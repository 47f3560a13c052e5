// Synthetic ugs-solve cases on box meshes: the pieces that the test case writers (mech_make_case,
// contact_make_case) and the benchmark case writers (make_thesis_case, make_faulted_bench) share — a sub-mesh of some
// materials as ugs-submesh writes it, the pressure-change series that ugs-flow would write for a
// pool, and the layered model with two hypo-plastic pools and their lagging aquifers.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "ugs/formats/mesh.hpp"

namespace ugs::cases {

// Sub-mesh of the tetrahedra of `materials`, keeping parent node and element tags (as ugs-submesh).
Mesh submesh(const Mesh& m, const std::vector<std::string>& materials);

struct Series {
  std::vector<std::string> dates;
  // dp [Pa] at a node of the sub-mesh for step k.
  std::function<double(const Point3&, std::size_t k)> dp;
};

// The node field dp of every date of `s` on `sub` (HDF5 + XDMF, as ugs-flow writes it).
void write_pressure(const std::filesystem::path& path, const Mesh& sub, const Series& s);

void write_text(const std::filesystem::path& p, const std::string& text);

// First days of the months from y0-m0 to y1-m1, ISO dates.
std::vector<std::string> monthly(int y0, int m0, int y1, int m1);

// The case file of the layered model (elastic rock, pools A and C with aquifers), `extra` appended.
std::string layered_case(const std::string& extra);

// The layered model: pools as ellipses of semi-axes ra / rc in x (0.7 of that in y), aquifers to raq.
struct Layered {
  double lx, ly, ztop_a, zbot_a, ztop_c, zbot_c, ra, rc, raq;
};

std::string material_of(const Layered& L, const Point3& c);

// flow_pool_a.h5 and flow_pool_c.h5: primary production from year y0, then seasonal storage cycles,
// the aquifers lagging and decaying with distance from the pool's edge; p0 [Pa] the initial pressure.
void write_pools(const std::filesystem::path& dir, const Mesh& m, const Layered& L, const std::vector<std::string>& dates,
                 int y0, double p0);

}  // namespace ugs::cases
