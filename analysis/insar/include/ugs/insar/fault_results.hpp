// The safety factor chi = |tau| / (c - sigma'_n tan(phi)) (thesis eq. 4.2, on the effective normal
// traction sigma'_n = sigma_n + p_f, tension positive: docs/theory.md section 6) on the faults, from a
// fault results file (HDF5 + XDMF: triangles, or interface prisms whose first three nodes are one
// side, with the cell field `chi` or a node field `chi` averaged to the cells), grouped by fault
// (the cells' physical tag; names from the mesh's fault:<name> groups when a mesh is given) and
// laid out in each fault's own plane for maps: s along the strike, z.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "ugs/formats/fields.hpp"
#include "ugs/formats/mesh.hpp"

namespace ugs::insar {

struct FaultChi {
  std::string name;
  std::vector<std::array<Point3, 3>> triangles;
  std::vector<double> chi;                   // per triangle
  std::vector<std::array<double, 6>> sz;     // per triangle: (s, z) of its three corners
  double max_chi = 0;
};

// The name of the fault whose cells carry physical tag `tag`: the mesh's fault:<name> group of that
// tag (interface prisms are 3-D, fault triangles 2-D; physical tags are per dimension), else any group
// with the tag, else "fault <tag>"; the "fault:" prefix dropped.
std::string fault_group_name(const Mesh* mesh, std::int32_t tag);

// InputError when the file has no fault cells or no field `field` at that step.
std::vector<FaultChi> read_fault_chi(const FieldSeriesReader& faults, std::size_t step, const Mesh* mesh,
                                     const std::string& field = "chi");

}  // namespace ugs::insar
