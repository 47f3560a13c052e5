// MSH 4.1 reader. Never seeks; every count is checked against limits and, when the input size
// is known, against the bytes left, before anything is allocated.
#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <set>
#include <unordered_map>

#include <fmt/format.h>

#include "ugs/formats/msh.hpp"

namespace ugs {
namespace {

// The largest node coordinate a mesh may hold, in metres (the Earth is 4e7 m around).
constexpr double kMaxCoordinate = 1e9;

class MshReader {
public:
  MshReader(InputStream& in, const MshLimits& limits) : in_(in), limits_(limits) {}

  Mesh read() {
    std::string line;
    bool seen_format = false, seen_nodes = false, any_line = false;
    while (in_.getline(line)) {
      if (line.empty()) continue;
      any_line = true;
      if (line[0] != '$') throw err(fmt::format("expected a section header like $Nodes, got '{}'", clip(line)));
      const std::string section = line.substr(1);
      if (!seen_format && section != "MeshFormat")
        throw err("not a Gmsh MSH file (first section must be $MeshFormat)");
      if (section == "MeshFormat") {
        read_format();
        seen_format = true;
      } else if (section == "PhysicalNames") {
        read_physical_names();
      } else if (section == "Entities") {
        read_entities();
      } else if (section == "PartitionedEntities") {
        throw err("partitioned meshes are not supported; merge the partitions in gmsh first");
      } else if (section == "Nodes") {
        read_nodes();
        seen_nodes = true;
      } else if (section == "Elements") {
        if (!seen_nodes) throw err("$Elements before $Nodes");
        read_elements();
      } else if (section == "UgsProvenance") {
        read_provenance();
      } else {
        skip_section(section);
        continue;
      }
      expect_end(section);
    }
    if (!any_line) throw InputError(in_.name(), "empty input (no mesh)");
    if (!seen_nodes) throw InputError(in_.name(), "no $Nodes section");
    finish_entities();
    return std::move(mesh_);
  }

private:
  // Errors name the line of ASCII input and the byte offset of binary input (docs/cli.md:
  // "model.msh: byte 4096: ..."), there of the offending record, not of the chunk read.
  InputError err(const std::string& msg) const { return binary_ ? in_.error_at_byte(msg) : in_.error(msg); }
  InputError err_at(std::uint64_t byte, const std::string& msg) const {
    return InputError(fmt::format("{}: byte {}", in_.name(), byte), msg);
  }

  static std::string clip(std::string_view s) {
    std::string r(s.substr(0, 40));
    for (auto& c : r)
      if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
    return s.size() > 40 ? r + "..." : r;
  }

  // --- scalar readers: ASCII tokens or raw binary ---
  template <class T>
  T ascii_int(const char* what) {
    auto tok = in_.token();
    if (tok.empty()) throw err(fmt::format("unexpected end of input while reading {}", what));
    T v{};
    auto [p, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    if (ec != std::errc() || p != tok.data() + tok.size())
      throw err(fmt::format("expected an integer for {}, got '{}'", what, clip(tok)));
    return v;
  }
  double ascii_double(const char* what) {
    auto tok = in_.token();
    if (tok.empty()) throw err(fmt::format("unexpected end of input while reading {}", what));
    double v{};
    auto [p, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    if (ec == std::errc::result_out_of_range) v = tok[0] == '-' ? -INFINITY : INFINITY;
    else if (ec != std::errc() || p != tok.data() + tok.size())
      throw err(fmt::format("expected a number for {}, got '{}'", what, clip(tok)));
    return v;
  }
  template <class T>
  T bin() {
    T v;
    in_.read_exact(&v, sizeof v);
    return v;
  }
  int read_int(const char* what) { return binary_ ? bin<int>() : ascii_int<int>(what); }
  std::uint64_t read_size(const char* what) {
    if (!binary_) return ascii_int<std::uint64_t>(what);
    return bin<std::uint64_t>();
  }
  double read_double(const char* what) { return binary_ ? bin<double>() : ascii_double(what); }

  // Checks a count against a limit and against what the rest of the input can hold.
  void check_count(std::uint64_t count, std::uint64_t limit, std::uint64_t min_bytes_each, const char* what) {
    if (auto rem = in_.remaining(); rem && min_bytes_each > 0 && count > *rem / min_bytes_each)
      throw err(fmt::format("{} count {} is larger than the file can hold ({} bytes left; truncated file?)", what, count, *rem));
    if (count > limit)
      throw err(fmt::format("{} count {} exceeds the limit {}", what, count, limit));
  }

  void read_format() {
    std::string line;
    if (!in_.getline(line)) throw in_.error("truncated $MeshFormat");
    double version = 0;
    int file_type = -1, data_size = 0;
    char extra = 0;
    if (std::sscanf(line.c_str(), "%lf %d %d %c", &version, &file_type, &data_size, &extra) != 3)
      throw in_.error(fmt::format("malformed $MeshFormat line '{}'", clip(line)));
    if (std::abs(version - 4.1) > 1e-9)
      throw in_.error(fmt::format("MSH version {} is not supported (need 4.1; convert with: gmsh in.msh -save -format msh41 -o out.msh)", version));
    if (file_type != 0 && file_type != 1) throw in_.error(fmt::format("unknown file type {}", file_type));
    if (data_size != 8) throw in_.error(fmt::format("data size {} is not supported (need 8)", data_size));
    binary_ = file_type == 1;
    if (binary_) {
      const int one = bin<int>();
      if (one != 1) {
        if (__builtin_bswap32(static_cast<std::uint32_t>(one)) == 1u)
          throw in_.error_at_byte("binary MSH file of the wrong endianness (written on a big-endian machine)");
        throw in_.error_at_byte("corrupt binary MSH header (endianness marker is not 1)");
      }
      std::string rest;
      in_.getline(rest);  // end of the marker line
    }
  }

  void read_physical_names() {
    const auto n = ascii_int<std::uint64_t>("number of physical names");
    check_count(n, 1'000'000, 6, "physical name");
    std::string line;
    in_.getline(line);  // rest of the count line
    for (std::uint64_t i = 0; i < n; ++i) {
      if (!in_.getline(line)) throw err("truncated $PhysicalNames");
      int dim = 0, tag = 0, used = 0;
      if (std::sscanf(line.c_str(), "%d %d %n", &dim, &tag, &used) < 2)
        throw err(fmt::format("malformed physical name line '{}'", clip(line)));
      std::string name = line.substr(used);
      if (name.size() < 2 || name.front() != '"' || name.back() != '"')
        throw err("physical name must be quoted");
      if (dim < 0 || dim > 3) throw err(fmt::format("physical group dimension {} out of range", dim));
      if (tag <= 0) throw err(fmt::format("physical tag {} must be positive", tag));
      if (!seen_physicals_.insert({dim, tag}).second)
        throw err(fmt::format("physical tag {} of dimension {} is named twice", tag, dim));
      mesh_.physicals.push_back({dim, tag, name.substr(1, name.size() - 2)});
    }
  }

  void read_entities() {
    std::uint64_t counts[4];
    for (auto& c : counts) c = read_size("number of entities");
    for (int dim = 0; dim < 4; ++dim) {
      check_count(counts[dim], 100'000'000, binary_ ? 28 : 8, "entity");
      for (std::uint64_t i = 0; i < counts[dim]; ++i) {
        Entity e;
        e.dim = dim;
        const std::uint64_t at = in_.offset();
        e.tag = read_int("entity tag");
        if (e.tag <= 0) throw binary_ ? err_at(at, fmt::format("entity tag {} must be positive", e.tag))
                                      : err(fmt::format("entity tag {} must be positive", e.tag));
        if (!seen_entities_.insert({dim, e.tag}).second)
          throw binary_ ? err_at(at, fmt::format("entity {} of dimension {} is listed twice", e.tag, dim))
                        : err(fmt::format("entity {} of dimension {} is listed twice", e.tag, dim));
        const int nb = dim == 0 ? 3 : 6;
        for (int k = 0; k < nb; ++k) e.bbox[k] = read_double("entity bounding box");
        const auto np = read_size("number of physical tags");
        check_count(np, 1'000'000, binary_ ? 4 : 2, "physical tag");
        for (std::uint64_t k = 0; k < np; ++k) {
          const std::uint64_t pat = in_.offset();
          const int ptag = read_int("physical tag");
          if (ptag == 0) throw binary_ ? err_at(pat, fmt::format("entity {}: physical tag 0 is not allowed", e.tag))
                                       : err(fmt::format("entity {}: physical tag 0 is not allowed", e.tag));
          e.physicals.push_back(ptag);
        }
        if (dim > 0) {
          const auto nbnd = read_size("number of bounding entities");
          check_count(nbnd, 100'000'000, binary_ ? 4 : 2, "bounding entity");
          for (std::uint64_t k = 0; k < nbnd; ++k) read_int("bounding entity tag");
        }
        mesh_.entities.push_back(std::move(e));
      }
    }
  }

  void read_nodes() {
    const auto nblocks = read_size("number of node blocks");
    const auto nnodes = read_size("number of nodes");
    read_size("minimum node tag");
    read_size("maximum node tag");
    check_count(nnodes, limits_.max_nodes, binary_ ? 32 : 8, "node");
    check_count(nblocks, limits_.max_nodes, binary_ ? 20 : 8, "node block");
    const std::size_t reserve = in_.remaining() ? nnodes : std::min<std::uint64_t>(nnodes, 1 << 20);
    mesh_.node_tags.reserve(reserve);
    mesh_.nodes.reserve(reserve);
    std::uint64_t total = 0;
    std::vector<std::uint64_t> tags;
    for (std::uint64_t b = 0; b < nblocks; ++b) {
      const std::uint64_t block_at = in_.offset();
      const int edim = read_int("entity dimension");
      const int etag = read_int("entity tag");
      const int parametric = read_int("parametric flag");
      const auto n = read_size("number of nodes in block");
      auto block_err = [&](const std::string& msg) { return binary_ ? err_at(block_at, msg) : err(msg); };
      if (edim < 0 || edim > 3) throw block_err(fmt::format("node block entity dimension {} out of range", edim));
      if (etag < 0) throw block_err(fmt::format("node block entity tag {} must not be negative", etag));
      if (parametric != 0 && parametric != 1) throw block_err(fmt::format("parametric flag {} must be 0 or 1", parametric));
      if (n > nnodes - total)
        throw block_err(fmt::format("node blocks hold more nodes than the header's {}", nnodes));
      check_count(n, limits_.max_nodes, binary_ ? 32 : 8, "node");
      tags.resize(n);
      const std::uint64_t tags_at = in_.offset();
      node_blocks_.push_back({mesh_.node_tags.size(), tags_at});
      if (binary_) {
        if (n) in_.read_exact(tags.data(), n * sizeof(std::uint64_t));
      } else {
        for (auto& t : tags) t = ascii_int<std::uint64_t>("node tag");
      }
      const int npar = parametric ? std::min(edim, 2) : 0;
      for (std::uint64_t i = 0; i < n; ++i) {
        Point3 x;
        const std::uint64_t at = in_.offset();
        if (binary_) {
          double v[5];
          in_.read_exact(v, sizeof(double) * (3 + npar));
          x = {v[0], v[1], v[2]};
        } else {
          for (auto& c : x) c = ascii_double("node coordinate");
          for (int k = 0; k < npar; ++k) ascii_double("parametric coordinate");
        }
        if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
          throw binary_ ? err_at(at, fmt::format("node {} has a non-finite coordinate", tags[i]))
                        : err(fmt::format("node {} has a non-finite coordinate", tags[i]));
        // Coordinates are metres in a projected CRS: beyond kMaxCoordinate a value is damage, and
        // volumes and Jacobians of such nodes would overflow to inf.
        if (std::abs(x[0]) > kMaxCoordinate || std::abs(x[1]) > kMaxCoordinate || std::abs(x[2]) > kMaxCoordinate) {
          const std::string what = fmt::format("node {} has a coordinate ({:g}, {:g}, {:g}) beyond +-{:g} m (expected metres "
                                               "in a projected CRS)", tags[i], x[0], x[1], x[2], kMaxCoordinate);
          throw binary_ ? err_at(at, what) : err(what);
        }
        if (tags[i] == 0)
          throw binary_ ? err_at(tags_at + 8 * i, "node tag 0 is not allowed") : err("node tag 0 is not allowed");
        mesh_.node_tags.push_back(tags[i]);
        mesh_.nodes.push_back(x);
      }
      total += n;
    }
    if (total != nnodes)
      throw err(fmt::format("$Nodes header announces {} nodes but its blocks hold {}", nnodes, total));
    build_node_lookup();
  }

  void build_node_lookup() {
    std::uint64_t maxtag = 0;
    for (auto t : mesh_.node_tags) maxtag = std::max(maxtag, t);
    dense_ = maxtag <= 2 * mesh_.node_tags.size() + 1024;
    if (dense_) {
      dense_index_.assign(maxtag + 1, kMissing);
      for (std::uint32_t i = 0; i < mesh_.node_tags.size(); ++i) {
        auto& slot = dense_index_[mesh_.node_tags[i]];
        if (slot != kMissing) throw duplicate_node(i);
        slot = i;
      }
    } else {
      sparse_index_.reserve(mesh_.node_tags.size());
      for (std::uint32_t i = 0; i < mesh_.node_tags.size(); ++i)
        if (!sparse_index_.emplace(mesh_.node_tags[i], i).second)
          throw duplicate_node(i);
    }
  }

  // The second node with an already used tag, at the byte offset of its tag in binary input.
  InputError duplicate_node(std::uint32_t i) const {
    const auto msg = fmt::format("duplicate node tag {}", mesh_.node_tags[i]);
    if (!binary_) return err(msg);
    auto b = std::upper_bound(node_blocks_.begin(), node_blocks_.end(), std::size_t{i},
                              [](std::size_t v, const NodeBlock& nb) { return v < nb.first; });
    --b;
    return err_at(b->tags_at + 8 * (i - b->first), msg);
  }

  std::uint32_t node_index(std::uint64_t tag, std::uint64_t element_tag, std::uint64_t element_at = 0) {
    if (dense_) {
      if (tag < dense_index_.size() && dense_index_[tag] != kMissing) return dense_index_[tag];
    } else if (auto it = sparse_index_.find(tag); it != sparse_index_.end()) {
      return it->second;
    }
    const auto msg = fmt::format("element {} refers to missing node {}", element_tag, tag);
    throw binary_ ? err_at(element_at, msg) : err(msg);
  }

  void read_elements() {
    const auto nblocks = read_size("number of element blocks");
    const auto nelem = read_size("number of elements");
    read_size("minimum element tag");
    read_size("maximum element tag");
    check_count(nelem, limits_.max_elements, binary_ ? 16 : 4, "element");
    check_count(nblocks, limits_.max_elements, binary_ ? 20 : 8, "element block");
    std::uint64_t total = 0;
    std::vector<std::uint64_t> raw;
    for (std::uint64_t b = 0; b < nblocks; ++b) {
      const std::uint64_t block_at = in_.offset();
      const int edim = read_int("entity dimension");
      const int etag = read_int("entity tag");
      const int gtype = read_int("element type");
      const auto n = read_size("number of elements in block");
      const auto type = element_type_from_gmsh(gtype);
      auto block_err = [&](const std::string& msg) { return binary_ ? err_at(block_at, msg) : err(msg); };
      if (etag <= 0) throw block_err(fmt::format("element block entity tag {} must be positive", etag));
      if (!type)
        throw block_err(fmt::format("unsupported element type {} (ugs reads points, lines, triangles, linear tetrahedra and 6-node interface prisms)", gtype));
      if (edim < 0 || edim > 3) throw block_err(fmt::format("element block entity dimension {} out of range", edim));
      if (n > nelem - total)
        throw block_err(fmt::format("element blocks hold more elements than the header's {}", nelem));
      const int npe = nodes_per_element(*type);
      check_count(n, limits_.max_elements, static_cast<std::uint64_t>(binary_ ? 8 * (1 + npe) : 2 * (1 + npe)), "element");
      ElementBlock blk;
      blk.entity_dim = edim;
      blk.entity_tag = etag;
      blk.type = *type;
      const std::size_t reserve = in_.remaining() ? n : std::min<std::uint64_t>(n, 1 << 20);
      blk.tags.reserve(reserve);
      blk.nodes.reserve(reserve * npe);
      if (binary_) {
        constexpr std::uint64_t chunk = 1 << 16;
        for (std::uint64_t first = 0; first < n; first += chunk) {
          const std::uint64_t m = std::min(chunk, n - first);
          raw.resize(m * (1 + npe));
          const std::uint64_t chunk_at = in_.offset();
          in_.read_exact(raw.data(), raw.size() * sizeof(std::uint64_t));
          for (std::uint64_t i = 0; i < m; ++i) {
            const std::uint64_t* e = raw.data() + i * (1 + npe);
            const std::uint64_t at = chunk_at + i * (1 + npe) * sizeof(std::uint64_t);  // this element's record
            if (e[0] == 0) throw err_at(at, "element tag 0 is not allowed");
            blk.tags.push_back(e[0]);
            for (int k = 0; k < npe; ++k) blk.nodes.push_back(node_index(e[1 + k], e[0], at));
          }
        }
      } else {
        for (std::uint64_t i = 0; i < n; ++i) {
          const auto tag = ascii_int<std::uint64_t>("element tag");
          if (tag == 0) throw err("element tag 0 is not allowed");
          const std::size_t line = in_.line();
          blk.tags.push_back(tag);
          for (int k = 0; k < npe; ++k) blk.nodes.push_back(node_index(ascii_int<std::uint64_t>("element node tag"), tag));
          // Each element must sit on its own line: extra numbers mean a wrong node count.
          in_.skip_whitespace();
          if (in_.line() == line && in_.peek() != -1)
            throw err(fmt::format("element {} has more than {} nodes for a {}", tag, npe, element_name(*type)));
        }
      }
      total += n;
      mesh_.blocks.push_back(std::move(blk));
    }
    if (total != nelem)
      throw err(fmt::format("$Elements header announces {} elements but its blocks hold {}", nelem, total));
  }

  void read_provenance() {
    const auto n = ascii_int<std::uint64_t>("number of provenance lines");
    check_count(n, 100'000, 1, "provenance line");
    std::string line;
    in_.getline(line);
    for (std::uint64_t i = 0; i < n; ++i) {
      if (!in_.getline(line)) throw err("truncated $UgsProvenance");
      mesh_.provenance.push_back(line);
    }
  }

  void skip_section(const std::string& section) {
    const std::string end = "$End" + section;
    std::string line;
    while (in_.getline(line))
      if (line == end) return;
    throw err(fmt::format("section ${} has no {}", section, end));
  }

  void expect_end(const std::string& section) {
    const std::string end = "$End" + section;
    std::string line;
    while (in_.getline(line)) {
      if (line.find_first_not_of(" \t") == std::string::npos) continue;  // rest of a data line
      if (line == end) return;
      throw err(fmt::format("expected {}, got '{}' (wrong count or corrupt data?)", end, clip(line)));
    }
    throw err(fmt::format("unexpected end of input: missing {} (truncated file?)", end));
  }

  // Entities referenced by element blocks but absent from $Entities (files without that section).
  void finish_entities() {
    for (const auto& b : mesh_.blocks)
      if (!mesh_.find_entity(b.entity_dim, b.entity_tag))
        mesh_.entities.push_back({b.entity_dim, b.entity_tag, {}, {}});
  }

  struct NodeBlock {
    std::size_t first;        // index of its first node
    std::uint64_t tags_at;    // byte offset of its node tags
  };
  std::vector<NodeBlock> node_blocks_;
  std::set<std::pair<int, int>> seen_entities_;
  std::set<std::pair<int, int>> seen_physicals_;  // (dim, tag) of $PhysicalNames
  static constexpr std::uint32_t kMissing = 0xffffffffu;
  InputStream& in_;
  MshLimits limits_;
  Mesh mesh_;
  bool binary_ = false;
  bool dense_ = true;
  std::vector<std::uint32_t> dense_index_;
  std::unordered_map<std::uint64_t, std::uint32_t> sparse_index_;
};

}  // namespace

Mesh read_msh(InputStream& in, const MshLimits& limits) { return MshReader(in, limits).read(); }

Mesh read_msh(const std::string& path) {
  auto in = InputStream::open(path, "an MSH file");
  return read_msh(*in);
}

}  // namespace ugs
