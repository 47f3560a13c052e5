// ugs-import-eclipse — the pore-pressure change of a reservoir simulation (ECLIPSE, OPM Flow,
// Intersect, tNavigator: ECLIPSE binary output) on the mechanics mesh: for each tetrahedron whose
// centroid lies in an active grid cell, dp = PRESSURE(step) - PRESSURE(first step) in Pa at every
// report step, as the cell field `dp` of a ugs-fields file that ugs-solve --pressure reads. The file
// holds the tetrahedra that got a value (their parent node and element tags); the others get none
// and are counted. Corner points in map coordinates (MAPAXES applied in double), depth down -> z
// up, lengths in m, pressures in Pa (docs/eclipse.md).
//
//   flow CASE.DATA && ugs-import-eclipse CASE.EGRID --mesh model.msh -o dp_sim.h5
//   ugs-import-eclipse CASE.EGRID --restart CASE.X0000 --mesh model.msh --case case.toml --offset 0,0,-5 -o dp_sim.h5
//
// With --export, the way back: ugs-solve's volumetric strain change and mean effective stress
// change per active cell, at the dates asked, as GRDECL keywords (grdecl.hpp):
//
//   ugs-import-eclipse CASE.EGRID --export solve.h5 --dates 2020-03-01,2020-04-30 -o ugs_mech.grdecl
#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "ugs/cli/number_option.hpp"
#include "ugs/cli/tool.hpp"
#include "ugs/eclipse/eclipse.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/meshing/cell_locator.hpp"

#include "grdecl.hpp"

namespace {

struct Options {
  std::string egrid;
  std::string restart;
  std::string mesh;
  std::string case_file;
  std::vector<double> offset;
  std::string export_results;
  std::vector<std::string> dates;
};

std::string extent_text(const std::array<double, 6>& b) {
  return fmt::format("x {:.1f}..{:.1f}, y {:.1f}..{:.1f}, z {:.1f}..{:.1f}", b[0], b[3], b[1], b[4], b[2], b[5]);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  ugs::cli::Tool tool({"ugs-import-eclipse",
                       "Map the pressure change of a reservoir simulation (ECLIPSE binary EGRID + restart) onto the tetrahedra "
                       "of a mechanics mesh, as the cell field dp of a ugs-fields file for ugs-solve --pressure.",
                       "ugs-import-eclipse CASE.EGRID --restart CASE.UNRST --mesh model.msh -o dp_sim.h5"});
  Options o;
  auto& app = tool.app();
  app.add_option("egrid", o.egrid, "Grid of the simulation (CASE.EGRID)")->required();
  app.add_option("--restart", o.restart,
                 "Restart: unified CASE.UNRST, or any of the non-unified CASE.X0000, CASE.X0001, ... (all are read); "
                 "default: the one beside the EGRID");
  app.add_option("--mesh", o.mesh, "Mechanics mesh (MSH 4.1; '-' = stdin)");
  app.add_option("--case", o.case_file,
                 "Case file: only tetrahedra of its pools' materials and aquifer_materials take the simulator's pressure");
  app.add_option("--offset", o.offset, "dx,dy,dz [m] added to the grid's map coordinates (a local grid origin)")
      ->delimiter(',')
      ->expected(3)
      ->check(ugs::cli::number_in(-ugs::cli::kNoLimit, ugs::cli::kNoLimit));
  app.add_option("--export", o.export_results,
                 "The way back: ugs-solve results (strain, stress_change) to GRDECL keywords per active cell, written to -o");
  app.add_option("--dates", o.dates, "With --export: the output dates to write (default: all), comma-separated")->delimiter(',');
  tool.add_output("", "Pressure change field series (HDF5 + XDMF beside it); with --export, the GRDECL file");
  return tool.run(argc, argv, [&] {
    ugs::Point3 offset{0, 0, 0};
    if (!o.offset.empty()) {
      for (int d = 0; d < 3; ++d) {
        offset[d] = o.offset[d];
      }
    }
    if (!o.export_results.empty()) {
      if (!o.restart.empty() || !o.mesh.empty() || !o.case_file.empty())
        throw ugs::InputError("--export", "goes without --restart, --mesh and --case (the results file holds its mesh)");
      if (tool.output().empty()) throw ugs::InputError("-o", "give the GRDECL file to write ('-' = stdout)");
      const ugs::eclipse::Grid grid = ugs::eclipse::read_egrid(o.egrid, offset);
      const auto r = ugs::eclipse::export_grdecl(grid, o.export_results, o.dates, tool.output(), tool.command_line());
      ugs::cli::info("wrote {}: {} keywords; {} of {} tetrahedra in active cells, {} active cells hold none (written as 0)", tool.output(),
                     r.keywords.size(), r.tetrahedra - r.outside, r.tetrahedra, r.empty_cells);
      return;
    }
    if (!o.dates.empty()) throw ugs::InputError("--dates", "goes with --export");
    if (o.mesh.empty()) throw ugs::InputError("--mesh", "give the mechanics mesh the pressure goes onto");
    if (tool.output().empty() || tool.output() == "-")
      throw ugs::InputError("-o", "give the output file (dp.h5): HDF5 needs a file, not a pipe");
    std::set<std::string> materials;  // with --case: "mat:<name>" of the pools' materials
    if (!o.case_file.empty()) {
      const ugs::CaseFile cs = ugs::read_case_file(o.case_file);
      for (const auto& p : cs.pools) {
        for (const auto& m : p.materials) materials.insert("mat:" + m);
        for (const auto& m : p.aquifer_materials) materials.insert("mat:" + m);
      }
      if (materials.empty()) throw ugs::InputError(o.case_file, "no [[pool]] with materials: nothing would take the pressure");
    }

    // 1. The grid and the restart, checked against each other before anything heavy.
    const auto t0 = std::chrono::steady_clock::now();
    const ugs::eclipse::Grid grid = ugs::eclipse::read_egrid(o.egrid, offset);
    if (o.restart.empty()) {
      o.restart = ugs::eclipse::default_restart(o.egrid);
      if (o.restart.empty())
        throw ugs::InputError(o.egrid, "no restart beside it (CASE.UNRST or CASE.X0000); name one with --restart");
    }
    ugs::eclipse::Restart restart(o.restart);
    restart.check_grid(grid);
    const auto tg = std::chrono::steady_clock::now();
    const auto& steps = restart.steps();

    // 2. Every tetrahedron's centroid in an active cell.
    const ugs::Mesh mesh = ugs::read_msh(o.mesh);
    std::vector<ugs::Point3> centroids;
    std::vector<std::pair<std::size_t, std::size_t>> tets;  // (block, element)
    std::size_t other_material = 0;
    for (std::size_t b = 0; b < mesh.blocks.size(); ++b) {
      const auto& blk = mesh.blocks[b];
      if (blk.type != ugs::ElementType::Tetrahedron) continue;
      const bool take = materials.empty() || materials.count(mesh.physical_name_of(blk.entity_dim, blk.entity_tag));
      for (std::size_t e = 0; e < blk.size(); ++e) {
        if (!take) {
          ++other_material;
          continue;
        }
        ugs::Point3 c{0, 0, 0};
        for (const std::uint32_t n : blk.element(e))
          for (int d = 0; d < 3; ++d) c[d] += 0.25 * mesh.nodes[n][d];
        centroids.push_back(c);
        tets.emplace_back(b, e);
      }
    }
    if (centroids.empty())
      throw ugs::InputError(o.mesh, materials.empty() ? "no tetrahedra" : "no tetrahedra of the case's pool materials");
    const auto t1 = std::chrono::steady_clock::now();
    const ugs::HexLocator locator(grid.corners);
    const std::vector<std::int64_t> cell = locator.locate(centroids);
    const double locate_s = seconds_since(t1);
    std::size_t located = 0;
    for (const auto c : cell) located += c >= 0;
    if (located == 0) {
      std::array<double, 6> mb{1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
      for (const auto& p : centroids)
        for (int d = 0; d < 3; ++d) {
          mb[d] = std::min(mb[d], p[d]);
          mb[d + 3] = std::max(mb[d + 3], p[d]);
        }
      throw ugs::InputError(o.egrid, fmt::format("the grid ({}) does not overlap the mesh {} (tetrahedron centroids {}): same CRS? "
                                                 "--offset for a local grid origin",
                                                 extent_text(locator.extent()), o.mesh, extent_text(mb)));
    }

    // 3. The sub-mesh of the located tetrahedra, with the parent's node and element tags.
    ugs::Mesh sub;
    sub.physicals = mesh.physicals;
    sub.entities = mesh.entities;
    sub.provenance = mesh.provenance;
    sub.provenance.push_back(tool.command_line());
    std::vector<std::int64_t> new_node(mesh.num_nodes(), -1);
    std::vector<std::uint32_t> active_of;  // active cell of each written tetrahedron, in output order
    active_of.reserve(located);
    for (std::size_t b = 0; b < mesh.blocks.size(); ++b) {
      ugs::ElementBlock* out = nullptr;
      for (std::size_t t = 0; t < tets.size(); ++t) {
        if (tets[t].first != b || cell[t] < 0) continue;
        const auto& blk = mesh.blocks[b];
        if (!out) {
          sub.blocks.push_back({blk.entity_dim, blk.entity_tag, blk.type, {}, {}});
          out = &sub.blocks.back();
        }
        out->tags.push_back(blk.tags[tets[t].second]);
        for (const std::uint32_t n : blk.element(tets[t].second)) {
          if (new_node[n] < 0) {
            new_node[n] = static_cast<std::int64_t>(sub.nodes.size());
            sub.nodes.push_back(mesh.nodes[n]);
            sub.node_tags.push_back(mesh.node_tags[n]);
          }
          out->nodes.push_back(static_cast<std::uint32_t>(new_node[n]));
        }
        active_of.push_back(static_cast<std::uint32_t>(cell[t]));
      }
    }
    const std::size_t outside = centroids.size() - located;
    // Everything is checked: the messages start here, so a refused input gives one line only.
    ugs::cli::info("{}: {} x {} x {} cells, {} active, {} NNCs, {}{}; {}: {} report steps {} .. {}", o.egrid, grid.dims[0],
                   grid.dims[1], grid.dims[2], grid.num_active(), grid.nnc, grid.length_unit, grid.mapaxes ? ", MAPAXES" : "",
                   o.restart, steps.size(), steps.front().date, steps.back().date);
    ugs::cli::info("{} of {} tetrahedra in active cells; {} outside every active cell get no value{}", located,
                   centroids.size() + other_material, outside,
                   other_material ? fmt::format("; {} not of the case's pool materials", other_material) : std::string());

    // 4. dp per report step.
    const auto t2 = std::chrono::steady_clock::now();
    ugs::FieldSeriesOptions fo;
    fo.cell_types = {ugs::ElementType::Tetrahedron};
    ugs::FieldSeriesWriter writer(tool.output(), sub, fo);
    const std::vector<double> p0 = restart.pressure(0);
    double lo = 0, hi = 0, read_s = 0;
    for (std::size_t s = 0; s < steps.size(); ++s) {
      const auto tr = std::chrono::steady_clock::now();
      const std::vector<double> p = s == 0 ? p0 : restart.pressure(s);
      read_s += seconds_since(tr);
      ugs::Field dp{"dp", 1, std::vector<double>(active_of.size())};
      for (std::size_t t = 0; t < active_of.size(); ++t) {
        dp.values[t] = p[active_of[t]] - p0[active_of[t]];
        lo = std::min(lo, dp.values[t]);
        hi = std::max(hi, dp.values[t]);
      }
      writer.add_step(steps[s].date, static_cast<double>(steps[s].time), {}, std::span<const ugs::Field>(&dp, 1));
    }
    writer.commit();
    ugs::cli::info("wrote {}: dp {:.4f} .. {:.4f} MPa over {} report steps", tool.output(), lo / 1e6, hi / 1e6, steps.size());
    ugs::cli::detail("timing: reading the grid and restart headers {:.2f} s, the mesh {:.2f} s, locating {:.2f} s, {} steps {:.2f} s ({:.3f} s per "
                     "step, of which reading PRESSURE {:.3f} s)",
                     std::chrono::duration<double>(tg - t0).count(), std::chrono::duration<double>(t1 - tg).count(), locate_s, steps.size(), seconds_since(t2),
                     seconds_since(t2) / static_cast<double>(steps.size()), read_s / static_cast<double>(steps.size()));
  });
}
