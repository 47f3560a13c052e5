// Gmsh MSH 4.1 reader, ASCII and binary (formats/src/msh_reader.cpp), as ugs-meshinfo and every mesh
// consumer call it, then the checks a plan goes through in ugs-meshgen (meshing/plan/src/plan.cpp) and
// the summary of ugs-meshinfo.
#include "fuzz_support.hpp"
#include "ugs/formats/io.hpp"
#include "ugs/formats/mesh_summary.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/plan.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ugs::Mesh mesh;
  const bool ok = ugs::fuzz::outcome([&] {
    auto in = ugs::InputStream::from_string(ugs::fuzz::text(data, size), "fuzz.msh");
    mesh = ugs::read_msh(*in);
  });
  if (!ok) return 0;
  ugs::fuzz::outcome([&] { (void)ugs::format_summary(ugs::summarize(mesh)); });
  ugs::fuzz::outcome([&] { (void)ugs::plan_from_mesh(mesh, "fuzz.msh"); });
  return 0;
}
