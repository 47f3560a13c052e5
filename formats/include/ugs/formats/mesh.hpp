// The mesh model shared by every tool, shaped like Gmsh MSH 4.1: nodes with stable tags,
// elements grouped in blocks by (entity, type), entities carrying physical groups with names.
//
// Conventions (docs/conventions.md): x east, y north, z up, metres. Element connectivity is
// stored as 0-based node *indices* into `Mesh::nodes`; tags are what files and users see.
// The material of a cell is the physical group of its entity (`mat:<name>`).
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace ugs {

// Gmsh element type numbers we support.
enum class ElementType : int {
  Point = 15,
  Line = 1,
  Triangle = 2,
  Tetrahedron = 4,
  Prism = 6,  // 6-node zero-thickness interface element: nodes 1-3 one side, 4-6 their twins
};

int nodes_per_element(ElementType t);
int element_dimension(ElementType t);
std::string_view element_name(ElementType t);
// Returns nullopt for types we do not handle.
std::optional<ElementType> element_type_from_gmsh(int gmsh_type);

using Point3 = std::array<double, 3>;

struct PhysicalGroup {
  int dim = 0;
  int tag = 0;
  std::string name;
};

// A geometric entity (Gmsh "point", "curve", "surface", "volume") with its physical groups.
struct Entity {
  int dim = 0;
  int tag = 0;
  std::vector<int> physicals;             // physical group tags
  std::array<double, 6> bbox{};           // xmin ymin zmin xmax ymax zmax (points use the first 3)
};

// All elements of one type on one entity.
struct ElementBlock {
  int entity_dim = 0;
  int entity_tag = 0;
  ElementType type = ElementType::Tetrahedron;
  std::vector<std::uint64_t> tags;        // element tags, one per element
  std::vector<std::uint32_t> nodes;       // node indices, nodes_per_element(type) per element

  std::size_t size() const { return tags.size(); }
  int npe() const { return nodes_per_element(type); }
  std::span<const std::uint32_t> element(std::size_t i) const {
    return {nodes.data() + i * npe(), static_cast<std::size_t>(npe())};
  }
};

class Mesh {
public:
  std::vector<std::uint64_t> node_tags;   // stable tags, one per node
  std::vector<Point3> nodes;              // coordinates, same order
  std::vector<Entity> entities;
  std::vector<PhysicalGroup> physicals;
  std::vector<ElementBlock> blocks;
  std::vector<std::string> provenance;    // command lines that built this mesh ($UgsProvenance)

  std::size_t num_nodes() const { return nodes.size(); }
  std::size_t count(ElementType t) const;

  // Adds a node; its tag is max tag + 1 unless given. Returns its index.
  std::uint32_t add_node(const Point3& x, std::uint64_t tag = 0);

  // Finds or creates the physical group `name` of dimension `dim` and an entity carrying it;
  // returns the entity tag. Elements added with this entity belong to the group.
  int entity_for_physical(int dim, const std::string& name);
  // Appends elements (node indices) to the block (entity, type), creating it if needed.
  // Element tags are assigned after the current maximum.
  ElementBlock& block(int entity_dim, int entity_tag, ElementType type);
  void add_element(ElementBlock& b, std::span<const std::uint32_t> node_indices, std::uint64_t tag = 0);

  const PhysicalGroup* find_physical(int dim, std::string_view name) const;
  const PhysicalGroup* find_physical_tag(int dim, int tag) const;
  const Entity* find_entity(int dim, int tag) const;
  // Name of the first physical group of an entity, or "" if it has none.
  std::string physical_name_of(int entity_dim, int entity_tag) const;

  std::uint64_t max_node_tag() const;
  std::uint64_t max_element_tag() const;

  // Map node tag -> index, built on demand.
  std::unordered_map<std::uint64_t, std::uint32_t> node_index_by_tag() const;

  // Recomputes entity bounding boxes from the nodes their elements use.
  void update_entity_bboxes();

private:
  std::uint64_t next_element_tag_ = 0;
  std::uint64_t next_node_tag_ = 0;
};

// Signed volume of a tetrahedron (positive when nodes 1-2-3 turn counter-clockwise seen from node 4... i.e. Gmsh's orientation).
double tet_signed_volume(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

// ugs-solve's test of a flat tetrahedron (solver/fem/src/tet4.cpp): the Jacobian's determinant
// |det| = 6 |V| against scale^3, scale the sum of the |components| of the three edges from node a.
// A tetrahedron whose ratio |det| / scale^3 is at most kDegenerateTetRatio is refused by the solver.
// Rounding alone gives a ratio of about 1e-16 to four coplanar points, with either sign: a volume
// "> 0" does not tell a tetrahedron from a flat one, this ratio does.
inline constexpr double kDegenerateTetRatio = 1e-14;
double tet_volume_ratio(const Point3& a, const Point3& b, const Point3& c, const Point3& d);
inline bool tet_is_degenerate(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return !(tet_volume_ratio(a, b, c, d) > kDegenerateTetRatio);
}

}  // namespace ugs
