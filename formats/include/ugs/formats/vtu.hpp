// VTK XML output written by hand (zlib, no VTK library, so tools stay free of VTK's HDF5):
// a mesh with point and cell fields as an UnstructuredGrid `.vtu`, and a `.pvd` time series.
#pragma once
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "ugs/formats/field.hpp"
#include "ugs/formats/io.hpp"
#include "ugs/formats/mesh.hpp"

namespace ugs {

struct VtuOptions {
  // Element types to write, in this order (see field.hpp); empty means default_output_cell_types().
  std::vector<ElementType> cell_types;
};

// Writes every node of `mesh` and its cells of the chosen types, binary and zlib-compressed
// (appended raw data, UInt64 headers). Besides the given fields it writes the point array
// `node_tag` (Int64) and the cell arrays `material` (Int32, physical tag of the cell's entity,
// 0 if none) and `element_tag` (Int64). Point fields have one tuple per node, cell fields one
// per written cell in output order (output_cell_count). Interface prisms become VTK_WEDGE.
void write_vtu(const Mesh& mesh, OutputFile& out, std::span<const Field> point_fields = {},
               std::span<const Field> cell_fields = {}, const VtuOptions& options = {});
// Same, atomically to `path` ("-" = stdout).
void write_vtu(const Mesh& mesh, const std::string& path, std::span<const Field> point_fields = {},
               std::span<const Field> cell_fields = {}, const VtuOptions& options = {});

// A `.pvd` collection: one entry per time, each naming a `.vtu` relative to the `.pvd`.
class PvdWriter {
public:
  explicit PvdWriter(std::string path);
  void add(double time, std::string vtu_file);
  // Writes the collection atomically.
  void commit();

private:
  std::string path_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace ugs
