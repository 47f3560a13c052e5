// ugs-mesh2d — a graded 2D plan mesh of triangles (gmsh SDK) for ugs-meshgen: a domain (polygon or
// box), refinement polygons with target sizes, and constraint lines that become mesh edges (fault
// traces, section lines, reservoir traces). The size is the target size inside a refinement and
// grows with the distance from it up to --hmax. Inputs are any OGR vector files, reprojected to the
// model CRS. Output: MSH 4.1 triangles in region:<name> groups, line elements in fault:<name>,
// section:<name> and trace:<name> groups.
//
//   ugs-mesh2d --domain domain.geojson --refine refinement.geojson --trace reservoir_traces.geojson
//              --fault faults.geojson --section sections.geojson --hmax 2000 -o plan.msh   (one line)
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <sstream>

#include "ugs/cli/number_option.hpp"
#include "ugs/cli/tool.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/plan_mesh.hpp"

namespace {

struct Options {
  ugs::PlanInputs in;
  std::string box;
  std::string algorithm = "frontal-delaunay";
  bool ascii = false;
  double max_elements = 20e6;
};

std::array<double, 4> parse_box(const std::string& s) {
  std::array<double, 4> b{};
  std::istringstream is(s);
  std::string part;
  int k = 0;
  while (std::getline(is, part, '/')) {
    if (k == 4) throw ugs::InputError("--box", "expected xmin/xmax/ymin/ymax, got '" + s + "'");
    try {
      std::size_t used = 0;
      b[k] = std::stod(part, &used);
      if (used != part.size()) throw std::invalid_argument(part);
    } catch (const std::exception&) {
      throw ugs::InputError("--box", "'" + part + "' is not a number (expected xmin/xmax/ymin/ymax)");
    }
    ++k;
  }
  if (k != 4) throw ugs::InputError("--box", "expected xmin/xmax/ymin/ymax, got '" + s + "'");
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  ugs::cli::Tool tool({"ugs-mesh2d",
                       "Graded 2D plan mesh (gmsh) from a domain, refinement polygons and constraint lines, for ugs-meshgen.",
                       "ugs-mesh2d --domain domain.geojson --refine refinement.geojson --trace reservoir_traces.geojson "
                       "--fault faults.geojson --section sections.geojson --hmax 2000 -o plan.msh"});
  Options opt;
  auto& app = tool.app();
  auto* dom = app.add_option("--domain", opt.in.domain_file, "Domain polygon(s), any OGR vector file");
  app.add_option("--box", opt.box, "Rectangular domain xmin/xmax/ymin/ymax in the model CRS (instead of --domain)")
      ->excludes(dom);
  app.add_option("--refine", opt.in.refine_files,
                 "Refinement polygons; target size from the size field (default size_m) or --refine-size (repeatable)");
  app.add_option("--trace", opt.in.trace_files,
                 "Traces (e.g. reservoir outlines): polygons become region:<name> and their outline trace:<name>, "
                 "lines become trace:<name> (repeatable)");
  app.add_option("--fault", opt.in.fault_files, "Fault traces (lines) -> fault:<name> edges (repeatable)");
  app.add_option("--section", opt.in.section_files, "Section lines -> section:<name> edges (repeatable)");
  app.add_option("--hmax", opt.in.hmax, "Largest element size, far from refinements (m); default: the domain's size field")
      ->check(ugs::cli::number_in(0, ugs::cli::kNoLimit));
  app.add_option("--grading", opt.in.grading, "Growth of the size with the distance from a refinement (m per m)")
      ->capture_default_str()
      ->check(ugs::cli::number_in(0, ugs::cli::kNoLimit, ugs::cli::Ends::OpenLow));
  app.add_option("--refine-size", opt.in.refine_size, "Target size (m) of refinement polygons without a size field")
      ->check(ugs::cli::number_in(0, ugs::cli::kNoLimit));
  app.add_option("--crs", opt.in.crs, "Model CRS (default: the first input's, else EPSG:32632)");
  app.add_option("--name-field", opt.in.name_field, "Field naming the features")->capture_default_str();
  app.add_option("--size-field", opt.in.size_field, "Field with a feature's target size (m)")->capture_default_str();
  app.add_option("--algorithm", opt.algorithm, "gmsh 2D algorithm: frontal-delaunay, delaunay, meshadapt")
      ->check(CLI::IsMember({"frontal-delaunay", "delaunay", "meshadapt"}))
      ->capture_default_str();
  app.add_option("--max-elements", opt.max_elements,
                 "Refuse sizes whose estimated triangle count (docs/meshing.md) is above this")
      ->capture_default_str()
      ->check(ugs::cli::number_in(0, ugs::cli::kNoLimit, ugs::cli::Ends::OpenLow));
  app.add_flag("--ascii", opt.ascii, "Write ASCII MSH (default: binary)");
  tool.add_output("-", "Plan mesh (MSH 4.1)");

  tool.name_setting("size grading", "--grading");
  tool.name_setting("far-field size", "--hmax");
  tool.name_setting("refinement size", "--refine-size");
  tool.name_setting("model CRS", "--crs");
  tool.name_setting("model box", "--box");
  tool.name_setting("element limit", "--max-elements");
  return tool.run(argc, argv, [&] {
    const auto t0 = std::chrono::steady_clock::now();
    if (opt.box.empty() && opt.in.domain_file.empty())
      throw ugs::InputError("", "give the domain: --domain FILE or --box xmin/xmax/ymin/ymax");
    if (!opt.box.empty()) {
      opt.in.use_box = true;
      opt.in.box = parse_box(opt.box);
    }
    if (tool.output() == "-" && !opt.ascii && ::isatty(STDOUT_FILENO))
      throw ugs::InputError("-o", "refusing to write a binary mesh to a terminal: redirect stdout, use -o FILE or --ascii");

    ugs::LoadedPlan loaded = ugs::load_plan_inputs(opt.in);
    for (const auto& n : loaded.notes) ugs::cli::detail("{}", tool.with_flags(n));
    for (const auto& w : loaded.warnings) ugs::cli::warning("{}", tool.with_flags(w));
    loaded.spec.algorithm = opt.algorithm == "delaunay" ? 5 : opt.algorithm == "meshadapt" ? 1 : 6;
    loaded.spec.gmsh_messages = ugs::cli::verbosity() >= 2;
    loaded.spec.max_triangles = opt.max_elements;
    ugs::cli::detail("estimated {:.3g} triangles (limit {:.0f})", ugs::estimate_plan_triangles(loaded.spec).triangles,
                     opt.max_elements);
    ugs::cli::Activity activity("meshing the plan with gmsh");

    ugs::PlanMeshStats stats;
    ugs::Mesh mesh = ugs::make_plan_mesh(loaded.spec, &stats);
    mesh.provenance.push_back(tool.command_line());
    ugs::OutputFile out(tool.output());
    ugs::write_msh(mesh, out, opt.ascii ? ugs::MshEncoding::Ascii : ugs::MshEncoding::Binary);
    out.commit();
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ugs::cli::info("plan: {} nodes, {} triangles, {} constraint edges; sizes {:g} .. {:g} m ({}), {:.2f} s", stats.nodes,
                   stats.triangles, stats.line_elements, stats.min_size, loaded.spec.hmax, loaded.crs, secs);
  });
}
