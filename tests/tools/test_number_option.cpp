// The one validator of numeric options (tools/common, ugs/cli/number_option.hpp): nan, inf, a value
// beyond double's range, text and a value out of range are refused, through Tool::run, with exit 2
// and one line naming the option; the ends of the range are taken or not as asked.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ugs/cli/number_option.hpp"
#include "ugs/cli/tool.hpp"

using namespace ugs;

namespace {

struct Outcome {
  int exit_code = -1;
  std::string err;
  double x = -1;
  int n = -1;
};

// ugs-test --x VALUE (a number in (0, 1]) or --n VALUE (an integer in [1, 256]).
Outcome run(const std::vector<std::string>& args) {
  cli::Tool tool({"ugs-test", "tests the numeric option validator", "ugs-test --x 0.5"});
  Outcome o;
  tool.app().add_option("--x", o.x, "a fraction")->check(cli::number_in(0, 1, cli::Ends::OpenLow));
  tool.app().add_option("-n,--jobs", o.n, "a count")->check(cli::number_in(1, 256));
  std::vector<std::string> words{"ugs-test"};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  testing::internal::CaptureStderr();
  o.exit_code = tool.run(static_cast<int>(argv.size()), argv.data(), [] {});
  o.err = testing::internal::GetCapturedStderr();
  return o;
}

}  // namespace

TEST(NumberOption, NonFiniteAndOutOfRangeAreOneLineWithExitTwo) {
  for (const char* v : {"nan", "inf", "-inf", "1e999", "0", "-0.5", "1.0000001", "abc", "0.5x", ""}) {
    const Outcome o = run({"--x", v});
    EXPECT_EQ(o.exit_code, 2) << v;
    EXPECT_EQ(o.err, fmt::format("ugs-test: error: --x: {} (expected a finite number in (0, 1]) (see --help)\n", v)) << v;
  }
  for (const char* v : {"0", "257", "nan", "-1"}) {
    const Outcome o = run({"--jobs", v});
    EXPECT_EQ(o.exit_code, 2) << v;
    EXPECT_EQ(o.err, fmt::format("ugs-test: error: --jobs: {} (expected a finite number in [1, 256]) (see --help)\n", v)) << v;
  }
}

TEST(NumberOption, ValuesInTheRangeAreTaken) {
  Outcome o = run({"--x", "1", "--jobs", "256"});
  EXPECT_EQ(o.exit_code, 0) << o.err;
  EXPECT_EQ(o.x, 1.0);
  EXPECT_EQ(o.n, 256);
  o = run({"--x", "+2.5e-1", "-n", "1"});
  EXPECT_EQ(o.exit_code, 0) << o.err;
  EXPECT_EQ(o.x, 0.25);
  EXPECT_EQ(o.n, 1);
}

TEST(NumberOption, RangeWordsOfEachKind) {
  auto message = [](CLI::Validator v, std::string text) { return v(text); };
  EXPECT_EQ(message(cli::number_in(0, cli::kNoLimit), "-1"), "-1 (expected a finite number >= 0)");
  EXPECT_EQ(message(cli::number_in(0, cli::kNoLimit, cli::Ends::OpenLow), "0"), "0 (expected a finite number > 0)");
  EXPECT_EQ(message(cli::number_in(0, 1, cli::Ends::Open), "1"), "1 (expected a finite number in (0, 1))");
  EXPECT_EQ(message(cli::number_in(-cli::kNoLimit, cli::kNoLimit), "nan"), "nan (expected a finite number)");
  EXPECT_EQ(message(cli::number_in(-cli::kNoLimit, cli::kNoLimit), "-1e300"), "");
  EXPECT_EQ(message(cli::number_in(0, cli::kNoLimit), "1.7976931348623157e308"), "");
}
