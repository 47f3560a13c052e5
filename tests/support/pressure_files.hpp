// The pressure-change files that ugs-flow writes, for tests and benchmark cases: the sub-mesh of
// some materials (parent node and element tags kept, as ugs-submesh writes it) and the node field
// dp [Pa] on it at each date (HDF5 + XDMF). Built once per HDF5 flavour (ugs_testcase_serial,
// ugs_testcase_mpi: docs/hdf5-split.md), so that a test linking PETSc can write them too.
#pragma once
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "ugs/formats/fields.hpp"
#include "ugs/formats/mesh.hpp"

namespace ugs::testcase {

// Sub-mesh of the tetrahedra of `materials` (groups mat:<name>), in the parent's element order.
Mesh submesh(const Mesh& m, const std::vector<std::string>& materials);
// Sub-mesh of every tetrahedron, each block under its parent's group.
Mesh tetrahedra_of(const Mesh& m);

struct Series {
  std::vector<std::string> dates;  // ISO dates
  // dp [Pa] at a node of the sub-mesh for step k.
  std::function<double(const Point3&, std::size_t k)> dp;
};

// A series with one value [Pa] a date, the same at every node.
Series uniform_series(std::vector<std::string> dates, std::vector<double> dp_Pa);

// The node field dp of every date of `s` on `sub` (HDF5 + XDMF, as ugs-flow writes it); `o` picks
// the cells written (default: as the writer's).
void write_pressure(const std::filesystem::path& path, const Mesh& sub, const Series& s, const FieldSeriesOptions& o = {});

// First days of the months from y0-m0 to y1-m1, ISO dates.
std::vector<std::string> monthly(int y0, int m0, int y1, int m1);

}  // namespace ugs::testcase
