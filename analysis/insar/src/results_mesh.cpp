#include "ugs/insar/results_mesh.hpp"

#include <cmath>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs::insar {

std::vector<Point3> checked_coordinates(const FieldSeriesReader& r) {
  std::vector<Point3> x = r.coordinates();
  static const char* kAxis[3] = {"x", "y", "z"};
  for (std::size_t n = 0; n < x.size(); ++n)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(x[n][k]))
        throw InputError(r.path(), fmt::format("/mesh/coordinates: node {} has {} = {} (expected finite coordinates)", n,
                                               kAxis[k], x[n][k]));
  return x;
}

std::vector<std::uint32_t> checked_cells(const FieldSeriesReader& r, ElementType type) {
  std::vector<std::uint32_t> c = r.cells(type);
  const std::size_t npe = static_cast<std::size_t>(nodes_per_element(type));
  const std::size_t nodes = r.num_nodes();
  const char* dataset = type == ElementType::Triangle      ? "triangles"
                        : type == ElementType::Tetrahedron ? "tetrahedra"
                        : type == ElementType::Prism       ? "prisms"
                                                           : "cells";
  if (npe == 0 || c.size() % npe != 0)
    throw InputError(r.path(), fmt::format("/mesh/{}: {} values (expected {} per cell)", dataset, c.size(), npe));
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c[i] >= nodes)
      throw InputError(r.path(), fmt::format("/mesh/{}: cell {} has node index {} (expected below the {} nodes of "
                                             "/mesh/coordinates)", dataset, i / npe, c[i], nodes));
  return c;
}

}  // namespace ugs::insar
