// The case file: the sample twin's case parses with SI conversions; unknown keys and
// non-physical values are refused with file:line.
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
  EXPECT_NE(error_of("[solver]\nmax_newton_iterations = 4294967297\n").find("must lie in [1, 1000000000], got 4294967297"),
            std::string::npos);
  EXPECT_NE(error_of("[solver]\nmax_substeps = 4294967297\n").find("must lie in [1, 4096], got 4294967297"), std::string::npos);
  EXPECT_NE(error_of("[output]\ncheckpoint_every = -4294967295\n").find("must lie in [0, 1000000], got -4294967295"),
            std::string::npos);
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
