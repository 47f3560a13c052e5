// What ugs-meshinfo prints, computed by the library so it can be unit-tested: counts per element
// type and physical group, bounding box, tetrahedron volume range and inverted elements.
#pragma once
#include <array>
#include <map>
#include <string>

#include "ugs/formats/mesh.hpp"

namespace ugs {

struct GroupCount {
  int dim = 0;
  std::string name;
  std::map<ElementType, std::size_t> elements;
};

struct MeshSummary {
  std::size_t nodes = 0;
  std::map<ElementType, std::size_t> elements;
  std::map<std::pair<int, int>, GroupCount> groups;  // (dim, physical tag)
  std::size_t elements_without_group = 0;
  std::array<double, 6> bbox{};                      // xmin ymin zmin xmax ymax zmax
  double min_tet_volume = 0, max_tet_volume = 0, total_tet_volume = 0;
  std::size_t inverted_tets = 0;                     // signed volume <= 0
};

MeshSummary summarize(const Mesh& mesh);
std::string format_summary(const MeshSummary& s);

}  // namespace ugs
