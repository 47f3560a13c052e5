// Material constants that vary in space on a mesh (docs/case-file.md, "Properties that vary in
// space"): each tetrahedron of a material with fields gets its own copy of the [[material]] with
// the fields' values at it, so the solvers read one MaterialSpec per element as they read one per
// material. Copies with equal values are one (a GRDECL property gives at most one per grid cell).
#pragma once
#include <cstdint>
#include <vector>

#include "ugs/formats/case_file.hpp"
#include "ugs/formats/mesh.hpp"

namespace ugs {

struct MaterialFieldValues {
  // Per tetrahedron of the mesh (its tetrahedron blocks in mesh order, elements in block order):
  // the index into `specs`, or -1 for a tetrahedron whose material has no field.
  std::vector<std::int32_t> instance;
  std::vector<MaterialSpec> specs;           // fields replaced by numbers, `fields` emptied
  std::vector<std::uint64_t> first_tag;      // per spec: the element tag of its first tetrahedron
  std::vector<Point3> first_centroid;        // and that tetrahedron's centroid, for messages
  bool empty() const { return specs.empty(); }
};

// The values of every field of the case's materials on the tetrahedra of `mesh` (only the
// materials the mesh holds; an empty result, read from no file, when none has a field).
// InputError, at the field's line in the case: a tetrahedron the source does not cover (naming its
// element tag and centroid), a value the key does not allow there (NaN, porosity outside (0, 1),
// a non-positive c_R, ...), and the sources' own errors (FieldSources).
MaterialFieldValues material_field_values(const Mesh& mesh, const CaseFile& cs);

// The MaterialSpec of tetrahedron `t` (index as in `instance`): its copy, or the case's own.
const MaterialSpec& material_of_tet(const MaterialFieldValues& v, std::size_t t, const MaterialSpec& own);

}  // namespace ugs
