// A point in plan: easting and northing (m) in the model CRS. Shared by the geodata (polygons, lines,
// raster sampling) and the plan (its columns).
#pragma once
#include <array>

namespace ugs {

using XY = std::array<double, 2>;

}  // namespace ugs
