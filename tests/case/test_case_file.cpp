// The case file: the sample twin's case parses with SI conversions; unknown keys and
// non-physical values are refused with file:line.
#include <sstream>

#include <gtest/gtest.h>

#include "run_tool.hpp"
#include "ugs/formats/case_file.hpp"

namespace fs = std::filesystem;
using namespace ugs;

TEST(CaseFile, SampleTwinParses) {
  const CaseFile c = read_case_file(std::string(UGS_SOURCE_DIR) + "/data-samples/po-plain/case.toml");
  EXPECT_EQ(c.crs, "EPSG:32632");
  ASSERT_EQ(c.materials.size(), 7u);
  const MaterialSpec* pc = c.material("pool_c");
  ASSERT_NE(pc, nullptr);
  EXPECT_EQ(pc->law, MaterialLaw::Hypoplastic);
  EXPECT_DOUBLE_EQ(*pc->c_R, 3.0);
  EXPECT_DOUBLE_EQ(pc->Eh_over_Ez, 3.0);
  EXPECT_DOUBLE_EQ((*pc->K)[2], 2.04e-8);
  EXPECT_EQ(c.material("surrounding_rock")->law, MaterialLaw::ElasticDepth);
  EXPECT_DOUBLE_EQ(c.initial_stress.lithostatic_gradient, 0.0226e6);
  ASSERT_EQ(c.pools.size(), 2u);
  EXPECT_NEAR(*c.pools[1].reference_pressure_Pa, 15.2055e6, 1.0);
  EXPECT_TRUE(fs::exists(c.pools[1].schedule)) << c.pools[1].schedule;
  EXPECT_EQ(c.faults.size(), 6u);
  EXPECT_EQ(c.output_dates.size(), 5u);
}

namespace {
std::string error_of(const std::string& toml) {
  const auto dir = test::temp_dir("case");
  test::spit(dir / "c.toml", toml);
  try {
    read_case_file((dir / "c.toml").string());
  } catch (const InputError& e) {
    fs::remove_all(dir);
    return e.what();
  }
  fs::remove_all(dir);
  return "no error";
}
}  // namespace

TEST(CaseFile, UnknownKeyIsAnErrorWithItsLine) {
  const auto e = error_of("crs = \"EPSG:32632\"\n[[material]]\nname = \"a\"\nnu_zz = 0.3\n");
  EXPECT_NE(e.find("c.toml:4: 'material[0].nu_zz': unknown key"), std::string::npos) << e;
}

TEST(CaseFile, NonPhysicalValuesAreRefused) {
  EXPECT_NE(error_of("[[material]]\nname = \"a\"\nnu_z = 0.5\n").find("outside (-1, 0.5)"), std::string::npos);
  EXPECT_NE(error_of("[[material]]\nname = \"a\"\nEh_over_Ez = 0\n").find("must be positive"), std::string::npos);
  EXPECT_NE(error_of("[[material]]\nname = \"a\"\nlaw = \"hypoplastic\"\nc_R = -3\n").find("must be positive"),
            std::string::npos);
  EXPECT_NE(error_of("[[material]]\nname = \"a\"\nlaw = \"hypoplastic\"\n").find("'material[0].c_R': is required"),
            std::string::npos);
  EXPECT_NE(error_of("[[fault]]\nname = \"f\"\nfriction_deg = 95\n").find("(0, 90)"), std::string::npos);
  EXPECT_NE(error_of("[[fault]]\nname = \"f\"\ncohesion_MPa = -1\n").find("must not be negative"), std::string::npos);
  EXPECT_NE(error_of("[boundary]\nfixed = [\"wes\"]\n").find("unknown boundary 'wes'"), std::string::npos);
  // Integers are checked before they are narrowed to int: 2^32 + 1 was read as 1.
  EXPECT_NE(error_of("[solver]\nmax_newton_iterations = 4294967297\n").find("max_newton_iterations = 4294967297: outside [1, 1000]"),
            std::string::npos);
  EXPECT_NE(error_of("[solver]\nmax_substeps = 4294967297\n").find("max_substeps = 4294967297: outside [1, 4096]"), std::string::npos);
  EXPECT_NE(error_of("[output]\ncheckpoint_every = -4294967295\n").find("must lie in [0, 1000000], got -4294967295"),
            std::string::npos);
}

// Every number of [solver] is range-checked in one place, where the case is read: file:line, the
// key, the value, the range and what the number is; all of them at once.
TEST(CaseFile, SolverNumbersOutOfRangeNameFileLineAndKey) {
  auto tail = [](const std::string& e) { return e.substr(e.find("c.toml:")); };
  EXPECT_EQ(tail(error_of("[solver]\ntolerance = 1\n")),
            "c.toml:2: [solver] tolerance = 1: outside [1e-14, 1) (a relative residual ||r|| / ||r_0||)");
  EXPECT_EQ(tail(error_of("[solver]\nmax_newton_iterations = 0\n")),
            "c.toml:2: [solver] max_newton_iterations = 0: outside [1, 1000] (a step takes 2-25)");
  EXPECT_EQ(tail(error_of("[solver]\nmax_substeps = 4097\n")),
            "c.toml:2: [solver] max_substeps = 4097: outside [1, 4096] (sub-steps of a step that does not converge whole)");
  EXPECT_EQ(tail(error_of("[solver]\nturning_point_tolerance_MPa = -0.5\n")),
            "c.toml:2: [solver] turning_point_tolerance_MPa = -0.5: must be > 0 (a pressure change in MPa)");
  const std::string all = error_of("[solver]\ntolerance = 1e-20\nmax_newton_iterations = 5000\nmax_substeps = 0\n");
  EXPECT_NE(all.find("c.toml:2: [solver] tolerance = 1e-20: outside [1e-14, 1)"), std::string::npos) << all;
  EXPECT_NE(all.find("c.toml:3: [solver] max_newton_iterations = 5000: outside [1, 1000]"), std::string::npos) << all;
  EXPECT_NE(all.find("c.toml:4: [solver] max_substeps = 0: outside [1, 4096]"), std::string::npos) << all;
  // At the edges of the ranges the values are taken.
  EXPECT_EQ(error_of("[solver]\ntolerance = 1e-14\nmax_newton_iterations = 1000\nmax_substeps = 1\n"), "no error");
}

TEST(CaseFile, SyntaxErrorNamesTheLine) {
  const auto e = error_of("crs = \"EPSG:32632\"\n[model\n");
  EXPECT_NE(e.find("c.toml:2: TOML syntax error"), std::string::npos) << e;
}

// Issue 20: TOML allows inf and nan; no input of ours means them. Every float of the document is
// checked at parse time (so every tool with --case or --strata refuses them), with file:line, the
// dotted key and the value; unused tables are checked too.
TEST(CaseFile, InfAndNanAreRefusedEverywhere) {
  auto tail = [](const std::string& e) { return e.substr(e.find("c.toml:")); };
  EXPECT_EQ(tail(error_of("crs = \"EPSG:32632\"\n[water]\ncompressibility_per_MPa = inf\n")),
            "c.toml:3: water.compressibility_per_MPa = inf is not a finite number");
  EXPECT_EQ(tail(error_of("[[material]]\nname = \"a\"\nK_m_per_s = [1e-7, -inf, 1e-8]\n")),
            "c.toml:3: material[0].K_m_per_s[1] = -inf is not a finite number");
  EXPECT_EQ(tail(error_of("[initial_stress]\nk0 = nan\n")), "c.toml:2: initial_stress.k0 = nan is not a finite number");
  EXPECT_EQ(tail(error_of("[scenario]\npressure_scale = +inf\n")),
            "c.toml:2: scenario.pressure_scale = inf is not a finite number");
  EXPECT_EQ(tail(error_of("[water]\ncompressibility_per_MPa = -1e-4\n")),
            "c.toml:2: 'water.compressibility_per_MPa': must not be negative, got -0.0001");
}

TEST(CaseFile, DirectoryIsNamedAsSuch) {
  const auto dir = test::temp_dir("case-dir");
  try {
    read_case_file(dir.string());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), dir.string() + ": is a directory (expected a TOML file)");
  }
  fs::remove_all(dir);
}

// Issue 21: the general in-situ stress. k_Hmax, k_hmin, Hmax_azimuth_deg are read; k0 stays the
// shorthand for k_Hmax = k_hmin; bad ratios, azimuths and both forms at once are refused.
namespace {
CaseFile parse(const std::string& toml) {
  const auto dir = test::temp_dir("case");
  test::spit(dir / "c.toml", toml);
  CaseFile c = read_case_file((dir / "c.toml").string());
  fs::remove_all(dir);
  return c;
}
}  // namespace

TEST(CaseFile, InsituStressRatiosAndAzimuth) {
  const CaseFile a = parse("[initial_stress]\nk_Hmax = 1.3\nk_hmin = 0.9\nHmax_azimuth_deg = 10\n");
  EXPECT_EQ(a.initial_stress.kH(), 1.3);
  EXPECT_EQ(a.initial_stress.kh(), 0.9);
  EXPECT_EQ(a.initial_stress.Hmax_azimuth_deg, 10.0);
  const CaseFile b = parse("[initial_stress]\nk0 = 0.7\n");
  EXPECT_EQ(b.initial_stress.kH(), 0.7);
  EXPECT_EQ(b.initial_stress.kh(), 0.7);
  EXPECT_EQ(b.initial_stress.Hmax_azimuth_deg, 0.0);
  const CaseFile c = parse("[initial_stress]\nk_Hmax = 1.2\n");  // the other ratio: 1 (k0's default)
  EXPECT_EQ(c.initial_stress.kH(), 1.2);
  EXPECT_EQ(c.initial_stress.kh(), 1.0);
}

TEST(CaseFile, InsituStressBadInput) {
  auto tail = [](const std::string& e) { return e.substr(e.find("c.toml:")); };
  EXPECT_EQ(tail(error_of("[initial_stress]\nk_Hmax = 1.3\nk_hmin = 0\n")), "c.toml:3: 'initial_stress.k_hmin': must be positive, got 0");
  EXPECT_EQ(tail(error_of("[initial_stress]\nk_Hmax = -1.3\n")), "c.toml:2: 'initial_stress.k_Hmax': must be positive, got -1.3");
  EXPECT_EQ(tail(error_of("[initial_stress]\nk_hmin = nan\n")), "c.toml:2: initial_stress.k_hmin = nan is not a finite number");
  EXPECT_EQ(tail(error_of("[initial_stress]\nk0 = 0.8\nk_Hmax = 1.3\n")),
            "c.toml:3: 'initial_stress.k_Hmax': 1.3 given together with k0 = 0.8 (k0 is the shorthand for k_Hmax = k_hmin; "
            "give one form)");
  EXPECT_EQ(tail(error_of("[initial_stress]\nk_hmin = 0.9\nk0 = 0.8\n")),
            "c.toml:2: 'initial_stress.k_hmin': 0.9 given together with k0 = 0.8 (k0 is the shorthand for k_Hmax = k_hmin; "
            "give one form)");
  for (const std::string v : {"360", "-5", "400.5"})
    EXPECT_EQ(tail(error_of("[initial_stress]\nHmax_azimuth_deg = " + v + "\n")),
              "c.toml:2: 'initial_stress.Hmax_azimuth_deg': " + v +
                  " is outside [0, 360) degrees (clockwise from north, the mesh's +y axis)");
}

// Issue 21: per-material stress ratios. A material's k0 sets both of its ratios, k_Hmax / k_hmin
// each one (the other stays the [initial_stress] one, resolved by ugs-solve); the azimuth is global.
TEST(CaseFile, PerMaterialStressRatios) {
  const CaseFile c = parse(
      "[initial_stress]\nk_Hmax = 1.3\nk_hmin = 0.9\n"
      "[[material]]\nname = \"a\"\n"
      "[[material]]\nname = \"b\"\nk0 = 0.6\n"
      "[[material]]\nname = \"c\"\nk_hmin = 0.7\n");
  EXPECT_FALSE(c.material("a")->own_stress_ratios());
  EXPECT_EQ(*c.material("b")->k_Hmax, 0.6);
  EXPECT_EQ(*c.material("b")->k_hmin, 0.6);
  EXPECT_FALSE(c.material("c")->k_Hmax.has_value());
  EXPECT_EQ(*c.material("c")->k_hmin, 0.7);
}

TEST(CaseFile, PerMaterialStressRatiosBadInput) {
  auto tail = [](const std::string& e) { return e.substr(e.find("c.toml:")); };
  const std::string m = "[[material]]\nname = \"a\"\n";
  EXPECT_EQ(tail(error_of(m + "k0 = 0\n")), "c.toml:3: 'material[0].k0': must be positive, got 0");
  EXPECT_EQ(tail(error_of(m + "k_Hmax = -0.5\n")), "c.toml:3: 'material[0].k_Hmax': must be positive, got -0.5");
  EXPECT_EQ(tail(error_of(m + "k_hmin = inf\n")), "c.toml:3: material[0].k_hmin = inf is not a finite number");
  EXPECT_EQ(tail(error_of(m + "k0 = 0.8\nk_hmin = 0.9\n")),
            "c.toml:4: 'material[0].k_hmin': 0.9 given together with k0 = 0.8 (k0 is the shorthand for k_Hmax = k_hmin; "
            "give one form)");
  EXPECT_EQ(tail(error_of(m + "Hmax_azimuth_deg = 30\n")),
            "c.toml:3: 'material[0].Hmax_azimuth_deg': the azimuth of sigma'_Hmax is global: set it in [initial_stress] (a "
            "material may set only its own k0, k_Hmax, k_hmin)");
}

// Issue 21: [[boundary_traction]] on a named boundary group: a constant total traction (MPa, SI
// on reading) or the in-situ one; a group both held and loaded, twice loaded, or an entry without
// a value is refused with its line.
TEST(CaseFile, BoundaryTractions) {
  const CaseFile c = parse(
      "[boundary]\nfixed = [\"bottom\"]\nrollers = [\"west\", \"south\"]\n"
      "[[boundary_traction]]\ngroup = \"east\"\ntraction_MPa = [-12.5, 0, 1]\n"
      "[[boundary_traction]]\ngroup = \"bnd:north\"\nin_situ = true\n");
  ASSERT_EQ(c.tractions.size(), 2u);
  EXPECT_EQ(c.tractions[0].group, "east");
  EXPECT_FALSE(c.tractions[0].in_situ);
  EXPECT_EQ(c.tractions[0].traction_Pa[0], -12.5e6);
  EXPECT_EQ(c.tractions[0].traction_Pa[2], 1e6);
  EXPECT_EQ(c.tractions[0].where, c.path + ":4");  // the entry's [[boundary_traction]] line
  EXPECT_EQ(c.tractions[1].group, "north");  // the bnd: prefix may be written
  EXPECT_TRUE(c.tractions[1].in_situ);
}

TEST(CaseFile, BoundaryTractionBadInput) {
  auto tail = [](const std::string& e) { return e.substr(e.find("c.toml:")); };
  const std::string b = "[boundary]\nfixed = [\"bottom\"]\nrollers = [\"west\"]\nfree = [\"top\"]\n[[boundary_traction]]\n";
  EXPECT_EQ(tail(error_of(b + "group = \"east\"\n")),
            "c.toml:5: boundary_traction on 'east' has no value (expected traction_MPa = [tx, ty, tz] or in_situ = true)");
  EXPECT_EQ(tail(error_of(b + "group = \"east\"\nin_situ = false\n")),
            "c.toml:5: boundary_traction on 'east' has no value (expected traction_MPa = [tx, ty, tz] or in_situ = true)");
  EXPECT_EQ(tail(error_of(b + "group = \"east\"\nin_situ = true\ntraction_MPa = [1, 2, 3]\n")),
            "c.toml:8: 'boundary_traction[0].traction_MPa': given together with in_situ = true (give one: a constant "
            "traction or the in-situ one)");
  EXPECT_EQ(tail(error_of(b + "group = \"east\"\ntraction_MPa = [1, 2]\n")),
            "c.toml:7: 'boundary_traction[0].traction_MPa': has 2 values (expected [tx, ty, tz] in MPa)");
  EXPECT_EQ(tail(error_of(b + "group = \"east\"\ntraction_MPa = [1, nan, 2]\n")),
            "c.toml:7: boundary_traction[0].traction_MPa[1] = nan is not a finite number");
  EXPECT_EQ(tail(error_of(b + "group = \"\"\nin_situ = true\n")),
            "c.toml:6: 'boundary_traction[0].group': is empty (expected the name of a mesh group bnd:<name>, e.g. \"east\")");
  EXPECT_EQ(tail(error_of(b + "group = \"bottom\"\nin_situ = true\n")),
            "c.toml:6: 'boundary_traction[0].group': boundary 'bottom' is also in [boundary] fixed (a group is either held "
            "or loaded: take it out of fixed)");
  EXPECT_EQ(tail(error_of(b + "group = \"west\"\ntraction_MPa = [0, 0, 0]\n")),
            "c.toml:6: 'boundary_traction[0].group': boundary 'west' is also in [boundary] rollers (a group is either held "
            "or loaded: take it out of rollers)");
  EXPECT_EQ(tail(error_of(b + "group = \"top\"\ntraction_MPa = [0, 0, -1]\n")),
            "c.toml:6: 'boundary_traction[0].group': boundary 'top' is also in [boundary] free (a group is either held "
            "or loaded: take it out of free)");
  const std::string twice = tail(error_of(b + "group = \"east\"\nin_situ = true\n[[boundary_traction]]\ngroup = \"east\"\nin_situ = true\n"));
  EXPECT_EQ(twice.substr(0, twice.find(" at ")), "c.toml:9: 'boundary_traction[1].group': boundary 'east' is already loaded by the entry");
  EXPECT_EQ(twice.substr(twice.size() - 9), "/c.toml:5") << twice;
  // Without [boundary] fixed the default holds the four sides and the bottom: loading one is refused.
  EXPECT_EQ(tail(error_of("[[boundary_traction]]\ngroup = \"east\"\nin_situ = true\n")),
            "c.toml:2: 'boundary_traction[0].group': boundary 'east' is also in [boundary] fixed (the default: fixed = "
            "[\"west\", \"east\", \"south\", \"north\", \"bottom\"]) (a group is either held or loaded: take it out of fixed)");
  EXPECT_NE(error_of(b + "group = \"east\"\ntraction = [1, 2, 3]\n").find("unknown key"), std::string::npos);
}

// Every problem of the file is reported at once, one line each in the order of the file's lines,
// and one mistake gives one line (a value that failed is not also reported as missing).
TEST(CaseFile, EveryProblemIsReportedAtOnceInFileOrder) {
  const std::string e = error_of(
      "[[material]]\nname = \"a\"\nlaw = \"hypoplastic\"\nc_R = -3\nporosity = 2\n"  // lines 1-5
      "[[pool]]\nname = \"p\"\nmaterials = [\"b\"]\nschedule = \"s.csv\"\ncolumn = \"p_MPa\"\n"  // 6-10
      "[[fault]]\nname = \"f\"\nfriction_deg = 95\ncohesion_MPa = -1\n"                        // 11-14
      "[[boundary_traction]]\ngroup = \"top\"\n"                                            // 15-16
      "[scenario]\nmax_scale = 0\nsure = true\n");                                          // 17-19
  std::vector<std::string> lines;
  std::istringstream in(e);
  for (std::string line; std::getline(in, line);) lines.push_back(line.substr(line.find("c.toml")));
  const std::vector<std::string> expected{
      "c.toml:4: 'material[0].c_R': must be positive, got -3",
      "c.toml:5: 'material[0].porosity': must lie in (0, 1)",
      "c.toml:6: pool 'p': material 'b' is not defined",
      "c.toml:13: 'fault[0].friction_deg': must lie in (0, 90) degrees",
      "c.toml:14: 'fault[0].cohesion_MPa': must not be negative",
      "c.toml:15: boundary_traction on 'top' has no value (expected traction_MPa = [tx, ty, tz] or in_situ = true)",
      "c.toml:18: 'scenario.max_scale': must be positive, got 0",
      "c.toml:19: 'scenario.sure': unknown key (known here: max_scale, pressure_scale, reference_date, scale_tolerance)"};
  EXPECT_EQ(lines, expected) << e;
}

// ---- [initial_stress] tables by depth and the pools' gas columns (issue 42) ---------------------
TEST(CaseFile, EarthModelTablesConvertToSI) {
  const auto dir = test::temp_dir("case");
  test::spit(dir / "c.toml",
             "[initial_stress]\nSv_gradients_MPa_per_m = [[0, 0.02], [800, 0.025]]\n"
             "Shmin_MPa = [\n  [1000, 18],\n  [2000, 40.5],\n]\nSHmax_over_Shmin = 1.2\n"
             "overpressure_MPa = [[1500, 0], [1600, 7]]\nregime = \"normal\"\n"
             "[[material]]\nname = \"res\"\n"
             "[[pool]]\nname = \"p\"\nmaterials = [\"res\"]\nschedule = \"p.csv\"\ncolumn = \"p_MPa\"\n"
             "gas_water_contact_m = -1540.5\ngas_density_kg_per_m3 = 180\n");
  const CaseFile c = read_case_file((dir / "c.toml").string());
  fs::remove_all(dir);
  const auto& is = c.initial_stress;
  // The intervals become a gradient with a step at 800 m.
  ASSERT_EQ(is.sv_gradient.size(), 3u);
  EXPECT_EQ(is.sv_gradient[1].depth, 800);
  EXPECT_EQ(is.sv_gradient[1].value, 0.02e6);
  EXPECT_EQ(is.sv_gradient[2].value, 0.025e6);
  ASSERT_EQ(is.shmin.size(), 2u);
  EXPECT_EQ(is.shmin[1].value, 40.5e6);
  EXPECT_EQ(*is.sHmax_over_shmin, 1.2);
  EXPECT_EQ(is.overpressure[1].value, 7e6);
  EXPECT_EQ(is.regime, "normal");
  EXPECT_TRUE(is.horizontal_table());
  EXPECT_EQ(c.where("initial_stress.regime"), (dir / "c.toml").string() + ":9");
  EXPECT_EQ(*c.pools[0].gas_water_contact_m, -1540.5);
  EXPECT_DOUBLE_EQ(c.pools[0].gas_gradient_Pa_per_m, 180 * kGravity);
}

TEST(CaseFile, EarthModelBadInputNamesTheLine) {
  auto has = [](const std::string& e, const std::string& part) {
    EXPECT_NE(e.find(part), std::string::npos) << e;
  };
  // A row that goes back up names its own line.
  has(error_of("[initial_stress]\nShmin_MPa = [\n  [1000, 18],\n  [900, 20],\n]\n"),
      "c.toml:4: 'initial_stress.Shmin_MPa' row 2: depth 900 m does not follow 1000 m");
  has(error_of("[initial_stress]\nShmin_MPa = [[0, 18]]\n"), "row 1: depth 0 m is not below the surface");
  has(error_of("[initial_stress]\nShmin_MPa = [[1000, -18]]\n"), "row 1: -18 MPa is not positive");
  has(error_of("[initial_stress]\nShmin_MPa = [[1000, 18, 3]]\n"), "row 1: expected 2 numbers [depth_m, value], got 3 values");
  has(error_of("[initial_stress]\nShmin_MPa = []\n"), "'initial_stress.Shmin_MPa': is empty");
  has(error_of("[initial_stress]\nlithostatic_gradient_MPa_per_m = 0.0226\nSv_density_kg_per_m3 = [[0, 2300]]\n"),
      "c.toml:3: 'initial_stress.Sv_density_kg_per_m3': S_v is given twice");
  has(error_of("[initial_stress]\nSv_density_kg_per_m3 = [[0, 2300], [500, 900]]\n"),
      "row 2: 900 kg/m3 gives a gradient of S_v of 0.008829 MPa/m, not above the hydrostatic 0.01 MPa/m");
  has(error_of("[initial_stress]\nSv_gradients_MPa_per_m = [[100, 0.0226]]\n"), "the first interval starts at depth 100 m (expected 0");
  has(error_of("[initial_stress]\nk0 = 0.8\nShmin_MPa = [[1000, 18]]\n"),
      "c.toml:2: 'initial_stress.k0': given together with Shmin_MPa");
  has(error_of("[initial_stress]\nSHmax_over_Shmin = 1.2\n"), "'initial_stress.SHmax_over_Shmin': needs Shmin_MPa");
  has(error_of("[initial_stress]\nShmin_MPa = [[1000, 18]]\nSHmax_over_Shmin = 0.9\n"), "0.9 is below 1");
  has(error_of("[initial_stress]\nregime = \"extensional\"\n"), "'extensional' is not one of normal, strike-slip, reverse");
  has(error_of("[initial_stress]\nShmin_MPa = [[1000, 18]]\n[[material]]\nname = \"a\"\nk_hmin = 0.7\n"),
      "c.toml:5: 'material[0].k_hmin': a material's own stress ratio with [initial_stress] Shmin_MPa");
  const std::string pool = "[[material]]\nname = \"a\"\n[[pool]]\nname = \"p\"\nmaterials = [\"a\"]\nschedule = \"p.csv\"\n"
                           "column = \"p_MPa\"\n";
  has(error_of(pool + "gas_water_contact_m = -1500\n"), "c.toml:8: 'pool[0].gas_water_contact_m': needs the gas weight");
  has(error_of(pool + "gas_density_kg_per_m3 = 180\n"), "'pool[0].gas_density_kg_per_m3': needs gas_water_contact_m");
  has(error_of(pool + "gas_water_contact_m = -1500\ngas_density_kg_per_m3 = 1100\n"),
      "1100 gives a gas gradient of 0.010791 MPa/m, outside [0, 0.01)");
  has(error_of(pool + "gas_water_contact_m = -1500\ngas_density_kg_per_m3 = 180\n" +
               "[[pool]]\nname = \"q\"\nmaterials = [\"a\"]\nschedule = \"p.csv\"\ncolumn = \"p_MPa\"\n"
               "gas_water_contact_m = -1400\ngas_gradient_MPa_per_m = 0.002\n"),
      "pool 'q': material 'a' is also in pool 'p', and both have a gas column");
}
