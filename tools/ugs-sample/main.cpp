// ugs-sample — the simulated land displacement at InSAR persistent scatterers (thesis 2.3, 4.2.2):
// each PS point (EGMS ortho CSV, generic CSV with x,y or lon,lat, or any OGR point file) is
// reprojected to the model CRS, located on the model's top surface (the mesh group bnd:top, or the
// results' own triangles) and the displacement u (east, north, up) is interpolated linearly on its
// triangle at every output date (or at the PS file's dates, linearly in time), relative to a
// reference date, and projected on the line of sight of ascending/descending geometries.
// Points outside the top surface are reported, or kept with --keep-outside (sampled at the
// nearest point of the surface; the sampled location and its distance are written).
//
//   ugs-sample --results run.h5 --mesh model.msh --points insar_vertical.csv --case case.toml
//              --ascending 34/-10 --descending 39/-170 -o samples.csv
#include <cmath>

#include "ugs/cli/tool.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/insar/crs.hpp"
#include "ugs/insar/inputs.hpp"
#include "ugs/insar/los.hpp"
#include "ugs/insar/ps_data.hpp"
#include "ugs/insar/sampling.hpp"

namespace {

using namespace ugs;
using namespace ugs::insar;

struct Options {
  std::string results, mesh, points, crs, case_file, points_crs, id_column;
  std::string top_group = "bnd:top";
  std::string field;
  std::string reference;            // ISO date, "first", "none"
  bool at_ps_dates = false;
  bool keep_outside = false;
  std::string ascending, descending;
};

}  // namespace

int main(int argc, char** argv) {
  cli::Tool tool({"ugs-sample", "Sample the simulated displacement at InSAR PS points: east, north, up and line of sight.",
                  "ugs-sample --results run.h5 --mesh model.msh --points insar_vertical.csv --case case.toml "
                  "--ascending 34/-10 --descending 39/-170 -o samples.csv"});
  Options o;
  auto& app = tool.app();
  app.add_option("--results", o.results, "Results of ugs-solve (HDF5 with the node field u)")->required();
  app.add_option("--mesh", o.mesh, "Mesh of the results (MSH) for the top surface; default: the results' own cells");
  app.add_option("--top-group", o.top_group, "Surface group of the top in the mesh")->capture_default_str();
  app.add_option("--points", o.points, "PS points: EGMS CSV, CSV (x,y or lon,lat), or any OGR point file")->required();
  app.add_option("--points-crs", o.points_crs, "CRS of the points (default: EPSG:3035 for EGMS, EPSG:4326 for lon/lat, the layer's)");
  app.add_option("--id-column", o.id_column, "Column holding the point id (default: pid, id or name)");
  app.add_option("--crs", o.crs, "Model CRS (default: the case file's crs)");
  app.add_option("--case", o.case_file, "Case file (for its crs)");
  app.add_option("--field", o.field, "Displacement node field (default: u)");
  app.add_option("--reference", o.reference,
                 "Series relative to this date (ISO); 'first' = first PS date (EGMS) or first output date; 'none' = absolute")
      ->default_str("first");
  app.add_flag("--at-ps-dates", o.at_ps_dates, "Sample at the PS file's dates (linear in time) instead of the output dates");
  app.add_flag("--keep-outside", o.keep_outside, "Keep points outside the top surface (sampled at its nearest point)");
  app.add_option("--ascending", o.ascending, "Ascending geometry INCIDENCE/HEADING in degrees -> column los_asc_mm");
  app.add_option("--descending", o.descending, "Descending geometry INCIDENCE/HEADING in degrees -> column los_desc_mm");
  std::string& output = tool.add_output("-", "Sample table (CSV)");
  // The library names these settings in words; the messages show the flags.
  tool.name_setting("mesh of the top surface", "--mesh");
  tool.name_setting("model CRS", "--crs");
  tool.name_setting("points CRS", "--points-crs");
  return tool.run(argc, argv, [&] {
    std::vector<LosGeometry> los;
    if (!o.ascending.empty()) los.push_back(parse_los_geometry("asc", o.ascending, "--ascending"));
    if (!o.descending.empty()) los.push_back(parse_los_geometry("desc", o.descending, "--descending"));
    std::optional<std::int64_t> reference_date;
    if (!o.reference.empty() && o.reference != "first" && o.reference != "none") {
      reference_date = parse_iso_date(o.reference);
      if (!reference_date) throw InputError("--reference", fmt::format("'{}' is not an ISO 8601 date", o.reference));
    }

    // 1. Points in the model CRS.
    PsReadOptions ro;
    ro.model_crs = model_crs(o.crs, o.case_file);
    ro.points_crs = o.points_crs;
    ro.id_column = o.id_column;
    ro.require_series = o.at_ps_dates;
    const PsData ps = read_ps_in_model(o.points, ro);
    cli::detail("{}: {} points ({} layout, {}{}), {} dates", ps.path, ps.points.size(), ps.layout,
                crs_name(ps.source_crs), ps.reprojected ? " reprojected to " + crs_name(ro.model_crs) : "", ps.dates.size());

    // 2. Locate them on the top surface.
    const TopSurface surface = load_top_surface(o.mesh, o.top_group, o.results);
    const SurfaceLocator locator(surface);
    cli::detail("top surface: {} triangles ({})", surface.triangles.size(), surface.source);
    const Located located = locate_points(locator, ps.points, o.keep_outside);
    for (std::size_t i = 0; i < located.outside.size() && i < 10; ++i)
      cli::warning("point '{}' ({}) lies {:.1f} m outside the top surface: not sampled (--keep-outside keeps it)",
                   located.outside[i].point.id, located.outside[i].point.where, located.outside[i].hit.distance);
    if (located.outside.size() > 10) cli::warning("... and {} more points outside the top surface", located.outside.size() - 10);
    for (const auto& lp : located.sampled)
      if (!lp.hit.inside) cli::info("point '{}' lies {:.1f} m outside the top surface: sampled at its nearest point",
                                    lp.point.id, lp.hit.distance);
    if (located.sampled.empty())
      throw InputError(o.points, fmt::format("none of the {} points lies on the top surface (x {:.0f}..{:.0f}, y {:.0f}..{:.0f}); "
                                             "wrong CRS?", ps.points.size(), surface.extent()[0], surface.extent()[1],
                                             surface.extent()[2], surface.extent()[3]));

    // 3. Interpolate in space and time.
    SurfaceDisplacement results(o.results, surface, o.field);
    if (!reference_date && o.reference != "none")
      reference_date = ps.has_series() ? ps.dates.front() : results.times().front();
    std::vector<std::int64_t> dates;
    if (o.at_ps_dates) {
      std::size_t dropped = 0;
      for (auto t : ps.dates)
        if (t >= results.times().front() && t <= results.times().back())
          dates.push_back(t);
        else
          ++dropped;
      if (dates.empty())
        throw InputError(o.results, fmt::format("no PS date ({} .. {}) lies within the results ({} .. {})",
                                                format_iso_date(ps.dates.front()), format_iso_date(ps.dates.back()),
                                                format_iso_date(results.times().front()), format_iso_date(results.times().back())));
      if (dropped) cli::warning("{} PS dates outside the results ({} .. {}) are left out", dropped,
                                format_iso_date(results.times().front()), format_iso_date(results.times().back()));
    }
    const Samples s = sample_displacement(results, located.sampled, dates, reference_date);

    std::vector<std::string> comments{tool.command_line(),
                                      fmt::format("displacement '{}' from {} ({} steps); top surface {}", results.field(),
                                                  o.results, results.times().size(), surface.source),
                                      reference_date ? "series relative to " + format_iso_date(*reference_date)
                                                     : std::string("absolute displacement (no reference date)")};
    for (const auto& g : los) {
      const auto l = los_unit_vector(g);
      comments.push_back(fmt::format("los_{}: incidence {} deg, heading {} deg, right-looking; ground-to-satellite unit "
                                     "vector (E, N, U) = ({:.4f}, {:.4f}, {:.4f}); positive towards the satellite",
                                     g.name, g.incidence_deg, g.heading_deg, l[0], l[1], l[2]));
    }
    write_samples_csv(output, s, los, comments);
    cli::detail("sampled {} points at {} dates", s.points.size(), s.dates.size());
  });
}
