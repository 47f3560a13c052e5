// HDF5 + XDMF 3 field series (layout in fields.hpp). Compiled once per HDF5 flavour; only the
// serial API with default property lists is used, which the OpenMPI build supports as well.
// Output is deterministic: object timestamps are off and everything is written in a fixed order.
#include "ugs/formats/fields.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hdf5_util.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/deflate_probe.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/io.hpp"
#include "xml_escape.hpp"

namespace ugs {
namespace {

constexpr const char* kFormatTag = "ugs-fields 1";
constexpr hsize_t kChunkValues = 1 << 16;  // 512 KiB chunks of doubles
constexpr unsigned kDeflateLevel = 1;      // speed over size
// A dataset claiming more bytes than zlib could expand its storage to is damaged (zlib's ratio
// is at most about 1032:1); refuse it before allocating.
constexpr hsize_t kMaxExpansion = 1100;

const char* dataset_name(ElementType t) {
  switch (t) {
    case ElementType::Triangle: return "triangles";
    case ElementType::Tetrahedron: return "tetrahedra";
    case ElementType::Prism: return "prisms";
    default: throw std::invalid_argument(fmt::format("field series: cannot write {} cells", element_name(t)));
  }
}

// A number type HDF5 converts safely: an integer of 1, 2, 4 or 8 bytes using all its bits, or an
// IEEE float of 4 or 8 bytes. A damaged type message (a 1024-bit integer) overruns HDF5's own
// conversion buffers (found by fuzzing, tests/fuzz).
bool plain_number_type(hid_t t) {
  const std::size_t size = H5Tget_size(t);
  switch (H5Tget_class(t)) {
    case H5T_INTEGER:
      return (size == 1 || size == 2 || size == 4 || size == 8) && H5Tget_precision(t) == 8 * size && H5Tget_offset(t) == 0;
    case H5T_FLOAT:
      for (hid_t ieee : {H5T_IEEE_F64LE, H5T_IEEE_F64BE, H5T_IEEE_F32LE, H5T_IEEE_F32BE})
        if (H5Tequal(t, ieee) > 0) return true;
      return false;
    default: return false;
  }
}

std::optional<ElementType> type_of_dataset(std::string_view name) {
  for (ElementType t : {ElementType::Triangle, ElementType::Tetrahedron, ElementType::Prism})
    if (name == dataset_name(t)) return t;
  return std::nullopt;
}

const char* xdmf_topology(ElementType t) {
  switch (t) {
    case ElementType::Triangle: return "Triangle";
    case ElementType::Tetrahedron: return "Tetrahedron";
    default: return "Wedge";  // interface prism: same node order as XDMF's wedge
  }
}

// Cell type codes of XDMF's "Mixed" topology.
std::uint32_t xdmf_mixed_code(ElementType t) {
  switch (t) {
    case ElementType::Triangle: return 4;
    case ElementType::Tetrahedron: return 6;
    default: return 8;
  }
}

const char* xdmf_attribute_type(int components) {
  switch (components) {
    case 1: return "Scalar";
    case 3: return "Vector";
    case 6: return "Tensor6";
    case 9: return "Tensor";
    default: return "Matrix";
  }
}

using detail::xml_escape;

std::string xdmf_path_for(const std::string& h5) {
  for (std::string_view ext : {".h5", ".hdf5"})
    if (h5.ends_with(ext)) return h5.substr(0, h5.size() - ext.size()) + ".xdmf";
  return h5 + ".xdmf";
}

std::string base_name(const std::string& p) {
  const auto k = p.find_last_of('/');
  return k == std::string::npos ? p : p.substr(k + 1);
}

std::string step_group(std::size_t index) { return fmt::format("{:06}", index); }

// Whether every byte is zero (a double's +0.0; -0.0 is written).
bool all_zero_bytes(const unsigned char* p, std::size_t n) {
  static constexpr unsigned char kZeros[4096] = {};
  for (std::size_t k = 0; k < n; k += sizeof kZeros)
    if (std::memcmp(p + k, kZeros, std::min(n - k, sizeof kZeros)) != 0) return false;
  return true;
}

}  // namespace

// ---- writer -----------------------------------------------------------------------------------

struct FieldSeriesWriter::Impl {
  struct FieldInfo {
    std::string name;
    int components;
  };
  struct Step {
    std::string date;
    double time;
    std::string group;
    std::vector<FieldInfo> node, cell;
  };

  Impl(const std::string& path, const Mesh& mesh, std::vector<ElementType> cell_types)
      : h5_path(path), xdmf_path(xdmf_path_for(path)), h5_name(base_name(path)), h5_out(path),
        types(std::move(cell_types)) {
    create_file();
    write_mesh(mesh);
    steps_group = group(file.get(), "steps");
  }

  Impl(const std::string& path, const Impl& source)
      : h5_path(path), xdmf_path(xdmf_path_for(path)), h5_name(base_name(path)), h5_out(path), types(source.types),
        num_nodes(source.num_nodes), num_cells(source.num_cells), mixed_length(source.mixed_length),
        topology_types(source.topology_types) {
    if (source.committed) throw std::logic_error("field series: the mesh source is committed");
    create_file();
    h5::Id lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
    check(lcpl.valid() && H5Ocopy(source.file.get(), "mesh", file.get(), "mesh", H5P_DEFAULT, lcpl.get()) >= 0,
          fmt::format("cannot copy the mesh of {}", source.h5_path));
    steps_group = group(file.get(), "steps");
  }

  void create_file() {
    gcpl = h5::Id(H5Pcreate(H5P_GROUP_CREATE), H5Pclose);
    check(gcpl.valid() && H5Pset_obj_track_times(gcpl.get(), false) >= 0, "cannot set up group properties");
    h5::Id fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
    check(fcpl.valid() && H5Pset_obj_track_times(fcpl.get(), false) >= 0, "cannot set up file properties");
    file = h5::Id(H5Fcreate(h5_out.temp_path().c_str(), H5F_ACC_TRUNC, fcpl.get(), H5P_DEFAULT), H5Fclose);
    check(file.valid(), "cannot create HDF5 file");
    string_attribute(file.get(), "ugs_format", kFormatTag);
  }

  [[noreturn]] void fail(const std::string& what) const {
    const std::string detail = h5::last_error();
    throw ComputeError(fmt::format("{}: {}{}{}", h5_path, what, detail.empty() ? "" : ": ", detail));
  }
  void check(bool ok, const std::string& what) const {
    if (!ok) fail(what);
  }

  h5::Id group(hid_t loc, const std::string& name) {
    h5::Id g(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT), H5Gclose);
    check(g.valid(), fmt::format("cannot create group '{}'", name));
    return g;
  }

  // A chunked dataset of `rows` values, or rows x cols when cols > 0; shuffled and deflated where
  // that shrinks it well (deflate_probe.hpp): full-precision stresses shrink by ~20 % for most of
  // the writing time (thesis-scale output date: 16 s of 19 s in zlib).
  //
  // A step's field (`sparse`) leaves out the chunks whose values are all +0.0: HDF5 reads a chunk
  // that was never written as its fill value, zero, and the state's strain and stress changes are
  // zero outside the hypo-plastic cells (a linear model's are zero everywhere). Mesh arrays are
  // always stored whole: the reader bounds every field by the mesh's counts before allocating.
  void dataset(hid_t loc, const std::string& name, hid_t file_type, hid_t mem_type, const void* data,
               hsize_t rows, hsize_t cols = 0, bool sparse = false) {
    const int rank = cols ? 2 : 1;
    const hsize_t dims[2] = {rows, cols};
    h5::Id space(H5Screate_simple(rank, dims, nullptr), H5Sclose);
    h5::Id dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    check(space.valid() && dcpl.valid() && H5Pset_obj_track_times(dcpl.get(), false) >= 0,
          fmt::format("cannot set up dataset '{}'", name));
    if (rows > 0) {
      const hsize_t chunk[2] = {std::clamp<hsize_t>(kChunkValues / std::max<hsize_t>(cols, 1), 1, rows), cols};
      check(H5Pset_chunk(dcpl.get(), rank, chunk) >= 0, fmt::format("cannot set up dataset '{}'", name));
      const std::size_t size = H5Tget_size(mem_type);
      if (H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0 &&
          deflate_pays(data, rows * std::max<hsize_t>(cols, 1) * size, size, {kDeflateLevel}))
        check(H5Pset_shuffle(dcpl.get()) >= 0 && H5Pset_deflate(dcpl.get(), kDeflateLevel) >= 0,
              fmt::format("cannot set up dataset '{}'", name));
    }
    h5::Id ds(H5Dcreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT), H5Dclose);
    check(ds.valid(), fmt::format("cannot create dataset '{}'", name));
    if (rows == 0) return;
    if (!sparse) {
      check(H5Dwrite(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0,
            fmt::format("cannot write dataset '{}'", name));
      return;
    }
    const hsize_t chunk_rows = std::clamp<hsize_t>(kChunkValues / std::max<hsize_t>(cols, 1), 1, rows);
    const std::size_t row_bytes = std::max<hsize_t>(cols, 1) * H5Tget_size(mem_type);
    for (hsize_t r0 = 0; r0 < rows; r0 += chunk_rows) {
      const hsize_t n = std::min(chunk_rows, rows - r0);
      const auto* p = static_cast<const unsigned char*>(data) + r0 * row_bytes;
      if (all_zero_bytes(p, n * row_bytes)) continue;
      const hsize_t start[2] = {r0, 0}, count[2] = {n, cols};
      h5::Id file_space(H5Dget_space(ds.get()), H5Sclose);
      h5::Id mem_space(H5Screate_simple(rank, count, nullptr), H5Sclose);
      check(file_space.valid() && mem_space.valid() &&
                H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr) >= 0 &&
                H5Dwrite(ds.get(), mem_type, mem_space.get(), file_space.get(), H5P_DEFAULT, p) >= 0,
            fmt::format("cannot write dataset '{}'", name));
    }
  }

  void string_attribute(hid_t loc, const char* name, const std::string& value) {
    h5::Id type(H5Tcopy(H5T_C_S1), H5Tclose);
    check(type.valid() && H5Tset_size(type.get(), value.size() + 1) >= 0 &&
              H5Tset_strpad(type.get(), H5T_STR_NULLTERM) >= 0,
          fmt::format("cannot set up attribute '{}'", name));
    h5::Id space(H5Screate(H5S_SCALAR), H5Sclose);
    h5::Id attr(H5Acreate2(loc, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    check(attr.valid() && H5Awrite(attr.get(), type.get(), value.c_str()) >= 0,
          fmt::format("cannot write attribute '{}'", name));
  }

  void double_attribute(hid_t loc, const char* name, double value) {
    h5::Id space(H5Screate(H5S_SCALAR), H5Sclose);
    h5::Id attr(H5Acreate2(loc, name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    check(attr.valid() && H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, &value) >= 0,
          fmt::format("cannot write attribute '{}'", name));
  }

  void write_mesh(const Mesh& mesh) {
    num_nodes = mesh.num_nodes();
    num_cells = output_cell_count(mesh, types);
    h5::Id g = group(file.get(), "mesh");
    static_assert(sizeof(Point3) == 3 * sizeof(double));
    dataset(g.get(), "coordinates", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, mesh.nodes.data(), num_nodes, 3);
    dataset(g.get(), "node_tags", H5T_STD_U64LE, H5T_NATIVE_UINT64, mesh.node_tags.data(), num_nodes);

    std::vector<std::string> names;
    std::vector<std::uint32_t> mixed;
    // XDMF's "Mixed" topology only when cells of several types are written: a volume without
    // interface prisms is indexed by its tetrahedra (no copy of them, 5 values a cell, to deflate).
    for (ElementType t : types)
      if (mesh.count(t) > 0) topology_types.push_back(t);
    if (topology_types.empty()) topology_types.push_back(types.front());
    const bool mixed_topology = topology_types.size() > 1;
    for (ElementType t : types) {
      std::vector<std::uint32_t> conn;
      for (const ElementBlock& b : mesh.blocks)
        if (b.type == t) conn.insert(conn.end(), b.nodes.begin(), b.nodes.end());
      const hsize_t npe = nodes_per_element(t), n = conn.size() / npe;
      dataset(g.get(), dataset_name(t), H5T_STD_U32LE, H5T_NATIVE_UINT32, conn.data(), n, npe);
      names.push_back(dataset_name(t));
      if (mixed_topology)
        for (hsize_t i = 0; i < n; ++i) {
          mixed.push_back(xdmf_mixed_code(t));
          mixed.insert(mixed.end(), conn.begin() + i * npe, conn.begin() + (i + 1) * npe);
        }
    }
    string_attribute(g.get(), "cell_types", fmt::format("{}", fmt::join(names, ",")));
    if (mixed_topology) {
      dataset(g.get(), "mixed_topology", H5T_STD_U32LE, H5T_NATIVE_UINT32, mixed.data(), mixed.size());
      mixed_length = mixed.size();
    }

    std::vector<std::uint64_t> tags;
    std::vector<std::int32_t> material;
    tags.reserve(num_cells);
    material.reserve(num_cells);
    for_each_output_cell(mesh, types, [&](const ElementBlock& b, std::size_t i) {
      const Entity* e = mesh.find_entity(b.entity_dim, b.entity_tag);
      tags.push_back(b.tags[i]);
      material.push_back(e && !e->physicals.empty() ? e->physicals.front() : 0);
    });
    dataset(g.get(), "cell_tags", H5T_STD_U64LE, H5T_NATIVE_UINT64, tags.data(), num_cells);
    dataset(g.get(), "material", H5T_STD_I32LE, H5T_NATIVE_INT32, material.data(), num_cells);
  }

  void add_step(const std::string& date, double time, std::span<const Field> node_fields,
                std::span<const Field> cell_fields) {
    if (committed) throw std::logic_error("field series: add_step after commit");
    if (!parse_iso_date(date)) throw std::invalid_argument(fmt::format("field series: '{}' is not an ISO 8601 date", date));
    for (const Step& s : steps)
      if (s.date == date) throw std::invalid_argument(fmt::format("field series: step {} given twice", date));
    check_fields(node_fields, num_nodes, "node");
    check_fields(cell_fields, num_cells, "cell");

    Step step{date, time, step_group(steps.size()), {}, {}};
    h5::Id g = group(steps_group.get(), step.group);
    string_attribute(g.get(), "date", date);
    double_attribute(g.get(), "time", time);
    for (auto [fields, kind, infos] : {std::tuple{node_fields, "node", &step.node}, std::tuple{cell_fields, "cell", &step.cell}}) {
      h5::Id sub = group(g.get(), kind);
      for (const Field& f : fields) {
        dataset(sub.get(), f.name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, f.values.data(), f.count(),
                f.components == 1 ? 0 : f.components, true);
        infos->push_back({f.name, f.components});
      }
    }
    steps.push_back(std::move(step));
  }

  void add_cell_field(const Field& f) {
    if (committed) throw std::logic_error("field series: add_cell_field after commit");
    if (steps.empty()) throw std::logic_error("field series: add_cell_field before add_step");
    check_fields(std::span<const Field>(&f, 1), num_cells, "cell");
    Step& step = steps.back();
    for (const FieldInfo& i : step.cell)
      if (i.name == f.name) throw std::invalid_argument(fmt::format("field series: cell field {} given twice", f.name));
    const std::string path = step.group + "/cell";
    h5::Id sub(H5Gopen2(steps_group.get(), path.c_str(), H5P_DEFAULT), H5Gclose);
    check(sub.valid(), fmt::format("cannot open group '{}'", path));
    dataset(sub.get(), f.name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, f.values.data(), f.count(),
            f.components == 1 ? 0 : f.components, true);
    step.cell.push_back({f.name, f.components});
  }

  std::string data_item(std::string_view dims, std::string_view number_type, int precision, std::string_view h5path) const {
    return fmt::format("<DataItem Dimensions=\"{}\" NumberType=\"{}\" Precision=\"{}\" Format=\"HDF\">{}:{}</DataItem>",
                       dims, number_type, precision, xml_escape(h5_name), xml_escape(h5path));
  }

  void xdmf_grid(std::string& x, const std::string& name, const Step* step, std::string_view in) const {
    x += fmt::format("{}<Grid Name=\"{}\" GridType=\"Uniform\">\n", in, xml_escape(name));
    if (step) x += fmt::format("{}  <Time Value=\"{}\"/>\n", in, step->time);
    if (topology_types.size() == 1) {
      const ElementType t = topology_types[0];
      const int npe = nodes_per_element(t);
      x += fmt::format("{}  <Topology TopologyType=\"{}\" NumberOfElements=\"{}\" NodesPerElement=\"{}\">\n", in,
                       xdmf_topology(t), num_cells, npe);
      x += fmt::format("{}    {}\n", in, data_item(fmt::format("{} {}", num_cells, npe), "UInt", 4,
                                                   fmt::format("/mesh/{}", dataset_name(t))));
    } else {
      x += fmt::format("{}  <Topology TopologyType=\"Mixed\" NumberOfElements=\"{}\">\n", in, num_cells);
      x += fmt::format("{}    {}\n", in, data_item(fmt::format("{}", mixed_length), "UInt", 4, "/mesh/mixed_topology"));
    }
    x += fmt::format("{}  </Topology>\n", in);
    x += fmt::format("{}  <Geometry GeometryType=\"XYZ\">\n", in);
    x += fmt::format("{}    {}\n", in, data_item(fmt::format("{} 3", num_nodes), "Float", 8, "/mesh/coordinates"));
    x += fmt::format("{}  </Geometry>\n", in);
    auto attribute = [&](const std::string& aname, const char* center, int components, std::size_t count,
                         std::string_view number_type, int precision, const std::string& h5path) {
      const std::string dims = components == 1 ? fmt::format("{}", count) : fmt::format("{} {}", count, components);
      x += fmt::format("{}  <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"{}\">\n", in, xml_escape(aname),
                       xdmf_attribute_type(components), center);
      x += fmt::format("{}    {}\n", in, data_item(dims, number_type, precision, h5path));
      x += fmt::format("{}  </Attribute>\n", in);
    };
    // node_tags are uint64 in the file; declared Int 8 because VTK's XDMF reader lacks UInt 8.
    attribute("node_tag", "Node", 1, num_nodes, "Int", 8, "/mesh/node_tags");
    attribute("material", "Cell", 1, num_cells, "Int", 4, "/mesh/material");
    if (step) {
      for (const FieldInfo& f : step->node)
        attribute(f.name, "Node", f.components, num_nodes, "Float", 8, fmt::format("/steps/{}/node/{}", step->group, f.name));
      for (const FieldInfo& f : step->cell)
        attribute(f.name, "Cell", f.components, num_cells, "Float", 8, fmt::format("/steps/{}/cell/{}", step->group, f.name));
    }
    x += fmt::format("{}</Grid>\n", in);
  }

  std::string xdmf() const {
    std::string x = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n";
    if (steps.empty()) {
      xdmf_grid(x, "mesh", nullptr, "    ");
    } else {
      std::string name = h5_name.substr(0, h5_name.find_last_of('.'));
      x += fmt::format("    <Grid Name=\"{}\" GridType=\"Collection\" CollectionType=\"Temporal\">\n", xml_escape(name));
      for (const Step& s : steps) xdmf_grid(x, s.date, &s, "      ");
      x += "    </Grid>\n";
    }
    x += "  </Domain>\n</Xdmf>\n";
    return x;
  }

  void commit() {
    if (committed) return;
    steps_group.reset();
    check(file.reset(), "cannot close HDF5 file");
    OutputFile index(xdmf_path);
    index.write(xdmf());
    h5_out.commit();  // the data first: the index refers to it
    index.commit();
    committed = true;
  }

  std::string h5_path, xdmf_path, h5_name;
  OutputFile h5_out;  // owns the temporary; declared before the HDF5 ids so they close first
  h5::Id gcpl, file, steps_group;
  std::vector<ElementType> types;
  std::size_t num_nodes = 0, num_cells = 0, mixed_length = 0;
  std::vector<ElementType> topology_types;  // the written types that have cells (XDMF topology)
  std::vector<Step> steps;
  bool committed = false;
};

namespace {
void check_h5_path(const std::string& path) {
  if (path.empty() || path == "-") throw InputError(path, "HDF5 output needs a file name, not stdout");
}

std::vector<ElementType> checked_types(const std::string& path, const Mesh& mesh, const FieldSeriesOptions& options) {
  check_h5_path(path);
  std::vector<ElementType> types = options.cell_types.empty() ? default_output_cell_types(mesh) : options.cell_types;
  for (std::size_t i = 0; i < types.size(); ++i) {
    dataset_name(types[i]);  // throws for types we cannot write
    if (std::find(types.begin(), types.begin() + i, types[i]) != types.begin() + i)
      throw std::invalid_argument("field series: cell type given twice");
  }
  if (types.empty()) throw std::invalid_argument("field series: no cell types");
  return types;
}
}  // namespace

FieldSeriesWriter::FieldSeriesWriter(const std::string& h5_path, const Mesh& mesh, const FieldSeriesOptions& options) {
  std::vector<ElementType> types = checked_types(h5_path, mesh, options);
  h5::QuietErrors quiet;
  impl_ = std::make_unique<Impl>(h5_path, mesh, std::move(types));
}

FieldSeriesWriter::FieldSeriesWriter(const std::string& h5_path, const FieldSeriesWriter& mesh_source) {
  check_h5_path(h5_path);
  h5::QuietErrors quiet;
  impl_ = std::make_unique<Impl>(h5_path, *mesh_source.impl_);
}

FieldSeriesWriter::~FieldSeriesWriter() {
  h5::QuietErrors quiet;
  impl_.reset();
}

void FieldSeriesWriter::add_step(const std::string& date_iso, double time_seconds, std::span<const Field> node_fields,
                                 std::span<const Field> cell_fields) {
  h5::QuietErrors quiet;
  impl_->add_step(date_iso, time_seconds, node_fields, cell_fields);
}

void FieldSeriesWriter::add_cell_field(const Field& field) {
  h5::QuietErrors quiet;
  impl_->add_cell_field(field);
}

void FieldSeriesWriter::commit() {
  h5::QuietErrors quiet;
  impl_->commit();
}

std::size_t FieldSeriesWriter::cell_count() const { return impl_->num_cells; }
const std::string& FieldSeriesWriter::h5_path() const { return impl_->h5_path; }
const std::string& FieldSeriesWriter::xdmf_path() const { return impl_->xdmf_path; }

// ---- reader -----------------------------------------------------------------------------------

struct FieldSeriesReader::Impl {
  explicit Impl(const std::string& p) : path(p) {
    if (std::error_code ec; std::filesystem::is_directory(path, ec))
      throw InputError(path, "is a directory (expected an HDF5 file)");
    if (std::FILE* f = std::fopen(path.c_str(), "rb")) std::fclose(f);
    else throw InputError(path, fmt::format("cannot open: {}", std::strerror(errno)));
    if (H5Fis_hdf5(path.c_str()) <= 0) fail("not an HDF5 file");
    file = h5::Id(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    if (!file.valid()) fail("cannot open HDF5 file");
    if (H5Aexists(file.get(), "ugs_format") <= 0) fail("not a field series written by ugs (no ugs_format attribute)");
    const std::string format = string_attribute(file.get(), "/", "ugs_format");
    if (format != kFormatTag) fail(fmt::format("unsupported format '{}' (this build reads '{}')", format, kFormatTag));

    const auto coords = dims("/mesh/coordinates");
    if (coords.size() != 2 || coords[1] != 3) fail("/mesh/coordinates is not a nodes x 3 array");
    num_nodes = coords[0];
    if (dims("/mesh/node_tags") != std::vector<hsize_t>{num_nodes}) fail("/mesh/node_tags does not match the coordinates");

    h5::Id mesh(H5Gopen2(file.get(), "/mesh", H5P_DEFAULT), H5Gclose);
    if (!mesh.valid()) fail("no /mesh group");
    const std::string type_list = string_attribute(mesh.get(), "/mesh", "cell_types");
    std::string_view list = type_list;
    std::size_t total = 0;
    while (!list.empty()) {
      const std::string_view name = list.substr(0, list.find(','));
      list.remove_prefix(std::min(list.size(), name.size() + 1));
      const auto t = type_of_dataset(name);
      if (!t) fail(fmt::format("/mesh: unknown cell type '{}'", name));
      const auto d = dims(fmt::format("/mesh/{}", name));
      if (d.size() != 2 || d[1] != static_cast<hsize_t>(nodes_per_element(*t)))
        fail(fmt::format("/mesh/{} is not a cells x {} array", name, nodes_per_element(*t)));
      types.push_back(*t);
      total += d[0];
    }
    num_cells = total;
    for (const char* name : {"/mesh/cell_tags", "/mesh/material"})
      if (dims(name) != std::vector<hsize_t>{num_cells}) fail(fmt::format("{} does not match the cells", name));
    check_stored("/mesh/coordinates");
    check_stored("/mesh/cell_tags");

    h5::Id steps_group(H5Gopen2(file.get(), "/steps", H5P_DEFAULT), H5Gclose);
    if (!steps_group.valid()) fail("no /steps group");
    for (const std::string& g : link_names(steps_group.get(), "/steps")) {
      h5::Id sg(H5Gopen2(steps_group.get(), g.c_str(), H5P_DEFAULT), H5Gclose);
      if (!sg.valid()) fail(fmt::format("/steps/{} is not a group", g));
      const std::string where = "/steps/" + g;
      steps.push_back({string_attribute(sg.get(), where, "date"), double_attribute(sg.get(), where, "time")});
      groups.push_back(g);
    }
  }

  [[noreturn]] void fail(const std::string& what) const {
    const std::string detail = h5::last_error();
    throw InputError(path, detail.empty() ? what : fmt::format("{}: {}", what, detail));
  }

  std::vector<hsize_t> dims(const std::string& name) const {
    h5::Id ds(H5Dopen2(file.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!ds.valid()) fail(fmt::format("no dataset {}", name));
    return dims(ds.get(), name);
  }
  std::vector<hsize_t> dims(hid_t ds, const std::string& name) const {
    h5::Id space(H5Dget_space(ds), H5Sclose);
    const int rank = space.valid() ? H5Sget_simple_extent_ndims(space.get()) : -1;
    if (rank < 0 || rank > 2) fail(fmt::format("{}: not a 1- or 2-dimensional array", name));
    std::vector<hsize_t> d(rank);
    H5Sget_simple_extent_dims(space.get(), d.data(), nullptr);
    return d;
  }

  // A dataset claiming more values than its storage could expand to is damaged: refused before
  // anything is allocated. The mesh's arrays are checked when the file is opened, so their counts
  // bound the fields (whose chunks of zeros are not stored).
  void check_stored(hid_t ds, const std::string& name, hsize_t count) const {
    h5::Id type(H5Dget_type(ds), H5Tclose);
    const hsize_t bytes = count * (type.valid() ? H5Tget_size(type.get()) : 1);
    if (bytes > kMaxExpansion * H5Dget_storage_size(ds) + (1 << 20))
      fail(fmt::format("{} claims {} values but stores only {} bytes (damaged file?)", name, count,
                       H5Dget_storage_size(ds)));
  }
  void check_stored(const std::string& name) const {
    h5::Id ds(H5Dopen2(file.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!ds.valid()) fail(fmt::format("no dataset {}", name));
    hsize_t count = 1;
    for (hsize_t k : dims(ds.get(), name)) count *= k;
    check_stored(ds.get(), name, count);
  }

  // All values of a dataset, converted to `mem_type` by HDF5; `out_dims` receives its shape.
  // `mesh_rows` (a field's node or cell count, from the mesh's arrays, which are stored whole):
  // the rows the dataset must have, checked before anything is allocated; a field's chunks of
  // zeros are not stored (dataset() of the writer), so its size is bounded by the mesh instead of
  // by what its storage could expand to.
  template <class T>
  std::vector<T> read(const std::string& name, hid_t mem_type, std::vector<hsize_t>* out_dims = nullptr,
                      std::optional<hsize_t> mesh_rows = std::nullopt) const {
    h5::Id ds(H5Dopen2(file.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!ds.valid()) fail(fmt::format("no dataset {}", name));
    const std::vector<hsize_t> d = dims(ds.get(), name);
    hsize_t count = 1;
    for (hsize_t k : d) count *= k;
    h5::Id type(H5Dget_type(ds.get()), H5Tclose);
    if (!type.valid() || !plain_number_type(type.get()))
      fail(fmt::format("{}: not stored as plain numbers (expected integers or IEEE floats of 1 to 8 bytes)", name));
    // Chunks larger than the array (a damaged layout message) make HDF5 copy past its chunk buffer.
    h5::Id dcpl(H5Dget_create_plist(ds.get()), H5Pclose);
    if (count > 0 && dcpl.valid() && H5Pget_layout(dcpl.get()) == H5D_CHUNKED) {
      hsize_t chunk[2] = {0, 0};
      const int rank = H5Pget_chunk(dcpl.get(), 2, chunk);
      bool fits = rank == static_cast<int>(d.size());
      for (std::size_t k = 0; fits && k < d.size(); ++k) fits = chunk[k] >= 1 && chunk[k] <= d[k];
      if (!fits)
        fail(fmt::format("{}: its chunks ({}) do not fit its shape ({}) (damaged file?)", name,
                         fmt::join(std::span(chunk, static_cast<std::size_t>(std::clamp(rank, 0, 2))), " x "),
                         fmt::join(d, " x ")));
    }
    if (mesh_rows && (d.empty() || d[0] != *mesh_rows || (d.size() == 2 && d[1] > static_cast<hsize_t>(kMaxFieldComponents))))
      fail(fmt::format("{}: {} values{} (expected {} of at most {} components)", name, d.empty() ? 0 : d[0],
                       d.size() == 2 ? fmt::format(" of {} components", d[1]) : "", *mesh_rows, kMaxFieldComponents));
    if (!mesh_rows) check_stored(ds.get(), name, count);
    std::vector<T> v(count);
    if (count > 0 && H5Dread(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
      fail(fmt::format("cannot read {}", name));
    if (out_dims) *out_dims = d;
    return v;
  }

  std::string string_attribute(hid_t loc, const std::string& where, const char* name) const {
    h5::Id attr(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose);
    if (!attr.valid()) fail(fmt::format("{}: no attribute '{}'", where, name));
    h5::Id type(H5Aget_type(attr.get()), H5Tclose);
    h5::Id space(H5Aget_space(attr.get()), H5Sclose);
    if (!type.valid() || H5Tget_class(type.get()) != H5T_STRING || !space.valid() ||
        H5Sget_simple_extent_npoints(space.get()) != 1)
      fail(fmt::format("{}: attribute '{}' is not a single text", where, name));
    h5::Id mem(H5Tcopy(H5T_C_S1), H5Tclose);
    if (H5Tis_variable_str(type.get()) > 0) {
      H5Tset_size(mem.get(), H5T_VARIABLE);
      char* s = nullptr;
      if (H5Aread(attr.get(), mem.get(), &s) < 0 || !s) fail(fmt::format("{}: cannot read attribute '{}'", where, name));
      std::string r = s;
      H5free_memory(s);
      return r;
    }
    const std::size_t size = H5Tget_size(type.get());
    if (size == 0 || size > 4096) fail(fmt::format("{}: attribute '{}' has an implausible size", where, name));
    std::string buf(size, '\0');
    H5Tset_size(mem.get(), size);
    if (H5Aread(attr.get(), mem.get(), buf.data()) < 0) fail(fmt::format("{}: cannot read attribute '{}'", where, name));
    return buf.substr(0, buf.find('\0'));
  }

  double double_attribute(hid_t loc, const std::string& where, const char* name) const {
    h5::Id attr(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose);
    double v = 0;
    h5::Id type(attr.valid() ? H5Aget_type(attr.get()) : H5I_INVALID_HID, H5Tclose);
    h5::Id space(attr.valid() ? H5Aget_space(attr.get()) : H5I_INVALID_HID, H5Sclose);
    if (!type.valid() || !plain_number_type(type.get()) || !space.valid() || H5Sget_simple_extent_npoints(space.get()) != 1)
      fail(fmt::format("{}: attribute '{}' is not a single number", where, name));
    if (H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &v) < 0)
      fail(fmt::format("{}: cannot read attribute '{}'", where, name));
    return v;
  }

  // Names of the links in a group, in name order.
  std::vector<std::string> link_names(hid_t group, const std::string& where) const {
    H5G_info_t info;
    if (H5Gget_info(group, &info) < 0) fail(fmt::format("cannot list {}", where));
    std::vector<std::string> names;
    for (hsize_t i = 0; i < info.nlinks; ++i) {
      const ssize_t n = H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
      if (n < 0) fail(fmt::format("cannot list {}", where));
      std::string name(static_cast<std::size_t>(n) + 1, '\0');
      H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT);
      name.resize(static_cast<std::size_t>(n));
      names.push_back(std::move(name));
    }
    return names;
  }

  const std::string& step_date(std::size_t step) const {
    if (step >= steps.size())
      throw std::out_of_range(fmt::format("{}: step index {} of {}", path, step, steps.size()));
    return steps[step].date;
  }

  std::vector<std::string> field_names(std::size_t step, const char* kind) const {
    step_date(step);
    const std::string where = fmt::format("/steps/{}/{}", groups[step], kind);
    h5::Id g(H5Gopen2(file.get(), where.c_str(), H5P_DEFAULT), H5Gclose);
    if (!g.valid()) fail(fmt::format("no group {}", where));
    return link_names(g.get(), where);
  }

  // What field() checks before it reads: the dataset opens, holds plain numbers, one row per
  // node or cell. Metadata only, so a whole series can be checked before a long run.
  void check_field(std::size_t step, const std::string& name, const char* kind, std::size_t count) const {
    const std::string where = fmt::format("/steps/{}/{}/{}", groups.at(step), kind, name);
    h5::Id ds(H5Dopen2(file.get(), where.c_str(), H5P_DEFAULT), H5Dclose);
    if (!ds.valid()) fail(fmt::format("no dataset {}", where));
    const std::vector<hsize_t> d = dims(ds.get(), where);
    h5::Id type(H5Dget_type(ds.get()), H5Tclose);
    if (!type.valid() || !plain_number_type(type.get()))
      fail(fmt::format("{}: not stored as plain numbers (expected integers or IEEE floats of 1 to 8 bytes)", where));
    if (d.empty() || d[0] != count)
      fail(fmt::format("{}: {} values, the mesh has {} {}s", where, d.empty() ? 0 : d[0], count, kind));
  }

  Field field(std::size_t step, const std::string& name, const char* kind, std::size_t count) const {
    const std::vector<std::string> names = field_names(step, kind);
    if (std::find(names.begin(), names.end(), name) == names.end())
      throw InputError(path, fmt::format("no {} field '{}' at step {}{}{}", kind, name, steps[step].date,
                                         names.empty() ? "" : fmt::format(" ({} fields: ", kind),
                                         names.empty() ? "" : fmt::format("{})", fmt::join(names, ", "))));
    const std::string where = fmt::format("/steps/{}/{}/{}", groups[step], kind, name);
    std::vector<hsize_t> d = dims(where);
    if (d.empty() || d[0] != count)
      fail(fmt::format("{}: {} values, the mesh has {} {}s", where, d.empty() ? 0 : d[0], count, kind));
    Field f{name, 1, read<double>(where, H5T_NATIVE_DOUBLE, &d, count)};
    if (d.size() == 2) f.components = static_cast<int>(d[1]);
    return f;
  }

  std::string path;
  h5::Id file;
  std::size_t num_nodes = 0, num_cells = 0;
  std::vector<ElementType> types;
  std::vector<FieldStep> steps;
  std::vector<std::string> groups;  // HDF5 group name of each step
};

FieldSeriesReader::FieldSeriesReader(const std::string& h5_path) {
  h5::QuietErrors quiet;
  impl_ = std::make_unique<Impl>(h5_path);
}

FieldSeriesReader::~FieldSeriesReader() {
  h5::QuietErrors quiet;
  impl_.reset();
}

const std::string& FieldSeriesReader::path() const { return impl_->path; }
const std::vector<FieldStep>& FieldSeriesReader::steps() const { return impl_->steps; }
std::size_t FieldSeriesReader::num_nodes() const { return impl_->num_nodes; }
std::size_t FieldSeriesReader::num_cells() const { return impl_->num_cells; }
std::vector<ElementType> FieldSeriesReader::cell_types() const { return impl_->types; }

std::size_t FieldSeriesReader::step(std::string_view date) const {
  const auto& s = impl_->steps;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s[i].date == date) return i;
  if (s.empty()) throw InputError(impl_->path, fmt::format("no step {} (the file has no steps)", date));
  throw InputError(impl_->path, fmt::format("no step {} ({} steps, {} to {})", date, s.size(), s.front().date, s.back().date));
}

std::vector<std::uint64_t> FieldSeriesReader::node_tags() const {
  h5::QuietErrors quiet;
  return impl_->read<std::uint64_t>("/mesh/node_tags", H5T_NATIVE_UINT64);
}

std::vector<Point3> FieldSeriesReader::coordinates() const {
  h5::QuietErrors quiet;
  const std::vector<double> flat = impl_->read<double>("/mesh/coordinates", H5T_NATIVE_DOUBLE);
  static const char* kAxis[3] = {"x", "y", "z"};
  for (std::size_t i = 0; i < flat.size(); ++i)
    if (!std::isfinite(flat[i]))
      throw InputError(impl_->path, fmt::format("/mesh/coordinates: node {} has {} = {} (expected finite coordinates)", i / 3,
                                                kAxis[i % 3], flat[i]));
  std::vector<Point3> x(flat.size() / 3);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
  return x;
}

std::vector<std::uint32_t> FieldSeriesReader::cells(ElementType type) const {
  if (std::find(impl_->types.begin(), impl_->types.end(), type) == impl_->types.end()) return {};
  h5::QuietErrors quiet;
  const std::string name = dataset_name(type);
  std::vector<std::uint32_t> c = impl_->read<std::uint32_t>("/mesh/" + name, H5T_NATIVE_UINT32);
  // The shape (cells x nodes per cell) was checked when the file was opened; the values are
  // node indices that every caller indexes the coordinates and node fields with.
  const std::size_t npe = static_cast<std::size_t>(nodes_per_element(type));
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c[i] >= impl_->num_nodes)
      throw InputError(impl_->path, fmt::format("/mesh/{}: cell {} has node index {} (expected below the {} nodes of "
                                                "/mesh/coordinates)", name, i / npe, c[i], impl_->num_nodes));
  return c;
}

std::vector<std::uint64_t> FieldSeriesReader::cell_tags() const {
  h5::QuietErrors quiet;
  return impl_->read<std::uint64_t>("/mesh/cell_tags", H5T_NATIVE_UINT64);
}

std::vector<std::int32_t> FieldSeriesReader::materials() const {
  h5::QuietErrors quiet;
  return impl_->read<std::int32_t>("/mesh/material", H5T_NATIVE_INT32);
}

std::vector<std::string> FieldSeriesReader::node_field_names(std::size_t step) const {
  h5::QuietErrors quiet;
  return impl_->field_names(step, "node");
}

std::vector<std::string> FieldSeriesReader::cell_field_names(std::size_t step) const {
  h5::QuietErrors quiet;
  return impl_->field_names(step, "cell");
}

Field FieldSeriesReader::node_field(std::size_t step, const std::string& name) const {
  h5::QuietErrors quiet;
  return impl_->field(step, name, "node", impl_->num_nodes);
}

Field FieldSeriesReader::cell_field(std::size_t step, const std::string& name) const {
  h5::QuietErrors quiet;
  return impl_->field(step, name, "cell", impl_->num_cells);
}

void FieldSeriesReader::check_field(std::size_t step, const std::string& name, bool cells) const {
  h5::QuietErrors quiet;
  impl_->step_date(step);
  if (cells) impl_->check_field(step, name, "cell", impl_->num_cells);
  else impl_->check_field(step, name, "node", impl_->num_nodes);
}

}  // namespace ugs
