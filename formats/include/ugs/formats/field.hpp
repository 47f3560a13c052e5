// A named array of values over a mesh's nodes or cells — what every field writer takes — and the
// one rule for which cells an output holds and in which order, so cell fields line up in every format.
#pragma once
#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "ugs/formats/mesh.hpp"

namespace ugs {

struct Field {
  std::string name;
  int components = 1;          // 1 scalar, 3 vector, 6 symmetric tensor (xx yy zz xy yz xz), ...
  std::vector<double> values;  // node- or cell-major: values[i * components + k]

  std::size_t count() const { return components > 0 ? values.size() / components : 0; }
};

// Cells of an output: grouped by type in the order of `types`, each type in mesh block order.
// The default is the volume (tetrahedra, then interface prisms), or the triangles of a surface mesh.
inline std::vector<ElementType> default_output_cell_types(const Mesh& mesh) {
  if (mesh.count(ElementType::Tetrahedron) + mesh.count(ElementType::Prism) > 0)
    return {ElementType::Tetrahedron, ElementType::Prism};
  return {ElementType::Triangle};
}

inline std::size_t output_cell_count(const Mesh& mesh, std::span<const ElementType> types) {
  std::size_t n = 0;
  for (ElementType t : types) n += mesh.count(t);
  return n;
}

// Calls f(block, i) for every output cell, in output order.
template <class F>
void for_each_output_cell(const Mesh& mesh, std::span<const ElementType> types, F&& f) {
  for (ElementType t : types)
    for (const ElementBlock& b : mesh.blocks)
      if (b.type == t)
        for (std::size_t i = 0; i < b.size(); ++i) f(b, i);
}

// The most components a field may have (a full 3 x 3 tensor has 9): the readers refuse more before
// allocating anything.
inline constexpr int kMaxFieldComponents = 64;

// A field handed to a writer must match the mesh; a mismatch is a bug in the calling tool.
inline void check_field(const Field& f, std::size_t count, std::string_view what) {
  if (f.name.empty() || f.name.find_first_of("/<>&\"") != std::string::npos)
    throw std::invalid_argument(fmt::format("{} field '{}': name must be non-empty, without / < > & \"", what, f.name));
  if (f.components < 1 || f.components > kMaxFieldComponents || f.values.size() != count * static_cast<std::size_t>(f.components))
    throw std::invalid_argument(fmt::format("{} field '{}': {} values for {} x {} components", what, f.name,
                                            f.values.size(), count, f.components));
}

inline void check_fields(std::span<const Field> fields, std::size_t count, std::string_view what) {
  for (std::size_t i = 0; i < fields.size(); ++i) {
    check_field(fields[i], count, what);
    for (std::size_t j = 0; j < i; ++j)
      if (fields[j].name == fields[i].name)
        throw std::invalid_argument(fmt::format("{} field '{}' given twice", what, fields[i].name));
  }
}

}  // namespace ugs
