// ugs-submesh — the flow mesh of a pool (thesis 4.2.1, Fig. 4.5): the tetrahedra of the given
// materials (names or physical ids), optionally only those whose centroid lies inside a plan
// polygon (any OGR vector file, reprojected to the model CRS), with the parent's node and element
// tags so results map back. Interface elements are dropped (non-barrier faults become `tie:` lines
// that keep flow crossing them); faults named with --barrier cut the connection (nodes on them are
// duplicated on one side, recorded by `twin:` lines). Writes MSH 4.1 to stdout or -o.
//
//   ugs-submesh model.msh --materials pool_c,aquifer_pool_c --barrier fault:F3 -o pool_c.msh
//   ugs-submesh model.msh --materials 4,7 --polygon aquifers.geojson --where "name = 'Pool C'" > pool_c.msh
//   ugs-submesh model.msh --case case.toml --pool "Pool C" -o pool_c.msh   (its materials + aquifer_materials)
#include "ugs/cli/tool.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/geodata.hpp"
#include "ugs/meshing/submesh.hpp"
#include <fmt/ranges.h>

namespace {

struct Options {
  std::string input = "-";
  std::vector<std::string> materials;
  std::string polygon;
  std::string where;
  std::string crs;
  std::vector<std::string> barriers;
  std::string case_file, pool;
  bool ascii = false;
};

std::string join(const std::vector<std::string>& v) { return fmt::format("{}", fmt::join(v, ", ")); }

}  // namespace

int main(int argc, char** argv) {
  ugs::cli::Tool tool({"ugs-submesh",
                       "Extract the flow mesh of a pool: cells of some materials, optionally inside a polygon, parent tags "
                       "kept, interface elements dropped, barrier faults cut.",
                       "ugs-submesh model.msh --materials pool_c,aquifer_pool_c --barrier fault:F3 -o pool_c.msh"});
  Options o;
  auto& app = tool.app();
  app.add_option("mesh", o.input, "Parent mesh (MSH 4.1; '-' = stdin)")->capture_default_str();
  app.add_option("-m,--materials", o.materials, "Materials to keep: names (mat: optional) or physical ids, comma-separated")
      ->delimiter(',');
  app.add_option("--case", o.case_file, "Case file: with --pool, keep that pool's materials and aquifer_materials");
  app.add_option("--pool", o.pool, "Pool of the case file whose flow mesh to cut (e.g. \"Pool C\")");
  app.add_option("--polygon", o.polygon, "Keep only cells whose centroid lies inside these polygons (any OGR vector file)");
  app.add_option("--where", o.where, "OGR attribute filter on the polygon features, e.g. \"name = 'Pool C'\"");
  app.add_option("--crs", o.crs, "Model CRS (e.g. EPSG:32632): polygons in another CRS are reprojected to it");
  app.add_option("--barrier", o.barriers, "Fault group that flow must not cross (fault:<name>; repeatable)");
  app.add_flag("--ascii", o.ascii, "Write ASCII MSH instead of binary");
  tool.add_output("-", "Sub-mesh (MSH 4.1)");
  return tool.run(argc, argv, [&] {
    if (!o.where.empty() && o.polygon.empty()) throw ugs::InputError("--where", "needs --polygon");
    if (o.case_file.empty() != o.pool.empty()) throw ugs::InputError(o.pool.empty() ? "--case" : "--pool", "--case and --pool go together");
    if (!o.pool.empty()) {
      const ugs::CaseFile cs = ugs::read_case_file(o.case_file);
      const ugs::PoolSpec* p = nullptr;
      for (const auto& q : cs.pools)
        if (q.name == o.pool) p = &q;
      if (!p) throw ugs::InputError(o.case_file, "no pool '" + o.pool + "'");
      if (p->aquifer_materials.empty())
        ugs::cli::warning("pool '{}' lists no aquifer_materials: only its own materials are kept", o.pool);
      o.materials.insert(o.materials.end(), p->materials.begin(), p->materials.end());
      o.materials.insert(o.materials.end(), p->aquifer_materials.begin(), p->aquifer_materials.end());
    }
    if (o.materials.empty()) throw ugs::InputError("--materials", "say which materials to keep (--materials, or --case with --pool)");
    const ugs::Mesh parent = ugs::read_msh(o.input);
    ugs::SubmeshSpec spec;
    spec.materials = o.materials;
    spec.barriers = o.barriers;
    if (!o.polygon.empty()) {
      const std::string model_wkt = o.crs.empty() ? std::string() : ugs::geo::crs_wkt(o.crs, "--crs");
      const ugs::geo::VectorData v = ugs::geo::read_vector(o.polygon, model_wkt, o.where);
      for (const auto& f : v.features)
        for (const auto& p : f.polygons) {
          spec.rings.push_back(p.outer);
          for (const auto& h : p.holes) spec.rings.push_back(h);
        }
      if (spec.rings.empty())
        throw ugs::InputError(o.polygon, o.where.empty() ? "has no polygon" : "has no polygon where " + o.where);
      ugs::cli::detail("{}: {} features, {} rings", o.polygon, v.features.size(), spec.rings.size());
    }
    ugs::SubmeshReport r;
    ugs::Mesh sub;
    try {
      sub = ugs::extract_submesh(parent, spec, &r);
    } catch (const ugs::InputError& e) {
      if (!e.where().empty()) throw;
      throw ugs::InputError(o.input == "-" ? "stdin" : o.input, e.what());
    }
    sub.provenance.push_back(tool.command_line());
    ugs::write_msh(sub, tool.output(), o.ascii ? ugs::MshEncoding::Ascii : ugs::MshEncoding::Binary);
    ugs::cli::info("{} tetrahedra ({}), {} nodes, {} boundary/fault triangles", r.tetrahedra, join(r.materials), r.nodes,
                   r.triangles);
    if (r.clipped_tetrahedra) ugs::cli::detail("{} tetrahedra of those materials lie outside the polygon", r.clipped_tetrahedra);
    if (r.dropped_interface_elements)
      ugs::cli::info("dropped {} interface elements; {} node pairs tied across non-barrier faults", r.dropped_interface_elements,
                     r.tied_pairs);
    if (!o.barriers.empty()) ugs::cli::info("barriers {}: {} nodes duplicated", join(o.barriers), r.duplicated_nodes);
  });
}
