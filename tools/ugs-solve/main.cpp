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
#include <string>
#include <vector>

#include "ugs/cli/tool.hpp"
#include "ugs/contact/cli.hpp"
#include "ugs/mechanics/petsc_session.hpp"
#include "ugs/mechanics/run.hpp"

int main(int argc, char** argv) {
  ugs::cli::Tool tool({"ugs-solve",
                       "Solve the geomechanics of the continuous model: displacement, strain and stress changes per date "
                       "from the pool pressure changes (PETSc, MPI).",
                       "mpirun -n 2 ugs-solve model.msh --case case.toml --pressure flow_poolA.h5 --pressure flow_poolC.h5 "
                       "-o solve.h5 -- -log_view"});
  ugs::mech::RunOptions opt;
  auto& app = tool.app();
  app.add_option("mesh", opt.mesh, "Mesh (MSH 4.1, ASCII or binary; '-' = stdin); with interface elements the faults are solved too")
      ->capture_default_str();
  app.add_option("--case", opt.case_file, "Case file (TOML, docs/case-file.md)")->required();
  app.add_option("--pressure", opt.pressure,
                 "Pressure change field series from ugs-flow (HDF5, node field dp in Pa); repeat for several pools, "
                 "summed per node")
      ->required();
  tool.add_output("solve.h5", "Results at the output dates (HDF5 + XDMF beside it)");
  app.add_option("--top", opt.top, "Top-surface displacement at every step (HDF5 + XDMF; default <output>_top.h5; 'none')");
  app.add_option("--top-csv", opt.top_csv, "Also write the top-surface displacement as a CSV table (mm)");
  app.add_option("--state", opt.state, "Restart state file (default <output>_state.h5; 'none': no state)");
  app.add_option("--restart", opt.restart, "Resume from a saved state (written by an earlier run)");
  app.add_option("--until", opt.until, "Stop after this date (ISO 8601); the state is saved for --restart");
  app.add_option("--solver", opt.solver, "Linear solver: cg-hypre (default), cg-gamg, mumps, cholmod (overrides the case)")
      ->check(CLI::IsMember({"cg-gamg", "cg-hypre", "mumps", "cholmod"}));
  app.add_option("--partition", opt.partition, "Partition of the mesh over MPI ranks: ptscotch or rcb")
      ->capture_default_str()
      ->check(CLI::IsMember({"ptscotch", "rcb"}));
  app.add_option("--checkpoint-every", opt.checkpoint_every, "Also save the restart state every N steps (overrides the case)")
      ->check(CLI::Range(0, 1000000));
  ugs::contact::FaultedRunOptions fault_opt;
  ugs::contact::add_fault_options(app, fault_opt);
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
  return tool.run(ours, argv, [&] {
    opt.output = tool.output();
    opt.command_line = tool.command_line();
    ugs::mech::PetscSession petsc(petsc_args);
    // One voice: messages (and the error line) come from rank 0 unless -vv asks for all ranks.
    if (petsc.rank() != 0) {
      if (ugs::cli::verbosity() < 2) std::freopen("/dev/null", "w", stderr);
      ugs::cli::set_verbosity(-1);
    }
    opt.log = [](int level, const std::string& s) {
      if (level < 0) ugs::cli::warning("{}", s);
      else if (level == 0) ugs::cli::info("{}", s);
      else ugs::cli::detail("{}", s);
    };
    std::unique_ptr<ugs::cli::Progress> bar;
    opt.progress = [&](std::size_t done, std::size_t total) {
      if (!bar) bar = std::make_unique<ugs::cli::Progress>("steps", total);
      bar->update(done);
      if (done == total) bar->finish();
    };
    ugs::contact::use_fault_mechanics(opt, fault_opt);
    const ugs::mech::RunSummary s = ugs::mech::run_solve(MPI_COMM_WORLD, opt);
    ugs::cli::detail("{} steps: {} Newton iterations, {} linear iterations, {} preconditioner setups, {} sub-steps",
                     s.steps, s.newton_iterations, s.linear_iterations, s.preconditioner_setups, s.substeps);
    ugs::cli::detail("time: reading {:.2f} s, setup {:.2f} s, solving {:.2f} s, output {:.2f} s", s.seconds_read,
                     s.seconds_setup, s.seconds_solve, s.seconds_output);
  });
}
