// The one check of every numeric option (docs/cli.md): a CLI11 validator that refuses a value that
// is not a finite number (nan, inf, 1e999, text) or lies outside the option's range, before the
// option is converted and before anything is read. The tool then stops with exit 2 and one line
// naming the option:
//   ugs-calibrate: error: --xtol: inf (expected a finite number in (0, 1]) (see --help)
// CLI11's own Range and NonNegativeNumber let nan through (every comparison with it is false).
#pragma once
#include <limits>

#include <CLI/CLI.hpp>

namespace ugs::cli {

// Which ends of [lo, hi] belong to the range.
enum class Ends { Closed, OpenLow, OpenHigh, Open };

// No upper limit: the range is written "> lo" or ">= lo"; with lo = -kNoLimit too, any finite number.
inline constexpr double kNoLimit = std::numeric_limits<double>::max();

// For ->check(): the value is a finite number in the range `lo`..`hi` with `ends`. Integer options
// use it too (their values are then converted by CLI11, which refuses a fraction).
CLI::Validator number_in(double lo, double hi, Ends ends = Ends::Closed);

}  // namespace ugs::cli
