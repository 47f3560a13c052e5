// Test support for the field writers: the unit cube of run_tool.hpp with a zero-thickness
// interface prism, and fields whose every value is distinct, so a value read back from the wrong
// node, cell, component or step cannot pass.
#pragma once
#include <cmath>
#include <vector>

#include "run_tool.hpp"
#include "ugs/formats/field.hpp"

namespace ugs::test {

// Unit cube: 8 nodes, 6 tets (mat:rock), 2 top triangles (bnd:top), and one interface prism
// (fault:F1) on the top-face nodes 4 5 7 and their 3 twins: 11 nodes in all.
inline Mesh faulted_cube_mesh() {
  Mesh m = unit_cube_mesh();
  const std::uint32_t side[3] = {4, 5, 7};
  std::uint32_t prism[6] = {side[0], side[1], side[2], 0, 0, 0};
  for (int k = 0; k < 3; ++k) prism[3 + k] = m.add_node(m.nodes[side[k]]);
  const int f = m.entity_for_physical(3, "fault:F1");
  m.add_element(m.block(3, f, ElementType::Prism), prism);
  m.update_entity_bboxes();
  return m;
}

// Values depending on field, step, item and component; not round numbers, so the bits matter.
inline Field sample_field(std::string name, int components, std::size_t count, int step, double seed) {
  Field f{std::move(name), components, {}};
  for (std::size_t i = 0; i < count; ++i)
    for (int k = 0; k < components; ++k)
      f.values.push_back(seed + step * 1.0e3 + static_cast<double>(i) / 7.0 + k * std::sqrt(2.0) + 1e-9 / (1 + i));
  return f;
}

}  // namespace ugs::test
