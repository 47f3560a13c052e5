// ugs-flow — pressure propagation from the pools into their aquifers (thesis 3.4, eq. 3.35, and
// 4.2.1): transient Darcy flow div(K grad p) = S_s dp/dt on the linear tetrahedra of a flow
// sub-mesh, S_s = gamma_w (n beta + c_M) with c_M from the compressibility law at the initial
// effective vertical stress; each pool's nodes follow its pressure schedule, no flow elsewhere;
// backward Euler with lumped storage, one CHOLMOD factorization per step size.
// Writes the pressure change dp [Pa] (and dp_norm) at every node and date (HDF5 + XDMF, parent
// node tags) and the cumulative water volume entering each pool (CSV, the material balance).
// With --calibrate-k it first finds the aquifer conductivity that matches a target influx.
//
//   ugs-flow pool_c.msh --case case.toml -o pool_c_dp.h5
//   ugs-flow pool_c.msh --case case.toml --calibrate-k 3.78e6@1964-01-01 -o pool_c_dp.h5 > k.csv
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>

#include "async_writer.hpp"
#include "ugs/cli/number_option.hpp"
#include "ugs/cli/tool.hpp"
#include "ugs/flow/calibration.hpp"
#include "ugs/flow/flow_model.hpp"
#include "ugs/flow/schedule.hpp"
#include "ugs/flow/transient.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"

namespace {

using namespace ugs;
using namespace ugs::flow;

struct Options {
  std::string mesh = "-";
  std::string case_file;
  std::string influx;                    // default: beside the fields, <stem>_influx.csv
  std::vector<std::string> pools;
  int substeps = 1;
  double max_step_days = 31;
  std::string end;
  std::vector<std::string> output_dates;
  double reference_MPa = 0;
  std::string calibrate;                 // TARGET_M3@DATE
  std::vector<std::string> calibrate_materials;
  std::string calibrate_pool;
  std::string calibration_out = "-";
  double calibrate_tolerance = 1e-4;
  std::size_t cache = 8;
};

std::int64_t parse_date(const std::string& where, const std::string& text) {
  const auto t = parse_iso_date(text);
  if (!t) throw InputError(where, fmt::format("'{}' is not an ISO 8601 date", text));
  return *t;
}

double parse_number(const std::string& where, const std::string& text) {
  double v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
    throw InputError(where, fmt::format("'{}' is not a number", text));
  return v;
}

// CSV column name of a pool: letters, digits, '-' and '_' kept, anything else becomes '_'.
std::string column_slug(const std::string& name) {
  std::string s = name;
  for (auto& ch : s)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_') ch = '_';
  return s;
}

struct Calibration {
  double target = 0;
  std::int64_t date = 0;
  std::size_t pool = 0;
  std::vector<std::size_t> materials;
};

Calibration parse_calibration(const Options& o, const FlowModel& fm, const CaseFile& cs) {
  Calibration c;
  const auto at = o.calibrate.find('@');
  if (at == std::string::npos) throw InputError("--calibrate-k", fmt::format("'{}' is not TARGET_M3@DATE", o.calibrate));
  c.target = parse_number("--calibrate-k", o.calibrate.substr(0, at));
  if (c.target == 0) throw InputError("--calibrate-k", "the target volume must not be zero");
  c.date = parse_date("--calibrate-k", o.calibrate.substr(at + 1));
  if (!o.calibrate_pool.empty()) {
    auto it = std::find_if(fm.pools.begin(), fm.pools.end(), [&](const FlowPool& p) { return p.name == o.calibrate_pool; });
    if (it == fm.pools.end()) throw InputError("--calibrate-pool", fmt::format("no pool '{}' in this run", o.calibrate_pool));
    c.pool = static_cast<std::size_t>(it - fm.pools.begin());
  } else if (fm.pools.size() > 1) {
    throw InputError("--calibrate-k", "this run has several pools: say which with --calibrate-pool");
  }
  for (const auto& name : o.calibrate_materials) {
    auto it = std::find_if(fm.materials.begin(), fm.materials.end(), [&](const FlowMaterial& m) { return m.name == name; });
    if (it == fm.materials.end() || it->pool >= 0)
      throw InputError("--calibrate-materials", fmt::format("'{}' is not an aquifer material of the mesh", name));
    c.materials.push_back(static_cast<std::size_t>(it - fm.materials.begin()));
  }
  if (c.materials.empty()) {
    // Default: the pool's aquifer_materials found in the mesh, else every aquifer material.
    const PoolSpec* spec = nullptr;
    for (const auto& p : cs.pools)
      if (p.name == fm.pools[c.pool].name) spec = &p;
    for (std::size_t m = 0; m < fm.materials.size(); ++m)
      if (fm.materials[m].pool < 0 && spec &&
          std::find(spec->aquifer_materials.begin(), spec->aquifer_materials.end(), fm.materials[m].name) != spec->aquifer_materials.end())
        c.materials.push_back(m);
    if (c.materials.empty())
      for (std::size_t m = 0; m < fm.materials.size(); ++m)
        if (fm.materials[m].pool < 0) c.materials.push_back(m);
  }
  if (c.materials.empty()) throw InputError("--calibrate-k", "the mesh has no aquifer material to calibrate");
  return c;
}

// Finds the multiplier on K of the chosen materials matching the target influx; leaves it in the model.
void calibrate(FlowModel& fm, const TimeGrid& grid, const Calibration& cal, const Options& o) {
  const std::size_t idx = static_cast<std::size_t>(std::find(grid.dates.begin(), grid.dates.end(), cal.date) - grid.dates.begin());
  TransientOptions topt;
  topt.substeps = o.substeps;
  topt.cache_capacity = o.cache;
  topt.last_date = idx;
  auto influx_at = [&](double x) {
    for (auto m : cal.materials) fm.k_multiplier[m] = x;
    const TransientResult r = run_transient(fm, grid, topt);
    return r.influx[cal.pool].back();
  };
  RootOptions ropt;
  ropt.g_tolerance = o.calibrate_tolerance * std::abs(cal.target);
  const std::string date = format_iso_date(cal.date);
  const RootResult root = find_multiplier([&](double x) { return influx_at(x) - cal.target; }, ropt, [&](const RootEvaluation& e) {
    cli::info("calibration {:2d} ({}): K x {:.6g} -> influx {:.6g} m3 into '{}' at {} (target {:.6g}, misfit {:+.3f} %)",
              e.evaluation, e.phase, e.x, e.g + cal.target, fm.pools[cal.pool].name, date, cal.target, 100.0 * e.g / cal.target);
  });
  for (auto m : cal.materials) fm.k_multiplier[m] = root.x;
  cli::info("calibration: K multiplier {:.6g} after {} runs (influx {:.6g} m3, target {:.6g} m3)", root.x, root.evaluations,
            root.g + cal.target, cal.target);
  CsvWriter w(o.calibration_out, {"material", "Kx_m_per_s", "Ky_m_per_s", "Kz_m_per_s", "multiplier"},
              std::vector<std::string>{fmt::format("ugs-flow --calibrate-k {:g}@{} on pool '{}': influx {:.6g} m3 after {} runs",
                                                   cal.target, date, fm.pools[cal.pool].name, root.g + cal.target, root.evaluations)});
  for (auto m : cal.materials) {
    const auto& mat = fm.materials[m];
    w.text(mat.name).number(mat.K[0] * root.x).number(mat.K[1] * root.x).number(mat.K[2] * root.x).number(root.x).end_row();
  }
  w.commit();
}

void run(const Options& o, cli::Tool& tool) {
  // 1. Mesh, case, model.
  const Mesh mesh = read_msh(o.mesh);
  const CaseFile cs = read_case_file(o.case_file);
  FlowModel fm = build_flow_model(mesh, cs, {o.pools, o.mesh == "-" ? std::string("stdin") : o.mesh});
  for (const auto& p : cs.pools)
    if (std::none_of(fm.pools.begin(), fm.pools.end(), [&](const FlowPool& q) { return q.name == p.name; }) && o.pools.empty())
      cli::info("pool '{}' is not simulated: none of its materials is in the mesh", p.name);
  // A mesh material that no simulated pool lists among its aquifer_materials (when they list any)
  // is probably a sub-mesh cut with the wrong materials: say so, but run.
  std::vector<std::string> listed;
  for (const auto& p : cs.pools)
    if (std::any_of(fm.pools.begin(), fm.pools.end(), [&](const FlowPool& q) { return q.name == p.name; }))
      listed.insert(listed.end(), p.aquifer_materials.begin(), p.aquifer_materials.end());
  for (const auto& m : fm.materials)
    if (m.pool < 0 && !listed.empty() && std::find(listed.begin(), listed.end(), m.name) == listed.end())
      cli::warning("material '{}' of the mesh is in no simulated pool's aquifer_materials: it is treated as aquifer", m.name);
  for (const auto& m : fm.materials) {
    if (m.pool >= 0)
      cli::detail("material '{}': {} tetrahedra, in pool '{}'", m.name, m.tets, fm.pools[m.pool].name);
    else
      cli::detail("material '{}': {} tetrahedra, K = [{:g}, {:g}, {:g}] m/s, n = {:g}, c_M {:.4g} .. {:.4g} 1/MPa", m.name, m.tets,
                  m.K[0], m.K[1], m.K[2], m.porosity, m.cm_min * 1e6, m.cm_max * 1e6);
  }

  // 2. Schedules and the time grid.
  ScheduleLimits lim{static_cast<std::int64_t>(std::llround(o.max_step_days * 86400))};
  std::vector<PoolSchedule> schedules;
  for (const auto& p : fm.pools) {
    const auto spec = std::find_if(cs.pools.begin(), cs.pools.end(), [&](const PoolSpec& s) { return s.name == p.name; });
    schedules.push_back(read_pool_schedule(*spec, lim));
    cli::detail("pool '{}': {} nodes on {} ({} rows)", p.name, p.dofs.size(), spec->schedule, schedules.back().times.size());
  }
  std::optional<std::int64_t> end;
  if (!o.end.empty()) end = parse_date("--end", o.end);
  const RunWindow window = run_window(cs, schedules, end);
  auto check_in_run = [&](const std::string& opt, std::int64_t t) {
    if (t < window.start || t > window.end)
      throw InputError(opt, fmt::format("{} lies outside the run {} .. {}", format_iso_date(t), format_iso_date(window.start),
                                        format_iso_date(window.end)));
    return t;
  };
  std::vector<std::int64_t> extra, outputs;
  for (const auto& d : o.output_dates) outputs.push_back(check_in_run("--output-dates", parse_date("--output-dates", d)));
  extra = outputs;
  std::optional<Calibration> cal;
  if (!o.calibrate.empty()) {
    cal = parse_calibration(o, fm, cs);
    extra.push_back(check_in_run("--calibrate-k", cal->date));
  }
  const TimeGrid grid = make_time_grid(schedules, window, extra);
  cli::info("{} nodes ({} unknowns, {} on pool schedules), {} dates {} .. {}, {} steps", mesh.num_nodes(), fm.num_dofs,
            std::count_if(fm.pool_of_dof.begin(), fm.pool_of_dof.end(), [](int p) { return p >= 0; }), grid.dates.size(),
            format_iso_date(grid.dates.front()), format_iso_date(grid.dates.back()), (grid.dates.size() - 1) * o.substeps);

  // 3. Calibration of the aquifer conductivity, if asked.
  if (cal) calibrate(fm, grid, *cal, o);

  // 4. The run, writing fields at the output dates as it goes.
  std::optional<double> reference;
  if (o.reference_MPa > 0) reference = o.reference_MPa * 1e6;
  for (const auto& s : schedules)
    if (!reference && s.reference_Pa) reference = s.reference_Pa;
  for (const auto& s : schedules)
    if (s.reference_Pa && reference && *s.reference_Pa != *reference && o.reference_MPa <= 0)
      cli::warning("pools have different reference pressures: dp_norm uses {:g} MPa (--reference-pressure sets it)", *reference / 1e6);
  std::vector<char> write_date(grid.dates.size(), 0);
  for (std::size_t k = 0; k < grid.dates.size(); ++k)
    write_date[k] = outputs.empty() ? grid.is_schedule_date[k]
                                    : std::find(outputs.begin(), outputs.end(), grid.dates[k]) != outputs.end();
  const std::string out = tool.output();
  std::string influx_path = o.influx;
  if (influx_path.empty())
    influx_path = (out.size() > 3 && out.ends_with(".h5") ? out.substr(0, out.size() - 3) : out) + "_influx.csv";
  cli::Activity activity("solving the flow");
  FieldSeriesWriter writer(out, mesh);
  flowtool::AsyncSeriesWriter async(writer);
  cli::Progress progress("flow", grid.dates.size() - 1);
  TransientOptions topt;
  topt.substeps = o.substeps;
  topt.cache_capacity = o.cache;
  const TransientResult res = run_transient(fm, grid, topt, [&](const DateState& s) {
    progress.update(s.index);
    // Never write a NaN or an infinity: a failed step stops the run here (exit 1), with nothing written.
    for (std::size_t d = 0; d < s.dp->size(); ++d)
      if (!std::isfinite((*s.dp)[d])) {
        const auto n = std::find(fm.dof_of_node.begin(), fm.dof_of_node.end(), d) - fm.dof_of_node.begin();
        throw ComputeError(fmt::format("the pressure change at node {} on {} is {} (the flow solve failed: check K_m_per_s, "
                                       "porosity and compressibilities of the aquifer materials)",
                                       mesh.node_tags[n], format_iso_date(s.date), (*s.dp)[d]));
      }
    for (std::size_t q = 0; q < s.influx->size(); ++q)
      if (!std::isfinite((*s.influx)[q]))
        throw ComputeError(fmt::format("the water influx into pool '{}' on {} is {} (the flow solve failed)", fm.pools[q].name,
                                       format_iso_date(s.date), (*s.influx)[q]));
    if (!write_date[s.index]) return;
    std::vector<Field> fields;
    Field dp{"dp", 1, std::vector<double>(mesh.num_nodes(), 0.0)};
    for (std::size_t n = 0; n < mesh.num_nodes(); ++n)
      if (fm.dof_of_node[n] != kNoDof) dp.values[n] = (*s.dp)[fm.dof_of_node[n]];
    if (reference) {
      Field norm{"dp_norm", 1, dp.values};
      for (auto& v : norm.values) v /= *reference;
      fields.push_back(std::move(dp));
      fields.push_back(std::move(norm));
    } else {
      fields.push_back(std::move(dp));
    }
    async.push(format_iso_date(s.date), static_cast<double>(s.date), std::move(fields));
  });
  progress.finish();
  async.finish();

  // 5. Influx table, then both outputs appear together.
  std::vector<std::string> columns{"date"};
  for (const auto& p : fm.pools) columns.push_back(column_slug(p.name) + "_influx_m3");
  columns.push_back("storage_change_m3");
  CsvWriter csv(influx_path, columns,
                std::vector<std::string>{"ugs-flow: cumulative water volume entering each pool from its aquifer since the run "
                                         "start [m3]; storage_change_m3 = change of water stored in the aquifer"});
  for (std::size_t k = 0; k < res.dates.size(); ++k) {
    csv.date(res.dates[k]);
    for (const auto& q : res.influx) csv.number(q[k]);
    csv.number(res.stored[k]).end_row();
  }
  writer.commit();
  csv.commit();
  for (std::size_t q = 0; q < fm.pools.size(); ++q)
    cli::info("pool '{}': {:.6g} m3 of water entered by {}", fm.pools[q].name, res.influx[q].back(), format_iso_date(res.dates.back()));
  cli::detail("{} steps, {} factorizations ({:.2f} s, {:.3g} nonzeros in L), analysis {:.2f} s, solves {:.2f} s", res.steps,
              res.solver.factorizations, res.solver.factor_seconds, res.solver.factor_nonzeros, res.solver.analyze_seconds,
              res.solver.solve_seconds);
  cli::detail("mass balance: stored water change {:.6g} m3, net influx {:.6g} m3, relative error {:.2g}", res.stored.back(),
              [&] {
                double s = 0;
                for (const auto& q : res.influx) s += q.back();
                return s;
              }(),
              res.balance_error());
  cli::detail("wrote {}, {} and {}", writer.h5_path(), writer.xdmf_path(), influx_path);
}

}  // namespace

int main(int argc, char** argv) {
  cli::Tool tool({"ugs-flow",
                  "Transient Darcy flow from the pools into their aquifers: pressure change at every node and date, "
                  "water influx into each pool, optional calibration of the aquifer conductivity.",
                  "ugs-flow pool_c.msh --case case.toml -o pool_c_dp.h5 --influx pool_c_influx.csv"});
  Options o;
  auto& app = tool.app();
  app.add_option("mesh", o.mesh, "Flow sub-mesh (MSH 4.1, from ugs-submesh; '-' = stdin)")->capture_default_str();
  app.add_option("--case", o.case_file, "Case file (TOML): materials (K_m_per_s, porosity), initial stress, [[pool]]s")->required();
  tool.add_output("dp.h5", "Pressure change per node and date, HDF5 (+ .xdmf beside it)");
  app.add_option("--influx", o.influx, "Cumulative water influx CSV (default: <output stem>_influx.csv)");
  app.add_option("--pool", o.pools, "Pool(s) to simulate (default: every pool with a material in the mesh)");
  app.add_option("--substeps", o.substeps, "Equal sub-steps per schedule interval")->check(cli::number_in(1, 1000))->capture_default_str();
  app.add_option("--max-step", o.max_step_days, "Longest allowed gap between schedule dates [days]")
      ->capture_default_str()
      ->check(cli::number_in(0, 36525, cli::Ends::OpenLow));
  app.add_option("--end", o.end, "Stop the run at this date (schedule rows after it are ignored)");
  app.add_option("--output-dates", o.output_dates, "Write fields only at these dates (default: every schedule date)")->delimiter(',');
  app.add_option("--reference-pressure", o.reference_MPa, "Reference pressure for dp_norm [MPa] (default: the pool's)")
      ->check(cli::number_in(0, cli::kNoLimit));
  app.add_option("--calibrate-k", o.calibrate, "Find the aquifer K multiplier giving this influx: TARGET_M3@DATE");
  app.add_option("--calibrate-materials", o.calibrate_materials, "Materials whose K is calibrated (default: every aquifer material)")
      ->delimiter(',');
  app.add_option("--calibrate-pool", o.calibrate_pool, "Pool whose influx is matched (needed when several)");
  app.add_option("--calibrate-tolerance", o.calibrate_tolerance, "Relative tolerance on the matched influx")
      ->capture_default_str()
      ->check(cli::number_in(0, 1, cli::Ends::Open));
  app.add_option("--calibration-out", o.calibration_out, "Calibrated K table (CSV; '-' = stdout)")->capture_default_str();
  app.add_option("--factor-cache", o.cache, "Factorizations kept in memory (one per step size)")
      ->capture_default_str()
      ->check(cli::number_in(0, 100000));
  tool.name_setting("end date", "--end");
  tool.name_setting("pool selection", "--pool");
  tool.name_setting("longest step", "--max-step");
  return tool.run(argc, argv, [&] { run(o, tool); });
}
