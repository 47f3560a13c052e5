// ugs-ensemble — uncertainty and sensitivity of a case's answers (thesis ch. 5): the parameters of
// the case file named in an ensemble file (TOML: distributions and a design, docs/ensemble.md) are
// sampled (Latin hypercube, Sobol'-Saltelli or Morris), each member is run through the solver
// command template as ugs-calibrate runs its evaluations (concurrent subprocesses, content-addressed
// cache: a rerun skips finished members), and `collect` computes each member's metrics and the
// ensemble's statistics as CSV. `--emit make|slurm` writes the members as a Makefile or a Slurm
// job array instead of running them.
//
//   ugs-ensemble run --spec ensemble.toml --case case.toml --solver-command "ugs-solve {mesh} --case {case}
//     --pressure dp.h5 -o {out}" --mesh model.msh --phase storage=2015-05-01/2015-11-01 -j 2 -o ensemble
#include <unistd.h>

#include <filesystem>
#include <limits>

#include <fmt/format.h>

#include "ugs/cli/number_option.hpp"
#include "ugs/cli/tool.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/ensemble/collect.hpp"
#include "ugs/ensemble/members.hpp"
#include "ugs/ensemble/spec.hpp"
#include "ugs/formats/io.hpp"
#include "ugs/insar/inputs.hpp"
#include "ugs/runner/case_params.hpp"
#include "ugs/runner/output_folder.hpp"
#include "ugs/runner/subprocess.hpp"

namespace {

using namespace ugs;
using namespace ugs::ensemble;
namespace fs = std::filesystem;

enum class Mode { run, collect };
enum class Emit { none, make, slurm };

struct Options {
  Mode mode = Mode::run;
  Emit emit = Emit::none;
  std::string spec, case_file, solver_command, mesh, cache_dir, output;
  std::vector<std::string> phases, seismic_windows;
  std::string inside, inside_where, measured, measured_east, points_crs, crs, id_column, window, field;
  double east_weight = 1.0;
  int jobs = 1;
  std::size_t member = 0;  // 1-based; 0 = all
};

std::string absolute(const std::string& p) { return p.empty() ? p : fs::absolute(p).lexically_normal().string(); }

// The command that repeats these options for one mode (absolute paths: it runs from anywhere).
std::string command_for(const Options& o, const std::string& mode) {
  std::string self = "ugs-ensemble";
  std::error_code ec;
  const auto exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) self = exe.string();
  std::string c = runner::shell_quote(self) + " " + mode;
  auto add = [&](const std::string& flag, const std::string& v, bool path) {
    if (!v.empty()) c += " " + flag + " " + runner::shell_quote(path ? absolute(v) : v);
  };
  add("--spec", o.spec, true);
  add("--case", o.case_file, true);
  add("--solver-command", o.solver_command, false);
  add("--mesh", o.mesh, true);
  add("--cache-dir", o.cache_dir, true);
  for (const auto& p : o.phases) add("--phase", p, false);
  for (const auto& w : o.seismic_windows) add("--seismic-window", w, false);
  add("--inside", o.inside, true);
  add("--inside-where", o.inside_where, false);
  add("--measured", o.measured, true);
  add("--measured-east", o.measured_east, true);
  if (!o.measured_east.empty()) add("--east-weight", fmt::format("{}", o.east_weight), false);
  add("--points-crs", o.points_crs, false);
  add("--crs", o.crs, false);
  add("--id-column", o.id_column, false);
  add("--window", o.window, false);
  add("--field", o.field, false);
  return c;
}

MetricOptions metric_options(const Options& o) {
  MetricOptions m;
  for (const auto& p : o.phases) m.phases.push_back(parse_phase(p));
  for (const auto& w : o.seismic_windows) {
    try {
      m.seismic_windows.push_back(parse_phase(w));
    } catch (const InputError& e) {
      throw InputError("--seismic-window " + w, "expected NAME=START/END (ISO dates, START before END), e.g. forecast=2025-01-01/2033-01-01");
    }
  }
  if (!m.seismic_windows.empty() && !read_case_file(o.case_file).seismicity)
    throw InputError(o.case_file, "has no [seismicity] section, which --seismic-window needs (docs/seismicity.md)");
  m.window = insar::parse_window(o.window, "--window");
  m.field = o.field;
  const std::string crs = insar::model_crs(o.crs, o.case_file);
  if (!o.inside.empty()) m.trace = insar::read_polygons(o.inside, crs, o.inside_where);
  if (!o.measured.empty()) {
    insar::PsReadOptions ro;
    ro.model_crs = crs;
    ro.points_crs = o.points_crs;
    ro.id_column = o.id_column;
    m.ps = insar::read_ps_in_model(o.measured, ro);
    if (!o.measured_east.empty()) {
      // The east series of the points that have one (ugs-calibrate's rule).
      const insar::PsData e = insar::read_ps_in_model(o.measured_east, ro);
      std::vector<std::string> have;
      for (const auto& p : m.ps->points)
        if (e.find(p.id)) have.push_back(p.id);
      if (have.empty()) throw InputError(o.measured_east, "has none of the PS points of --measured");
      m.ps_east = insar::select_points(e, have);
      m.east_weight = o.east_weight;
    }
  }
  return m;
}

void run(const Options& o, const cli::Tool& tool) {
  // 1. Every input checked before anything runs: the ensemble file, its paths against the case
  // (numbers there, and a valid case at each parameter's ends), the command, the metric options.
  const EnsembleSpec spec = read_spec(o.spec);
  const runner::CaseTemplate tmpl(o.case_file);
  check_against_case(spec, tmpl);
  runner::check_command_template(o.solver_command, !o.mesh.empty());
  const MetricOptions metrics = metric_options(o);
  Design design = make_design(spec);
  if (o.member > design.x.size())
    throw InputError("--member", fmt::format("{} is past the last member ({})", o.member, design.x.size()));
  const std::string cache = o.cache_dir.empty() ? o.output + ".cache" : o.cache_dir;
  cli::info("{} design: {} members ({} requested), {} parameters", to_string(spec.method), design.x.size(), spec.members,
            spec.parameters.size());
  EnsembleMembers members(spec, std::move(design), tmpl, o.solver_command, o.mesh, cache);

  // 2. Emit: the members as make or Slurm jobs, each `run --member K` into the same cache.
  if (o.emit != Emit::none) {
    Options same = o;
    same.cache_dir = cache;
    const std::string member = command_for(same, "run");
    const std::string collect_cmd = command_for(same, "collect") + " -o " + runner::shell_quote(absolute(o.output) + ".out");
    OutputFile f(o.output);
    f.write(o.emit == Emit::make ? makefile(members, member, collect_cmd) : slurm_script(members, member, collect_cmd));
    f.commit();
    cli::info("{} jobs written to {}", members.size(), o.output);
    return;
  }

  // 3. Run (all members, or the one asked for).
  if (o.mode == Mode::run) {
    std::vector<std::size_t> which;
    if (o.member) which.push_back(o.member - 1);
    else
      for (std::size_t k = 0; k < members.size(); ++k) which.push_back(k);
    std::size_t done = 0;
    const auto st = members.run(which, o.jobs, [&](std::size_t k, const MemberStatus& s) {
      ++done;
      if (s.state == MemberState::failed) cli::warning("member {} failed: {}", k + 1, s.error);
      else if (!s.derived_from.empty()) cli::info("member {} ({}/{}) derived from {}: {}", k + 1, done, which.size(), s.derived_from, s.note);
      else cli::info("member {} ({}/{}){}{}", k + 1, done, which.size(), s.ran_now ? fmt::format(" {:.1f} s", s.seconds) : " (cached)",
                     s.note.empty() ? "" : fmt::format(" (run, not derived: {})", s.note));
    });
    if (o.member) {
      if (st.front().state == MemberState::failed) throw ComputeError(st.front().error);
      return;
    }
  }

  // 4. Collect: metrics and statistics into the output folder, all at once.
  runner::OutputFolder out(o.output);
  const CollectSummary sum = collect(spec, members, metrics, out.temp().string(), {tool.command_line()});
  out.commit();
  for (const auto& [k, e] : sum.failures) cli::warning("member {} excluded from the statistics: {}", k, e);
  for (const auto& n : sum.notes) cli::info("{}", n);
  std::printf("%zu of %zu members in the statistics (%zu failed or missing: failures.csv); outputs in %s\n", sum.done, sum.members,
              sum.failures.size(), out.target().string().c_str());
}

}  // namespace

int main(int argc, char** argv) {
  cli::Tool tool({"ugs-ensemble",
                  "Run an ensemble of a case (parameter distributions from a TOML file) and compute quantiles, exceedance "
                  "probabilities and Sobol' or Morris sensitivity indices.",
                  "ugs-ensemble run --spec ensemble.toml --case case.toml --mesh model.msh --solver-command \"ugs-solve {mesh} "
                  "--case {case} --pressure dp.h5 -o {out}\" --phase storage=2015-05-01/2015-11-01 -j 2 -o ensemble"});
  Options o;
  auto& app = tool.app();
  std::string mode = "run", emit;
  app.add_option("mode", mode, "run (run the members, then collect) or collect (statistics of the members in the cache)")
      ->check(CLI::IsMember({"run", "collect"}));
  app.add_option("--spec", o.spec, "Ensemble file (TOML): [design] and [[parameter]] with distributions")->required();
  app.add_option("--case", o.case_file, "Case file (TOML) whose parameters vary")->required();
  app.add_option("--solver-command", o.solver_command,
                 "Command run for each member ({case}, {out}, {mesh}, {dir} are replaced; it must write {out})")
      ->required();
  app.add_option("--mesh", o.mesh, "Mesh ({mesh} in the command)");
  app.add_option("--cache-dir", o.cache_dir, "Cache of members (default: <output>.cache)");
  app.add_option("-j,--jobs", o.jobs, "Members run at once")->capture_default_str()->check(cli::number_in(1, 256));
  app.add_option("--member", o.member, "Run only member K (1-based; what --emit's jobs run), no collect")
      ->check(cli::number_in(1, 10'000'000));
  app.add_option("--emit", emit, "Write the members as a Makefile (make) or Slurm array script (slurm) to -o instead of running")
      ->check(CLI::IsMember({"make", "slurm"}));
  app.add_option("--phase", o.phases, "NAME=START/END: uplift and settlement over this phase (repeat; default: the whole run)");
  app.add_option("--seismic-window", o.seismic_windows,
                 "NAME=START/END: expected events and P(event >= M) per fault over this window (repeat; needs [seismicity] in "
                 "the case and the members' per-pair fault CSVs)");
  app.add_option("--inside", o.inside, "Surface metrics only inside these polygons (any OGR file, e.g. the reservoir trace)");
  app.add_option("--inside-where", o.inside_where, "OGR attribute filter on the --inside polygons");
  app.add_option("--measured", o.measured, "PS points (EGMS CSV, CSV or OGR): metrics at them, and the InSAR misfit if they have series");
  app.add_option("--measured-east", o.measured_east, "East-west series of the --measured points, added to the misfit with --east-weight");
  app.add_option("--east-weight", o.east_weight, "Weight of east-west residuals in the misfit")
      ->capture_default_str()
      ->check(cli::number_in(0, cli::kNoLimit));
  app.add_option("--window", o.window, "Dates of the misfit, START/END (ISO; either may be empty)");
  app.add_option("--points-crs", o.points_crs, "CRS of the PS coordinates (default: EPSG:3035 for EGMS)");
  app.add_option("--crs", o.crs, "Model CRS (default: the case file's crs)");
  app.add_option("--id-column", o.id_column, "Column holding the PS id (default: pid)");
  app.add_option("--field", o.field, "Displacement node field in the results (default: u, or u_mm)");
  std::string& output = tool.add_output("ensemble", "Output folder (--emit: the Makefile or script)");
  // The library names these settings in words; the messages show the flags.
  tool.name_setting("solver command", "--solver-command");
  tool.name_setting("solver mesh", "--mesh");
  tool.name_setting("metric phase", "--phase");
  tool.name_setting("misfit window", "--window");
  tool.name_setting("PS selection", "--measured, --inside");
  tool.name_setting("polygon filter", "--inside-where");
  tool.name_setting("model CRS", "--crs");
  tool.name_setting("points CRS", "--points-crs");
  return tool.run(argc, argv, [&] {
    o.mode = mode == "collect" ? Mode::collect : Mode::run;
    o.emit = emit == "make" ? Emit::make : emit == "slurm" ? Emit::slurm : Emit::none;
    o.output = output;
    if (o.member && (o.mode != Mode::run || o.emit != Emit::none))
      throw InputError("--member", "runs one member: only with the run mode and without --emit");
    if (o.output == "-") throw InputError("-o", "an output folder (or file for --emit) is needed, not stdout");
    if (!o.measured_east.empty() && o.measured.empty())
      throw InputError("--measured-east", "needs the PS points of --measured (the east series adds to their misfit)");
    run(o, tool);
  });
}
