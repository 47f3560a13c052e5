// ugs-solve end to end: V1 through the tool (the three inversion rules, c_M in use and loading
// state), the same problem on 1 and 2 MPI processes, restart against an uninterrupted run, the
// top-surface outputs, PETSc options, direct solvers, bad input (exit 2) and a failing step (exit 1).
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>
#include <hdf5.h>

#include "solve_support.hpp"
#include "v1_oedometer.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

// Column shortening [m] at each date of the V1 case (4 layers of 0.25 m about sigma'_v0 = 20 MPa).
std::vector<double> v1_shortening(const std::string& rule, double cR) {
  const double d20 = 20.0 / 0.0126;
  std::vector<double> total(5, 0.0);
  for (int k = 0; k < 4; ++k) {
    const double zc = -d20 - 0.5 + 0.25 * (k + 0.5), s0 = 0.0126 * -zc;
    const std::vector<double> e = test::v1::layer_strain(rule, s0, cR, {0, 6, 3, 8, 5});
    for (int t = 0; t < 5; ++t) total[t] += 0.25 * e[t];
  }
  return total;
}

using Dir = test::TempDir;

std::string column_args(const Dir& d, const std::string& case_file = "case.toml") {
  return d / "mesh.msh" + " --case " + d / case_file + " --pressure " + d / "flow.h5";
}

// Writes mech_make_case's two-pool "small" case into d; returns ugs-solve's mesh and pressure
// arguments (empty when the case could not be made).
std::string small_case_args(const Dir& d) {
  if (test::run(test::make_case() + " small " + d.path.string()).exit_code != 0) return {};
  return d / "mesh.msh" + " --pressure " + d / "flow_pool_a.h5" + " --pressure " + d / "flow_pool_c.h5";
}

// Writes a variant of the V1 case file with `from` replaced by `to`.
void variant(const Dir& d, const std::string& from, const std::string& to, const std::string& out) {
  std::string text = test::slurp(d / "case.toml");
  const auto p = text.find(from);
  ASSERT_NE(p, std::string::npos) << from;
  text.replace(p, from.size(), to);
  test::spit(d / out, text);
}

// Runs `args` (no shell: the signals reach the program itself), stdout and stderr to `log`,
// stopping it with SIGSTOP for 1-40 ms after every 1-20 ms of running, at moments drawn from
// `seed`. Returns the exit code and counts the pauses.
int run_paused(const std::vector<std::string>& args, const std::string& log, unsigned seed, int& pauses) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), ::environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) return -1;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> run_ms(1, 20), stop_ms(1, 40);
  pauses = 0;
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(run_ms(rng)));
    if (kill(pid, SIGSTOP) != 0) continue;
    std::this_thread::sleep_for(std::chrono::milliseconds(stop_ms(rng)));
    kill(pid, SIGCONT);
    ++pauses;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Damages one entry of a dataset of an HDF5 file in place (a corrupt or hand-edited input).
// `dataset` may name the n-th step's group as "{step}": "/steps/{step}/node/dp".
template <class T>
void poke(const std::string& file, std::string dataset, std::size_t index, T value, hid_t mem_type, int step = 0) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0) << file;
  if (const auto p = dataset.find("{step}"); p != std::string::npos) {
    char name[256] = {};
    ASSERT_GT(H5Lget_name_by_idx(f, "/steps", H5_INDEX_NAME, H5_ITER_INC, step, name, sizeof name, H5P_DEFAULT), 0);
    dataset.replace(p, 6, name);
  }
  const hid_t ds = H5Dopen2(f, dataset.c_str(), H5P_DEFAULT);
  ASSERT_GE(ds, 0) << dataset;
  const hid_t space = H5Dget_space(ds);
  std::vector<T> v(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  ASSERT_GE(H5Dread(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
  ASSERT_LT(index, v.size());
  v[index] = value;
  ASSERT_GE(H5Dwrite(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
  H5Sclose(space);
  H5Dclose(ds);
  H5Fclose(f);
}

// Removes a link (a dataset) from an HDF5 file.
void unlink(const std::string& file, const std::string& name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0) << file;
  EXPECT_GE(H5Ldelete(f, name.c_str(), H5P_DEFAULT), 0) << name;
  H5Fclose(f);
}

// Replaces a dataset by a group of the same name (a listing still shows it; it does not open as data).
void replace_by_group(const std::string& file, const std::string& name) {
  unlink(file, name);
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0) << file;
  const hid_t g = H5Gcreate2(f, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(g, 0) << name;
  H5Gclose(g);
  H5Fclose(f);
}

// Sets the time attribute of the n-th step of a field series.
void poke_time(const std::string& file, int step, double t) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0) << file;
  char name[256] = {};
  EXPECT_GT(H5Lget_name_by_idx(f, "/steps", H5_INDEX_NAME, H5_ITER_INC, step, name, sizeof name, H5P_DEFAULT), 0);
  const hid_t g = H5Gopen2(f, (std::string("/steps/") + name).c_str(), H5P_DEFAULT);
  const hid_t a = H5Aopen(g, "time", H5P_DEFAULT);
  EXPECT_GE(H5Awrite(a, H5T_NATIVE_DOUBLE, &t), 0);
  H5Aclose(a);
  H5Gclose(g);
  H5Fclose(f);
}

}  // namespace

class SolveV1 : public ::testing::TestWithParam<std::string> {};

TEST_P(SolveV1, OedometerPathThroughTheTool) {
  const std::string rule = GetParam();
  Dir d("solve-v1");
  ASSERT_EQ(test::run(test::make_case() + " column " + d.path.string() + " --rule " + rule).exit_code, 0);
  const auto r = test::run(test::solve_cmd() + " " + column_args(d) + " -o " + d / "out.h5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto ref = v1_shortening(rule, 3.0);
  FieldSeriesReader top(d / "out_top.h5");
  ASSERT_EQ(top.steps().size(), 5u);
  EXPECT_EQ(top.steps()[1].date, "2001-01-01");
  for (std::size_t s = 1; s < 5; ++s) {
    const Field u = top.node_field(s, "u_mm");
    double uz = 0;
    for (std::size_t i = 0; i < u.count(); ++i) uz += u.values[3 * i + 2];
    uz = uz / u.count() * 1e-3;
    EXPECT_NEAR(-uz / ref[s], 1.0, 0.005) << rule << " date " << s;
  }
  // The state and c_M in use: unloading from 28 MPa (last date) runs at c_M / c_R of the rule.
  FieldSeriesReader res(d / "out.h5");
  ASSERT_EQ(res.steps().size(), 5u);
  const Field st2 = res.cell_field(2, "state"), st3 = res.cell_field(3, "state"), st4 = res.cell_field(4, "state");
  for (double v : st2.values) EXPECT_EQ(v, 2.0);  // unloading
  for (double v : st3.values) EXPECT_EQ(v, 1.0);  // virgin again past sigma_max
  for (double v : st4.values) EXPECT_EQ(v, 2.0);
  const Field cm = res.cell_field(4, "cM"), smax = res.cell_field(4, "sigma_z_max");
  for (std::size_t c = 0; c < cm.values.size(); ++c) {
    const double s_max = smax.values[c] * 1e-6;
    EXPECT_NEAR(s_max, 28.0, 0.02);
    if (rule != "stress-dependent") {
      EXPECT_NEAR(cm.values[c] / (test::v1::cM(s_max) / 3.0 * 1e-6), 1.0, 1e-9);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Rules, SolveV1, ::testing::Values("sigma-max", "sigma-inversion", "stress-dependent"),
                         [](const auto& info) {
                           std::string s = info.param;
                           for (auto& c : s)
                             if (c == '-') c = '_';
                           return s;
                         });

TEST(SolveTool, TopSurfaceCsvAndDirectSolversAgree) {
  Dir d("solve-csv");
  ASSERT_EQ(test::run(test::make_case() + " column " + d.path.string()).exit_code, 0);
  auto r = test::run(test::solve_cmd() + " " + column_args(d) + " -o " + d / "gamg.h5" + " --top-csv " + d / "top.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string csv = test::slurp(d / "top.csv");
  EXPECT_NE(csv.find("date,node,x_m,y_m,ux_mm,uy_mm,uz_mm"), std::string::npos);
  std::size_t rows = 0;
  for (std::size_t p = csv.find("\n2"); p != std::string::npos; p = csv.find("\n2", p + 1)) ++rows;
  EXPECT_EQ(rows, 4u * 5u);  // 4 top nodes, 5 dates
  const auto u0 = test::last_field(d / "gamg.h5", "u", false);
  for (const char* s : {"mumps", "cholmod"}) {
    r = test::run(test::solve_cmd() + " " + column_args(d) + " -o " + d / (std::string(s) + ".h5") + " --solver " + s);
    ASSERT_EQ(r.exit_code, 0) << s << ": " << r.err;
    EXPECT_LT(test::max_rel_diff(u0, test::last_field(d / (std::string(s) + ".h5"), "u", false)), 1e-6) << s;
  }
}

TEST(SolveTool, TurningPointStepsMatchEveryDate) {
  // The two-pool case, monthly 1959-10 .. 1960-09: production to 1960, then the first cycle with
  // the aquifers lagging. Depletion is monotonic to 1960-01-01, so the first three dates are
  // skipped; after it some aquifer element reaches a new low and turns back every month.
  Dir d("solve-turning");
  const std::string args = small_case_args(d);
  ASSERT_FALSE(args.empty());
  auto r = test::run(test::solve_cmd() + " " + args + " --case " + d / "case.toml" + " -o " + d / "all.h5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  variant(d, "[output]", "[solver]\nsteps = \"turning-points\"\n\n[output]", "turning.toml");
  r = test::run(test::solve_cmd() + " " + args + " --case " + d / "turning.toml" + " -o " + d / "turning.h5" + " -v");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("turning-point steps: 9 of 12 dates"), std::string::npos) << r.err;
  // The dates skipped are named once, with how to keep them (issue 20: they were dropped from the
  // top-surface series without a word).
  const std::string skipped = "turning.toml: steps = \"turning-points\": 3 of the 12 pressure dates are not stepped on and are "
                              "missing from the top-surface series; list the dates you need in [output] dates, or set [solver] "
                              "steps = \"every-date\"";
  const auto at = r.err.find("ugs-solve: warning: ");
  EXPECT_NE(at, std::string::npos) << r.err;
  EXPECT_NE(r.err.find(skipped), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(skipped), r.err.rfind(skipped)) << r.err;
  // Every output date is kept: the results hold both, the top surface has them.
  FieldSeriesReader results(d / "turning.h5");
  ASSERT_EQ(results.steps().size(), 2u);
  EXPECT_EQ(results.steps()[0].date, "1960-03-01");
  EXPECT_EQ(results.steps()[1].date, "1960-09-01");
  // An output date that is no turning point (1959-11-01, during the monotonic depletion) is a step,
  // in the results and the top surface, and only the dates not asked for are skipped.
  variant(d, "dates = [\"1960-03-01\", \"1960-09-01\"]", "dates = [\"1959-11-01\", \"1960-03-01\", \"1960-09-01\"]",
          "turning_out.toml");
  {
    std::string t = test::slurp(d / "turning_out.toml");
    t.replace(t.find("[output]"), 8, "[solver]\nsteps = \"turning-points\"\n\n[output]");
    test::spit(d / "turning_out.toml", t);
  }
  r = test::run(test::solve_cmd() + " " + args + " --case " + d / "turning_out.toml" + " -o " + d / "turning_out.h5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("2 of the 12 pressure dates are not stepped on"), std::string::npos) << r.err;
  FieldSeriesReader out_results(d / "turning_out.h5"), out_top(d / "turning_out_top.h5");
  ASSERT_EQ(out_results.steps().size(), 3u);
  EXPECT_EQ(out_results.steps()[0].date, "1959-11-01");
  ASSERT_EQ(out_top.steps().size(), 10u);
  EXPECT_EQ(out_top.steps()[0].date, "1959-11-01");
  FieldSeriesReader all(d / "all_top.h5"), turning(d / "turning_top.h5");
  ASSERT_EQ(all.steps().size(), 12u);
  ASSERT_EQ(turning.steps().size(), 9u);
  EXPECT_EQ(turning.steps().front().date, "1960-01-01");
  EXPECT_EQ(turning.steps().back().date, "1960-09-01");
  // The same displacement on every date both took: the production step of 3 months instead of 3
  // monthly steps changes the strain path a little (measured 4.8e-6 of the largest settlement).
  for (std::size_t s = 0; s < turning.steps().size(); ++s) {
    const std::size_t k = s + 3;
    ASSERT_EQ(all.steps()[k].date, turning.steps()[s].date);
    EXPECT_LT(test::max_rel_diff(all.node_field(k, "u_mm").values, turning.node_field(s, "u_mm").values), 1e-5)
        << turning.steps()[s].date;
  }
  // Turning windows (--steps overrides the case): no more dates than the turning points, the plan
  // and the note of the dates skipped name the mode, and the output dates keep the every-date
  // answer (each low secured within the 0.01 MPa tolerance).
  r = test::run(test::solve_cmd() + " " + args + " --case " + d / "turning.toml" + " --steps turning-windows -o " +
                d / "windows.h5" + " -v");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("dates (the fewest dates within the tolerance of every turn of the pressure"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("turning.toml: steps = \"turning-windows\": "), std::string::npos) << r.err;
  FieldSeriesReader windows(d / "windows_top.h5"), windows_results(d / "windows.h5");
  EXPECT_LE(windows.steps().size(), turning.steps().size());
  ASSERT_EQ(windows_results.steps().size(), 2u);
  std::size_t compared = 0;
  for (std::size_t s = 0; s < windows.steps().size(); ++s)
    for (std::size_t k = 0; k < all.steps().size(); ++k)
      if (all.steps()[k].date == windows.steps()[s].date && (all.steps()[k].date == "1960-03-01" || all.steps()[k].date == "1960-09-01")) {
        ++compared;
        EXPECT_LT(test::max_rel_diff(all.node_field(k, "u_mm").values, windows.node_field(s, "u_mm").values), 1e-4)
            << windows.steps()[s].date;
      }
  EXPECT_EQ(compared, 2u);
}

TEST(SolveTool, PetscOptionsPassThrough) {
  Dir d("solve-petsc");
  ASSERT_EQ(test::run(test::make_case() + " column " + d.path.string()).exit_code, 0);
  const auto r = test::run(test::solve_cmd() + " " + column_args(d) + " -o " + d / "out.h5" +
                           " -- -ksp_type gmres -ksp_gmres_restart 50 -log_view");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Performance Summary"), std::string::npos);
  EXPECT_NE(r.out.find("UgsResidual"), std::string::npos);
}

TEST(SolveTool, SameResultOnOneAndTwoProcesses) {
  Dir d("solve-mpi");
  const std::string args = small_case_args(d);
  ASSERT_FALSE(args.empty());
  // Both MUMPS-preconditioned GMRES and CG + GAMG, driven to 1e-12 (each is a Krylov solve to the
  // Newton forcing term, so the processor count shows at the tolerance).
  std::string text = test::slurp(d / "case.toml");
  text.replace(text.find("[output]"), 8, "[solver]\ntolerance = 1e-12\n\n[output]");
  test::spit(d / "tight.toml", text);
  for (const auto& [opts, tag] : std::vector<std::pair<std::string, std::string>>{
           {" --case " + d / "tight.toml" + " --solver mumps", "mumps"}, {" --case " + d / "tight.toml", "gamg"}}) {
    auto r1 = test::run(test::solve_cmd() + " " + args + opts + " -o " + d / (tag + "1.h5"));
    ASSERT_EQ(r1.exit_code, 0) << r1.err;
    auto r2 = test::run(test::solve_cmd(2) + " " + args + opts + " -o " + d / (tag + "2.h5"));
    ASSERT_EQ(r2.exit_code, 0) << r2.err;
    const auto u1 = test::last_field(d / (tag + "1.h5"), "u", false), u2 = test::last_field(d / (tag + "2.h5"), "u", false);
    const auto s1 = test::last_field(d / (tag + "1.h5"), "stress", true), s2 = test::last_field(d / (tag + "2.h5"), "stress", true);
    EXPECT_GT(test::max_abs(u1), 1e-4);  // millimetres of compaction: a real solution
    EXPECT_LT(test::max_rel_diff(u1, u2), 1e-10) << tag;
    EXPECT_LT(test::max_rel_diff(s1, s2), 1e-10) << tag;
  }
}

// u and stress of the last step of two runs (1 and 2 processes) within 1e-10 of their largest values.
static void expect_same_last_step(const std::string& a, const std::string& b, const std::string& tag) {
  EXPECT_LT(test::max_rel_diff(test::last_field(a, "u", false), test::last_field(b, "u", false)), 1e-10) << tag;
  EXPECT_LT(test::max_rel_diff(test::last_field(a, "stress", true), test::last_field(b, "stress", true)), 1e-10) << tag;
}

// Issue 21: per-material ratios and boundary tractions reach every rank (distributed with the model):
// the small case with its rock at k_Hmax 1.2 / k_hmin 0.6, rollers on west, south and bottom, the
// in-situ load on east and north and 1 MPa pressing the top gives the same u and stress on 1 and 2
// processes; the top load settles the model (u differs from the unloaded run) and the rock's output
// stress at the first output date (two monthly steps, --until 1959-12-01) keeps sigma'_xx / sigma'_yy near k_hmin / k_Hmax = 0.5.
TEST(SolveTool, RatiosAndTractionsOnOneAndTwoProcesses) {
  Dir d("solve-traction");
  ASSERT_EQ(test::run(test::make_case() + " small " + d.path.string() + " --refine 0.5").exit_code, 0);
  const std::string args = d / "mesh.msh" + " --pressure " + d / "flow_pool_a.h5" + " --pressure " + d / "flow_pool_c.h5" +
                           " --until 1959-12-01";
  std::string text = test::slurp(d / "case.toml");
  text.replace(text.find("dates = ["), 36, "dates = [\"1959-11-01\", \"1959-12-01\"]");
  text.replace(text.find("nu = 0.3\n"), 9, "nu = 0.3\nk_Hmax = 1.2\nk_hmin = 0.6\n");
  const std::string bc = "[boundary]\nfixed = []\nrollers = [\"west\", \"south\", \"bottom\"]\n\n"
                         "[[boundary_traction]]\ngroup = \"east\"\nin_situ = true\n\n"
                         "[[boundary_traction]]\ngroup = \"north\"\nin_situ = true\n\n";
  test::spit(d / "unloaded.toml", text.substr(0, text.find("[output]")) + bc + text.substr(text.find("[output]")));
  test::spit(d / "loaded.toml", text.substr(0, text.find("[output]")) + bc +
                                    "[[boundary_traction]]\ngroup = \"top\"\ntraction_MPa = [0, 0, -1]\n\n" +
                                    text.substr(text.find("[output]")));
  for (const std::string tag : {"unloaded", "loaded"}) {
    const std::string opts = " --case " + d / (tag + ".toml") + " --solver mumps";
    auto r1 = test::run(test::solve_cmd() + " " + args + opts + " -o " + d / (tag + "1.h5"));
    ASSERT_EQ(r1.exit_code, 0) << r1.err;
    auto r2 = test::run(test::solve_cmd(2) + " " + args + opts + " -o " + d / (tag + "2.h5"));
    ASSERT_EQ(r2.exit_code, 0) << r2.err;
    expect_same_last_step(d / (tag + "1.h5"), d / (tag + "2.h5"), tag);
  }
  const auto u0 = test::last_field(d / "unloaded1.h5", "u", false), u1 = test::last_field(d / "loaded1.h5", "u", false);
  double settle = 0;  // the top load's extra settlement: 1 MPa over ~2.5 km of rock, centimetres
  for (std::size_t i = 2; i < u0.size(); i += 3) settle = std::max(settle, u0[i] - u1[i]);
  std::printf("1 MPa on the top: up to %.4f m more settlement\n", settle);
  EXPECT_GT(settle, 1e-3);
  FieldSeriesReader r(d / "unloaded1.h5");
  const auto s = r.cell_field(0, "stress").values;
  std::size_t rock_like = 0;
  for (std::size_t c = 0; 6 * c + 5 < s.size(); ++c)
    if (s[6 * c + 1] < -1e6 && std::abs(s[6 * c] / s[6 * c + 1] - 0.5) < 0.02) ++rock_like;
  EXPECT_GT(rock_like, s.size() / 6 / 2) << "most elements are rock with sigma'_xx / sigma'_yy = 0.6 / 1.2";
}

// Issue 42: a mechanical earth model (tables by depth, an overpressure, a gas column in Pool A)
// reaches every rank (its tables are serialized with the model): the small case gives the same u
// and stress on 1 and 2 processes, and other numbers than the gradient form it replaces.
TEST(SolveTool, EarthModelOnOneAndTwoProcesses) {
  Dir d("solve-earth");
  ASSERT_EQ(test::run(test::make_case() + " small " + d.path.string() + " --refine 0.5").exit_code, 0);
  const std::string args = d / "mesh.msh" + " --pressure " + d / "flow_pool_a.h5" + " --pressure " + d / "flow_pool_c.h5" +
                           " --until 1959-12-01 --solver mumps";
  std::string text = test::slurp(d / "case.toml");
  text.replace(text.find("dates = ["), 36, "dates = [\"1959-11-01\", \"1959-12-01\"]");
  test::spit(d / "gradients.toml", text);
  auto swap = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  swap("lithostatic_gradient_MPa_per_m = 0.0226\n", "Sv_density_kg_per_m3 = [[0, 2100], [1500, 2400]]\n");
  swap("k0 = 0.9\n", "Shmin_MPa = [[1000, 17], [2000, 36]]\nSHmax_over_Shmin = 1.1\nHmax_azimuth_deg = 30\n"
                     "overpressure_MPa = [[1450, 0], [1500, 3]]\nregime = \"normal\"\n");
  swap("column = \"p_MPa\"\n", "column = \"p_MPa\"\ngas_water_contact_m = -1425\ngas_density_kg_per_m3 = 180\n");
  test::spit(d / "earth.toml", text);
  for (const std::string tag : {"earth", "gradients"}) {
    auto r1 = test::run(test::solve_cmd() + " " + args + " --case " + d / (tag + ".toml") + " -o " + d / (tag + "1.h5"));
    ASSERT_EQ(r1.exit_code, 0) << r1.err;
    if (tag != "earth") continue;
    auto r2 = test::run(test::solve_cmd(2) + " " + args + " --case " + d / (tag + ".toml") + " -o " + d / (tag + "2.h5"));
    ASSERT_EQ(r2.exit_code, 0) << r2.err;
    expect_same_last_step(d / "earth1.h5", d / "earth2.h5", tag);
  }
  const auto se = test::last_field(d / "earth1.h5", "stress", true), sg = test::last_field(d / "gradients1.h5", "stress", true);
  const auto ue = test::last_field(d / "earth1.h5", "u", false), ug = test::last_field(d / "gradients1.h5", "u", false);
  EXPECT_GT(test::max_rel_diff(se, sg), 1e-2);  // other initial stresses
  EXPECT_GT(test::max_rel_diff(ue, ug), 1e-3);  // other c_M (sigma'_v0 with the density log, the gas cap)
}

// Determinism: the same input on the same number of processes gives the same numbers, bit for bit
// (the partition is Scotch's with a fixed seed: through PETSc's PT-Scotch path it changed from run
// to run, and the displacements with it, by ~1e-9 m on a 52,000-node box).
TEST(SolveTool, TwoProcessRunsAreIdentical) {
  Dir d("solve-determinism");
  const std::string small = small_case_args(d);
  ASSERT_FALSE(small.empty());
  const std::string args = small + " --case " + d / "case.toml";
  for (const std::string tag : {"a", "b"}) {
    auto r = test::run(test::solve_cmd(2) + " " + args + " -o " + d / (tag + ".h5"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const auto ua = test::last_field(d / "a.h5", "u", false), ub = test::last_field(d / "b.h5", "u", false);
  const auto sa = test::last_field(d / "a.h5", "stress", true), sb = test::last_field(d / "b.h5", "stress", true);
  EXPECT_GT(test::max_abs(ua), 1e-4);
  EXPECT_EQ(ua, ub);
  EXPECT_EQ(sa, sb);
}

// Determinism on a busy machine (issue 20): CHOLMOD's factorization is kept or rebuilt by a rule
// on iteration counts (reuse_rule.hpp). When the rule compared measured seconds, a run paused now
// and then (as a loaded machine does) took other decisions, and the hypo-plastic branches
// amplified them: runs of this case (to 1960-09) took 54-56 Newton and 230-306 linear
// iterations, 2-5 factorizations, and their output files differed. Now every output file is the
// same, byte for byte, whether the run was paused or not. The steps to 1960-06 cross the load
// reversal of 1960-02 (elements go from virgin loading to unloading and back).
TEST(SolveTool, CholmodRunsAreIdenticalWhenPausedAtRandomMoments) {
  Dir d("solve-paused");
  const std::string small = small_case_args(d);
  ASSERT_FALSE(small.empty());
  auto args = [&](const std::string& tag) {
    return std::vector<std::string>{test::tool("ugs-solve"), d / "mesh.msh", "--case", d / "case.toml", "--pressure",
                                    d / "flow_pool_a.h5", "--pressure", d / "flow_pool_c.h5", "--solver", "cholmod",
                                    "--until", "1960-06-01", "-o", d / (tag + "/out.h5"), "-v"};
  };
  // The reference runs its course; two runs are stopped for up to 40 ms after every 1-20 ms.
  fs::create_directories(d.path / "quiet");
  ASSERT_EQ(test::run(test::solve_cmd() + " " + small + " --case " + d / "case.toml" + " --solver cholmod --until 1960-06-01 -o " +
                      d / "quiet/out.h5" + " -v > " + d / "quiet.log" + " 2>&1").exit_code, 0)
      << test::slurp(d / "quiet.log");
  auto summary = [](const std::string& log) {  // the -v line of the iteration counts
    const auto p = log.find("9 steps:");
    return p == std::string::npos ? log : log.substr(p, log.find('\n', p) - p);
  };
  for (const unsigned seed : {20u, 21u}) {
    const std::string tag = "paused" + std::to_string(seed);
    fs::create_directories(d.path / tag);
    int pauses = 0;
    ASSERT_EQ(run_paused(args(tag), d / (tag + ".log"), seed, pauses), 0) << test::slurp(d / (tag + ".log"));
    EXPECT_GT(pauses, 10) << "the run ended before it could be paused often";
    EXPECT_EQ(summary(test::slurp(d / "quiet.log")), summary(test::slurp(d / (tag + ".log"))));
    for (const std::string f : {"out.h5", "out.xdmf", "out_top.h5", "out_top.xdmf", "out_state.h5"}) {
      const std::string a = test::slurp(d / ("quiet/" + f)), b = test::slurp(d / (tag + "/" + f));
      EXPECT_FALSE(a.empty()) << f;
      EXPECT_TRUE(a == b) << f << " differs between the quiet run and " << tag;
    }
  }
}

TEST(SolveTool, RestartReproducesAnUninterruptedRun) {
  Dir d("solve-restart");
  const std::string small = small_case_args(d);
  ASSERT_FALSE(small.empty());
  const std::string args = small + " --case " + d / "case.toml";
  for (const std::string solver : {"mumps", "cg-gamg"}) {
    const std::string s = " --solver " + solver;
    auto r = test::run(test::solve_cmd() + " " + args + s + " -o " + d / "full.h5");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = test::run(test::solve_cmd() + " " + args + s + " -o " + d / "first.h5" + " --until 1960-04-01");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = test::run(test::solve_cmd(2) + " " + args + s + " -o " + d / "second.h5" + " --restart " + d / "first_state.h5");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    FieldSeriesReader first(d / "first.h5"), second(d / "second.h5"), full(d / "full.h5");
    EXPECT_EQ(first.steps().size(), 1u);   // 1960-03-01
    EXPECT_EQ(second.steps().size(), 1u);  // 1960-09-01
    EXPECT_EQ(second.steps()[0].date, full.steps().back().date);
    // Both pieces converge each step to the Newton tolerance (1e-8); MUMPS' factorization
    // preconditions a Krylov solve too, so the restart agrees to about that tolerance.
    const double tol = solver == "mumps" ? 1e-8 : 1e-6;
    EXPECT_LT(test::max_rel_diff(test::last_field(d / "full.h5", "u", false), test::last_field(d / "second.h5", "u", false)), tol)
        << solver;
    EXPECT_LT(test::max_rel_diff(test::last_field(d / "full.h5", "stress", true),
                                 test::last_field(d / "second.h5", "stress", true)), tol)
        << solver;
    // The top surface of the two pieces covers every date once.
    FieldSeriesReader t1(d / "first_top.h5"), t2(d / "second_top.h5"), tf(d / "full_top.h5");
    EXPECT_EQ(t1.steps().size() + t2.steps().size(), tf.steps().size());
  }
}

TEST(SolveTool, FailingStepExitsOneAndSavesTheLastGoodState) {
  Dir d("solve-fail");
  ASSERT_EQ(test::run(test::make_case() + " column " + d.path.string()).exit_code, 0);
  variant(d, "[solver]\n", "[solver]\nmax_newton_iterations = 1\nmax_substeps = 1\n", "fail.toml");
  const auto r = test::run(test::solve_cmd() + " " + column_args(d, "fail.toml") + " -o " + d / "out.h5");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("ugs-solve: error: step 2/5 (2001-01-01): Newton did not converge in 1 iterations"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("relative residuals 1.00e+00, "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("last good state (2000-01-01) saved"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(d / "out.h5"));
  ASSERT_TRUE(fs::exists(d / "out_state.h5"));
  FieldSeriesReader st(d / "out_state.h5");
  EXPECT_EQ(st.steps()[0].date, "2000-01-01");
  // The first step after a restart fails on 2 processes: the restart state is the last good one
  // (every rank takes part in gathering it).
  const auto again = test::run(test::solve_cmd(2) + " " + column_args(d, "fail.toml") + " -o " + d / "again.h5" + " --restart " +
                               d / "out_state.h5");
  EXPECT_EQ(again.exit_code, 1) << again.err;
  EXPECT_NE(again.err.find("last good state (2000-01-01) saved"), std::string::npos) << again.err;
  EXPECT_TRUE(fs::exists(d / "again_state.h5"));
}

struct BadCase {
  std::string name, from, to, expect;
};
void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class SolveBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(SolveBadInput, ExitsTwoWithOneLine) {
  const BadCase& c = GetParam();
  Dir d("solve-bad");
  ASSERT_EQ(test::run(test::make_case() + " column " + d.path.string()).exit_code, 0);
  variant(d, c.from, c.to, "bad.toml");
  const auto r = test::run(test::solve_cmd() + " " + column_args(d, "bad.toml") + " -o " + d / "out.h5");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("ugs-solve: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(d / "out.h5"));
  EXPECT_FALSE(fs::exists(d / "out_top.h5"));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SolveBadInput,
    ::testing::Values(BadCase{"missing_cR", "c_R = 3.0\n", "", "c_R': is required for law = \"hypoplastic\""},
                      BadCase{"nu_too_large", "nu_z = 0.3", "nu_z = 0.5", "outside (-1, 0.5)"},
                      BadCase{"nu_too_small", "nu_z = 0.3", "nu_z = -1.2", "outside (-1, 0.5)"},
                      BadCase{"Eh_over_Ez_zero", "Eh_over_Ez = 3.0", "Eh_over_Ez = 0", "Eh_over_Ez': must be positive, got 0"},
                      BadCase{"Eh_over_Ez_negative", "Eh_over_Ez = 3.0", "Eh_over_Ez = -1", "must be positive"},
                      BadCase{"negative_cR", "c_R = 3.0", "c_R = -3.0", "c_R': must be positive, got -3"},
                      BadCase{"not_positive_definite", "nuh_over_nuz = 0.2", "nuh_over_nuz = 2.5", "not positive definite"},
                      BadCase{"unknown_boundary", "fixed = [\"bottom\"]", "fixed = [\"bottom\", \"upper\"]",
                              "unknown boundary 'upper'"},
                      BadCase{"boundary_twice", "free = [\"top\"]", "free = [\"bottom\"]", "boundary 'bottom' is also in fixed"},
                      BadCase{"unknown_material", "name = \"rock\"", "name = \"granite\"", "mesh material 'rock'"},
                      // Issue 21: stress ratios, azimuth, boundary tractions.
                      BadCase{"k0_zero", "hydrostatic_gradient_MPa_per_m = 0.0100\n", "hydrostatic_gradient_MPa_per_m = 0.0100\nk0 = 0\n",
                              "bad.toml:5: 'initial_stress.k0': must be positive, got 0"},
                      BadCase{"k_hmin_negative", "hydrostatic_gradient_MPa_per_m = 0.0100\n",
                              "hydrostatic_gradient_MPa_per_m = 0.0100\nk_hmin = -0.7\n",
                              "bad.toml:5: 'initial_stress.k_hmin': must be positive, got -0.7"},
                      BadCase{"azimuth_360", "hydrostatic_gradient_MPa_per_m = 0.0100\n",
                              "hydrostatic_gradient_MPa_per_m = 0.0100\nHmax_azimuth_deg = 360\n",
                              "bad.toml:5: 'initial_stress.Hmax_azimuth_deg': 360 is outside [0, 360) degrees"},
                      BadCase{"material_k_Hmax_zero", "c_R = 3.0\n", "c_R = 3.0\nk_Hmax = 0\n",
                              "'material[0].k_Hmax': must be positive, got 0"},
                      BadCase{"material_k0_inf", "c_R = 3.0\n", "c_R = 3.0\nk0 = inf\n", "material[0].k0 = inf is not a finite number"},
                      BadCase{"traction_group_not_in_mesh", "[solver]", "[[boundary_traction]]\ngroup = \"flank\"\ntraction_MPa = [1, 0, 0]\n\n[solver]",
                              "bad.toml:19: boundary_traction: the mesh has no group bnd:flank (expected one of its boundary groups: "
                              "west, east, south, north, bottom, top)"},
                      BadCase{"traction_without_value", "[solver]", "[[boundary_traction]]\ngroup = \"flank\"\n\n[solver]",
                              "bad.toml:19: boundary_traction on 'flank' has no value (expected traction_MPa = [tx, ty, tz] or "
                              "in_situ = true)"},
                      BadCase{"traction_on_rollers", "[solver]", "[[boundary_traction]]\ngroup = \"east\"\nin_situ = true\n\n[solver]",
                              "boundary 'east' is also in [boundary] rollers (a group is either held or loaded: take it out of rollers)"},
                      BadCase{"unknown_key", "c_R = 3.0", "c_R = 3.0\ncr = 2", "cr': unknown key"},
                      BadCase{"bad_rule", "inversion_rule = \"sigma-max\"", "inversion_rule = \"max\"", "inversion_rule"},
                      BadCase{"bad_steps", "inversion_rule = \"sigma-max\"", "inversion_rule = \"sigma-max\"\nsteps = \"some\"",
                              "steps': must be one of every-date, turning-points"},
                      BadCase{"turning_points_need_sigma_max", "inversion_rule = \"sigma-max\"",
                              "inversion_rule = \"sigma-inversion\"\nsteps = \"turning-points\"", "turning-points needs inversion_rule"},
                      // Numbers the reader accepts but ugs-solve cannot use (issue 20).
                      BadCase{"tolerance_one", "inversion_rule = \"sigma-max\"", "inversion_rule = \"sigma-max\"\ntolerance = 1",
                              "bad.toml:21: [solver] tolerance = 1: outside [1e-14, 1)"},
                      BadCase{"tolerance_below_precision", "inversion_rule = \"sigma-max\"",
                              "inversion_rule = \"sigma-max\"\ntolerance = 1e-20", "[solver] tolerance = 1e-20: outside [1e-14, 1)"},
                      // Issue 42: the mechanical earth model.
                      BadCase{"stress_table_not_monotonic", "hydrostatic_gradient_MPa_per_m = 0.0100\n",
                              "hydrostatic_gradient_MPa_per_m = 0.0100\nShmin_MPa = [[1000, 18], [900, 20]]\n",
                              "bad.toml:5: 'initial_stress.Shmin_MPa' row 2: depth 900 m does not follow 1000 m"},
                      BadCase{"shmin_above_sv_in_normal_regime", "hydrostatic_gradient_MPa_per_m = 0.0100\n",
                              "hydrostatic_gradient_MPa_per_m = 0.0100\nShmin_MPa = [[1000, 25]]\nregime = \"normal\"\n",
                              "bad.toml:6: regime = \"normal\" but S_hmin above S_v at depth"},
                      BadCase{"gas_column_above_pool_top", "[solver]",
                              "[[pool]]\nname = \"store\"\nmaterials = [\"rock\"]\nschedule = \"p.csv\"\ncolumn = \"p_MPa\"\n"
                              "gas_water_contact_m = -1000\ngas_density_kg_per_m3 = 150\n\n[solver]",
                              "bad.toml:19: pool 'store': gas_water_contact_m = -1000 m lies at or above the pool's top"},
                      BadCase{"newton_iterations_huge", "inversion_rule = \"sigma-max\"",
                              "inversion_rule = \"sigma-max\"\nmax_newton_iterations = 1000000",
                              "[solver] max_newton_iterations = 1000000: outside [1, 1000]"}),
    [](const auto& info) { return info.param.name; });

// The problems on ugs-solve's one error line, each without the folder that starts it (every problem
// names a file in `folder`; they are separated by "; ").
static std::vector<std::string> problems_on_the_error_line(const std::string& err, const std::string& folder) {
  std::vector<std::string> out;
  const std::string prefix = "ugs-solve: error: ";
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_EQ(err.rfind(prefix + folder, 0), 0u) << err;
  if (err.rfind(prefix + folder, 0) != 0 || err.back() != '\n') return out;
  const std::string line = err.substr(prefix.size(), err.size() - prefix.size() - 1), sep = "; " + folder;
  for (std::size_t p = folder.size();;) {
    const auto q = line.find(sep, p);
    out.push_back(line.substr(p, q == std::string::npos ? std::string::npos : q - p));
    if (q == std::string::npos) return out;
    p = q + sep.size();
  }
}

// Every problem of the [solver] settings is reported at once, on the one error line (the libraries
// that use them check them: mechanics the linear solver and the Newton numbers, contact the
// saddle-point solver), then exit 2 with no results.
TEST(SolveTool, EverySolverSettingProblemIsReportedAtOnce) {
  Dir d("solve-bad-all");
  ASSERT_EQ(test::run(test::make_case() + " column " + d.path.string()).exit_code, 0);
  variant(d, "inversion_rule = \"sigma-max\"",
          "inversion_rule = \"sigma-max\"\ntolerance = 1\nmax_newton_iterations = 5000\nlinear_solver = \"lu\"\n"
          "fault_solver = \"x\"",
          "bad.toml");
  const auto r = test::run(test::solve_cmd() + " " + column_args(d, "bad.toml") + " -o " + d / "out.h5");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  // In the order of their lines (21-24 of bad.toml).
  const char* expected[] = {"bad.toml:21: [solver] tolerance = 1: outside [1e-14, 1)",
                            "bad.toml:22: [solver] max_newton_iterations = 5000: outside [1, 1000]",
                            "bad.toml:23: [solver] linear_solver = \"lu\": must be one of cg-hypre, cg-gamg, mumps, cholmod",
                            "bad.toml:24: [solver] fault_solver = \"x\": must be one of auto, mumps, fieldsplit"};
  const auto problems = problems_on_the_error_line(r.err, d.path.string() + "/");
  ASSERT_EQ(problems.size(), std::size(expected)) << r.err;
  for (std::size_t k = 0; k < problems.size(); ++k) EXPECT_EQ(problems[k].rfind(expected[k], 0), 0u) << problems[k];
  EXPECT_FALSE(fs::exists(d / "out.h5"));
}

// Every problem of the whole case file is reported at once (GMT's n_errors): all on the one line, in the
// order of the file's lines, from the reader's sections (materials, boundaries, output, an unknown
// table) and the solver libraries' own checks alike; exit 2 and nothing written.
TEST(SolveTool, EveryCaseFileProblemIsReportedAtOnceInFileOrder) {
  Dir d("solve-bad-sections");
  ASSERT_EQ(test::run(test::make_case() + " column " + d.path.string()).exit_code, 0);
  std::string text = test::slurp(d / "case.toml");
  auto replace = [&](const std::string& from, const std::string& to) {
    const auto p = text.find(from);
    ASSERT_NE(p, std::string::npos) << from;
    text.replace(p, from.size(), to);
  };
  replace("lithostatic_gradient_MPa_per_m = 0.0226", "lithostatic_gradient_MPa_per_m = 0.0226\nk0 = -1");  // line 4
  replace("nu_z = 0.3", "nu_z = 0.7\nbiot = 2");                                                   // lines 10, 11
  replace("fixed = [\"bottom\"]", "fixed = [\"bottm\"]");                                          // line 17
  replace("inversion_rule = \"sigma-max\"", "inversion_rule = \"sigma-max\"\ntolerance = 1\nlinear_solver = \"lu\"");  // 23, 24
  text += "\n[output]\ndates = [\"2002-13-01\"]\nevery = 2\n";                                     // lines 27, 28
  test::spit(d / "bad.toml", text);
  auto files_in = [](const Dir& dir) {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir.path)) names.insert(e.path().filename().string());
    return names;
  };
  const auto files_before = files_in(d);
  const auto r = test::run(test::solve_cmd() + " " + column_args(d, "bad.toml") + " -o " + d / "out.h5");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const char* expected[] = {
      "bad.toml:4: 'initial_stress.k0': must be positive, got -1",
      "bad.toml:10: 'material[0].nu_z': Poisson ratio 0.7 outside (-1, 0.5)",
      "bad.toml:11: 'material[0].biot': must lie in [0, 1]",
      "bad.toml:17: 'boundary.fixed': unknown boundary 'bottm' (west, east, south, north, bottom, top)",
      "bad.toml:23: [solver] tolerance = 1: outside [1e-14, 1) (a relative residual ||r|| / ||r_0||)",
      "bad.toml:24: [solver] linear_solver = \"lu\": must be one of cg-hypre, cg-gamg, mumps, cholmod",
      "bad.toml:27: 'output.dates': '2002-13-01' is not an ISO 8601 date",
      "bad.toml:28: 'output.every': unknown key (known here: checkpoint_every, dates, fields)"};
  const auto problems = problems_on_the_error_line(r.err, d.path.string() + "/");
  ASSERT_EQ(problems.size(), std::size(expected)) << r.err;
  for (std::size_t k = 0; k < problems.size(); ++k) EXPECT_EQ(problems[k], expected[k]);
  EXPECT_FALSE(fs::exists(d / "out.h5"));
  EXPECT_EQ(files_in(d), files_before) << "nothing written";
}

TEST(SolveTool, PressureFromAnotherMeshIsBadInput) {
  Dir d("solve-badp");
  ASSERT_EQ(test::run(test::make_case() + " column " + d.path.string()).exit_code, 0);
  ASSERT_EQ(test::run(test::make_case() + " small " + (d.path / "other").string()).exit_code, 0);
  const auto r = test::run(test::solve_cmd() + " " + d / "mesh.msh" + " --case " + d / "case.toml" + " --pressure " +
                           d / "other/flow_pool_c.h5" + " -o " + d / "out.h5");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("is not in the mesh"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(d / "out.h5"));
  // Under mpirun the same one line, from rank 0 only.
  const auto r2 = test::run(test::solve_cmd(2) + " " + d / "mesh.msh" + " --case " + d / "case.toml" + " --pressure " +
                            d / "other/flow_pool_c.h5" + " -o " + d / "out.h5");
  // mpirun's own notice of the failed rank may be printed before or after the forwarded line.
  EXPECT_NE(r2.exit_code, 0);
  std::size_t error_lines = 0;
  std::istringstream lines(r2.err);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("ugs-solve: error: ", 0) == 0) {
      ++error_lines;
      EXPECT_NE(line.find("is not in the mesh"), std::string::npos) << line;
    }
  EXPECT_EQ(error_lines, 1u) << r2.err;
}

// Every count, index and value read from a pressure file or a restart state is checked before it
// is used (issue 20): a pressure file whose /mesh/tetrahedra held node 4294967295 ended in PETSc's
// segfault handler (MPI_ABORT, exit 59, 15 lines); now exit 2 and one line naming the file, the
// dataset and the value.
TEST(SolveTool, DamagedPressureAndStateFilesAreBadInput) {
  Dir d("solve-damaged");
  ASSERT_EQ(test::run(test::make_case() + " column " + d.path.string()).exit_code, 0);
  const std::string good = test::slurp(d / "flow.h5");
  // (What the damage is compared with is read from copies: the files poked are opened only there.)
  fs::copy_file(d / "flow.h5", d / "flow_ref.h5");
  std::size_t nodes = 0;
  std::vector<std::uint64_t> tags;
  std::vector<std::string> dates;
  {
    FieldSeriesReader ref(d / "flow_ref.h5");
    nodes = ref.num_nodes();
    tags = ref.node_tags();
    for (const auto& st : ref.steps()) dates.push_back(st.date);
  }
  auto expect_bad = [&](const std::string& extra, const std::string& expect, const std::string& what) {
    const auto r = test::run(test::solve_cmd() + " " + column_args(d) + " -o " + d / "out.h5" + extra);
    EXPECT_EQ(r.exit_code, 2) << what << ": " << r.err;
    EXPECT_EQ(r.err.rfind("ugs-solve: error: ", 0), 0u) << what << ": " << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << what << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what << ": " << r.err;
    EXPECT_FALSE(fs::exists(d / "out.h5")) << what;
    EXPECT_FALSE(fs::exists(d / "out_top.h5")) << what;
  };
  // A corner of a tetrahedron out of range, the largest 32-bit index and one past the nodes.
  poke<std::uint32_t>(d / "flow.h5", "/mesh/tetrahedra", 5, 4294967295u, H5T_NATIVE_UINT32);
  expect_bad("", d / "flow.h5: /mesh/tetrahedra: cell 1 has node index 4294967295 (expected below the", "index");
  test::spit(d / "flow.h5", good);
  poke<std::uint32_t>(d / "flow.h5", "/mesh/tetrahedra", 0, static_cast<std::uint32_t>(nodes), H5T_NATIVE_UINT32);
  expect_bad("", fmt::format("cell 0 has node index {} (expected below the {} nodes of /mesh/coordinates)", nodes, nodes), "one past");
  // A node tag twice: the node would take two pressures.
  test::spit(d / "flow.h5", good);
  poke<std::uint64_t>(d / "flow.h5", "/mesh/node_tags", 1, tags[0], H5T_NATIVE_UINT64);
  expect_bad("", fmt::format("/mesh/node_tags: node tag {} appears twice (entries 0 and 1)", tags[0]), "tag twice");
  // A pressure change that is not a number, at the first date and at a later one (found when the
  // run reaches it: no results are left).
  for (const int step : {0, 2}) {
    test::spit(d / "flow.h5", good);
    poke<double>(d / "flow.h5", "/steps/{step}/node/dp", 3, NAN, H5T_NATIVE_DOUBLE, step);
    expect_bad("", fmt::format("flow.h5: field 'dp' at step {}: value nan at entry 3 is not a finite number", dates[step]),
               "nan dp");
  }
  // A finite pressure change no reservoir has (1e12 Pa): refused rather than solved.
  test::spit(d / "flow.h5", good);
  poke<double>(d / "flow.h5", "/steps/{step}/node/dp", 3, 1e12, H5T_NATIVE_DOUBLE, 1);
  expect_bad("", fmt::format("flow.h5: field 'dp' at step {}: value 1e+12 at entry 3 is beyond +-1e+09", dates[1]), "huge dp");
  test::spit(d / "flow.h5", good);
  poke_time(d / "flow.h5", 1, INFINITY);
  expect_bad("", "flow.h5: step 1 (2001-01-01): time inf is not a finite number of seconds", "time");
  // The restart state: values, stress magnitudes and cells.
  test::spit(d / "flow.h5", good);
  auto r = test::run(test::solve_cmd() + " " + column_args(d) + " -o " + d / "first.h5" + " --until 2001-01-01");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string state = test::slurp(d / "first_state.h5");
  fs::copy_file(d / "first_state.h5", d / "state_ref.h5");
  const auto cells = FieldSeriesReader(d / "state_ref.h5").cell_tags();
  poke<double>(d / "first_state.h5", "/steps/{step}/cell/hypo", 4 * 2, NAN, H5T_NATIVE_DOUBLE);
  expect_bad(" --restart " + d / "first_state.h5", "first_state.h5: cell field 'hypo': value nan at entry 2 is not a finite number",
             "nan state");
  test::spit(d / "first_state.h5", state);
  poke<double>(d / "first_state.h5", "/steps/{step}/cell/hypo", 4 * 2, -26.0, H5T_NATIVE_DOUBLE);
  expect_bad(" --restart " + d / "first_state.h5", "cell field 'hypo': sigma_max -26 MPa of cell 2 is negative", "sigma_max");
  test::spit(d / "first_state.h5", state);
  poke<std::uint64_t>(d / "first_state.h5", "/mesh/cell_tags", 0, cells[1], H5T_NATIVE_UINT64);
  expect_bad(" --restart " + d / "first_state.h5", fmt::format("/mesh/cell_tags: cell 0 has tag {}, the mesh's tetrahedron 0 has tag {}",
                                                                cells[1], cells[0]),
             "cell tags");
}

// Warnings about the inputs come after every input was checked (issue 20: "[[fault]] entries are
// ignored by the continuous model" was printed before every error, so a bad input gave two lines).
TEST(SolveTool, WarningsOnlyOnceTheInputsAreChecked) {
  Dir d("solve-warn");
  ASSERT_EQ(test::run(test::make_case() + " column " + d.path.string()).exit_code, 0);
  ASSERT_EQ(test::run(test::make_case() + " small " + (d.path / "other").string()).exit_code, 0);
  test::spit(d / "fault.toml", test::slurp(d / "case.toml") + "\n[[fault]]\nname = \"F1\"\n");
  const std::string warning = "fault.toml: [[fault]] entries are ignored by the continuous model";
  // A pressure file whose third step lost its dp (the mutation test found the warning before
  // that error too: the steps were read during the run).
  fs::copy_file(d / "flow.h5", d / "flow_nodp.h5");
  unlink(d / "flow_nodp.h5", "/steps/000002/node/dp");
  // ... or whose third step's dp is listed but is no dataset (mutation_tools, replay solve:707007).
  fs::copy_file(d / "flow.h5", d / "flow_dpgroup.h5");
  replace_by_group(d / "flow_dpgroup.h5", "/steps/000002/node/dp");
  // ... or whose third step's values are damaged (a NaN: the values are checked when a step is
  // read; every step is read before the run starts since mutation_tools' seed 1307020, an inflate()
  // that failed at the second step).
  fs::copy_file(d / "flow.h5", d / "flow_nan.h5");
  poke<double>(d / "flow_nan.h5", "/steps/{step}/node/dp", 3, NAN, H5T_NATIVE_DOUBLE, 2);
  // Bad input: the error line only.
  for (const std::string& extra : {" --pressure " + d / "other/flow_pool_c.h5", " --pressure " + d / "flow.h5" + " --restart " + d / "nothing.h5",
                                   " --pressure " + d / "flow_nodp.h5", " --pressure " + d / "flow_dpgroup.h5",
                                   " --pressure " + d / "flow_nan.h5"}) {
    const auto r = test::run(test::solve_cmd() + " " + d / "mesh.msh" + " --case " + d / "fault.toml" + extra + " -o " + d / "out.h5");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("ugs-solve: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.find("[[fault]]"), std::string::npos) << r.err;
  }
  const auto nodp = test::run(test::solve_cmd() + " " + d / "mesh.msh" + " --case " + d / "fault.toml" + " --pressure " +
                              d / "flow_nodp.h5" + " -o " + d / "out.h5");
  EXPECT_NE(nodp.err.find("flow_nodp.h5: step 2 (2002-01-01) has no node field 'dp' (the first step has one)"), std::string::npos)
      << nodp.err;
  const auto group = test::run(test::solve_cmd() + " " + d / "mesh.msh" + " --case " + d / "fault.toml" + " --pressure " +
                               d / "flow_dpgroup.h5" + " -o " + d / "out.h5");
  EXPECT_NE(group.err.find("flow_dpgroup.h5: no dataset /steps/000002/node/dp"), std::string::npos) << group.err;
  // Good input: the warning, once.
  const auto r = test::run(test::solve_cmd() + " " + column_args(d, "fault.toml") + " -o " + d / "out.h5");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto first = r.err.find(warning);
  EXPECT_NE(first, std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(warning, first + 1), std::string::npos) << r.err;
}

// The predictor after reloading past sigma_max (issue 20). V1 column: depletion to 26 MPa,
// recharge to 23, deeper depletion to 28 (virgin again past sigma_max = 26), recharge to 25. The
// projection on the earlier increments, A-orthonormal for the matrix of the last preconditioner
// setup, started the last step's Krylov solve from 1.3e9 times its residual: DIVERGED_DTOL, and a
// silent split into 2 sub-steps. Now a prediction that does not reduce the residual is rebuilt
// for the current matrix or dropped, and a split says why at -v.
TEST(SolveTool, PredictorAfterReloadingPastSigmaMaxReducesTheResidual) {
  Dir d("solve-predictor");
  ASSERT_EQ(test::run(test::make_case() + " column " + d.path.string()).exit_code, 0);
  const auto r = test::run(test::solve_cmd() + " " + column_args(d) + " -o " + d / "out.h5" + " -v -- -ugs_newton_monitor");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::size_t predictions = 0, steps = 0;
  std::istringstream lines(r.out + r.err);
  for (std::string line; std::getline(lines, line);) {
    if (const auto p = line.find(", predictor "); p != std::string::npos) {
      ++predictions;
      const std::string v = line.substr(p + 12, line.find(',', p + 12) - p - 12);
      ASSERT_NE(v, "dropped") << line;
      EXPECT_LT(std::stod(v), 1.0) << line;  // it reduces the step's residual
    }
    if (line.find(": step ") != std::string::npos && line.find(" Newton iteration") != std::string::npos) {
      ++steps;
      EXPECT_NE(line.find(", 1 sub-step,"), std::string::npos) << line;
    }
    EXPECT_EQ(line.find("split into"), std::string::npos) << line;
  }
  EXPECT_EQ(steps, 5u) << r.err;
  EXPECT_EQ(predictions, 3u) << r.out << r.err;  // steps 3-5 (step 2 has no earlier increment)
  // -v names the Krylov method that runs: GMRES for the non-symmetric hypo-plastic tangent.
  EXPECT_NE(r.err.find("KSP gmres + PC hypre (linear solver cg-hypre, with GMRES: the hypo-plastic tangent is not symmetric)"),
            std::string::npos) << r.err;
}

// A step split into sub-steps says why at -v (one line naming the first failure).
TEST(SolveTool, SubStepsSayWhy) {
  Dir d("solve-substeps");
  ASSERT_EQ(test::run(test::make_case() + " column " + d.path.string()).exit_code, 0);
  // Steps 2 (virgin loading) and 4 (the reload past sigma_max) take 4 Newton iterations in one
  // piece (5 for step 4 before the hypo-plastic corrections were solved to the Newton target); step 2
  // needed 8 sub-steps of at most 3 iterations while the matrix skipped tangent changes under 0.5 %.
  variant(d, "[solver]\n", "[solver]\nmax_newton_iterations = 3\n", "split.toml");
  const auto r = test::run(test::solve_cmd() + " " + column_args(d, "split.toml") + " -o " + d / "out.h5" + " -v");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string step : {"step 2/5 (2001-01-01): split into 4 sub-steps", "step 4/5 (2003-01-01): split into 5 sub-steps"})
    EXPECT_NE(r.err.find("ugs-solve: " + step + ": Newton did not converge in 3 iterations (relative residuals 1.00e+00, "),
              std::string::npos)
        << step << "\n" << r.err;
  std::size_t splits = 0;
  for (std::size_t p = r.err.find("split into"); p != std::string::npos; p = r.err.find("split into", p + 1)) ++splits;
  EXPECT_EQ(splits, 2u) << r.err;  // the other steps are whole
}

TEST(SolveTool, HelpAndUsage) {
  auto r = test::run(test::solve_cmd() + " --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("Example:"), std::string::npos);
  EXPECT_NE(r.out.find("--pressure"), std::string::npos);
  r = test::run(test::solve_cmd() + " mesh.msh --pressure p.h5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--case"), std::string::npos);
  r = test::run(test::solve_cmd() + " mesh.msh --case c.toml --pressure p.h5 --solver lu");
  EXPECT_EQ(r.exit_code, 2);
  // Command-line numbers: in range or exit 2, one line naming the option and the value.
  for (const std::string v : {"-1", "nan", "1e99", "2.5", "2000000"}) {
    r = test::run(test::solve_cmd() + " mesh.msh --case c.toml --pressure p.h5 --checkpoint-every " + v);
    EXPECT_EQ(r.exit_code, 2) << v;
    EXPECT_NE(r.err.find("--checkpoint-every"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(v == "-1" || v == "2000000" ? "(expected a finite number in [0, 1000000])" : v), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  // Under mpirun every process reads the command line, and only rank 0 speaks: one error line
  // (each rank printed its own before), one --version.
  r = test::run(test::solve_cmd(2) + " mesh.msh --case c.toml");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  std::size_t error_lines = 0;
  std::istringstream lines(r.err);
  for (std::string line; std::getline(lines, line);) error_lines += line.rfind("ugs-solve: error: ", 0) == 0;
  EXPECT_EQ(error_lines, 1u) << r.err;
  EXPECT_NE(r.err.find("--pressure is required"), std::string::npos) << r.err;
  r = test::run(test::solve_cmd(2) + " --version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
}
