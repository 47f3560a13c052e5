// ugs-meshgen — a layered tetrahedral mesh from a 2D plan and a stack of stratigraphic surfaces:
// node columns above the plan nodes with one node per surface and sub-layer boundary (merged where
// a unit pinches out), each triangular prism split into three tetrahedra by the global node order
// (conforming), materials mat:<name> by unit and polygon, boundary triangles bnd:top|bottom|west|
// east|south|north, vertical fault:<name> triangles above the plan's fault lines over their depth
// range, and dipping or listric faults of the faults file (dip_deg < 90) as fault:<name> faces of a
// conforming cut of the mesh by their planes (docs/dipping-faults.md). A quality report goes to
// stderr, the mesh (binary MSH 4.1) to stdout.
//
//   ugs-mesh2d --domain domain.geojson --refine refinement.geojson --fault faults.geojson |
//     ugs-meshgen --strata strata.toml > model.msh   (one line)
#include <unistd.h>

#include <chrono>
#include <cmath>

#include "ugs/cli/number_option.hpp"
#include "ugs/cli/tool.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/formats/run_beside.hpp"
#include "ugs/meshing/fault_cut.hpp"
#include "ugs/meshing/layered_mesh.hpp"
#include "ugs/meshing/mesh_quality.hpp"
#include "ugs/meshing/plan.hpp"
#include "ugs/meshing/strata.hpp"

namespace {

struct Options {
  std::string plan = "-";
  std::string strata;
  std::string faults;
  double small_angle = 5.0;
  bool ascii = false;
  double max_elements = 50e6;
};

class Stopwatch {
public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace

int main(int argc, char** argv) {
  ugs::cli::Tool tool({"ugs-meshgen",
                       "Layered tetrahedral mesh from a 2D plan and stratigraphic surfaces (materials, boundary and "
                       "fault groups).",
                       "ugs-mesh2d --domain domain.geojson --refine refinement.geojson --fault faults.geojson | "
                       "ugs-meshgen --strata strata.toml > model.msh"});
  Options opt;
  auto& app = tool.app();
  app.add_option("plan", opt.plan, "2D plan mesh (MSH, from ugs-mesh2d or any gmsh triangle mesh; '-' = stdin)")
      ->capture_default_str();
  app.add_option("--strata", opt.strata, "Stratigraphy file (TOML): surfaces, units, materials (docs/meshing.md)")
      ->required();
  app.add_option("--faults", opt.faults,
                 "Faults file (OGR) replacing the strata file's `faults`: depth ranges, and dips for dipping faults "
                 "(docs/dipping-faults.md)");
  app.add_option("--small-angle", opt.small_angle, "Report tetrahedra with a dihedral angle below this (degrees)")
      ->capture_default_str()
      ->check(ugs::cli::number_in(0, 180));
  app.add_option("--max-elements", opt.max_elements,
                 "Refuse a mesh of more tetrahedra than this (estimated before building: 3 per plan triangle and "
                 "sub-layer)")
      ->capture_default_str()
      ->check(ugs::cli::number_in(0, ugs::cli::kNoLimit, ugs::cli::Ends::OpenLow));
  app.add_flag("--ascii", opt.ascii, "Write ASCII MSH (default: binary)");
  tool.add_output("-", "Layered mesh (MSH 4.1)");

  return tool.run(argc, argv, [&] {
    Stopwatch clock;
    if (!(opt.small_angle > 0 && opt.small_angle < 90))
      throw ugs::InputError("--small-angle", fmt::format("must be an angle in (0, 90) degrees, got {}", opt.small_angle));
    if (tool.output() == "-" && !opt.ascii && ::isatty(STDOUT_FILENO))
      throw ugs::InputError("-o", "refusing to write a binary mesh to a terminal: redirect stdout, use -o FILE or --ascii");

    if (opt.plan == "-" && ::isatty(STDIN_FILENO))
      throw ugs::InputError("stdin", "no plan: give a plan file or pipe one in (ugs-mesh2d ... | ugs-meshgen ...)");
    ugs::Strata strata = ugs::read_strata(opt.strata);
    if (!opt.faults.empty()) strata.faults_file = opt.faults;
    const ugs::Mesh plan_mesh = ugs::read_msh(opt.plan);
    const ugs::Plan plan = ugs::plan_from_mesh(plan_mesh, opt.plan == "-" ? std::string("stdin") : opt.plan);
    double t = clock.lap(), total = t;
    ugs::cli::detail("plan: {} columns, {} triangles, {} line groups (read in {:.3f} s)", plan.num_columns(),
                     plan.triangles.size(), plan.lines.size(), t);
    // Refuse before building what would not fit in memory: 3 tetrahedra per plan triangle and sub-layer
    // (pinch-outs only remove some).
    {
      double layers = 0;
      for (const auto& u : strata.units) layers += u.layers;
      const double tets = 3.0 * static_cast<double>(plan.triangles.size()) * layers;
      ugs::cli::detail("at most {:.3g} tetrahedra (limit {:.0f})", tets, opt.max_elements);
      if (tets > opt.max_elements)
        throw ugs::InputError("--max-elements",
                              fmt::format("{} plan triangles x {:.0f} sub-layers ({}) ask for up to {:.3g} tetrahedra (3 per "
                                          "prism), more than the limit of {:.0f}: use fewer sub-layers or a coarser plan, or "
                                          "raise --max-elements",
                                          plan.triangles.size(), layers, opt.strata, tets, opt.max_elements));
    }
    ugs::cli::Activity activity("building the layered mesh");

    ugs::PreparedModel model = ugs::prepare_model(strata, plan);
    for (const auto& n : model.notes) ugs::cli::detail("{}", n);
    for (const auto& w : model.warnings) ugs::cli::warning("{}", w);
    t = clock.lap();
    total += t;
    ugs::cli::detail("surfaces sampled, order rule and materials applied in {:.3f} s (model CRS {})", t, model.crs);

    ugs::LayeredMeshStats stats;
    ugs::Mesh mesh = ugs::build_layered_mesh(model.input, &stats);
    mesh.provenance = plan.provenance;
    mesh.provenance.push_back(tool.command_line());
    t = clock.lap();
    total += t;
    ugs::cli::detail("mesh built in {:.3f} s: {} levels per column, {} nodes merged at pinch-outs, {} tetrahedra dropped",
                     t, stats.levels, stats.merged_nodes, stats.dropped_tetrahedra);

    if (!model.cut_faults.empty()) {
      // Dipping faults: conforming cut of the layered mesh by their panels (docs/dipping-faults.md).
      const ugs::FaultCutSummary cut = ugs::cut_faults(mesh, model.cut_faults);
      t = clock.lap();
      total += t;
      ugs::cli::detail("dipping faults cut in {:.3f} s: {} -> {} tetrahedra, {} new nodes, {} nodes snapped onto a fault, {} edges bisected "
                       "against tearing, {} short edges collapsed, {} smoothing moves (on-plane tolerance {:.2g} m)",
                       t, cut.tetrahedra_before, cut.tetrahedra_after, cut.nodes_after - cut.nodes_before, cut.snapped,
                       cut.untorn, cut.collapsed, cut.smoothed, cut.tolerance);
      for (std::size_t i = 0; i < cut.faults.size(); ++i) {
        const auto& f = cut.faults[i];  // in the order of model.cut_faults
        ugs::cli::info("fault:{:<20} {}, {} panel(s): {} triangles, {:.4g} km2, z {:.1f} .. {:.1f} m, off-plane "
                       "{:.1e} m, normal {:.1e} deg",
                       f.name, model.cut_faults[i].surface ? "surface" : "dipping", f.panels, f.triangles, f.area * 1e-6,
                       f.zmax, f.zmin, f.max_distance, f.max_angle_deg);
        if (f.boundary_faces > 0)
          ugs::cli::warning("fault '{}': {} faces of its surface lie on the model boundary and are not part of it",
                            f.name, f.boundary_faces);
      }
      ugs::cli::info("fault cut: {} tetrahedra hold a node the cut made: smallest dihedral angle {:.2f} deg; {} below "
                     "min(2 deg, their input tetrahedron's), {} below a tenth of it",
                     cut.band_tetrahedra, cut.band_min_dihedral_deg, cut.band_below_reference, cut.band_below_bound);
      if (cut.band_below_bound > 0)
        ugs::cli::warning("the fault cut left {} tetrahedra below a tenth of min(2 deg, their input tetrahedron's smallest "
                          "dihedral angle) (docs/dipping-faults.md, \"Mesh quality\")",
                          cut.band_below_bound);
    }

    // The quality report is measured on other threads while the mesh is written to the output's
    // temporary file (two cores: the writer is one thread); an inverted mesh is then not committed,
    // so it is never written. To stdout, whose bytes cannot be taken back, it is measured first.
    ugs::OutputFile out(tool.output());
    const auto encoding = opt.ascii ? ugs::MshEncoding::Ascii : ugs::MshEncoding::Binary;
    ugs::QualityReport q;
    if (out.is_stdout()) {
      q = ugs::mesh_quality(mesh, opt.small_angle);
    } else {
      ugs::run_beside([&] { q = ugs::mesh_quality(mesh, opt.small_angle); }, [&] { ugs::write_msh(mesh, out, encoding); });
    }
    if (q.inverted > 0)  // cannot happen with the split rule on a valid plan; never write such a mesh
      throw ugs::ComputeError(std::to_string(q.inverted) + " tetrahedra are inverted or flat; no mesh written");
    if (q.degenerate > 0)  // the fault cut keeps clear of it (docs/dipping-faults.md, "Mesh quality"); ugs-solve would refuse it
      throw ugs::ComputeError(fmt::format("tetrahedron {} (output index) is degenerate (|det| <= {:g} scale^3, ugs-solve's "
                                          "test){}; no mesh written",
                                          q.first_degenerate, ugs::kDegenerateTetRatio,
                                          q.degenerate > 1 ? fmt::format(", and {} more", q.degenerate - 1) : std::string()));
    if (out.is_stdout()) ugs::write_msh(mesh, out, encoding);
    out.commit();
    t = clock.lap();
    total += t;
    ugs::cli::detail("quality measured and mesh written in {:.3f} s", t);

    std::string report = ugs::format_quality(q);
    std::size_t start = 0;
    while (start < report.size()) {
      const auto end = report.find('\n', start);
      ugs::cli::info("{}", report.substr(start, end - start));
      start = end == std::string::npos ? report.size() : end + 1;
    }
    ugs::cli::detail("total {:.2f} s", total);
  });
}
