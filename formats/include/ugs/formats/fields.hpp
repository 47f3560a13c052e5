// Fields over time as HDF5 + an XDMF 3 index that ParaView opens: one writer and one reader shared
// by every tool. The library is built twice, against Debian's serial and OpenMPI HDF5
// (ugs_fields_serial, ugs_fields_mpi; docs/hdf5-split.md), and uses only the serial API.
//
// Layout of `name.h5`:
//   /            attribute ugs_format = "ugs-fields 1"
//   /mesh/coordinates   (nodes x 3, float64)     /mesh/node_tags (nodes, uint64)
//   /mesh/tetrahedra | triangles | prisms  (cells of that type x nodes per cell, uint32, 0-based
//                       node indices), attribute cell_types on /mesh lists them in output order
//   /mesh/cell_tags, /mesh/material  (cells, uint64 / int32) in output order (see field.hpp)
//   /mesh/mixed_topology  (XDMF "Mixed" encoding, only when cells of several types are written)
//   /steps/000012       attributes date (ISO 8601 text) and time (seconds)
//   /steps/000012/node/<field>, /steps/000012/cell/<field>  (count, or count x components, float64;
//                       chunks of +0.0 are not stored: HDF5 reads them as the fill value, zero)
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ugs/formats/error.hpp"
#include "ugs/formats/field.hpp"
#include "ugs/formats/mesh.hpp"

namespace ugs {

struct FieldSeriesOptions {
  // Triangle, Tetrahedron and/or Prism, in output order; empty means default_output_cell_types().
  std::vector<ElementType> cell_types;
};

class FieldSeriesWriter {
public:
  // Writes `h5_path` and the XDMF beside it (".h5" replaced by ".xdmf") as temporaries; the mesh
  // goes in now, so `mesh` need not outlive the writer. Throws InputError for "-" (HDF5 needs a file).
  FieldSeriesWriter(const std::string& h5_path, const Mesh& mesh, const FieldSeriesOptions& options = {});
  // The same with the mesh of `mesh_source`, a writer not yet committed: HDF5 copies its stored
  // (deflated) arrays as they are instead of deflating the mesh again (the restart state beside
  // the results of a large model). std::logic_error if `mesh_source` is committed.
  FieldSeriesWriter(const std::string& h5_path, const FieldSeriesWriter& mesh_source);
  // Without commit(), removes both temporaries: a failed run leaves nothing.
  ~FieldSeriesWriter();
  FieldSeriesWriter(const FieldSeriesWriter&) = delete;
  FieldSeriesWriter& operator=(const FieldSeriesWriter&) = delete;

  // One output date. Node fields have one tuple per mesh node, cell fields one per written cell
  // (cell_count()). `date_iso` must be an ISO 8601 date, not used by an earlier step.
  void add_step(const std::string& date_iso, double time_seconds, std::span<const Field> node_fields,
                std::span<const Field> cell_fields = {});
  // Appends a cell field to the step added last, as if add_step had been given it after its cell
  // fields (the same file): a large output writes its fields one at a time, each gathered only then.
  void add_cell_field(const Field& field);
  // Closes the HDF5 file, writes the XDMF index and renames both into place.
  void commit();

  std::size_t cell_count() const;
  const std::string& h5_path() const;
  const std::string& xdmf_path() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct FieldStep {
  std::string date;  // as given to add_step
  double time = 0;   // seconds
};

class FieldSeriesReader {
public:
  // Opens a file written by FieldSeriesWriter (either HDF5 flavour); InputError if it is missing
  // or not such a file.
  explicit FieldSeriesReader(const std::string& h5_path);
  ~FieldSeriesReader();
  FieldSeriesReader(const FieldSeriesReader&) = delete;
  FieldSeriesReader& operator=(const FieldSeriesReader&) = delete;

  const std::string& path() const;
  const std::vector<FieldStep>& steps() const;
  // Index of the step with this date; InputError "r.h5: no step 1964-01-01 (steps: ...)" if none.
  std::size_t step(std::string_view date) const;

  std::size_t num_nodes() const;
  std::size_t num_cells() const;
  std::vector<std::uint64_t> node_tags() const;
  // Every coordinate finite; InputError "r.h5: /mesh/coordinates: node 7 has x = nan (expected
  // finite coordinates)" otherwise.
  std::vector<Point3> coordinates() const;
  std::vector<ElementType> cell_types() const;  // in output order
  // Connectivity (0-based node indices, nodes_per_element(type) per cell); empty if not written.
  // Every index below num_nodes(); InputError "r.h5: /mesh/tetrahedra: cell 3 has node index
  // 4294967295 (expected below the 1234 nodes of /mesh/coordinates)" otherwise. So a damaged or
  // hand-made file is refused with one line before anything indexes with it.
  std::vector<std::uint32_t> cells(ElementType type) const;
  std::vector<std::uint64_t> cell_tags() const;
  std::vector<std::int32_t> materials() const;

  std::vector<std::string> node_field_names(std::size_t step) const;
  std::vector<std::string> cell_field_names(std::size_t step) const;
  // InputError "r.h5: no node field 'dp' at step 1964-01-01" if absent.
  Field node_field(std::size_t step, const std::string& name) const;
  Field cell_field(std::size_t step, const std::string& name) const;
  // InputError unless node_field / cell_field(step, name) would find a readable dataset of the right
  // length; reads no values (for checking a whole series before a long run).
  void check_field(std::size_t step, const std::string& name, bool cells) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ugs
