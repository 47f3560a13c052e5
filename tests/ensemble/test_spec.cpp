// The ensemble file: what it accepts, the one-line errors for what it refuses, and the designs'
// sizes and determinism.
#include <gtest/gtest.h>

#include "run_tool.hpp"
#include "ugs/ensemble/design.hpp"
#include "ugs/ensemble/metrics.hpp"
#include "ugs/ensemble/spec.hpp"
#include "ugs/formats/error.hpp"

using namespace ugs;
using namespace ugs::ensemble;

namespace {

std::string error_of(const std::string& text) {
  const auto dir = test::temp_dir("spec");
  test::spit(dir / "e.toml", text);
  try {
    (void)read_spec((dir / "e.toml").string());
  } catch (const InputError& e) {
    std::filesystem::remove_all(dir);
    return e.what();
  }
  std::filesystem::remove_all(dir);
  return "";
}

const char* kTwo = R"(
[[parameter]]
path = "material.pool_c.c_R"
distribution = "uniform"
lower = 2.0
upper = 6.0

[[parameter]]
paths = ["initial_stress.k0", "initial_stress.k_Hmax"]
distribution = "normal"
mean = 0.9
std = 0.05
lower = 0.8
)";

EnsembleSpec spec_of(const std::string& text) {
  const auto dir = test::temp_dir("spec-ok");
  test::spit(dir / "e.toml", text);
  EnsembleSpec s = read_spec((dir / "e.toml").string());
  std::filesystem::remove_all(dir);
  return s;
}

}  // namespace

TEST(EnsembleSpec, ReadsParametersAndDistributions) {
  const EnsembleSpec s = spec_of(std::string("[design]\nmethod = \"lhs\"\nmembers = 10\nseed = 3\n") + kTwo);
  ASSERT_EQ(s.parameters.size(), 2u);
  EXPECT_EQ(s.parameters[1].paths.size(), 2u);
  EXPECT_EQ(s.parameters[1].distribution.kind, DistributionKind::normal);
  EXPECT_EQ(*s.parameters[1].distribution.lower, 0.8);
  EXPECT_FALSE(s.parameters[1].distribution.upper);
  EXPECT_EQ(s.seed, 3u);
  EXPECT_EQ(s.parameters[0].name, "material.pool_c.c_R");  // no name: the first path
  EXPECT_EQ(s.parameters[1].name, "initial_stress.k0");
}

TEST(EnsembleSpec, AParameterNameHeadsItsColumnsAndIsChecked) {
  const std::string head = "[design]\nmethod = \"lhs\"\nmembers = 10\n";
  const std::string uni = "distribution = \"uniform\"\nlower = 1.0\nupper = 2.0\n";
  const EnsembleSpec s = spec_of(head + "[[parameter]]\nname = \"k (both)\"\npaths = [\"a\", \"b\"]\n" + uni);
  EXPECT_EQ(s.parameters[0].name, "k (both)");
  EXPECT_EQ(s.parameters[0].paths, (std::vector<std::string>{"a", "b"}));
  const std::string comma = error_of(head + "[[parameter]]\nname = \"a,b\"\npath = \"a\"\n" + uni);
  EXPECT_NE(comma.find("'parameter[0].name': must be non-empty text without commas"), std::string::npos) << comma;
  const std::string same = error_of(head + "[[parameter]]\nname = \"c\"\npath = \"a\"\n" + uni + "[[parameter]]\npath = \"c\"\n" + uni);
  EXPECT_NE(same.find("'c' names two parameters"), std::string::npos) << same;
}

TEST(EnsembleSpec, BadInputIsOneLineNamingTheKey) {
  const std::string head = "[design]\nmethod = \"sobol\"\nmembers = 8\n";
  // 2 parameters: Sobol' needs 2 (2 + 2) = 8 members; 7 are too few.
  EXPECT_EQ(error_of(head + kTwo), "");
  const std::string few = error_of("[design]\nmethod = \"sobol\"\nmembers = 7\n" + std::string(kTwo));
  EXPECT_NE(few.find(":3: 'design.members': 7 members"), std::string::npos) << few;
  EXPECT_NE(few.find("fewer than the sobol design needs with 2 parameters (at least 8)"), std::string::npos) << few;
  const std::string morris = error_of("[design]\nmethod = \"morris\"\nmembers = 5\n" + std::string(kTwo));
  EXPECT_NE(morris.find("(at least 6)"), std::string::npos) << morris;
  const std::string rev = error_of(head + "[[parameter]]\npath = \"a\"\ndistribution = \"uniform\"\nlower = 6.0\nupper = 2.0\n");
  EXPECT_NE(rev.find(":8: 'parameter[0].upper': uniform bounds reversed or equal: lower 6 >= upper 2"), std::string::npos) << rev;
  const std::string sd = error_of(head + "[[parameter]]\npath = \"a\"\ndistribution = \"normal\"\nmean = 1.0\nstd = -1.0\n");
  EXPECT_NE(sd.find("'parameter[0].std': must be > 0 (got -1)"), std::string::npos) << sd;
  const std::string mode = error_of(head + "[[parameter]]\npath = \"a\"\ndistribution = \"triangular\"\nlower = 1.0\nmode = 3.0\nupper = 2.0\n");
  EXPECT_NE(mode.find("'parameter[0].mode': mode 3 outside [lower, upper] = [1, 2]"), std::string::npos) << mode;
  const std::string trunc = error_of(head + "[[parameter]]\npath = \"a\"\ndistribution = \"normal\"\nmean = 0.0\nstd = 1.0\nlower = 50.0\n");
  EXPECT_NE(trunc.find("leaves no probability"), std::string::npos) << trunc;
  const std::string kind = error_of(head + "[[parameter]]\npath = \"a\"\ndistribution = \"weibull\"\n");
  EXPECT_NE(kind.find("unknown distribution 'weibull'"), std::string::npos) << kind;
  const std::string twice = error_of(head + "[[parameter]]\npath = \"a\"\ndistribution = \"uniform\"\nlower = 1.0\nupper = 2.0\n"
                                            "[[parameter]]\npath = \"a\"\ndistribution = \"uniform\"\nlower = 1.0\nupper = 2.0\n");
  EXPECT_NE(twice.find("'a' is named twice"), std::string::npos) << twice;
  const std::string unknown = error_of(head + "[[parameter]]\npath = \"a\"\ndistribution = \"uniform\"\nlower = 1.0\nupper = 2.0\nmean = 3.0\n");
  EXPECT_NE(unknown.find("mean"), std::string::npos) << unknown;
  EXPECT_NE(error_of("[design]\nmethod = \"grid\"\nmembers = 8\n" + std::string(kTwo)).find("unknown design 'grid'"), std::string::npos);
  EXPECT_NE(error_of("[design]\nmethod = \"lhs\"\nmembers = 8\n").find("no [[parameter]]"), std::string::npos);
}

// Found by fuzz_ensemble_spec (tests/fuzz/corpus/ensemble_spec/regress-*): a string or quoted key
// that is not UTF-8 made toml11 3.7.1 read out of bounds (ASan heap-buffer-overflow in its error
// path); the file is now refused before toml11 sees it, naming the line and column.
TEST(EnsembleSpec, TextThatIsNotUtf8IsOneLine) {
  const std::string corpus = std::string(UGS_SOURCE_DIR) + "/tests/fuzz/corpus/ensemble_spec/";
  const auto message = [](const std::string& path) {
    try {
      (void)read_spec(path);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message(corpus + "regress-quoted-key-not-utf8.toml"),
            corpus + "regress-quoted-key-not-utf8.toml:1: byte 0x9d at column 2 is not UTF-8 (expected a UTF-8 text file)");
  EXPECT_EQ(message(corpus + "regress-ml-literal-not-utf8.toml"),
            corpus + "regress-ml-literal-not-utf8.toml:5: byte 0x9d at column 1 is not UTF-8 (expected a UTF-8 text file)");
  // Overlong forms, surrogates and a cut sequence are not UTF-8 either; real UTF-8 reads.
  EXPECT_NE(error_of("[design]\nmethod = \"lhs\"\nmembers = 8\n# \xc0\xaf\n").find(":4: byte 0xc0 at column 3"), std::string::npos);
  EXPECT_NE(error_of("# \xed\xa0\x80\n").find(":1: byte 0xed at column 3"), std::string::npos);
  EXPECT_NE(error_of("# \xe2\x82").find(":1: byte 0xe2 at column 3"), std::string::npos);
  EXPECT_EQ(error_of(std::string("[design]\nmethod = \"lhs\"\nmembers = 8\n# \xc3\xa9t\xc3\xa9 \xe2\x82\xac \xf0\x9f\x99\x82\n") + kTwo), "");
}

// Found by fuzz_ensemble_spec and by probing its neighbours after the first
// (tests/fuzz/corpus/ensemble_spec/regress-*): laws that OpenTURNS refuses with its own exception
// (ugs-ensemble's "internal error", exit 1) or whose members are not finite numbers.
TEST(EnsembleSpec, LawsOpenTurnsCannotDrawAreOneLine) {
  const std::string corpus = std::string(UGS_SOURCE_DIR) + "/tests/fuzz/corpus/ensemble_spec/";
  const auto message = [&](const std::string& name) {
    try {
      const EnsembleSpec s = read_spec(corpus + name);
      (void)make_design(s);
    } catch (const InputError& e) {
      return std::string(e.what()).substr(corpus.size());
    }
    return std::string();
  };
  // OpenTURNS: "Errors found when parsing expression 'inf+-nan*(x0-0.5)'".
  EXPECT_EQ(message("regress-uniform-infinite-width.toml"),
            "regress-uniform-infinite-width.toml:8: 'parameter[0].upper': uniform range [-1e+308, 1e+308]: upper - lower = inf "
            "(expected a width from 2.22507e-308 to 1.79769e+308)");
  // OpenTURNS: "Invalid numeric token: '9.8813129168249308835e-324'".
  EXPECT_EQ(message("regress-uniform-subnormal-width.toml"),
            "regress-uniform-subnormal-width.toml:8: 'parameter[0].upper': 4.94066e-324 is too close to 0 (expected 0 or a "
            "magnitude above 2.22507e-308)");
  // Members at -inf and inf (no exception).
  EXPECT_EQ(message("regress-triangular-infinite-width.toml"),
            "regress-triangular-infinite-width.toml:9: 'parameter[0].upper': triangular range [-1e+308, 1e+308]: upper - lower = "
            "inf (expected a width from 2.22507e-308 to 1e+150)");
  // A finite width whose square is not: the triangular quantile drew -inf (found by fuzz_ensemble_spec).
  EXPECT_EQ(message("regress-triangular-squared-width.toml"),
            "regress-triangular-squared-width.toml:9: 'parameter[0].upper': triangular range [-0, 1e+308]: upper - lower = 1e+308 "
            "(expected a width from 2.22507e-308 to 1e+150)");
  // OpenTURNS: "MuLog=0 and SigmaLog=1000 lead to a LogNormal distribution with a too much wide range".
  EXPECT_EQ(message("regress-lognormal-too-wide.toml"),
            "regress-lognormal-too-wide.toml:8: 'parameter[0].sigma_log': lognormal(median 1, sigma_log 1000) spans more than "
            "doubles hold within 9 sigma_log (expected |ln median| + 9 sigma_log < 700)");
  // OpenTURNS: "the truncation interval does not contain a non-empty part of the support".
  EXPECT_EQ(message("regress-truncation-zero-probability.toml").rfind(
                "regress-truncation-zero-probability.toml:9: 'parameter[0].lower': the truncation [0.5, 0.5000000000000001] leaves "
                "no probability of normal(0, 1) (",
                0),
            0u)
      << message("regress-truncation-zero-probability.toml");
  // The neighbours: a normal law reaching past the largest double, a truncation in a far tail that
  // keeps its 1e-6, a lognormal law at the edge.
  const std::string head = "[design]\nmethod = \"lhs\"\nmembers = 32\n[[parameter]]\npath = \"a\"\n";
  EXPECT_NE(error_of(head + "distribution = \"normal\"\nmean = 0.0\nstd = 1e308\n").find(":8: 'parameter[0].std': normal(0, 1e+308) "
                                                                                      "reaches beyond the largest double"),
            std::string::npos);
  EXPECT_EQ(error_of(head + "distribution = \"normal\"\nmean = 0.0\nstd = 1.0\nlower = 4.7\n"), "");   // 1.3e-6 left
  EXPECT_NE(error_of(head + "distribution = \"normal\"\nmean = 0.0\nstd = 1.0\nlower = 4.8\n").find("(7.93e-07 of it"),
            std::string::npos);
  EXPECT_NE(error_of(head + "distribution = \"normal\"\nmean = 0.0\nstd = 1.0\nupper = -4.8\n").find("(7.93e-07 of it"),
            std::string::npos);
  EXPECT_EQ(error_of(head + "distribution = \"lognormal\"\nmedian = 1e-300\nsigma_log = 1.0\n"), "");
  const EnsembleSpec s = spec_of(head + "distribution = \"lognormal\"\nmedian = 1e-300\nsigma_log = 1.0\nlower = 1e-301\n");
  for (const auto& x : make_design(s).x) EXPECT_GE(x[0], 1e-301);
}

// OpenTURNS' Sobol' sequence has 1111 dimensions, and the blocks A and B take 2 per parameter: with
// more than 555 parameters it threw its own exception ("Dimension must be in range [0-1111]"; found
// while looking at the fuzzing's neighbours, out of the fuzzer's reach: 30 kB of parameters).
TEST(EnsembleSpec, SobolDesignOfMoreParametersThanTheSequenceHasIsOneLine) {
  auto spec = [](std::size_t d) {
    std::string s = "[design]\nmethod = \"sobol\"\nmembers = " + std::to_string(2 * (d + 2)) + "\n";
    for (std::size_t i = 0; i < d; ++i)
      s += "[[parameter]]\npath = \"p" + std::to_string(i) + "\"\ndistribution = \"uniform\"\nlower = 0.0\nupper = 1.0\n";
    return s;
  };
  EXPECT_NE(error_of(spec(556)).find(":2: 'design.method': the sobol design takes at most 555 parameters (OpenTURNS' Sobol' "
                                     "sequence has 1111 dimensions, 2 per parameter), here 556"),
            std::string::npos);
  EXPECT_EQ(make_design(spec_of(spec(555))).x.size(), 2u * 557u);
}

TEST(EnsembleDesign, SizesBoundsAndSameSeedSameMembers) {
  const EnsembleSpec lhs = spec_of(std::string("[design]\nmethod = \"lhs\"\nmembers = 50\nseed = 11\n") + kTwo);
  const Design a = make_design(lhs), b = make_design(lhs);
  ASSERT_EQ(a.x.size(), 50u);
  EXPECT_EQ(a.x, b.x);  // bit for bit
  // One member in each of the 50 equally likely strata of each parameter.
  std::vector<int> strata(50, 0);
  for (const auto& x : a.x) {
    EXPECT_GE(x[0], 2.0);
    EXPECT_LE(x[0], 6.0);
    EXPECT_GE(x[1], 0.8);  // truncated normal
    ++strata[static_cast<std::size_t>((x[0] - 2.0) / 4.0 * 50)];
  }
  for (int c : strata) EXPECT_EQ(c, 1);
  EnsembleSpec other = lhs;
  other.seed = 12;
  EXPECT_NE(make_design(other).x, a.x);

  const EnsembleSpec sobol = spec_of(std::string("[design]\nmethod = \"sobol\"\nmembers = 34\n") + kTwo);
  const Design s = make_design(sobol);
  EXPECT_EQ(s.base, 8u);  // 34 / (2 + 2)
  ASSERT_EQ(s.x.size(), 32u);
  // Block 2 + i is A with column i from B.
  for (std::size_t k = 0; k < 8; ++k) {
    EXPECT_EQ(s.x[16 + k][0], s.x[8 + k][0]);
    EXPECT_EQ(s.x[16 + k][1], s.x[k][1]);
    EXPECT_EQ(s.x[24 + k][1], s.x[8 + k][1]);
    EXPECT_EQ(s.x[24 + k][0], s.x[k][0]);
  }
}

// The library names the setting in words (ugs-ensemble's main maps "metric phase" to --phase).
TEST(EnsemblePhase, BadPhaseNamesTheSettingInWords) {
  const auto message = [](const std::string& text) {
    try {
      ugs::ensemble::parse_phase(text);
    } catch (const ugs::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message("storage"), "metric phase storage: expected NAME=START/END, e.g. storage=2015-05-01/2015-11-01");
  EXPECT_EQ(message("storage=2015-13-01/2015-11-01"), "metric phase storage=2015-13-01/2015-11-01: dates must be ISO 8601 (YYYY-MM-DD)");
  EXPECT_EQ(message("storage=2015-11-01/2015-05-01"), "metric phase storage=2015-11-01/2015-05-01: the start must come before the end");
  const auto p = ugs::ensemble::parse_phase("storage=2015-05-01/2015-11-01");
  EXPECT_EQ(p.name, "storage");
}
