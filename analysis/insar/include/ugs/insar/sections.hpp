// Stress pictures (thesis 4.3.2): vertical sections through the tetrahedra along a polyline
// (figures 4.27-4.32), the top of a layer of cells with the cells just above it (4.33-4.35), and
// how far above that top a stress change reaches (the height where it falls below a fraction of
// its peak in the layer).
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "ugs/formats/mesh.hpp"
#include "ugs/insar/surface.hpp"

namespace ugs::insar {

using Tet = std::array<std::uint32_t, 4>;

struct SectionSlice {
  std::string name;
  double length = 0;                  // m, along the polyline
  std::vector<double> sz;             // polygon vertices (s along the line [m], z [m]) flattened
  std::vector<std::int32_t> offsets;  // polygon i has vertices offsets[i] .. offsets[i+1]-1
  std::vector<std::uint32_t> cell;    // tetrahedron of each polygon
};

// The intersection of every tetrahedron with the vertical planes through the polyline's segments
// (convex polygons in section coordinates), clipped to zmin <= z <= zmax: the polygons tile the
// section's rectangle [0, length] x [zmin, zmax] where the mesh fills it.
SectionSlice slice_tets(std::span<const Point3> x, std::span<const Tet> tets, const std::string& name,
                        const std::vector<std::array<double, 2>>& polyline, double zmin, double zmax);

struct LayerTop {
  TopSurface surface;                  // the upward boundary of the layer's cells
  std::vector<std::uint32_t> below;    // layer cell under each triangle
  std::vector<std::int64_t> above;     // cell on the other side of each triangle (-1: none)
};

// The top of the cells flagged in `in_layer` and the cells just above it.
LayerTop layer_top(std::span<const Point3> x, std::span<const std::uint64_t> tags, std::span<const Tet> tets,
                   const std::vector<char>& in_layer);

struct ConfinementHeight {
  double peak = 0;           // max |value| over the layer's cells
  double height = 0;         // m above the layer top: beyond it every |value| < fraction * peak
  std::size_t cells_above = 0;
  std::size_t cells_over = 0;  // cells above the top with |value| >= fraction * peak
};

// Over the cells outside the layer whose centroid lies above the layer top (inside its footprint):
// the largest height above the top of a cell whose |value| reaches fraction x the layer's peak.
// Cells flagged in `own_load` (empty: none) are left out: they respond to a pressure change of their
// own (another pool, its aquifers), not to the one propagating from the layer. (Until 2026-11-29
// they counted: at the po-plain thesis scale Pool A's own re-pressurization, 2.5 % of Pool C's peak,
// made a 168 m height where no rock cell above Pool C reaches 1 %.)
ConfinementHeight confinement_height(std::span<const Point3> x, std::span<const Tet> tets,
                                     const std::vector<double>& cell_values, const std::vector<char>& in_layer,
                                     const SurfaceLocator& layer_top, double fraction,
                                     const std::vector<char>& own_load = {});

}  // namespace ugs::insar
