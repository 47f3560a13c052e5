// The mesh of a results file (ugs-fields HDF5), checked before anything indexes with it: the
// reader checks the shapes of the datasets, these check their values — every cell's node indices
// below the number of nodes, every coordinate finite — so a damaged or hand-made file is refused
// with one line (InputError, exit 2) instead of being read out of bounds.
#pragma once
#include <cstdint>
#include <vector>

#include "ugs/formats/fields.hpp"
#include "ugs/formats/mesh.hpp"

namespace ugs::insar {

// /mesh/coordinates; InputError "r.h5: /mesh/coordinates: node 7 has x = nan (expected finite
// coordinates)" otherwise.
std::vector<Point3> checked_coordinates(const FieldSeriesReader& r);

// The cells of one type (nodes_per_element(type) 0-based node indices per cell; empty if none);
// InputError "r.h5: /mesh/tetrahedra: cell 3 has node index 4294967295 (expected below the 1234
// nodes of /mesh/coordinates)" otherwise.
std::vector<std::uint32_t> checked_cells(const FieldSeriesReader& r, ElementType type);

}  // namespace ugs::insar
