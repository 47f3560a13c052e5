// VTK XML UnstructuredGrid writer. Arrays go in one appended raw section, each compressed the way
// vtkZLibDataCompressor expects: a UInt64 header [blocks, block size, last block size,
// compressed sizes...] followed by the zlib streams of each block.
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>

#include <fmt/format.h>

#include "ugs/formats/vtu.hpp"
#include "xml_escape.hpp"

namespace ugs {
namespace {

constexpr std::size_t kBlockSize = 1 << 20;
constexpr int kZlibLevel = 1;  // speed over size: coordinates and results compress poorly anyway

constexpr const char* kByteOrder = std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";

std::uint8_t vtk_cell_type(ElementType t) {
  switch (t) {
    case ElementType::Point: return 1;        // VTK_VERTEX
    case ElementType::Line: return 3;         // VTK_LINE
    case ElementType::Triangle: return 5;     // VTK_TRIANGLE
    case ElementType::Tetrahedron: return 10; // VTK_TETRA
    case ElementType::Prism: return 13;       // VTK_WEDGE: same node order as Gmsh's prism
  }
  return 0;
}

using detail::xml_escape;

// One compressed array of the appended section.
std::string compress_array(const void* data, std::size_t bytes) {
  const auto* src = static_cast<const Bytef*>(data);
  const std::uint64_t nblocks = bytes == 0 ? 0 : (bytes + kBlockSize - 1) / kBlockSize;
  const std::uint64_t last = bytes == 0 ? 0 : bytes - (nblocks - 1) * kBlockSize;
  std::vector<std::uint64_t> header{nblocks, kBlockSize, last == kBlockSize ? 0 : last};
  std::string body;
  std::vector<Bytef> tmp(compressBound(kBlockSize));
  for (std::uint64_t b = 0; b < nblocks; ++b) {
    const uLong n = static_cast<uLong>(std::min<std::size_t>(kBlockSize, bytes - b * kBlockSize));
    uLongf out = static_cast<uLongf>(tmp.size());
    if (compress2(tmp.data(), &out, src + b * kBlockSize, n, kZlibLevel) != Z_OK)
      throw ComputeError("vtu: zlib compression failed");
    header.push_back(out);
    body.append(reinterpret_cast<const char*>(tmp.data()), out);
  }
  std::string r(reinterpret_cast<const char*>(header.data()), header.size() * sizeof(std::uint64_t));
  return r + body;
}

class VtuWriter {
public:
  VtuWriter(const Mesh& mesh, OutputFile& out, std::vector<ElementType> types)
      : mesh_(mesh), out_(out), types_(std::move(types)) {}

  void write(std::span<const Field> point_fields, std::span<const Field> cell_fields) {
    const std::size_t ncells = output_cell_count(mesh_, types_);
    check_fields(point_fields, mesh_.num_nodes(), "vtu point");
    check_fields(cell_fields, ncells, "vtu cell");
    for (const Field& f : point_fields)
      if (f.name == "node_tag") throw std::invalid_argument("vtu point field 'node_tag' is reserved");
    for (const Field& f : cell_fields)
      if (f.name == "material" || f.name == "element_tag")
        throw std::invalid_argument(fmt::format("vtu cell field '{}' is reserved", f.name));

    xml_ += fmt::format(
        "<?xml version=\"1.0\"?>\n"
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"{}\" header_type=\"UInt64\" "
        "compressor=\"vtkZLibDataCompressor\">\n"
        "  <UnstructuredGrid>\n"
        "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
        kByteOrder, mesh_.num_nodes(), ncells);

    xml_ += "      <PointData>\n";
    add_array("node_tag", "Int64", 1, mesh_.node_tags.data(), mesh_.node_tags.size() * sizeof(std::uint64_t));
    for (const Field& f : point_fields) add_field(f);
    xml_ += "      </PointData>\n";

    xml_ += "      <CellData>\n";
    write_cell_tags(ncells);
    for (const Field& f : cell_fields) add_field(f);
    xml_ += "      </CellData>\n";

    xml_ += "      <Points>\n";
    static_assert(sizeof(Point3) == 3 * sizeof(double));
    add_array("Points", "Float64", 3, mesh_.nodes.data(), mesh_.nodes.size() * sizeof(Point3));
    xml_ += "      </Points>\n";

    xml_ += "      <Cells>\n";
    write_cells(ncells);
    xml_ += "      </Cells>\n";

    xml_ +=
        "    </Piece>\n"
        "  </UnstructuredGrid>\n"
        "  <AppendedData encoding=\"raw\">\n"
        "   _";
    out_.write(xml_);
    for (const std::string& a : appended_) out_.write(a);
    out_.write("\n  </AppendedData>\n</VTKFile>\n");
  }

private:
  void add_array(std::string_view name, std::string_view type, int components, const void* data,
                 std::size_t bytes) {
    xml_ += fmt::format(
        "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" "
        "offset=\"{}\"/>\n",
        type, xml_escape(name), components, offset_);
    appended_.push_back(compress_array(data, bytes));
    offset_ += appended_.back().size();
  }

  void add_field(const Field& f) {
    add_array(f.name, "Float64", f.components, f.values.data(), f.values.size() * sizeof(double));
  }

  void write_cell_tags(std::size_t ncells) {
    std::vector<std::int32_t> material;
    std::vector<std::uint64_t> tags;
    material.reserve(ncells);
    tags.reserve(ncells);
    const ElementBlock* last = nullptr;
    std::int32_t physical = 0;
    for_each_output_cell(mesh_, types_, [&](const ElementBlock& b, std::size_t i) {
      if (&b != last) {
        last = &b;
        const Entity* e = mesh_.find_entity(b.entity_dim, b.entity_tag);
        physical = e && !e->physicals.empty() ? e->physicals.front() : 0;
      }
      material.push_back(physical);
      tags.push_back(b.tags[i]);
    });
    add_array("material", "Int32", 1, material.data(), material.size() * sizeof(std::int32_t));
    add_array("element_tag", "Int64", 1, tags.data(), tags.size() * sizeof(std::uint64_t));
  }

  void write_cells(std::size_t ncells) {
    std::vector<std::int64_t> connectivity, offsets;
    std::vector<std::uint8_t> types;
    std::size_t nconn = 0;
    for (ElementType t : types_) nconn += mesh_.count(t) * nodes_per_element(t);
    connectivity.reserve(nconn);
    offsets.reserve(ncells);
    types.reserve(ncells);
    for_each_output_cell(mesh_, types_, [&](const ElementBlock& b, std::size_t i) {
      for (std::uint32_t n : b.element(i)) connectivity.push_back(n);
      offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
      types.push_back(vtk_cell_type(b.type));
    });
    add_array("connectivity", "Int64", 1, connectivity.data(), connectivity.size() * sizeof(std::int64_t));
    add_array("offsets", "Int64", 1, offsets.data(), offsets.size() * sizeof(std::int64_t));
    add_array("types", "UInt8", 1, types.data(), types.size());
  }

  const Mesh& mesh_;
  OutputFile& out_;
  std::vector<ElementType> types_;
  std::string xml_;
  std::vector<std::string> appended_;
  std::uint64_t offset_ = 0;
};

}  // namespace

void write_vtu(const Mesh& mesh, OutputFile& out, std::span<const Field> point_fields,
               std::span<const Field> cell_fields, const VtuOptions& options) {
  std::vector<ElementType> types = options.cell_types.empty() ? default_output_cell_types(mesh) : options.cell_types;
  VtuWriter(mesh, out, std::move(types)).write(point_fields, cell_fields);
}

void write_vtu(const Mesh& mesh, const std::string& path, std::span<const Field> point_fields,
               std::span<const Field> cell_fields, const VtuOptions& options) {
  OutputFile out(path);
  write_vtu(mesh, out, point_fields, cell_fields, options);
  out.commit();
}

PvdWriter::PvdWriter(std::string path) : path_(std::move(path)) {}

void PvdWriter::add(double time, std::string vtu_file) { entries_.emplace_back(time, std::move(vtu_file)); }

void PvdWriter::commit() {
  std::string xml = fmt::format(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"{}\" header_type=\"UInt64\">\n"
      "  <Collection>\n",
      kByteOrder);
  for (const auto& [time, file] : entries_)
    xml += fmt::format("    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", time, xml_escape(file));
  xml += "  </Collection>\n</VTKFile>\n";
  OutputFile out(path_);
  out.write(xml);
  out.commit();
}

}  // namespace ugs
