// The study's stepping (issue 43, docs/mechanics.md "Tolerance of the whole load" and "Turning-point
// steps"): Newton to a tolerance of the whole load agrees with a tight run within what a
// measurement can see (1e-5 of max |u|, 0.5 % of the largest stress change) at every date and in
// every cell, for fewer linear iterations; --every-date-in windows add their dates to the
// turning points; the new options' bad values exit 2 with one line.
#include <cstdio>
#include <regex>

#include <gtest/gtest.h>

#include "solve_support.hpp"

using namespace ugs;

namespace {

using Dir = test::TempDir;

// mech_make_case's two-pool case (monthly 1959-10 .. 1960-09, hypo-plastic pools and lagging
// aquifers) with every date an output date; returns the mesh and pressure arguments.
std::string two_pool_case(const Dir& d) {
  if (test::run(test::make_case() + " small " + d.path.string()).exit_code != 0) return {};
  std::string text = test::slurp(d / "case.toml");
  const auto p = text.find("[output]");
  if (p == std::string::npos) return {};
  test::spit(d / "case.toml", text.substr(0, p));  // no [output] dates: every date is written
  return d / "mesh.msh" + " --case " + d / "case.toml" + " --pressure " + d / "flow_pool_a.h5" + " --pressure " +
         d / "flow_pool_c.h5";
}

int linear_iterations(const std::string& log) {
  std::smatch m;
  if (!std::regex_search(log, m, std::regex(R"((\d+) steps: \d+ Newton iterations, (\d+) linear iterations)"))) return -1;
  return std::stoi(m[2]);
}

// Largest difference over every step and entry, relative to the largest magnitude of the reference.
double worst(const std::string& ref_h5, const std::string& h5, const std::string& field, bool cell) {
  FieldSeriesReader ref(ref_h5), run(h5);
  if (ref.steps().size() != run.steps().size()) return INFINITY;
  double scale = 0, diff = 0;
  for (std::size_t s = 0; s < ref.steps().size(); ++s) {
    if (ref.steps()[s].date != run.steps()[s].date) return INFINITY;
    const auto a = (cell ? ref.cell_field(s, field) : ref.node_field(s, field)).values;
    const auto b = (cell ? run.cell_field(s, field) : run.node_field(s, field)).values;
    if (a.size() != b.size()) return INFINITY;
    scale = std::max(scale, test::max_abs(a));
    for (std::size_t i = 0; i < a.size(); ++i) diff = std::max(diff, std::abs(a[i] - b[i]));
  }
  return diff / std::max(scale, 1e-300);
}

}  // namespace

TEST(StudySteps, WholeLoadToleranceAgreesWithATightRunForFewerIterations) {
  Dir d("study-tolerance");
  const std::string args = two_pool_case(d);
  ASSERT_FALSE(args.empty());
  auto tight = test::run(test::solve_cmd() + " " + args + " -o " + d / "tight.h5" + " --tolerance 1e-10 -v");
  ASSERT_EQ(tight.exit_code, 0) << tight.err;
  auto fast = test::run(test::solve_cmd() + " " + args + " -o " + d / "fast.h5" +
                        " --tolerance 1e-7 --tolerance-of total-load -v");
  ASSERT_EQ(fast.exit_code, 0) << fast.err;
  // The issue's bar, at all 12 dates and in every node and cell.
  const double du = worst(d / "tight.h5", d / "fast.h5", "u", false), ds = worst(d / "tight.h5", d / "fast.h5", "stress_change", true);
  EXPECT_LT(du, 1e-5);
  EXPECT_LT(ds, 5e-3);
  const int n_tight = linear_iterations(tight.err), n_fast = linear_iterations(fast.err);
  std::printf("tolerance 1e-7 of the whole load against 1e-10 of the step: u %.2e of max |u|, stress change %.2e of the "
              "largest; %d linear iterations instead of %d\n", du, ds, n_fast, n_tight);
  ASSERT_GT(n_tight, 0) << tight.err;
  ASSERT_GT(n_fast, 0) << fast.err;
  EXPECT_LT(n_fast, n_tight);
  // The case key says the same as the options.
  std::string text = test::slurp(d / "case.toml");
  test::spit(d / "case_key.toml", text + "\n[solver]\ntolerance = 1e-7\ntolerance_of = \"total-load\"\n");
  std::string key_args = args;
  key_args.replace(key_args.find(d / "case.toml"), (d / "case.toml").size(), d / "case_key.toml");
  auto key = test::run(test::solve_cmd() + " " + key_args + " -o " + d / "key.h5" + " -v");
  ASSERT_EQ(key.exit_code, 0) << key.err;
  EXPECT_EQ(linear_iterations(key.err), n_fast);
  EXPECT_EQ(worst(d / "fast.h5", d / "key.h5", "u", false), 0.0);
}

TEST(StudySteps, WindowDatesAreSteppedBesideTheTurningPoints) {
  Dir d("study-window");
  const std::string args = two_pool_case(d);
  ASSERT_FALSE(args.empty());
  // Turning points alone skip the monotonic depletion 1959-10 .. 1959-12 (SolveTool.
  // TurningPointStepsMatchEveryDate); the window brings back 1959-11-01 and 1959-12-01.
  auto r = test::run(test::solve_cmd() + " " + args + " -o " + d / "w.h5" +
                     " --steps turning-points --every-date-in 1959-11-01/1959-12-31 -v");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("turning-point steps: 11 of 12 dates"), std::string::npos) << r.err;
  FieldSeriesReader top(d / "w_top.h5");
  ASSERT_EQ(top.steps().size(), 11u);
  EXPECT_EQ(top.steps()[0].date, "1959-11-01");
  EXPECT_EQ(top.steps()[1].date, "1959-12-01");
  // Every date of the window is the every-date run's, within the Newton tolerance's reach (the
  // first step spans two months of monotonic depletion).
  auto all = test::run(test::solve_cmd() + " " + args + " -o " + d / "all.h5");
  ASSERT_EQ(all.exit_code, 0) << all.err;
  FieldSeriesReader every(d / "all_top.h5");
  ASSERT_EQ(every.steps().size(), 12u);
  for (std::size_t s = 0; s < top.steps().size(); ++s) {
    ASSERT_EQ(every.steps()[s + 1].date, top.steps()[s].date);
    EXPECT_LT(test::max_rel_diff(every.node_field(s + 1, "u_mm").values, top.node_field(s, "u_mm").values), 1e-5)
        << top.steps()[s].date;
  }
}

TEST(StudySteps, BadStepOptionsExitTwoWithOneLine) {
  Dir d("study-bad");
  const std::string args = two_pool_case(d);
  ASSERT_FALSE(args.empty());
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--every-date-in 1960-01-01", "--every-date-in: '1960-01-01' is not a window FROM/TO"},
      {"--every-date-in 1960-05-01/1960-01-01", "FROM not after TO"},
      {"--every-date-in 1960-13-01/1961-01-01", "is not a window"},
      {"--steps monthly", "--steps"},
      {"--tolerance 0", "--tolerance"},
      {"--tolerance nan", "--tolerance"},
      {"--tolerance-of increment", "--tolerance-of"},
  };
  for (const auto& [opt, says] : cases) {
    auto r = test::run(test::solve_cmd() + " " + args + " -o " + d / "bad.h5 " + opt);
    EXPECT_EQ(r.exit_code, 2) << opt << ": " << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << opt << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << opt << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(d / "bad.h5")) << opt;
  }
  // Turning points need the sigma-max rule, from the command line as from the case.
  std::string text = test::slurp(d / "case.toml");
  test::spit(d / "inversion.toml", text + "\n[solver]\ninversion_rule = \"sigma-inversion\"\n");
  std::string inv = args;
  inv.replace(inv.find(d / "case.toml"), (d / "case.toml").size(), d / "inversion.toml");
  auto r = test::run(test::solve_cmd() + " " + inv + " -o " + d / "bad.h5 --steps turning-points");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--steps: turning-points needs inversion_rule = \"sigma-max\""), std::string::npos) << r.err;
}
