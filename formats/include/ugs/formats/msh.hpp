// Gmsh MSH 4.1 reading (ASCII or binary, auto-detected, from a file or a pipe) and writing
// (binary by default). Sections we do not use are skipped as Gmsh does; `$UgsProvenance`
// carries the command lines that built the mesh.
#pragma once
#include <string>

#include "ugs/formats/io.hpp"
#include "ugs/formats/mesh.hpp"

namespace ugs {

// Refuse counts beyond these before allocating (independent of the file size check).
struct MshLimits {
  std::uint64_t max_nodes = 2'000'000'000;
  std::uint64_t max_elements = 2'000'000'000;
};

Mesh read_msh(InputStream& in, const MshLimits& limits = {});
Mesh read_msh(const std::string& path);  // "-" = stdin

enum class MshEncoding { Binary, Ascii };
void write_msh(const Mesh& mesh, OutputFile& out, MshEncoding enc = MshEncoding::Binary);
// Writes atomically to `path` ("-" = stdout).
void write_msh(const Mesh& mesh, const std::string& path, MshEncoding enc = MshEncoding::Binary);

}  // namespace ugs
