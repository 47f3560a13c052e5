// ugs-solve on a faulted mesh, end to end (contact_make_case: a box with a 45-degree fault F
// crossing a reservoir whose pressure rises by 6 MPa, or 3 MPa for the scale search):
//  - the fault outputs: HDF5 + XDMF on the fault surface (triangles in fault:F, a cell field chi,
//    node fields of tractions, slip, opening, state), the CSV per fault and date;
//  - 1 and 2 MPI processes give the same fault results;
//  - --find-safe-scale brackets the scale at which chi first reaches 1, which for this linear,
//    sticking case follows in closed form from the runs at scales 0 and 1 (the tractions are
//    linear in the scale): safe <= s* <= critical, critical - safe <= 1 % of critical;
//  - bad input exits 2 leaving no results: friction outside (0, 90), negative cohesion, a case
//    fault that is not in the mesh, a mesh fault the case does not describe, interface elements
//    without twins, a missing restart state; a Newton failure with slipping pairs exits 1 naming
//    the fault and its nodes;
//  - a faulted run stopped at a date and restarted from its state (volume and fault pairs) writes
//    the same numbers, bit for bit, as the uninterrupted run; checkpoints write the fault state;
//  - turning-point steps on a faulted model (a storage cycle): the low and the last date only, with
//    the results of every-date stepping there (linear rock, locked fault: path-independent);
//  - the fault reaching a side with rollers (not fixed) converges, chi <= 1 in the faults CSV;
//  - a saddle-point factorisation that always fails ends in exit 1 and one line, after the retries.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>

#include <gtest/gtest.h>

#include "run_tool.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"

using namespace ugs;
namespace fs = std::filesystem;

namespace {

using Dir = test::TempDir;

std::string make_case(const Dir& d, const std::string& args = "") {
  return std::string(UGS_BINARY_DIR) + "/tests/fault_mechanics/contact_make_case " + d.path.string() + " " + args;
}

std::string solve(const Dir& d, const std::string& args, int ranks = 1) {
  const std::string tool = test::tool("ugs-solve");
  const std::string pre = ranks > 1 ? "mpirun --allow-run-as-root --oversubscribe -n " + std::to_string(ranks) + " " : "";
  return pre + tool + " " + d / "faulted.msh" + " --case " + d / "case.toml" + " --pressure " + d / "flow.h5" + " " + args;
}

void replace_in(const std::string& path, const std::string& from, const std::string& to) {
  std::string text = test::slurp(path);
  const auto p = text.find(from);
  ASSERT_NE(p, std::string::npos) << from;
  text.replace(p, from.size(), to);
  test::spit(path, text);
}

// Node field of the last step of a fault output.
Field last_node(const std::string& h5, const std::string& name) {
  FieldSeriesReader r(h5);
  return r.node_field(r.steps().size() - 1, name);
}

}  // namespace

TEST(SolveFaults, OutputsOnTheFaultSurface) {
  Dir d("solve-faults");
  ASSERT_EQ(test::run(make_case(d, "--dp 6")).exit_code, 0);
  const auto r = test::run(solve(d, "-o " + d / "out.h5 -v"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("fault F: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("max chi"), std::string::npos) << r.err;
  for (const char* f : {"out.h5", "out.xdmf", "out_top.h5", "out_faults.h5", "out_faults.xdmf", "out_faults.csv"})
    EXPECT_TRUE(fs::exists(d / f)) << f;

  FieldSeriesReader faults(d / "out_faults.h5");
  ASSERT_EQ(faults.steps().size(), 2u);
  EXPECT_EQ(faults.cell_types(), std::vector<ElementType>{ElementType::Triangle});
  const Mesh mesh = read_msh(d / "faulted.msh");
  EXPECT_EQ(faults.num_cells(), mesh.count(ElementType::Prism));
  // The fault triangles carry the mesh's tag of their fault group, so readers name them from the mesh.
  const PhysicalGroup* group = mesh.find_physical(3, "fault:F");
  ASSERT_NE(group, nullptr);
  for (std::int32_t m : faults.materials()) EXPECT_EQ(m, group->tag);
  const Field chi = faults.cell_field(1, "chi");
  ASSERT_EQ(chi.count(), faults.num_cells());
  double cmax = 0;
  for (double c : chi.values) {
    EXPECT_GE(c, 0.0);
    EXPECT_LE(c, 1.0 + 1e-12);
    cmax = std::max(cmax, c);
  }
  EXPECT_GT(cmax, 0.2);
  for (const char* f : {"traction", "sigma_n", "sigma_n_eff", "tau", "tau_abs", "slip", "slip_abs", "opening", "u_r", "state",
                        "chi", "cfs_change", "p_fault", "interpolated"})
    EXPECT_NO_THROW(faults.node_field(1, f)) << f;
  // Effective normal stress = total + fluid pressure: compressive where the fault is closed, zero
  // where it opened (the 6 MPa rise opens part of it).
  const Field sn = faults.node_field(1, "sigma_n"), sne = faults.node_field(1, "sigma_n_eff"), p = faults.node_field(1, "p_fault");
  const Field state = faults.node_field(1, "state"), opening = faults.node_field(1, "opening");
  const Field interp = faults.node_field(1, "interpolated");
  std::size_t open = 0, slip = 0;
  for (std::size_t i = 0; i < sn.count(); ++i) {
    EXPECT_NEAR(sne.values[i], sn.values[i] + p.values[i], 1e-6 * std::abs(sn.values[i]) + 1e-6);
    if (interp.values[i] != 0) continue;
    if (state.values[i] == 2) {
      ++open;
      EXPECT_NEAR(sne.values[i], 0.0, 1e-3);
      EXPECT_GT(opening.values[i], 0.0);
    } else {
      slip += state.values[i] == 1;
      EXPECT_LT(sne.values[i], 0.0);
      EXPECT_NEAR(opening.values[i], 0.0, 1e-12);
    }
  }
  std::printf("fault F at +6 MPa: %zu node pairs open, %zu slipping\n", open, slip);
  // The volume results hold the tetrahedra only.
  FieldSeriesReader vol(d / "out.h5");
  EXPECT_EQ(vol.num_cells(), mesh.count(ElementType::Tetrahedron));

  const std::string csv = test::slurp(d / "out_faults.csv");
  EXPECT_NE(csv.find("date,fault,max_chi,x_m,y_m,z_m,max_slip_mm,slip_area_m2,open_area_m2,max_opening_mm,max_cfs_change_MPa,"
                     "node_pairs,slipping,open"),
            std::string::npos);
  EXPECT_NE(csv.find("\n2000-01-01,F,"), std::string::npos);
  EXPECT_NE(csv.find("\n2001-01-01,F,"), std::string::npos);

  // Two MPI processes: the same fault results.
  const auto r2 = test::run(solve(d, "-o " + d / "mpi.h5", 2));
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  for (const char* f : {"traction", "slip", "chi"}) {
    const Field a = last_node(d / "out_faults.h5", f), b = last_node(d / "mpi_faults.h5", f);
    ASSERT_EQ(a.values.size(), b.values.size());
    double amax = 0, diff = 0;
    for (std::size_t i = 0; i < a.values.size(); ++i)
      amax = std::max(amax, std::abs(a.values[i])), diff = std::max(diff, std::abs(a.values[i] - b.values[i]));
    EXPECT_LE(diff, 1e-6 * amax + 1e-12) << f;
  }
}

TEST(SolveFaults, SafeScaleMatchesTheClosedForm) {
  Dir d("solve-faults-scale");
  ASSERT_EQ(test::run(make_case(d, "--dp 3")).exit_code, 0);
  auto r = test::run(solve(d, "-o " + d / "s0.h5 --scale 0 --fault-csv none"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run(solve(d, "-o " + d / "s1.h5 --find-safe-scale"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("maximum safe scale"), std::string::npos) << r.err;
  // The bracket from the scenario table: the largest safe and the smallest critical scale tried.
  const std::string table = test::slurp(d / "s1_scenario.csv");
  double safe = 0, critical = 1e300;
  std::size_t trials = 0;
  for (std::size_t p = table.find("\n"); p != std::string::npos && p + 1 < table.size(); p = table.find('\n', p + 1)) {
    if (table[p + 1] == '#' || table[p + 1] == 's') continue;
    double s = 0, chi = 0;
    int crit = 0;
    if (std::sscanf(table.c_str() + p + 1, "%lf,%lf,%d", &s, &chi, &crit) != 3) continue;
    ++trials;
    if (crit) critical = std::min(critical, s);
    else safe = std::max(safe, s);
  }
  ASSERT_GT(trials, 3u);
  ASSERT_LT(critical, 1e300);
  // Closed form: tau(s) = tau0 + s (tau1 - tau0), sigma'_n(s) likewise; chi(s) = 1 where
  // |tau(s)| = c - sigma'_n(s) tan(phi), c = 0, phi = 30 degrees, over the node pairs.
  const double mu = std::tan(30 * M_PI / 180);
  const Field t0 = last_node(d / "s0_faults.h5", "tau"), t1 = last_node(d / "s1_faults.h5", "tau");
  const Field n0 = last_node(d / "s0_faults.h5", "sigma_n_eff"), n1 = last_node(d / "s1_faults.h5", "sigma_n_eff");
  const Field interp = last_node(d / "s1_faults.h5", "interpolated");
  double s_star = 1e300;
  for (std::size_t i = 0; i < n0.count(); ++i) {
    if (interp.values[i] != 0) continue;
    // |a + s b|^2 = (mu (c0 + s c1))^2 with c0 = -sigma'_n0, c1 = -(sigma'_n1 - sigma'_n0).
    double A = 0, B = 0, C = 0;
    for (int k = 0; k < 3; ++k) {
      const double a = t0.values[3 * i + k], b = t1.values[3 * i + k] - a;
      A += b * b, B += 2 * a * b, C += a * a;
    }
    const double c0 = -n0.values[i], c1 = -(n1.values[i] - n0.values[i]);
    A -= mu * mu * c1 * c1, B -= 2 * mu * mu * c0 * c1, C -= mu * mu * c0 * c0;
    // Smallest positive root of A s^2 + B s + C (C < 0: below the limit at s = 0).
    const double disc = B * B - 4 * A * C;
    if (disc < 0) continue;
    for (double s : {(-B - std::sqrt(disc)) / (2 * A), (-B + std::sqrt(disc)) / (2 * A)})
      if (s > 0) s_star = std::min(s_star, s);
  }
  std::printf("safe-scale search: %zu trials, bracket [%.4f, %.4f]; closed form s* = %.4f\n", trials, safe, critical, s_star);
  EXPECT_GT(s_star, 1.0);  // the base run is safe
  EXPECT_LE(safe, s_star * (1 + 1e-6));
  EXPECT_GE(critical, s_star * (1 - 1e-6));
  EXPECT_LE(critical - safe, 0.01 * critical * (1 + 1e-9));
}

TEST(SolveFaults, BadInputExitsTwoWithoutResults) {
  Dir d("solve-faults-bad");
  ASSERT_EQ(test::run(make_case(d)).exit_code, 0);
  const std::string good = test::slurp(d / "case.toml");
  auto expect2 = [&](const std::string& what, const std::string& args, const std::string& needle) {
    const auto r = test::run(solve(d, "-o " + d / "bad.h5 " + args));
    EXPECT_EQ(r.exit_code, 2) << what << ": " << r.err;
    EXPECT_EQ(r.err.rfind("ugs-solve: error: ", 0), 0u) << what << ": " << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << what << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what << ": " << r.err;
    for (const char* f : {"bad.h5", "bad.xdmf", "bad_faults.h5", "bad_faults.csv", "bad_top.h5"})
      EXPECT_FALSE(fs::exists(d / f)) << what << ": " << f;
    test::spit(d / "case.toml", good);
  };
  replace_in(d / "case.toml", "friction_deg = 30", "friction_deg = 95");
  expect2("friction", "", "friction_deg");
  replace_in(d / "case.toml", "friction_deg = 30", "friction_deg = 0");
  expect2("friction zero", "", "friction_deg");
  replace_in(d / "case.toml", "cohesion_MPa = 0", "cohesion_MPa = -1");
  expect2("cohesion", "", "cohesion_MPa");
  test::spit(d / "case.toml", good + "\n[[fault]]\nname = \"G\"\n");
  expect2("case fault not in the mesh", "", "fault 'G' is not in the mesh");
  replace_in(d / "case.toml", "name = \"F\"", "name = \"H\"");
  expect2("mesh fault not in the case", "", "fault 'H' is not in the mesh");
  {
    std::string t = good;
    const auto p = t.find("[[fault]]"), q = t.find("[solver]");
    t.erase(p, q - p);
    test::spit(d / "case.toml", t);
    expect2("mesh fault without an entry", "", "no [[fault]] entry named 'F'");
  }
  expect2("restart", "--restart " + d / "nothing.h5", "nothing.h5");
  {
    // Move the twin of one interface element's node: no twin any more.
    Mesh m = read_msh(d / "faulted.msh");
    bool moved = false;
    for (auto& b : m.blocks)
      for (std::size_t k = 0; b.type == ElementType::Prism && k < b.nodes.size() && !moved; k += 6)
        if (b.nodes[k] != b.nodes[k + 3]) {  // not a tip node: its twin is another node
          m.nodes[b.nodes[k + 3]][0] += 1.0;
          moved = true;
        }
    ASSERT_TRUE(moved);
    write_msh(m, d / "faulted.msh");
    expect2("twins", "", "has no twin");
  }
}

TEST(SolveFaults, NewtonFailureNamesTheFaultAndItsNodes) {
  Dir d("solve-faults-fail");
  // Friction 5 degrees: the geostatic stress exceeds the strength, the first step slips widely,
  // and one Newton iteration cannot settle it.
  ASSERT_EQ(test::run(make_case(d, "--friction 5 --extra 'max_newton_iterations = 1\nmax_substeps = 1'")).exit_code, 0);
  const auto r = test::run(solve(d, "-o " + d / "fail.h5"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const auto line = r.err.rfind("ugs-solve: error: ");  // the last line, after the log
  ASSERT_NE(line, std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\n', line), r.err.size() - 1) << r.err;
  EXPECT_NE(r.err.find("fault 'F'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("node pairs"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(d / "fail.h5"));
  EXPECT_FALSE(fs::exists(d / "fail_faults.h5"));
}

// A saddle-point factorisation that fails on every try (MUMPS told not to pivot: a zero pivot on
// the multiplier rows, INFOG(1)=-10), on 1 and 2 processes: the sub-step is retried down to its
// smallest (max_substeps = 4, for time) and the run exits 1 with one line naming the step, the solver's reason with MUMPS'
// INFOG(1) and INFOG(2), and the fault, leaving no
// results. Formerly the first retry reused the failed MUMPS instance and the run ended in "PETSc
// error 76 in KSPSolve ... MUMPS in solve phase: INFOG(1)=-3" (no step, no fault).
TEST(SolveFaults, FailedFactorisationExitsOneWithOneLine) {
  Dir d("solve-faults-mumps");
  ASSERT_EQ(test::run(make_case(d, "--dp 6 --cell 100 --extra 'max_substeps = 4'")).exit_code, 0);
  for (int ranks : {1, 2}) {
    const auto r = test::run(solve(d, "-o " + d / "out.h5 -- -contact_mat_mumps_cntl_1 0", ranks));
    EXPECT_EQ(r.exit_code, 1) << r.err;
    const std::string head = "ugs-solve: error: step 2/2 (2001-01-01): the saddle-point solver (MUMPS) failed: DIVERGED_PC_FAILED";
    const auto line = r.err.find(head);
    ASSERT_NE(line, std::string::npos) << r.err;
    const std::string text = r.err.substr(line, r.err.find('\n', line) - line);
    EXPECT_EQ(r.err.find("ugs-solve: error:", line + 1), std::string::npos) << r.err;  // one error line
    EXPECT_NE(text.find("fault 'F'"), std::string::npos) << text;
    EXPECT_NE(text.find("sub-step of 1/4 of the step"), std::string::npos) << text;
    // MUMPS' own code behind DIVERGED_PC_FAILED, read from the failed factor.
    EXPECT_NE(text.find("DIVERGED_PC_FAILED (MUMPS INFOG(1) = -10: numerically singular matrix; INFOG(2) = "), std::string::npos)
        << text;
    EXPECT_EQ(r.err.find("PETSC ERROR"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("PETSc error"), std::string::npos) << r.err;
    for (const char* f : {"out.h5", "out_faults.h5", "out_faults.csv", "out_fault_F.csv"}) EXPECT_FALSE(fs::exists(d / f)) << f;
  }
}

// The fault reaching the east side with rollers on every side instead of fixed ones (issue 21):
// its pairs there have x prescribed and are constrained in y and z only. Formerly the dip and the
// normal rows both reduced to z there, the saddle-point matrix was singular and ugs-solve stopped
// with "PETSc error 76 in KSPSolve ... MUMPS ... INFOG(1)=-3".
TEST(SolveFaults, FaultReachingRollersConverges) {
  Dir d("solve-faults-rollers");
  ASSERT_EQ(test::run(make_case(d, "--dp 6 --cell 100")).exit_code, 0);
  replace_in(d / "case.toml", "fixed = [\"bottom\", \"west\", \"east\", \"south\", \"north\"]",
             "fixed = []\nrollers = [\"bottom\", \"west\", \"east\", \"south\", \"north\"]");
  const auto r = test::run(solve(d, "-o " + d / "out.h5 -v"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("3 node pairs lie on prescribed boundaries"), std::string::npos) << r.err;
  // The faults CSV at the second date: chi <= 1, Coulomb stress changes of MPa.
  const std::string csv = test::slurp(d / "out_faults.csv");
  const auto at = csv.find("\n2001-01-01,F,");
  ASSERT_NE(at, std::string::npos) << csv;
  std::vector<double> v;
  std::string line = csv.substr(at + 15, csv.find('\n', at + 1) - at - 15);
  for (std::size_t p = 0; p <= line.size();) {
    const auto e = std::min(line.find(',', p), line.size());
    v.push_back(std::stod(line.substr(p, e - p)));
    p = e + 1;
  }
  ASSERT_EQ(v.size(), 12u) << line;  // max_chi, x, y, z, max_slip_mm, ..., node_pairs, slipping, open
  std::printf("fault F reaching rollers: %s\n", line.c_str());
  EXPECT_LE(v[0], 1.0);
  EXPECT_LT(std::abs(v[8]), 50.0);  // max_cfs_change_MPa
  EXPECT_EQ(v[9], 15);              // node pairs in the statistics: all
}

namespace {

// The values of every step of a field series at or after `from` (ISO dates compare as text), per
// field name and date: compared with == (bit for bit).
std::map<std::string, std::vector<double>> series_from(const std::string& h5, const std::string& from) {
  FieldSeriesReader r(h5);
  std::map<std::string, std::vector<double>> out;
  for (std::size_t s = 0; s < r.steps().size(); ++s) {
    if (r.steps()[s].date < from) continue;
    for (const auto& n : r.node_field_names(s)) out[r.steps()[s].date + " node " + n] = r.node_field(s, n).values;
    for (const auto& n : r.cell_field_names(s)) out[r.steps()[s].date + " cell " + n] = r.cell_field(s, n).values;
  }
  return out;
}

// The data rows of a CSV at or after `from` (rows start with the date).
std::vector<std::string> rows_from(const std::string& csv, const std::string& from) {
  std::vector<std::string> rows;
  const std::string text = test::slurp(csv);
  for (std::size_t p = 0; p < text.size();) {
    const auto q = text.find('\n', p);
    const std::string line = text.substr(p, q - p);
    if (!line.empty() && line[0] != '#' && line.substr(0, 10) >= from && std::isdigit(static_cast<unsigned char>(line[0])))
      rows.push_back(line);
    p = q == std::string::npos ? text.size() : q + 1;
  }
  return rows;
}

}  // namespace

// A storage cycle of 13 monthly dates: stopped after 2000-06-01 and restarted from the state saved
// there (the volume state and <state>_faults.h5), the second piece writes exactly the numbers of
// the uninterrupted run at the later dates — top surface, volume fields, fault fields and table.
TEST(SolveFaults, RestartReproducesTheUninterruptedRunBitForBit) {
  Dir d("solve-faults-restart");
  ASSERT_EQ(test::run(make_case(d, "--dp 8 --friction 20 --cell 100 --months 12")).exit_code, 0);
  auto r = test::run(solve(d, "-o " + d / "full.h5 --checkpoint-every 4 -v"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(d / "full_state_faults.h5"));
  r = test::run(solve(d, "-o " + d / "first.h5 --until 2000-06-01"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(d / "first_state.h5"));
  ASSERT_TRUE(fs::exists(d / "first_state_faults.h5"));
  r = test::run(solve(d, "-o " + d / "second.h5 --restart " + d / "first_state.h5 -v"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("restarting from"), std::string::npos) << r.err;
  // Pairs slip and open from February to May (friction 20 degrees), so the state carried over
  // from 2000-06-01 holds slip.
  EXPECT_NE(r.err.find("step 7/7 (2001-01-01)"), std::string::npos) << r.err;
  for (const char* suffix : {".h5", "_top.h5", "_faults.h5"}) {
    const auto full = series_from(d / (std::string("full") + suffix), "2000-07-01");
    const auto second = series_from(d / (std::string("second") + suffix), "2000-07-01");
    ASSERT_EQ(full.size(), second.size()) << suffix;
    EXPECT_FALSE(full.empty()) << suffix;
    for (const auto& [key, values] : full) {
      ASSERT_TRUE(second.count(key)) << suffix << " " << key;
      EXPECT_TRUE(values == second.at(key)) << suffix << " " << key << " differs";
    }
  }
  const auto full_rows = rows_from(d / "full_faults.csv", "2000-07-01");
  EXPECT_EQ(full_rows.size(), 7u);
  EXPECT_EQ(full_rows, rows_from(d / "second_faults.csv", "2000-07-01"));
  // Without its fault state a volume state cannot restart a faulted run.
  fs::remove(d / "first_state_faults.h5");
  r = test::run(solve(d, "-o " + d / "bad.h5 --restart " + d / "first_state.h5"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("first_state_faults.h5"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(d / "bad.h5"));
}

// Turning-point steps on a faulted model: of the 13 dates of a storage cycle, the high (2000-04-01),
// the low (2000-10-01) and the last date are stepped on; the rock is linear and the fault stays
// locked at this friction, so the state there does not depend on the path and matches every-date
// stepping. The high is where chi peaks (0.42, against 0.22 at the low): the continuous model's
// rule (new lows only) missed it before session 12 and reported the wrong peak.
TEST(SolveFaults, TurningPointStepsOnAFaultedModel) {
  Dir d("solve-faults-turning");
  ASSERT_EQ(test::run(make_case(d, "--dp 3 --friction 40 --cell 100 --months 12 --extra 'steps = \"turning-points\"'")).exit_code, 0);
  auto r = test::run(solve(d, "-o " + d / "tp.h5 -v"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("turning-point steps: 3 of 13 dates"), std::string::npos) << r.err;
  replace_in(d / "case.toml", "steps = \"turning-points\"", "steps = \"every-date\"");
  r = test::run(solve(d, "-o " + d / "all.h5"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  FieldSeriesReader tp(d / "tp_faults.h5"), all(d / "all_faults.h5");
  ASSERT_EQ(tp.steps().size(), 3u);
  EXPECT_EQ(tp.steps()[0].date, "2000-04-01");
  EXPECT_EQ(tp.steps()[1].date, "2000-10-01");
  EXPECT_EQ(tp.steps()[2].date, "2001-01-01");
  // The peak of chi over every date is on a date stepped on.
  const auto peak = [](FieldSeriesReader& f, std::size_t k) {
    const auto chi = f.node_field(k, "chi").values;
    return *std::max_element(chi.begin(), chi.end());
  };
  double peak_all = 0, peak_tp = 0;
  for (std::size_t k = 0; k < all.steps().size(); ++k) peak_all = std::max(peak_all, peak(all, k));
  for (std::size_t k = 0; k < tp.steps().size(); ++k) peak_tp = std::max(peak_tp, peak(tp, k));
  EXPECT_GT(peak_all, 0.3);
  EXPECT_NEAR(peak_tp, peak_all, 1e-6 * peak_all);
  for (std::size_t s = 0; s < 3; ++s) {
    const std::size_t k = all.step(tp.steps()[s].date);
    const auto a = all.node_field(k, "traction").values, b = tp.node_field(s, "traction").values;
    ASSERT_EQ(a.size(), b.size());
    double worst = 0, scale = 0;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i])), scale = std::max(scale, std::abs(a[i]));
    EXPECT_LT(worst, 1e-6 * scale) << tp.steps()[s].date;
    // Locked: no pair slips or opens.
    for (double st : tp.node_field(s, "state").values) EXPECT_EQ(st, 0.0);
  }
}
