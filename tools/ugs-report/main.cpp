// ugs-report — the pictures people look at (thesis 4.2.2, 4.3): from the results of ugs-solve,
//   - maps of u_x, u_y, u_z over each phase (storage, production, forecast; figures 4.21-4.26,
//     4.37-4.39) with the reservoir trace, as PNG and as GeoTIFF (model CRS, mm);
//   - time series at each PS point, simulated against measured, with the pool pressures (4.15-4.20);
//   - the normalized stress change along the sections (4.27-4.32, vertical exaggeration) and
//     above the top of Pool C (4.33-4.35);
//   - chi on the faults for the minimum and maximum pressure scenarios (4.43-4.44), given the
//     faulted solver's results;
//   - the calibration's misfit profile, given an ugs-calibrate folder;
//   - the ensemble's tornado and fan charts, given an ugs-ensemble folder (ensemble.cpp);
//   - summary.html / summary.md: the headline numbers next to the thesis' and every figure.
// Data go to plots.py (matplotlib, Debian's /usr/bin/python3) as CSV/NPY files and a JSON list of
// figures; GeoTIFFs are written here with GDAL. The output folder appears only when complete.
//
//   ugs-report --results solve.h5 --mesh model.msh --case case.toml --measured insar_vertical.csv
//              --trace reservoir_traces.geojson --sections sections.geojson -o report
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "report.hpp"
#include "ugs/cli/number_option.hpp"
#include "ugs/cli/tool.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/insar/crs.hpp"
#include "ugs/insar/inputs.hpp"
#include "ugs/insar/sampling.hpp"
#include "ugs/meshing/geodata.hpp"
#include "ugs/runner/output_folder.hpp"
#include "ugs/runner/subprocess.hpp"

namespace {

using namespace ugs;
using namespace ugs::report;
namespace fs = std::filesystem;

std::vector<Phase> parse_phases(const std::vector<std::string>& specs, const std::vector<std::int64_t>& times, const CaseFile* cs,
                                bool thesis_phases, std::vector<std::string>& notes) {
  std::vector<Phase> out;
  for (const auto& s : specs) {
    const auto eq = s.find('='), slash = s.find('/', eq == std::string::npos ? 0 : eq);
    if (eq == std::string::npos || slash == std::string::npos || eq == 0)
      throw InputError("--phase " + s, "expected NAME=START/END, e.g. storage=2015-05-01/2015-11-01");
    Phase p;
    p.name = s.substr(0, eq);
    const auto a = parse_iso_date(s.substr(eq + 1, slash - eq - 1)), b = parse_iso_date(s.substr(slash + 1));
    if (!a || !b) throw InputError("--phase " + s, "dates must be ISO 8601");
    if (*a >= *b) throw InputError("--phase " + s, "the start must come before the end");
    p.start = *a;
    p.end = *b;
    out.push_back(p);
  }
  if (!out.empty()) return out;
  // The study's own phases ([[report.phase]] of the case).
  if (cs && cs->report && !cs->report->phases.empty()) {
    for (const auto& p : cs->report->phases) {
      const Phase ph{p.name, *parse_iso_date(p.start), *parse_iso_date(p.end)};
      if (ph.start < times.front() || ph.end > times.back())
        throw InputError(cs->report->where, fmt::format("[[report.phase]] '{}' ({} to {}) is outside the results ({} to {})", p.name,
                                                        p.start, p.end, format_iso_date(times.front()), format_iso_date(times.back())));
      out.push_back(ph);
    }
    return out;
  }
  if (!thesis_phases) {
    out.push_back({"run", times.front(), times.back()});
    return out;
  }
  // The thesis' phases, where the results reach them.
  const std::pair<const char*, const char*> thesis[] = {{"storage", "2015-05-01/2015-11-01"},
                                                        {"production", "2015-11-01/2016-05-01"},
                                                        {"forecast storage", "2025-05-01/2025-11-01"}};
  for (const auto& [name, span] : thesis) {
    const std::string sp = span;
    const auto a = *parse_iso_date(sp.substr(0, 10)), b = *parse_iso_date(sp.substr(11));
    if (a >= times.front() && b <= times.back()) out.push_back({name, a, b});
  }
  if (out.empty()) {
    out.push_back({"run", times.front(), times.back()});
    notes.push_back("the results do not reach the thesis' phases (2015-05-01 .. 2016-05-01): the phase is the whole run "
                    "(give --phase NAME=START/END)");
  }
  return out;
}

std::string find_plots_script() {
  if (const char* e = std::getenv("UGS_REPORT_PLOTS")) return e;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (const fs::path& p : {exe.parent_path() / "plots.py", exe.parent_path().parent_path() / "share" / "ugs" / "plots.py"})
      if (fs::exists(p)) return p.string();
  }
  throw ComputeError("plots.py not found beside ugs-report nor in ../share/ugs (set UGS_REPORT_PLOTS)");
}

}  // namespace

int main(int argc, char** argv) {
  cli::Tool tool({"ugs-report", "Maps, sections, time series, fault safety and a summary page of a ugs-solve run (PNG, GeoTIFF).",
                  "ugs-report --results solve.h5 --mesh model.msh --case case.toml --measured insar_vertical.csv "
                  "--trace reservoir_traces.geojson --sections sections.geojson -o report"});
  Options o;
  auto& app = tool.app();
  app.add_option("--results", o.results, "Results of ugs-solve (HDF5: u, stress fields)")->required();
  app.add_option("--top", o.top, "Top-surface series of ugs-solve (default: <results>_top.h5 if present, else the results)");
  app.add_option("--mesh", o.mesh, "Mesh of the results (names of materials and faults, the top surface)");
  app.add_option("--case", o.case_file, "Case file (pools, pressures, CRS)");
  app.add_option("--crs", o.crs, "Model CRS (default: the case's crs)");
  app.add_option("--measured", o.measured, "Measured vertical PS series (EGMS CSV)");
  app.add_option("--measured-east", o.measured_east, "Measured east-west PS series (EGMS CSV)");
  app.add_option("--samples", o.samples, "Simulated series at the PS points (ugs-sample table; default: sampled here)");
  app.add_option("--trace", o.trace, "Reservoir trace (any OGR polygon or line file)");
  app.add_option("--trace-where", o.trace_where, "OGR attribute filter on the trace file");
  app.add_option("--sections", o.sections, "Section lines (any OGR line file; attribute name, from_label, to_label)");
  app.add_option("--sections-where", o.sections_where, "OGR attribute filter on the section lines");
  app.add_option("--faults", o.faults, "Fault results of the faulted solver (<output>_faults.h5: chi at the node pairs)");
  app.add_option("--fault-table", o.fault_table,
                 "Faults CSV of the faulted solver, for max chi against time (default: <faults stem>.csv beside --faults)");
  app.add_option("--fault-field", o.fault_field, "Safety-factor field in the fault results")->capture_default_str();
  app.add_option("--fault-dates", o.fault_dates, "MIN_DATE,MAX_DATE: the minimum and maximum pressure scenarios");
  app.add_option("--phase", o.phases, "NAME=START/END (repeat); default: the case's [[report.phase]], else with --thesis "
                                      "the thesis' storage 2015, production 2015-16, forecast 2025, else the whole run");
  app.add_flag("--thesis", o.thesis,
               "Compare with the thesis (the po-plain twin): its phases by default and its values beside the headlines");
  app.add_option("--stress-pool", o.stress_pool, "Pool whose layer the stress pictures look at (default: Pool C)");
  app.add_option("--stress-field", o.stress_field, "Stress cell field (default: stress_change, dstress or stress)");
  app.add_option("--reference-pressure-MPa", o.reference_pressure_MPa, "Normalisation of stress changes (default: the pool's)")
      ->check(cli::number_in(0, cli::kNoLimit));
  app.add_option("--exaggeration", o.exaggeration, "Vertical exaggeration of the sections")
      ->capture_default_str()
      ->check(cli::number_in(0, 1e6, cli::Ends::OpenLow));
  app.add_option("--edge-distance", o.edge_distance,
                 "Metres from the reservoir trace within which the fault patch that limits the safe scale is called at the "
                 "reservoir's edge (a mesh-dependent answer)")
      ->capture_default_str()
      ->check(cli::number_in(0, 1e6));
  app.add_option("--section-zrange", o.section_zrange, "ZMIN/ZMAX of the sections (default: the pool layer +- 150 m)");
  app.add_option("--compare", o.compare,
                 "LABEL=FILE (repeat): another run's top-surface series on the same mesh; the report compares the "
                 "vertical displacement over the trace");
  app.add_option("--compare-since", o.compare_since, "YYYY-MM-DD: the runs' changes count from this date (default: the first date they share)");
  app.add_option("--calibration", o.calibration, "An ugs-calibrate output folder: its misfit profile and best values");
  app.add_option("--ensemble", o.ensemble, "An ugs-ensemble output folder: tornado chart, fan charts of the PS series, chi exceedance")
      ->check(CLI::ExistingDirectory);
  app.add_option("--seismicity", o.seismicity,
                 "ugs-seismicity's per fault and date table (its _windows.csv and _pairs.csv beside it): R/r series, event "
                 "density map, expected events and P(M >= m) as headlines");
  app.add_option("--seismicity-window", o.seismicity_window, "START/END of the event density map (default: the first window)");
  app.add_option("--scenario", o.scenario,
                 "ugs-solve's safe-scale table (<output>_scenario.csv): the maximum safe scale, what limits it and the "
                 "maximum safe pressure per pool (MPa) as headlines")
      ->check(CLI::ExistingFile);
  app.add_option("--caprock", o.caprock,
                 "ugs-solve's caprock table (<output>_caprock.csv): the seals' smallest tensile and shear margins as headlines")
      ->check(CLI::ExistingFile);
  app.add_option("--discussion", o.discussion,
                 "Markdown file: why this case's numbers differ from the thesis' (a section of the summary)")
      ->check(CLI::ExistingFile);
  app.add_option("--raster-cell", o.raster_cell, "GeoTIFF cell size in m (default: about 400 cells across)")
      ->check(cli::number_in(0, cli::kNoLimit));
  app.add_option("--map-extent", o.map_extent, "XMIN/XMAX/YMIN/YMAX of the PNG maps (default: around the trace)");
  app.add_option("--python", o.python, "Python with matplotlib (default: /usr/bin/python3)");
  app.add_option("--width", o.width, "PNG width in pixels")->capture_default_str()->check(cli::number_in(200, 8000));
  app.add_option("--height", o.height, "PNG height in pixels")->capture_default_str()->check(cli::number_in(200, 8000));
  app.add_flag("--keep-work", o.keep_work, "Keep the CSV/NPY files handed to plots.py (work/ in the output)");
  std::string& output = tool.add_output("report", "Output folder");
  // The library names this setting in words; the messages show the flag.
  tool.name_setting("raster cell size", "--raster-cell");
  tool.name_setting("mesh of the top surface", "--mesh");
  tool.name_setting("model CRS", "--crs");
  tool.name_setting("seismicity window", "--seismicity-window");
  return tool.run(argc, argv, [&] {
    if (!o.section_zrange.empty()) {
      const auto z = insar::parse_number_list("--section-zrange", o.section_zrange, 2, "ZMIN/ZMAX");
      if (!(z[0] < z[1])) throw InputError("--section-zrange", fmt::format("'{}': ZMIN is not below ZMAX", o.section_zrange));
    }
    if (!o.map_extent.empty()) {
      const auto e = insar::parse_number_list("--map-extent", o.map_extent, 4, "XMIN/XMAX/YMIN/YMAX");
      if (!(e[0] < e[1]) || !(e[2] < e[3]))
        throw InputError("--map-extent", fmt::format("'{}': XMIN/YMIN are not below XMAX/YMAX", o.map_extent));
    }
    Context c;
    c.opt = o;
    c.command_line = tool.command_line();
    // 1. Inputs.
    if (!o.case_file.empty()) c.cs = read_case_file(o.case_file);
    c.crs_wkt = insar::model_crs(o.crs, o.case_file);
    if (c.crs_wkt.empty()) c.notes.push_back("no model CRS (--crs or the case's crs): GeoTIFFs carry no CRS");
    if (!o.mesh.empty()) c.mesh = read_msh(o.mesh);
    if (!o.seismicity.empty()) {
      // Checked before the long work: the columns of the R/r plot (build_seismicity reads it again).
      const CsvTable t = CsvTable::read(o.seismicity);
      for (const char* col : {"date", "fault", "R_over_r", "R_over_r_max"}) (void)t.column(col);
    }
    if (!o.fault_table.empty()) {
      // Checked before the long work: the columns of the max-chi plot (build_faults reads it again).
      const CsvTable t = CsvTable::read(o.fault_table);
      for (const char* col : {"date", "fault", "max_chi"}) (void)t.column(col);
    }
    c.results = std::make_unique<FieldSeriesReader>(o.results);
    if (c.results->steps().empty()) throw InputError(o.results, "has no steps");
    for (const auto& s : c.results->steps()) c.result_times.push_back(insar::step_time(s));
    c.surface_results = o.top;
    if (c.surface_results.empty()) {
      const std::string stem = o.results.size() > 3 && o.results.substr(o.results.size() - 3) == ".h5"
                                   ? o.results.substr(0, o.results.size() - 3) : o.results;
      c.surface_results = fs::exists(stem + "_top.h5") ? stem + "_top.h5" : o.results;
    }
    if (c.mesh && c.mesh->find_physical(2, "bnd:top"))
      c.top = insar::surface_from_mesh(*c.mesh, "bnd:top", o.mesh);
    else
      c.top = insar::load_top_surface("", "", c.surface_results);
    std::vector<std::int64_t> surface_times;
    {
      const FieldSeriesReader sr(c.surface_results);
      for (const auto& s : sr.steps()) surface_times.push_back(insar::step_time(s));
    }
    c.phases = parse_phases(o.phases, surface_times, c.cs ? &*c.cs : nullptr, o.thesis, c.notes);
    if (!o.trace.empty()) {
      const auto v = geo::read_vector(o.trace, c.crs_wkt, o.trace_where);
      for (const auto& f : v.features) {
        for (const auto& poly : f.polygons) {
          std::vector<std::array<double, 2>> ring(poly.outer.begin(), poly.outer.end());
          if (!ring.empty()) ring.push_back(ring.front());
          c.trace_lines.push_back(ring);
        }
        for (const auto& l : f.lines) c.trace_lines.emplace_back(l.begin(), l.end());
      }
      if (c.trace_lines.empty()) throw InputError(o.trace, "has no polygon or line (check --trace-where)");
    }
    insar::PsReadOptions ro;
    ro.model_crs = c.crs_wkt;
    ro.require_series = true;
    if (!o.measured.empty()) c.measured_up = insar::read_ps(o.measured, ro);
    if (!o.measured_east.empty()) c.measured_east = insar::read_ps(o.measured_east, ro);
    if (c.measured_up && c.crs_wkt.empty() && !c.measured_up->source_crs.empty())
      throw InputError(o.measured, fmt::format("points are in {}, but the model CRS is unknown: give --crs or --case",
                                               insar::crs_name(c.measured_up->source_crs)));
    // Measured series to compare with, none of them on the model: a wrong CRS or the wrong file,
    // refused as ugs-sample and ugs-calibrate do (a report without the comparison asked for
    // would look complete).
    if (c.measured_up && o.samples.empty()) insar::require_some_on_surface(*c.top, *c.measured_up);

    // 2. The data of every figure, into the work folder.
    runner::OutputFolder out(output);
    c.out = fs::absolute(out.temp()).string();
    c.work = c.out + "/work";
    fs::create_directories(c.work);
    if (!c.trace_lines.empty()) {
      CsvWriter w(c.work_file("trace.csv"), {"part", "x", "y"});
      for (std::size_t i = 0; i < c.trace_lines.size(); ++i)
        for (const auto& p : c.trace_lines[i]) w.integer(static_cast<std::int64_t>(i)).number(p[0], 3).number(p[1], 3).end_row();
      w.commit();
    }
    build_maps(c);
    build_series(c);
    build_stress(c);
    build_faults(c);
    build_calibration(c);
    build_ensemble(c);
    build_seismicity(c);
    build_safety(c);
    build_seal_pictures(c);
    build_comparison(c);
    build_acceptance(c);
    if (c.figures.empty()) throw InputError(o.results, "nothing to draw: " + (c.notes.empty() ? std::string("?") : c.notes.front()));

    // 3. The pictures: plots.py draws every figure of the manifest.
    {
      std::string m = fmt::format("{{\n\"width\": {}, \"height\": {}, \"dpi\": {},\n\"figures\": [\n", o.width, o.height, o.dpi);
      for (std::size_t i = 0; i < c.figures.size(); ++i) {
        const auto& f = c.figures[i];
        m += fmt::format("{{\"kind\": {}, \"png\": {}, \"title\": {}, {}}}{}\n", jstr(f.kind), jstr(f.png), jstr(f.title), f.json,
                         i + 1 < c.figures.size() ? "," : "");
      }
      m += "]\n}\n";
      OutputFile mf(c.work_file("manifest.json"));
      mf.write(m);
      mf.commit();
    }
    std::string python = o.python;
    if (python.empty()) python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    const std::string script = find_plots_script();
    cli::detail("drawing {} figures with {} {}", c.figures.size(), python, script);
    fs::create_directories(c.work + "/mpl");
    const auto r = runner::run_command({python, script, "work/manifest.json"}, c.out, c.work_file("plots.log"),
                                      {{"MPLBACKEND", "Agg"}, {"MPLCONFIGDIR", c.work + "/mpl"}, {"PYTHONHASHSEED", "0"},
                                       {"SOURCE_DATE_EPOCH", "0"}});
    if (r.exit_code != 0)
      throw ComputeError(fmt::format("plots.py failed (exit code {}): {}", r.exit_code, runner::last_line(c.work_file("plots.log"))));
    for (const auto& f : c.figures)
      if (!fs::exists(c.out + "/" + f.png)) throw ComputeError(fmt::format("plots.py did not write {}", f.png));

    // 4. The summary page, then everything appears at once.
    write_summary(c);
    if (!o.keep_work) fs::remove_all(c.work);
    out.commit();
    for (const auto& n : c.notes) cli::info("note: {}", n);
    std::printf("%zu figures, %zu GeoTIFFs and summary.html in %s\n", c.figures.size(), c.written.size(),
                out.target().string().c_str());
    for (const auto& h : c.headlines)
      if (h.group.find("InSAR") == std::string::npos)
        std::printf("  %s: %s: %s%s\n", h.group.c_str(), h.quantity.c_str(), h.value.c_str(),
                    h.thesis.empty() || !o.thesis ? "" : ("  [thesis: " + h.thesis + "]").c_str());
  });
}
