// ugs-calibrate — calibration of model parameters against InSAR series (thesis 4.2.2): finds the
// values of case-file parameters (e.g. c_R of Pool C and its aquifer, c_R of Pool A, aquifer
// conductivity) that minimise the RMS difference between simulated and measured vertical (and
// optionally east-west) displacement at chosen PS points over a date window, each series' offset
// removed. Every evaluation writes a modified copy of the case, runs the solver command as a
// subprocess and samples its result in-process; evaluations are cached by parameter value and run
// concurrently (-j). A scan of the bounds gives the misfit profile, then Brent's method (one
// parameter) or NLopt's BOBYQA (several) refines the best value. With --response reciprocal (one
// parameter whose series respond affinely to 1/x, as c_R's reloading uplift) three concurrent runs
// give a model of the series whose misfit minimum one run checks (reciprocal.hpp).
// Outputs (-o FOLDER): best.toml (the calibrated case), parameters.csv, misfit_points.csv,
// profile.csv (every evaluation), best_samples.csv (the best run at the PS dates, as ugs-sample)
// and, with --response reciprocal, model_profile.csv (the modelled misfit over the range).
//
//   ugs-calibrate --case case.toml --mesh model.msh --param material.pool_c.c_R,material.aquifer_pool_c.c_R=2:6
//     --measured insar_vertical.csv --inside reservoir_traces.geojson --window 2003-01-01/2021-12-31
//     --solver-command "ugs-solve {mesh} --case {case} --pressure dp_a.h5 --pressure dp_c.h5 --top {out} -o {dir}/solve.h5"
//     -j 2 -o calibration
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <set>

#include "ugs/calibration/evaluator.hpp"
#include "ugs/calibration/optimizer.hpp"
#include "ugs/calibration/reciprocal.hpp"
#include "ugs/cli/number_option.hpp"
#include "ugs/cli/tool.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/insar/crs.hpp"
#include "ugs/insar/inputs.hpp"
#include "ugs/insar/ps_data.hpp"
#include "ugs/insar/sampling.hpp"
#include "ugs/meshing/geodata.hpp"
#include "ugs/runner/case_params.hpp"
#include "ugs/runner/output_folder.hpp"

namespace {

using namespace ugs;
using namespace ugs::insar;
using namespace ugs::runner;
using namespace ugs::calibration;
namespace fs = std::filesystem;

struct Options {
  std::string case_file, mesh, top_group = "bnd:top", solver_command;
  std::vector<std::string> params;
  std::string measured, measured_east, points_crs, crs, id_column;
  double east_weight = 1.0;
  std::vector<std::string> points;
  std::string inside, inside_where;
  std::string window;
  std::string field;
  std::string cache_dir;
  int jobs = 1;
  bool keep_results = false;
  int scan = -1;
  double xtol = 0.005;
  int max_evals = 60;
  std::string response = "general";
};

std::string fmt_value(double v) { return fmt::format("{:.6g}", v); }

}  // namespace

int main(int argc, char** argv) {
  cli::Tool tool({"ugs-calibrate", "Calibrate case-file parameters against InSAR series (cached, concurrent solver runs).",
                  "ugs-calibrate --case case.toml --mesh model.msh --param material.pool_c.c_R=2:6 --measured "
                  "insar_vertical.csv --inside reservoir_traces.geojson --window 2003-01-01/2021-12-31 --solver-command "
                  "\"ugs-solve {mesh} --case {case} --pressure dp.h5 --top {out} -o {dir}/solve.h5\" -j 2 -o calibration"});
  Options o;
  auto& app = tool.app();
  app.add_option("--case", o.case_file, "Case file (TOML) whose parameters are calibrated")->required();
  app.add_option("--param", o.params,
                 "PATH[,PATH...]=LOWER:UPPER[:log], a number in the case, e.g. material.pool_c.c_R=2:6 (repeat for more)")
      ->required();
  app.add_option("--solver-command", o.solver_command,
                 "Command run for each evaluation ({case}, {out}, {mesh}, {dir} are replaced; it must write {out})")
      ->required();
  app.add_option("--mesh", o.mesh, "Mesh ({mesh}, and its top surface for sampling; default: the results' own cells)");
  app.add_option("--top-group", o.top_group, "Surface group of the top in the mesh")->capture_default_str();
  app.add_option("--measured", o.measured, "Measured vertical series: EGMS CSV (or CSV with YYYYMMDD columns), mm")->required();
  app.add_option("--measured-east", o.measured_east, "Measured east-west series, added to the misfit with --east-weight");
  app.add_option("--east-weight", o.east_weight, "Weight of east-west residuals in the misfit")
      ->capture_default_str()
      ->check(cli::number_in(0, cli::kNoLimit));
  app.add_option("--points", o.points, "PS ids used in the misfit (comma-separated; default: all)")->delimiter(',');
  app.add_option("--inside", o.inside, "Use only the PS inside these polygons (any OGR file, e.g. the reservoir trace)");
  app.add_option("--inside-where", o.inside_where, "OGR attribute filter on the --inside polygons, e.g. \"name = 'Pool C'\"");
  app.add_option("--window", o.window, "Dates compared, START/END (ISO; either may be empty)");
  app.add_option("--points-crs", o.points_crs, "CRS of the PS coordinates (default: EPSG:3035 for EGMS)");
  app.add_option("--crs", o.crs, "Model CRS (default: the case file's crs)");
  app.add_option("--id-column", o.id_column, "Column holding the PS id (default: pid)");
  app.add_option("--field", o.field, "Displacement node field in the results (default: u, or u_mm)");
  app.add_option("--cache-dir", o.cache_dir, "Cache of evaluations (default: <output>.cache)");
  app.add_option("-j,--jobs", o.jobs, "Evaluations run at once")->capture_default_str()->check(cli::number_in(1, 256));
  app.add_flag("--keep-results", o.keep_results, "Keep each evaluation's results file in the cache");
  app.add_option("--scan", o.scan, "Grid values per parameter before refining (default 5 for one parameter, 3 for more; 0: none)")
      ->check(cli::number_in(0, 100000));
  app.add_option("--xtol", o.xtol, "Stop when steps are below this fraction of each range")
      ->capture_default_str()
      ->check(cli::number_in(0, 1, cli::Ends::OpenLow));
  app.add_option("--max-evals", o.max_evals, "Evaluation budget (scan included)")->capture_default_str()->check(cli::number_in(1, 100000));
  app.add_option("--response", o.response,
                 "How the simulated series respond to the parameter: general (scan, then Brent or BOBYQA) or reciprocal "
                 "(one parameter, series affine in 1/x, e.g. c_R: three concurrent runs, a model, one check run)")
      ->capture_default_str()
      ->check(CLI::IsMember({"general", "reciprocal"}));
  std::string& output = tool.add_output("calibration", "Output folder");
  // The library names these settings in words; the messages show the flags.
  tool.name_setting("solver command", "--solver-command");
  tool.name_setting("solver mesh", "--mesh");
  tool.name_setting("parameter to calibrate", "--param");
  tool.name_setting("scan values per parameter", "--scan");
  tool.name_setting("evaluation budget", "--max-evals");
  tool.name_setting("response model", "--response");
  tool.name_setting("misfit window", "--window");
  tool.name_setting("PS selection", "--points, --inside");
  tool.name_setting("polygon filter", "--inside-where");
  tool.name_setting("mesh of the top surface", "--mesh");
  tool.name_setting("model CRS", "--crs");
  tool.name_setting("points CRS", "--points-crs");
  return tool.run(argc, argv, [&] {
    // 1. Numeric options, then the parameters: every path must exist in the case, and both bounds
    // must give a valid case.
    check_command_template(o.solver_command, !o.mesh.empty());
    const CaseTemplate tmpl(o.case_file);
    std::vector<ParameterSpec> params;
    for (const auto& text : o.params) params.push_back(parse_parameter(text));
    const bool reciprocal = o.response == "reciprocal";
    OptimizerOptions oo;
    oo.scan = o.scan;
    oo.xtol = o.xtol;
    oo.max_evals = o.max_evals;
    if (reciprocal) check_reciprocal(params, oo, app.count("--scan") > 0);
    // Every path a number of the case, named once, and a valid case at both bounds (checked in the
    // system's temporary folder: the cache is created only once every input is accepted).
    for (const auto& w : check_parameters(tmpl, params)) cli::warning("{}", w);
    const std::string cache_dir = o.cache_dir.empty() ? output + ".cache" : o.cache_dir;
    const MisfitWindow window = parse_window(o.window, "--window");

    // 2. Measured series at the chosen points, in the model CRS.
    PsReadOptions ro;
    ro.model_crs = model_crs(o.crs, o.case_file);
    ro.points_crs = o.points_crs;
    ro.id_column = o.id_column;
    ro.require_series = true;
    PsData up = read_ps_in_model(o.measured, ro);
    std::vector<std::string> ids = o.points;
    if (ids.empty())
      for (const auto& p : up.points) ids.push_back(p.id);
    if (!o.inside.empty()) {
      const geo::PolygonSet set = read_polygons(o.inside, ro.model_crs, o.inside_where);
      std::vector<std::string> kept;
      for (const auto& id : ids) {
        const auto i = up.find(id);
        if (i && set.contains({up.points[*i].x, up.points[*i].y})) kept.push_back(id);
      }
      if (kept.empty()) throw InputError(o.inside, "none of the chosen PS points lies inside these polygons");
      ids = kept;
    }
    up = select_points(up, ids);
    std::optional<PsData> east;
    if (!o.measured_east.empty()) {
      PsData e = read_ps(o.measured_east, ro);
      std::vector<std::string> have;
      for (const auto& id : ids)
        if (e.find(id)) have.push_back(id);
      if (have.empty()) throw InputError(o.measured_east, "has none of the chosen PS points");
      east = select_points(e, have);
    }
    {
      std::string list;
      for (const auto& id : ids) list += (list.empty() ? "" : ", ") + id;
      cli::info("{} PS points in the misfit: {}", ids.size(), list);
    }

    // 3. Where they sit on the top surface (from the mesh once, or from each results file).
    std::optional<TopSurface> mesh_top;
    std::unique_ptr<SurfaceLocator> mesh_locator;
    std::vector<LocatedPoint> located;
    std::vector<PsPoint> all_points = up.points;
    if (east)
      for (const auto& p : east->points)
        if (!up.find(p.id)) all_points.push_back(p);
    if (!o.mesh.empty()) {
      mesh_top = load_top_surface(o.mesh, o.top_group, "");
      mesh_locator = std::make_unique<SurfaceLocator>(*mesh_top);
      const Located l = locate_points(*mesh_locator, all_points, false);
      for (const auto& p : l.outside)
        cli::warning("PS '{}' lies {:.0f} m outside the top surface: left out of the misfit", p.point.id, p.hit.distance);
      if (l.sampled.empty()) throw InputError(o.measured, "no chosen PS point lies on the model's top surface (wrong CRS?)");
      located = l.sampled;
    }
    // With --mesh a cached series must hold every point located on the surface (the key covers
    // the positions, so it does; a damaged entry is computed again).
    std::vector<std::string> needed;
    for (const auto& l : located) needed.push_back(l.point.id);

    // 4. The outputs' folder (refused now if it cannot be made, before any solver run), then the
    // cache: its key covers the points' exact positions, the field and the top group.
    OutputFolder out(output);
    std::string extra = fmt::format("field={} top={} located={}\n", o.field, o.top_group, o.mesh.empty() ? "per-result" : "mesh");
    for (const auto& p : all_points) extra += fmt::format("point {} {:a} {:a}\n", p.id, p.x, p.y);
    EvaluatorSetup setup;
    setup.case_template = &tmpl;
    setup.params = params;
    setup.solver_command = o.solver_command;
    setup.mesh_path = o.mesh;
    setup.cache_dir = cache_dir;
    setup.jobs = o.jobs;
    setup.keep_results = o.keep_results;
    setup.setup_extra = extra;
    setup.needed_ids = needed;
    setup.sample = [&](const std::string& h5) {
      std::vector<LocatedPoint> pts = located;
      std::optional<TopSurface> own;
      if (!mesh_top) {
        own = load_top_surface("", "", h5);
        const SurfaceLocator loc(*own);
        pts = locate_points(loc, all_points, false).sampled;
      }
      SurfaceDisplacement res(h5, mesh_top ? *mesh_top : *own, o.field);
      const Samples s = sample_displacement(res, pts, {}, std::nullopt);
      SimulatedSeries out;
      out.times = s.dates;
      for (const auto& p : s.points) out.ids.push_back(p.point.id);
      out.enu = s.enu;
      // Points off the surface have no series: absent ids are left out of the misfit.
      return out;
    };
    // The misfit uses the points sampled on the surface: with --mesh those located on it (the ones
    // warned about as outside are left out, whatever a series holds), else those in the series.
    std::set<std::string> on_surface;
    for (const auto& l : located) on_surface.insert(l.point.id);
    auto located_for = [&](const SimulatedSeries& s, const PsData& d) {
      std::vector<LocatedPoint> pts;
      for (const auto& p : d.points)
        if (s.has(p.id) && (!mesh_top || on_surface.count(p.id))) pts.push_back({p, {}});
      return pts;
    };
    setup.misfit = [&](const SimulatedSeries& s) {
      const Samples su = s.at_dates(located_for(s, up), up.dates);
      auto mu = series_misfits(up, su, 2, window);
      std::vector<SeriesMisfit> me;
      if (east) me = series_misfits(*east, s.at_dates(located_for(s, *east), east->dates), 0, window);
      return combine_misfits(std::move(mu), std::move(me), east ? o.east_weight : 0.0);
    };
    Evaluator ev(std::move(setup));
    ev.on_evaluation = [&](const Evaluation& e) {
      std::string xs;
      for (std::size_t i = 0; i < e.x.size(); ++i) xs += (i ? ", " : "") + params[i].name + " = " + fmt_value(e.x[i]);
      cli::info("evaluation {} ({}): {} -> RMS {:.3f} mm{}", e.index, e.phase, xs, e.misfit.rms_mm,
                e.cached ? " (cached)" : fmt::format(" ({:.1f} s)", e.seconds));
    };

    // 5. Optimise.
    std::optional<ReciprocalReport> model;
    OptimizerResult best;
    if (reciprocal) {
      ReciprocalResult r = calibrate_reciprocal(ev, params, oo);
      best = std::move(r.result);
      model = std::move(r.report);
      if (!model->fallback.empty()) cli::warning("the reciprocal model was not used: {}", tool.with_flags(best.stop_reason));
    } else {
      best = optimize(ev, params, oo);
    }
    const std::size_t evaluations = ev.history().size();
    const auto solver_runs = static_cast<std::size_t>(
        std::count_if(ev.history().begin(), ev.history().end(), [](const Evaluation& e) { return !e.cached; }));
    const std::string stop_reason = tool.with_flags(best.stop_reason);  // "evaluation budget (--max-evals) used"
    if (!best.converged && !(model && !model->fallback.empty()))
      cli::warning("the optimizer stopped before converging: {}", stop_reason);
    if (model && (best.best_x[0] == params[0].lower || best.best_x[0] == params[0].upper))
      cli::warning("the best value is the bound {} of the range: the minimum may lie beyond it (widen --param)", fmt_value(best.best_x[0]));
    const Evaluation& be = ev.history()[best.best_index];
    if (!mesh_top)  // located on each results file's own surface: say which points it left out
      for (const auto& p : all_points)
        if (!ev.series_of(be).has(p.id))
          cli::warning("PS '{}' lies outside the results' top surface: left out of the misfit", p.id);

    // 6. Outputs, all at once.
    {
      std::vector<std::pair<std::string, double>> v;
      for (std::size_t i = 0; i < params.size(); ++i)
        for (const auto& p : params[i].paths) v.emplace_back(p, best.best_x[i]);
      OutputFile f(out.file("best.toml"));
      f.write(fmt::format("# Calibrated by ugs-calibrate (RMS misfit {:.3f} mm; {}); from {}\n", best.best_rms_mm, best.method,
                          o.case_file));
      f.write(tmpl.render(v));
      f.commit();
    }
    {
      CsvWriter w(out.file("parameters.csv"), {"parameter", "paths", "best", "lower", "upper", "case_value", "scale"},
                  std::vector<std::string>{tool.command_line(),
                                           fmt::format("{}; {}; RMS {:.4f} mm at evaluation {} of {}; {} solver runs", best.method,
                                                       stop_reason, best.best_rms_mm, be.index, evaluations, solver_runs)});
      for (std::size_t i = 0; i < params.size(); ++i) {
        std::string paths;
        for (const auto& p : params[i].paths) paths += (paths.empty() ? "" : ";") + p;
        w.text(params[i].name).text(paths).number(best.best_x[i]).number(params[i].lower).number(params[i].upper);
        w.number(tmpl.value(params[i].paths.front())).text(params[i].log_scale ? "log" : "linear").end_row();
      }
      w.commit();
    }
    {
      CsvWriter w(out.file("misfit_points.csv"), {"pid", "component", "n", "offset_mm", "rms_mm"},
                  std::vector<std::string>{"misfit of the best evaluation per point: offset = mean(simulated - measured), "
                                           "removed before the RMS"});
      for (const auto& s : be.misfit.series) w.text(s.id).text(s.component).integer(static_cast<std::int64_t>(s.n)).number(s.offset_mm, 4).number(s.rms_mm, 4).end_row();
      w.text("all").text(east ? "up+east" : "up").integer(static_cast<std::int64_t>(be.misfit.n)).text("").number(be.misfit.rms_mm, 4).end_row();
      w.commit();
    }
    {
      std::vector<std::string> cols{"evaluation", "phase"};
      for (const auto& p : params) cols.push_back(p.name);
      for (const std::string c : {"rms_mm", "cached", "entry"}) cols.push_back(c);  // timings: stderr, cache timing.txt
      CsvWriter w(out.file("profile.csv"), cols);
      for (const auto& e : ev.history()) {
        w.integer(static_cast<std::int64_t>(e.index)).text(e.phase);
        for (double v : e.x) w.number(v);
        w.number(e.misfit.rms_mm, 6).integer(e.cached ? 1 : 0).text(e.entry).end_row();
      }
      w.commit();
    }
    {
      // The best run at the measured dates, relative to the first one (as ugs-sample --at-ps-dates).
      const SimulatedSeries& s = ev.series_of(be);
      std::vector<LocatedPoint> pts;
      for (const auto& p : all_points)
        if (s.has(p.id) && (!mesh_top || on_surface.count(p.id))) {
          LocatedPoint lp{p, {}};
          for (const auto& l : located)
            if (l.point.id == p.id) lp = l;
          if (located.empty()) lp.hit = {true, 0, {}, {p.x, p.y, 0}, 0};
          pts.push_back(lp);
        }
      Samples sm = s.at_dates(pts, up.dates);
      const std::int64_t ref = up.dates.front();
      const Samples r0 = s.at_dates(pts, {ref});
      for (std::size_t p = 0; p < pts.size(); ++p)
        for (std::size_t d = 0; d < sm.dates.size(); ++d)
          for (int j = 0; j < 3; ++j) sm.enu[(p * sm.dates.size() + d) * 3 + j] -= r0.at(p, 0)[j];
      sm.reference = ref;
      write_samples_csv(out.file("best_samples.csv"), sm, {},
                        {tool.command_line(), "best evaluation " + be.entry + ", relative to " + format_iso_date(ref)});
    }
    if (model) {
      // The modelled misfit over the range (what the three runs predict), for plots next to profile.csv.
      CsvWriter w(out.file("model_profile.csv"), {params[0].name, "rms_mm"},
                  std::vector<std::string>{
                      "misfit of the series modelled as quadratic in 1/x through the runs at " + fmt_value(model->x[0]) + ", " +
                      fmt_value(model->x[1]) + ", " + fmt_value(model->x[2]) + " (--response reciprocal)"});
      for (const auto& [x, rms] : model->profile) w.number(x).number(rms, 6).end_row();
      w.commit();
    }
    out.commit();

    // 7. The answer, on stdout.
    std::printf("best (%s, %s):\n", best.method.c_str(), stop_reason.c_str());
    for (std::size_t i = 0; i < params.size(); ++i)
      std::printf("  %s = %s   [%g, %g]\n", params[i].name.c_str(), fmt_value(best.best_x[i]).c_str(), params[i].lower,
                  params[i].upper);
    if (model) {
      const std::string& n = params[0].name;
      std::printf("reciprocal response model: runs at %s = %s, %s, %s: RMS %.4f, %.4f, %.4f mm\n", n.c_str(), fmt_value(model->x[0]).c_str(),
                  fmt_value(model->x[1]).c_str(), fmt_value(model->x[2]).c_str(), model->rms_mm[0], model->rms_mm[1], model->rms_mm[2]);
      if (!std::isnan(model->curvature_mm))
        std::printf("  the middle run departs %.4f mm at most from the series affine in 1/x through the outer two (they differ by up "
                    "to %.4f mm)\n",
                    model->curvature_mm, model->response_mm);
      if (!std::isnan(model->x_model))
        std::printf("  model minimum %s = %s, RMS %.4f mm predicted\n", n.c_str(), fmt_value(model->x_model).c_str(),
                    model->predicted_rms_mm);
      if (!std::isnan(model->checked_rms_mm))
        std::printf("  check %s: RMS %.4f mm (check - predicted = %+.2g mm)\n",
                    model->check_is_new_point ? "run" : "(one of the three runs)", model->checked_rms_mm,
                    model->checked_rms_mm - model->predicted_rms_mm);
      if (!model->fallback.empty()) std::printf("  model not used: %s\n", tool.with_flags(model->fallback).c_str());
    }
    std::printf("RMS misfit %.3f mm over %zu values; %zu evaluations, %zu solver runs (%zu from the cache); outputs in %s\n",
                best.best_rms_mm, be.misfit.n, evaluations, solver_runs, evaluations - solver_runs, out.target().string().c_str());
  });
}
