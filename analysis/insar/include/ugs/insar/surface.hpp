// The model's top surface as a triangulation (from the mesh group bnd:top, from a results file's
// own triangles, or as the upward-facing boundary of a set of tetrahedra) and the location of a
// plan point (x, y) on it: the highest triangle crossed by the vertical through the point (a CGAL
// AABB tree), or, for a point outside the surface's plan footprint, the nearest point of the
// footprint. Linear interpolation with the returned weights reproduces any field that is linear
// on the triangle exactly.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "ugs/formats/fields.hpp"
#include "ugs/formats/mesh.hpp"

namespace ugs::insar {

struct TopSurface {
  std::vector<Point3> points;                           // surface nodes
  std::vector<std::uint64_t> node_tags;                 // their tags (results map back by tag)
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into points
  std::string source;                                   // for messages: "model.msh: bnd:top"

  std::array<double, 4> extent() const;                 // xmin, xmax, ymin, ymax
};

// The triangles of the 2-D physical group `group` (e.g. "bnd:top"); InputError if it has none.
TopSurface surface_from_mesh(const Mesh& mesh, const std::string& group, const std::string& where);

// The faces of `tets` (mesh node indices into x) that no other tetrahedron of the set shares and
// whose outward normal points up (n_z > min_nz): the top of a volume or of a layer of cells.
// `faces`, when given, receives for each surface triangle its face code: tet index * 4 + the
// local number of the node opposite the face.
TopSurface upward_boundary(std::span<const Point3> x, std::span<const std::uint64_t> tags,
                           std::span<const std::array<std::uint32_t, 4>> tets, double min_nz = 1e-6,
                           std::vector<std::uint32_t>* faces = nullptr);

// The triangles written in a results file (a surface output), else the upward boundary of its
// tetrahedra. InputError if it has neither.
TopSurface surface_from_results(const FieldSeriesReader& results);

struct SurfaceHit {
  bool inside = false;              // the vertical through (x, y) crosses the surface
  std::uint32_t triangle = 0;
  std::array<double, 3> weights{};  // barycentric weights of the triangle's nodes
  Point3 point{};                   // the sampled location on the surface
  double distance = 0;              // horizontal distance from (x, y) to `point` (0 inside)
};

class SurfaceLocator {
public:
  explicit SurfaceLocator(const TopSurface& surface);
  ~SurfaceLocator();
  SurfaceLocator(const SurfaceLocator&) = delete;
  SurfaceLocator& operator=(const SurfaceLocator&) = delete;

  // Thread-safe after construction.
  SurfaceHit locate(double x, double y) const;
  const TopSurface& surface() const { return surface_; }

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  const TopSurface& surface_;
};

}  // namespace ugs::insar
