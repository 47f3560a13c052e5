// Quality report of a tetrahedral mesh (what ugs-meshgen prints on stderr): counts, volume range,
// inverted elements, smallest dihedral angle, elements with a dihedral angle below a threshold,
// and the volume of each material. Same mesh, same report (fixed chunking of the parallel sums).
#pragma once
#include <string>
#include <vector>

#include "ugs/formats/mesh.hpp"

namespace ugs {

struct MaterialVolume {
  std::string name;           // physical name, e.g. "mat:pool_c"
  std::size_t tetrahedra = 0;
  double volume = 0;          // m3
};

struct GroupSize {
  std::string name;
  std::size_t elements = 0;
};

struct QualityReport {
  std::size_t nodes = 0, tetrahedra = 0, triangles = 0;
  double min_volume = 0, max_volume = 0, total_volume = 0;
  std::size_t inverted = 0;                     // signed volume <= 0
  std::size_t degenerate = 0;                   // flat by ugs-solve's test (tet_is_degenerate), inverted or not
  std::size_t first_degenerate = 0;             // the first of them: its index among the tetrahedra (output order)
  double min_dihedral_deg = 0;
  double small_angle_deg = 5.0;
  std::size_t small_angle = 0;                  // tetrahedra with a dihedral angle below small_angle_deg
  std::vector<MaterialVolume> materials;        // in the mesh's order
  std::vector<GroupSize> surfaces;              // triangle groups (bnd:*, fault:*)
};

// Smallest dihedral angle of a tetrahedron, in degrees (0 for a flat one: tet_is_degenerate).
double min_dihedral_angle_deg(const Point3& a, const Point3& b, const Point3& c, const Point3& d);
namespace detail {
// The same computed four faces at a time (lanes 4: AVX, where the processor has it) or two at a
// time (lanes 2: SSE2; the plain loop without it). Each gives min_dihedral_angle_deg's bits: for tests.
double min_dihedral_angle_deg_lanes(int lanes, const Point3& a, const Point3& b, const Point3& c, const Point3& d);
}  // namespace detail

QualityReport mesh_quality(const Mesh& mesh, double small_angle_deg = 5.0);
// Human-readable lines (MPa/mm are not involved; volumes in m3 and km3).
std::string format_quality(const QualityReport& q);

}  // namespace ugs
