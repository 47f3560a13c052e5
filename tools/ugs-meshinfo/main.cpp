// ugs-meshinfo — what is in a mesh: counts per element type and physical group, bounding box,
// tetrahedron volume range and inverted elements; optionally converts it to VTK (.vtu).
//
//   ugs-meshinfo model.msh
//   ugs-meshgen ... | ugs-meshinfo - --convert model.vtu
#include "ugs/cli/tool.hpp"
#include "ugs/formats/mesh_summary.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/formats/vtu.hpp"

namespace {
struct Options {
  std::string input = "-";
  std::string convert;
  bool fail_on_inverted = false;
};
}  // namespace

int main(int argc, char** argv) {
  ugs::cli::Tool tool({"ugs-meshinfo", "Print counts, groups, extent and element quality of a Gmsh MSH 4.1 mesh.",
                       "ugs-meshinfo model.msh --convert model.vtu"});
  Options opt;
  auto& app = tool.app();
  app.add_option("mesh", opt.input, "Mesh file (MSH 4.1, ASCII or binary; '-' = stdin)")->capture_default_str();
  app.add_option("--convert", opt.convert, "Also write the mesh as VTK XML (.vtu) to this file");
  app.add_flag("--fail-on-inverted", opt.fail_on_inverted, "Exit with code 1 if any tetrahedron is inverted");
  return tool.run(argc, argv, [&] {
    const ugs::Mesh mesh = ugs::read_msh(opt.input);
    const ugs::MeshSummary s = ugs::summarize(mesh);
    std::fputs(ugs::format_summary(s).c_str(), stdout);
    if (!opt.convert.empty()) {
      ugs::write_vtu(mesh, opt.convert);
      ugs::cli::detail("wrote {}", opt.convert);
    }
    if (opt.fail_on_inverted && s.inverted_tets > 0)
      throw ugs::ComputeError(std::to_string(s.inverted_tets) + " inverted tetrahedra");
  });
}
