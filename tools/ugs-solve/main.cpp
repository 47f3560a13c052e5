// ugs-solve — land displacement and stress change of the continuous model caused by the pool
// pressures (thesis 3.4-3.5.1, 4.2.2): quasi-static equilibrium on linear tetrahedra with the
// Biot forcing of the pressure change computed by ugs-flow, transversely isotropic elasticity
// (eq. 3.22) with E_z from the compressibility c_M (eq. 3.23), elastic, linear or hypo-plastic
// (virgin / unloading-reloading) units, Newton per step, PETSc (MPI) linear algebra. On a mesh with
// interface elements (ugs-faultinsert) the faults carry Lagrange multipliers with Mohr-Coulomb
// friction and the run also writes fault tractions, slip, opening and the safety factor chi
// (thesis 3.2-3.5.2, 4.3.4; docs/fault-mechanics.md).
//
//   mpirun -n 2 ugs-solve model.msh --case case.toml --pressure flow_poolA.h5 --pressure flow_poolC.h5 -o solve.h5
//   ugs-meshgen ... | ugs-solve - --case case.toml --pressure flow.h5 -o solve.h5 -- -ksp_monitor -log_view
//   ugs-solve faulted.msh --case case.toml --pressure flow.h5 -o solve.h5 --find-safe-scale
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "ugs/cli/number_option.hpp"
#include "ugs/cli/tool.hpp"
#include "ugs/driver/names.hpp"
#include "ugs/driver/run.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/mechanics/petsc_session.hpp"

#include <mpi.h>
#include <unistd.h>

namespace {

// The options as given; typed() turns them into the driver's settings.
struct Args {
  std::string mesh = "-", case_file, top, top_csv, state, restart, until, solver, partition = "ptscotch", steps, tolerance_of;
  std::vector<std::string> pressure, every_date_in;
  int checkpoint_every = -1;
  std::string fault_output, fault_csv, fault_pairs_csv, fault_solver, scenario_csv, caprock_output, caprock_csv;
  std::optional<double> scale, tolerance;
  bool find_safe_scale = false;
  bool fault_pairs_every_step = false;
};

template <class E>
std::vector<std::string> names_of(const ugs::driver::Names<E>& names) {
  std::vector<std::string> v;
  for (const auto& [n, e] : names) v.push_back(n);
  return v;
}

// "" -> the default path, "none" -> off.
std::optional<std::string> output_path(const std::string& given, const std::string& fallback) {
  if (given == "none") return std::nullopt;
  return given.empty() ? fallback : given;
}

ugs::driver::RunSettings typed(const Args& a, const std::string& output) {
  using namespace ugs::driver;
  if (output == "-" || output.empty()) throw ugs::InputError("-o", "results are HDF5 files: give a file name");
  RunSettings s;
  const std::string stem = output_stem(output);
  s.mesh = a.mesh;
  s.case_file = a.case_file;
  s.pressure = a.pressure;
  s.output = output;
  s.top = output_path(a.top, stem + "_top.h5");
  if (!a.top_csv.empty()) s.top_csv = a.top_csv;
  s.state = output_path(a.state, stem + "_state.h5");
  if (!a.restart.empty()) s.restart = a.restart;
  if (!a.until.empty()) {
    const auto t = ugs::parse_iso_date(a.until);
    if (!t) throw ugs::InputError("--until", "'" + a.until + "' is not an ISO 8601 date");
    s.until = static_cast<double>(*t);
  }
  if (!a.solver.empty()) s.linear = lookup(linear_solver_names(), a.solver);
  if (!a.steps.empty()) s.steps = a.steps;
  s.tolerance = a.tolerance;
  if (!a.tolerance_of.empty()) s.tolerance_of = a.tolerance_of;
  for (const std::string& w : a.every_date_in) {
    const auto slash = w.find('/');
    const auto from = ugs::parse_iso_date(w.substr(0, slash)), to = slash == std::string::npos ? std::nullopt : ugs::parse_iso_date(w.substr(slash + 1));
    if (!from || !to || *to < *from)
      throw ugs::InputError("--every-date-in", "'" + w + "' is not a window FROM/TO of ISO 8601 dates, FROM not after TO");
    s.every_date_in.emplace_back(static_cast<double>(*from), static_cast<double>(*to));
  }
  s.partition = *lookup(partition_names(), a.partition);
  if (a.checkpoint_every >= 0) s.checkpoint_every = a.checkpoint_every;
  FaultSettings& f = s.faults;
  f.fields = output_path(a.fault_output, stem + "_faults.h5");
  f.table = output_path(a.fault_csv, stem + "_faults.csv");
  f.pairs_prefix = output_path(a.fault_pairs_csv, stem + "_fault_");
  f.scenario_table = a.scenario_csv.empty() ? stem + "_scenario.csv" : a.scenario_csv;
  if (!a.fault_solver.empty()) f.solver = lookup(fault_solver_names(), a.fault_solver);
  f.scale = a.scale;
  f.find_safe_scale = a.find_safe_scale;
  f.pairs_every_step = a.fault_pairs_every_step;
  s.caprock_fields = output_path(a.caprock_output, stem + "_caprock.h5");
  s.caprock_table = output_path(a.caprock_csv, stem + "_caprock.csv");
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace ugs::driver;
  ugs::cli::Tool tool({"ugs-solve",
                       "Solve the geomechanics of the continuous model: displacement, strain and stress changes per date "
                       "from the pool pressure changes (PETSc, MPI).",
                       "mpirun -n 2 ugs-solve model.msh --case case.toml --pressure flow_poolA.h5 --pressure flow_poolC.h5 "
                       "-o solve.h5 -- -log_view"});
  Args a;
  auto& app = tool.app();
  app.add_option("mesh", a.mesh, "Mesh (MSH 4.1, ASCII or binary; '-' = stdin); with interface elements the faults are solved too")
      ->capture_default_str();
  app.add_option("--case", a.case_file, "Case file (TOML, docs/case-file.md)")->required();
  app.add_option("--pressure", a.pressure,
                 "Pressure change field series from ugs-flow (HDF5, node field dp in Pa); repeat for several pools, "
                 "summed per node")
      ->required();
  tool.add_output("solve.h5", "Results at the output dates (HDF5 + XDMF beside it)");
  app.add_option("--top", a.top, "Top-surface displacement at every step (HDF5 + XDMF; default <output>_top.h5; 'none')");
  app.add_option("--top-csv", a.top_csv, "Also write the top-surface displacement as a CSV table (mm)");
  app.add_option("--state", a.state, "Restart state file (default <output>_state.h5; 'none': no state)");
  app.add_option("--restart", a.restart, "Resume from a saved state (written by an earlier run)");
  app.add_option("--until", a.until, "Stop after this date (ISO 8601); the state is saved for --restart");
  app.add_option("--solver", a.solver, "Linear solver: cg-hypre (default), cg-gamg, mumps, cholmod (overrides the case)")
      ->check(CLI::IsMember(names_of(linear_solver_names())));
  app.add_option("--steps", a.steps,
                 "Dates stepped on: every-date; turning-points (those that set the state, the output dates, the last "
                 "date; sigma-max only); turning-windows (the fewest dates within the turning-point tolerance of every "
                 "turn) (overrides the case)")
      ->check(CLI::IsMember({"every-date", "turning-points", "turning-windows"}));
  app.add_option("--every-date-in", a.every_date_in,
                 "FROM/TO (ISO 8601): also step on every date of the pressure fields in this window, so that the "
                 "top-surface table and the fault table hold each (repeatable)")
      ->allow_extra_args(false);
  app.add_option("--tolerance", a.tolerance, "Newton tolerance, a relative residual (overrides the case's [solver] tolerance)")
      ->check(ugs::cli::number_in(1e-14, 1, ugs::cli::Ends::OpenHigh));
  app.add_option("--tolerance-of", a.tolerance_of,
                 "What the tolerance is relative to: step (the step's load increment) or total-load (the whole load at "
                 "the date, when larger) (overrides the case)")
      ->check(CLI::IsMember({"step", "total-load"}));
  app.add_option("--partition", a.partition, "Partition of the mesh over MPI ranks: ptscotch or rcb")
      ->capture_default_str()
      ->check(CLI::IsMember(names_of(partition_names())));
  app.add_option("--checkpoint-every", a.checkpoint_every, "Also save the restart state every N steps (overrides the case)")
      ->check(ugs::cli::number_in(0, 1000000));
  auto* g = app.add_option_group("Faults", "Meshes with interface elements (ugs-faultinsert): fault mechanics");
  g->add_option("--fault-output", a.fault_output,
                "Fault fields at the output dates (HDF5 + XDMF; default <output>_faults.h5; 'none')");
  g->add_option("--fault-csv", a.fault_csv, "Per fault and date: max chi, max slip, areas in slip and open (default "
                                            "<output>_faults.csv; 'none')");
  g->add_option("--fault-pairs-csv", a.fault_pairs_csv,
                "Per fault, every node pair at the output dates (position, along strike, down dip, state, tau, sigma'_n, chi, "
                "slip, opening, CFS change): PREFIX<fault>.csv (default <output>_fault_<fault>.csv; 'none')");
  g->add_flag("--fault-pairs-every-step", a.fault_pairs_every_step,
              "Write the per-pair CSVs at every step, not only at the output dates (the faults' stress history for "
              "ugs-seismicity; the volume and fault fields stay at the output dates)");
  g->add_option("--fault-solver", a.fault_solver, "Saddle-point solver: auto, mumps, fieldsplit (overrides the case)")
      ->check(CLI::IsMember(names_of(fault_solver_names())));
  g->add_option("--scale", a.scale, "Scale of the pressure swing after the scenario's reference date (overrides the case)")
      ->check(ugs::cli::number_in(0, ugs::cli::kNoLimit));
  g->add_flag("--find-safe-scale", a.find_safe_scale,
              "Search the smallest scale of the swing at which a fault patch reaches chi = 1 or a [[seal]] element fails "
              "(maximum safe storage pressure; also on a mesh without faults when the case has seals)");
  g->add_option("--scenario-csv", a.scenario_csv, "Scales tried by --find-safe-scale (default <output>_scenario.csv)");
  auto* c = app.add_option_group("Caprock", "Cases with [[seal]] materials: caprock integrity (docs/caprock.md)");
  c->add_option("--caprock-output", a.caprock_output,
                "Seal elements at the output dates: pore pressure, fracture pressure, tensile and shear margins (HDF5 + "
                "XDMF; default <output>_caprock.h5; 'none')");
  c->add_option("--caprock-csv", a.caprock_csv,
                "Per seal and step: the smallest tensile and shear margins and where (default <output>_caprock.csv; 'none')");
  app.footer("PETSc options follow a '--': ugs-solve ... -- -pc_type hypre -ksp_monitor -log_view");

  // Everything after "--" belongs to PETSc.
  std::vector<std::string> petsc_args;
  int ours = argc;
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--") {
      ours = i;
      for (int k = i + 1; k < argc; ++k) petsc_args.emplace_back(argv[k]);
      break;
    }
  tool.name_setting("linear solver", "--solver");
  tool.name_setting("restart state", "--restart");
  tool.name_setting("partition method", "--partition");
  // One voice: messages (and the error line) come from rank 0 unless -vv asks for all ranks. MPI
  // starts before the command line is read (PETSc then leaves it running at its end), so that the
  // other ranks are silent from the start and an error in the options is one line under mpirun too.
  MPI_Init(nullptr, nullptr);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const int own_stderr = rank != 0 ? dup(fileno(stderr)) : -1;
  if (rank != 0) {  // (stdout too: --help and --version once; results are written by rank 0)
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
  }
  const int code = tool.run(ours, argv, [&] {
    ugs::mech::PetscSession petsc(petsc_args);
    if (rank != 0) {
      if (ugs::cli::verbosity() >= 2) {  // every rank's errors
        std::fflush(stderr);
        dup2(own_stderr, fileno(stderr));
      }
      ugs::cli::set_verbosity(-1);
    }
    RunSettings s = typed(a, tool.output());
    s.command_line = tool.command_line();
    s.log = [](int level, const std::string& m) {
      if (level < 0) ugs::cli::warning("{}", m);
      else if (level == 0) ugs::cli::info("{}", m);
      else ugs::cli::detail("{}", m);
    };
    std::unique_ptr<ugs::cli::Progress> bar;
    s.progress = [&](std::size_t done, std::size_t total) {
      if (!bar) bar = std::make_unique<ugs::cli::Progress>("steps", total);
      bar->update(done);
      if (done == total) bar->finish();
    };
    const RunSummary r = run(MPI_COMM_WORLD, s);
    ugs::cli::detail("{} steps: {} Newton iterations, {} linear iterations, {} preconditioner setups, {} sub-steps",
                     r.steps, r.newton_iterations, r.linear_iterations, r.preconditioner_setups, r.substeps);
    ugs::cli::detail("time: reading {:.2f} s, setup {:.2f} s, solving {:.2f} s, output {:.2f} s", r.seconds_read,
                     r.seconds_setup, r.seconds_solve, r.seconds_output);
  });
  // The exit status is rank 0's, which also prints the error line: that line is printed after
  // PetscFinalize (the session ends as the error leaves the run), and another rank leaving with a
  // non-zero status first made mpirun kill rank 0 before it printed (seen on a loaded machine:
  // exit 1 without the line).
  MPI_Finalize();
  return rank == 0 ? code : 0;
}
