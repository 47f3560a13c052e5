// ugs-faultinsert — faults as zero-thickness interface elements (thesis 3.5.2, Fig. 3.3): the
// fault surfaces of a tetrahedral mesh, given as fault:<name> triangle groups and/or as traces with
// dip and depth range in any OGR vector file, get duplicated nodes on their two sides and one
// 6-node interface prism per fault triangle. Reads a mesh (stdin by default), writes the faulted
// mesh (binary MSH 4.1 to stdout by default) and a summary per fault on stderr. docs/faults.md.
//
//   ugs-meshgen plan.msh --strata strata.toml | ugs-faultinsert --faults faults.geojson > faulted.msh
//   ugs-faultinsert model.msh --only local_1,local_2 -o faulted.msh
#include <chrono>
#include <cmath>
#include <set>

#include "ugs/cli/number_option.hpp"
#include "ugs/cli/tool.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/fault_insert.hpp"
#include "ugs/meshing/fault_select.hpp"
#include "ugs/meshing/fault_traces.hpp"
#include "ugs/meshing/geodata.hpp"

namespace {

struct Options {
  std::string input = "-";
  std::string faults;                 // OGR file of traces
  std::vector<std::string> only;
  double tolerance = 0;
  double min_coverage = 99;
  std::string crs;
  bool ascii = false;
};

// 12345678 -> "12,345,678"
std::string grouped(std::size_t n) {
  std::string s = std::to_string(n), r;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (i && (s.size() - i) % 3 == 0) r += ',';
    r += s[i];
  }
  return r;
}

// -1234.5 -> "-1,235"
std::string metres(double v) {
  const long long r = std::llround(v);
  return (r < 0 ? "-" : "") + grouped(static_cast<std::size_t>(r < 0 ? -r : r));
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

std::string strip(const std::string& n) { return n.rfind("fault:", 0) == 0 ? n.substr(6) : n; }

}  // namespace

int main(int argc, char** argv) {
  ugs::cli::Tool tool({"ugs-faultinsert",
                       "Insert faults as zero-thickness interface elements (6-node prisms) on duplicated nodes.",
                       "ugs-meshgen plan.msh --strata strata.toml | ugs-faultinsert --faults faults.geojson > faulted.msh"});
  Options opt;
  auto& app = tool.app();
  app.add_option("mesh", opt.input, "Tetrahedral mesh (MSH 4.1, ASCII or binary; '-' = stdin)")->capture_default_str();
  tool.add_output("-", "Faulted mesh, binary MSH 4.1");
  app.add_option("--faults", opt.faults,
                 "Faults file (any OGR vector file, the one of ugs-mesh2d and ugs-meshgen): lines with name and, for a "
                 "fault the mesh has no fault:<name> group for, top_m, bottom_m, dip_deg, dip_dir_deg [, trace_z_m]: "
                 "the mesh faces on its surface become the fault");
  app.add_option("--only", opt.only, "Insert only these faults (comma-separated names); default: all")->delimiter(',');
  app.add_option("--tolerance", opt.tolerance,
                 "Distance (m) within which a face lies on a trace surface; default 1 % of the shortest edge at each node")
      ->check(ugs::cli::number_in(0, ugs::cli::kNoLimit));
  app.add_option("--min-coverage", opt.min_coverage, "Percentage of a trace surface inside the model that mesh faces must cover")
      ->check(ugs::cli::number_in(0, 100))
      ->capture_default_str();
  app.add_option("--crs", opt.crs, "The mesh's CRS (e.g. EPSG:32632): traces in another CRS are reprojected to it");
  app.add_flag("--ascii", opt.ascii, "Write ASCII MSH instead of binary");

  return tool.run(argc, argv, [&] {
    using clock = std::chrono::steady_clock;
    auto t = clock::now();
    ugs::Mesh mesh = ugs::read_msh(opt.input);
    const std::string source = opt.input == "-" ? "<stdin>" : opt.input;
    ugs::cli::detail("read {}: {} nodes, {} tetrahedra in {:.2f} s", source, grouped(mesh.num_nodes()),
                     grouped(mesh.count(ugs::ElementType::Tetrahedron)), seconds_since(t));
    const std::size_t nodes_before = mesh.num_nodes();

    std::vector<std::string> only;
    for (const auto& n : opt.only)
      if (!n.empty()) only.push_back(strip(n));

    // 1. Traces: their faces become fault:<name> groups (the mesh's own groups win).
    std::vector<ugs::FaultTrace> traces;
    std::vector<ugs::FaultSelection> selections;
    ugs::FaultInsertOptions ins;
    ins.source = source;
    if (!opt.faults.empty()) {
      t = clock::now();
      const std::string wkt = opt.crs.empty() ? "" : ugs::geo::crs_wkt(opt.crs, "--crs");
      // The faults file of ugs-mesh2d and ugs-meshgen, read with the same reader and schema
      // (docs/faults.md): a fault the mesh already holds as fault:<name> triangles needs from the
      // file only its reference normal (dip_dir_deg, and dip_deg or 90); one the mesh lacks needs
      // the whole trace (top_m, bottom_m, dip_deg, dip_dir_deg).
      const auto in_mesh = ugs::fault_triangle_groups(mesh);
      for (const auto& rec : ugs::read_fault_file(opt.faults, wkt)) {
        if (!only.empty() && std::find(only.begin(), only.end(), rec.name) == only.end()) continue;
        const bool mesh_has = std::find(in_mesh.begin(), in_mesh.end(), rec.name) != in_mesh.end();
        if (!rec.surface.empty()) {  // a surface fault (docs/faults.md, "Faults as surfaces"): cut by ugs-meshgen
          if (!mesh_has)
            throw ugs::InputError(rec.where, fmt::format("fault '{}' is given as a surface ({}) and the mesh has no "
                                                         "fault:{} group: cut it into the mesh with ugs-meshgen first",
                                                         rec.name, rec.surface, rec.name));
          const ugs::FaultTrace tr = ugs::fault_trace_from_record(rec);
          ins.reference_normals[rec.name] = ugs::surface_reference_normal(tr.surface->mesh);
          for (const auto& c : tr.surface->cleaned) ugs::cli::warning("fault '{}': {}", rec.name, c);
          ugs::cli::detail("fault '{}': the mesh's fault:{} triangles; reference normal from its surface {}", rec.name,
                           rec.name, rec.surface);
          continue;
        }
        const bool full = rec.has_depth_range() && rec.has_dip() && rec.dip_dir_deg;
        if (mesh_has && !full) {
          if (const auto n = ugs::record_reference_normal(rec)) ins.reference_normals[rec.name] = *n;
          ugs::cli::detail("fault '{}': the mesh's fault:{} triangles; {}", rec.name, rec.name,
                           rec.dip_dir_deg ? "reference normal from the file" : "no dip_dir_deg in the file: mesh orientation");
          continue;
        }
        traces.push_back(ugs::fault_trace_from_record(
            rec, fmt::format("the mesh has no fault:{} group to use, so the file must give", rec.name)));
      }
      ugs::FaultSelectOptions sel;
      sel.source = source;
      sel.tolerance = opt.tolerance;
      sel.min_coverage = opt.min_coverage / 100;
      selections = ugs::select_fault_faces(mesh, traces, sel);
      for (std::size_t i = 0; i < traces.size(); ++i) {
        ins.reference_normals[traces[i].name] = ugs::FaultSurface(traces[i]).reference_normal();
        const auto& s = selections[i];
        if (!s.from_mesh) continue;
        // The mesh's group wins; say where it departs from what the file describes.
        std::string why;
        if (s.max_deviation > std::max(1.0, opt.tolerance))
          why = fmt::format("lie up to {} m from the {:g}-degree surface", metres(s.max_deviation), traces[i].dip_deg);
        if (s.beyond_depth > 0)
          why += fmt::format("{}reach from z = {} to {} m, beyond top_m {} / bottom_m {} ({} triangles wholly outside: give "
                             "ugs-meshgen the depth ranges)",
                             why.empty() ? "" : " and ", metres(s.zmin), metres(s.zmax), metres(traces[i].top),
                             metres(traces[i].bottom), grouped(s.beyond_depth));
        if (!why.empty())
          ugs::cli::warning("fault '{}': the mesh's own {} fault:{} triangles are used; they {} of {}", s.name,
                            grouped(s.triangles), s.name, why, opt.faults);
      }
      ugs::cli::detail("selected fault faces from {} traces in {:.2f} s", traces.size(), seconds_since(t));
    }
    // Names asked for must exist somewhere: in the traces or in the mesh.
    if (!only.empty()) {
      const auto tri = ugs::fault_triangle_groups(mesh), ie = ugs::fault_interface_groups(mesh);
      for (const auto& n : only) {
        if (std::find(tri.begin(), tri.end(), n) != tri.end() || std::find(ie.begin(), ie.end(), n) != ie.end()) continue;
        std::string known;
        for (const auto& k : tri) known += (known.empty() ? "" : ", ") + k;
        throw ugs::InputError("--only", fmt::format("unknown fault '{}' (faults: {})", n,
                                                    known.empty() ? "none in the mesh or the trace file" : known));
      }
    }

    // 2. Insertion.
    ugs::cli::Activity activity("inserting the faults");
    t = clock::now();
    ins.only = only;
    const ugs::FaultInsertReport rep = ugs::insert_faults(mesh, ins);
    ugs::cli::detail("inserted in {:.2f} s", seconds_since(t));

    // 3. Output.
    t = clock::now();
    mesh.provenance.push_back(tool.command_line());
    ugs::write_msh(mesh, tool.output(), opt.ascii ? ugs::MshEncoding::Ascii : ugs::MshEncoding::Binary);
    ugs::cli::detail("wrote {} in {:.2f} s", tool.output() == "-" ? "<stdout>" : tool.output(), seconds_since(t));

    // 4. Summary on stderr.
    ugs::cli::info("{:<24} {:<12} {:>10} {:>10} {:>8} {:>10} {:>6}  {}", "fault", "source", "triangles", "area_km2", "nodes",
                   "duplicated", "tips", "intersections (shared nodes)");
    std::size_t elements = 0;
    for (const auto& f : rep.faults) {
      std::string src = "mesh";
      for (const auto& s : selections)
        if (s.name == f.name && !s.from_mesh) src = fmt::format("trace {:.1f}%", 100 * s.coverage);
      std::string meets;
      for (const auto& [g, n] : f.meets) meets += fmt::format("{}{} ({})", meets.empty() ? "" : ", ", g, grouped(n));
      ugs::cli::info("{:<24} {:<12} {:>10} {:>10.4g} {:>8} {:>10} {:>6}  {}", f.name, src, grouped(f.triangles),
                     f.area * 1e-6, grouped(f.nodes), grouped(f.duplicated_nodes), grouped(f.tip_nodes),
                     meets.empty() ? "-" : meets);
      elements += f.triangles;
      // A few corner triangles on a buried edge always have three tip nodes; many mean a fault too
      // narrow for the mesh.
      if (f.unsplit_triangles > 0 && 10 * f.unsplit_triangles > f.triangles)
        ugs::cli::warning("fault '{}': {} of its {} interface elements have no split node (all their nodes are tips), so "
                          "they cannot open or slide; refine the mesh across the fault",
                          f.name, grouped(f.unsplit_triangles), grouped(f.triangles));
      else if (f.unsplit_triangles > 0)
        ugs::cli::detail("fault '{}': {} interface elements with three tip nodes (corners of its buried edge)", f.name,
                         grouped(f.unsplit_triangles));
    }
    ugs::cli::info("{} fault{}: {} interface elements, {} new nodes ({} -> {} nodes), {} other elements moved to "
                   "their side's nodes",
                   rep.faults.size(), rep.faults.size() == 1 ? "" : "s", grouped(elements), grouped(rep.new_nodes),
                   grouped(nodes_before), grouped(mesh.num_nodes()), grouped(rep.renumbered_elements));
    if (rep.unattached_elements > 0)
      ugs::cli::warning("{} elements on split nodes belong to no tetrahedron and keep the original nodes",
                        grouped(rep.unattached_elements));
  });
}
