// Caprock integrity (issue 42, docs/caprock.md).
//  - rock_margins: a stress state given in a rotated frame against its principal values, the
//    fracture pressure S3 + T0 and the Mohr-Coulomb shear margin written out by hand.
//  - ugs-solve on a box of seal rock under a uniform pressure change with lateral rollers and a fixed bottom
//    (oedometric: the vertical total stress does not change, d sigma'_h = nu / (1 - nu) d sigma'_z):
//    every seal element's pore pressure, fracture pressure and margins against the closed form;
//    --find-safe-scale stops where the closed form says, on the criterion it says: tensile failure
//    under injection, shear failure under depletion (the Mohr circle grows when friction is low).
//  - [[seal]] bad input: one line, exit 2.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>

#include "solve_support.hpp"
#include "ugs/fem/rock_integrity.hpp"
#include "ugs/formats/csv.hpp"

using namespace ugs;

namespace {

using Dir = test::TempDir;

// The box of mech_make_case caprock: surface at z = 0, gradients 0.0226 / 0.0100 MPa/m, k0 0.7,
// E 10 GPa, nu 0.25, Biot 1.
constexpr double kLith = 0.0226e6, kHyd = 0.0100e6, kK0 = 0.7, kNu = 0.25;

struct Closed {
  double p, frac, tensile, shear;
};

// The closed form of one element: centroid depth dc, deepest node depth dn (the element's pore
// pressure is its highest nodal one), pressure change dp.
Closed closed_form(double dc, double dn, double dp, double c, double phi_deg, double T0) {
  const double p0c = kHyd * dc;
  const double sv0 = (kLith - kHyd) * dc;  // effective, compression positive
  const double Sv = sv0 + p0c;             // total vertical: unchanged (free top)
  const double Sh = kK0 * sv0 - kNu / (1 - kNu) * dp + p0c + dp;  // total horizontal
  const double p = kHyd * dn + dp;
  Closed r;
  r.p = p;
  r.frac = std::min(Sh, Sv) + T0;
  r.tensile = r.frac - p;
  const double s1 = std::max(Sh, Sv) - p, s3 = std::min(Sh, Sv) - p, phi = phi_deg * M_PI / 180;
  r.shear = c * std::cos(phi) + 0.5 * (s1 + s3) * std::sin(phi) - 0.5 * (s1 - s3);
  return r;
}

struct SealCell {
  double dc, dn;
};

std::vector<SealCell> seal_cells(const std::string& h5) {
  FieldSeriesReader r(h5);
  const auto x = r.coordinates();
  const auto t = r.cells(ElementType::Tetrahedron);
  std::vector<SealCell> cells;
  for (std::size_t c = 0; 4 * c < t.size(); ++c) {
    double zc = 0, zmin = INFINITY;
    for (int j = 0; j < 4; ++j) zc += 0.25 * x[t[4 * c + j]][2], zmin = std::min(zmin, x[t[4 * c + j]][2]);
    cells.push_back({-zc, -zmin});
  }
  return cells;
}

std::string make(const Dir& d, double dp_MPa, double c, double phi, double T0) {
  const auto r = test::run(fmt::format("{} caprock {} --dp {} --cohesion {} --friction {} --tensile {}", test::make_case(),
                                       d.path.string(), dp_MPa, c, phi, T0));
  if (r.exit_code != 0) return {};
  return d / "mesh.msh" + " --case " + d / "case.toml" + " --pressure " + d / "flow.h5";
}

// The smallest scale at which some element's margin reaches zero. The margins are piecewise linear
// in dp (S3 switches from S_h to S_v where they cross) and fall monotonically along these paths:
// bisection on each element's closed form.
double critical_scale(const std::vector<SealCell>& cells, double dp, double c, double phi, double T0, bool tensile) {
  double s = INFINITY;
  for (const SealCell& e : cells) {
    auto margin = [&](double scale) {
      const Closed r = closed_form(e.dc, e.dn, scale * dp, c, phi, T0);
      return tensile ? r.tensile : r.shear;
    };
    if (margin(10) > 0) continue;
    double lo = 0, hi = 10;
    for (int k = 0; k < 80; ++k) (margin(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
    s = std::min(s, hi);
  }
  return s;
}

struct Search {
  double safe = 0, critical = 0;
  std::string limiter;
};

Search searched(const std::string& scenario_csv) {
  const CsvTable t = CsvTable::read(scenario_csv);
  Search s;
  s.critical = INFINITY;
  const auto cs = t.column("scale"), cc = t.column("critical"), cl = t.column("limiter");
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const double v = t.number(r, cs);
    if (t.integer(r, cc)) {
      if (v < s.critical) s.critical = v, s.limiter = std::string(t.text(r, cl));
    }
  }
  for (std::size_t r = 0; r < t.rows(); ++r)
    if (!t.integer(r, cc) && t.number(r, cs) < s.critical) s.safe = std::max(s.safe, t.number(r, cs));
  return s;
}

}  // namespace

TEST(RockMargins, RotatedStressAgainstItsPrincipalValues) {
  // Principal total stresses -30, -20, -12 MPa (S1 30, S3 12) rotated by 30 deg about z then 20 deg about x.
  const double P[3] = {-30e6, -20e6, -12e6};
  const double a = 30 * M_PI / 180, b = 20 * M_PI / 180;
  const double Rz[3][3] = {{std::cos(a), -std::sin(a), 0}, {std::sin(a), std::cos(a), 0}, {0, 0, 1}};
  const double Rx[3][3] = {{1, 0, 0}, {0, std::cos(b), -std::sin(b)}, {0, std::sin(b), std::cos(b)}};
  double R[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) R[i][j] += Rx[i][k] * Rz[k][j];
  double S[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) S[i][j] += R[i][k] * P[k] * R[j][k];
  const std::array<double, 6> s{S[0][0], S[1][1], S[2][2], S[0][1], S[1][2], S[0][2]};
  const auto e = fem::principal_values(s);
  EXPECT_NEAR(e[0], -30e6, 1e-6);
  EXPECT_NEAR(e[1], -20e6, 1e-6);
  EXPECT_NEAR(e[2], -12e6, 1e-6);
  // p = 10 MPa, T0 = 1 MPa, c = 2 MPa, phi = 30 deg: s'1 = 20, s'3 = 2 MPa.
  const fem::RockMargins m = fem::rock_margins(s, 10e6, {2e6, 30, 1e6});
  EXPECT_NEAR(m.S1_Pa, 30e6, 1e-6);
  EXPECT_NEAR(m.S3_Pa, 12e6, 1e-6);
  EXPECT_NEAR(m.fracture_pressure_Pa, 13e6, 1e-6);
  EXPECT_NEAR(m.tensile_margin_Pa, 3e6, 1e-6);
  EXPECT_NEAR(m.shear_margin_Pa, 2e6 * std::cos(M_PI / 6) + 11e6 * 0.5 - 9e6, 1e-6);
  // At the fracture pressure the margin is zero; beyond it negative.
  EXPECT_NEAR(fem::rock_margins(s, 13e6, {2e6, 30, 1e6}).tensile_margin_Pa, 0.0, 1e-6);
  EXPECT_LT(fem::rock_margins(s, 13.5e6, {2e6, 30, 1e6}).tensile_margin_Pa, 0.0);
}

TEST(CaprockSolve, InjectionFracturesTheSealWhereTheClosedFormSays) {
  Dir d("caprock-inject");
  const double dp = 10, c = 20, phi = 30, T0 = 0;  // strong in shear: tension decides
  const std::string args = make(d, dp, c, phi, T0);
  ASSERT_FALSE(args.empty());
  const auto r = test::run(test::solve_cmd() + " " + args + " -o " + d / "s.h5 --find-safe-scale --top none --state none");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Every seal element at scale 1 on 2001-01-01.
  const std::vector<SealCell> cells = seal_cells(d / "s_caprock.h5");
  ASSERT_EQ(cells.size(), 2u * 2u * 4u * 6u);  // the whole box is seal (six tetrahedra per hexahedron)
  FieldSeriesReader f(d / "s_caprock.h5");
  const std::size_t last = f.step("2001-01-01");
  const auto p = f.cell_field(last, "pore_pressure").values, frac = f.cell_field(last, "fracture_pressure").values;
  const auto tm = f.cell_field(last, "tensile_margin").values, sm = f.cell_field(last, "shear_margin").values;
  double worst_tensile = INFINITY, worst_error = 0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const Closed e = closed_form(cells[i].dc, cells[i].dn, dp * 1e6, c * 1e6, phi, T0 * 1e6);
    worst_error = std::max({worst_error, std::abs(frac[i] - e.frac), std::abs(tm[i] - e.tensile), std::abs(sm[i] - e.shear)});
    // The solver's tolerance (1e-8 of the load) moves the stresses by far less than 100 Pa.
    EXPECT_NEAR(p[i], e.p, 1e-3) << i;
    EXPECT_NEAR(frac[i], e.frac, 100) << i;
    EXPECT_NEAR(tm[i], e.tensile, 100) << i;
    EXPECT_NEAR(sm[i], e.shear, 100) << i;
    worst_tensile = std::min(worst_tensile, e.tensile);
  }
  std::printf("seal box: %zu elements, worst error of the fracture pressure and margins %.3g Pa\n", cells.size(), worst_error);
  // The table's worst element of the date is the fields' smallest margin.
  const CsvTable t = CsvTable::read(d / "s_caprock.csv");
  ASSERT_EQ(t.rows(), 2u);  // one seal, two steps
  EXPECT_EQ(t.text(1, t.column("seal")), "seal");
  EXPECT_NEAR(t.number(1, t.column("min_tensile_margin_MPa")), worst_tensile * 1e-6, 1e-4);
  // The search: the first scale at which the closed form's worst element fractures, within the bracket.
  const double s_star = critical_scale(cells, dp * 1e6, c * 1e6, phi, T0 * 1e6, true);
  // (The horizontal stress overtakes the vertical one on the way: the fracture there is horizontal,
  // S3 = S_v, which injection does not raise.)
  ASSERT_GT(s_star, 1.0);
  ASSERT_LT(s_star, 10);
  const Search s = searched(d / "s_scenario.csv");
  EXPECT_LE(s.safe, s_star * (1 + 1e-6));
  EXPECT_GE(s.critical, s_star * (1 - 1e-6));
  EXPECT_LE(s.critical - s.safe, 0.003 * s.critical);
  EXPECT_EQ(s.limiter, "caprock tensile failure");
  EXPECT_NE(r.err.find("seal seal fails first (caprock tensile failure)"), std::string::npos) << r.err;
}

TEST(CaprockSolve, DepletionShearsAWeakSealWhereTheClosedFormSays) {
  Dir d("caprock-deplete");
  const double dp = -5, c = 0.5, phi = 15, T0 = 0;
  const std::string args = make(d, dp, c, phi, T0);
  ASSERT_FALSE(args.empty());
  const auto r = test::run(test::solve_cmd() + " " + args + " -o " + d / "s.h5 --find-safe-scale --top none --state none");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<SealCell> cells = seal_cells(d / "s_caprock.h5");
  const double s_star = critical_scale(cells, dp * 1e6, c * 1e6, phi, T0 * 1e6, false);
  ASSERT_GT(s_star, 1.0);
  ASSERT_LT(s_star, 10);
  EXPECT_EQ(critical_scale(cells, dp * 1e6, c * 1e6, phi, T0 * 1e6, true), INFINITY);  // depletion never fractures
  const Search s = searched(d / "s_scenario.csv");
  EXPECT_LE(s.safe, s_star * (1 + 1e-6));
  EXPECT_GE(s.critical, s_star * (1 - 1e-6));
  EXPECT_EQ(s.limiter, "caprock shear failure");
}

TEST(CaprockSolve, BadSealEntriesExitTwoWithOneLine) {
  Dir d("caprock-bad");
  const std::string args = make(d, 10, 20, 30, 0);
  ASSERT_FALSE(args.empty());
  const std::string good = test::slurp(d / "case.toml");
  struct Bad {
    std::string from, to, says;
  };
  const Bad cases[] = {
      {"material = \"seal\"", "material = \"shale\"", "'seal[0].material': 'shale' is not a [[material]] of the case"},
      {"friction_deg = 30", "friction_deg = 95", "'seal[0].friction_deg': must lie in (0, 90) degrees"},
      {"cohesion_MPa = 20", "cohesion_MPa = -1", "'seal[0].cohesion_MPa': must be finite and not negative"},
      {"tensile_strength_MPa = 0", "tensile_strength_MPa = -2", "'seal[0].tensile_strength_MPa': must be finite and not negative"},
      {"cohesion_MPa = 20", "cohesion_MPa = 20\nstrength = 3", "strength"},
  };
  for (const Bad& b : cases) {
    std::string text = good;
    const auto at = text.find(b.from);
    ASSERT_NE(at, std::string::npos) << b.from;
    text.replace(at, b.from.size(), b.to);
    test::spit(d / "case.toml", text);
    const auto r = test::run(test::solve_cmd() + " " + args + " -o " + d / "bad.h5 --top none --state none");
    EXPECT_EQ(r.exit_code, 2) << b.to << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(b.says), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(d / "bad.h5"));
    EXPECT_FALSE(std::filesystem::exists(d / "bad_caprock.csv"));
  }
  // A seal twice, and --find-safe-scale with nothing to keep safe.
  test::spit(d / "case.toml", good + "\n[[seal]]\nmaterial = \"seal\"\n");
  auto r = test::run(test::solve_cmd() + " " + args + " -o " + d / "bad.h5 --top none --state none");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("'seal' is a seal twice"), std::string::npos) << r.err;
  std::string none = good.substr(0, good.find("[[seal]]"));
  test::spit(d / "case.toml", none);
  r = test::run(test::solve_cmd() + " " + args + " -o " + d / "bad.h5 --top none --state none --find-safe-scale");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nothing to keep safe"), std::string::npos) << r.err;
}

// The seal tables on 1 and 2 processes: the same margins, and the same worst element named (ties of
// the uniform box broken in output order, not by rounding).
TEST(CaprockSolve, SameTablesOnOneAndTwoProcesses) {
  Dir d("caprock-mpi");
  const std::string args = make(d, 10, 20, 30, 0);
  ASSERT_FALSE(args.empty());
  for (int n : {0, 2}) {
    const auto r = test::run(test::solve_cmd(n) + " " + args + " -o " + d / fmt::format("s{}.h5", n) +
                             " --find-safe-scale --top none --state none -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  auto rows = [&](const std::string& f) {
    std::istringstream in(test::slurp(d / f));
    std::string out, line;
    while (std::getline(in, line))
      if (line.rfind("#", 0) != 0) out += line + "\n";  // the comments hold the command line
    return out;
  };
  EXPECT_EQ(rows("s0_caprock.csv"), rows("s2_caprock.csv"));
  EXPECT_EQ(rows("s0_scenario.csv"), rows("s2_scenario.csv"));
}
