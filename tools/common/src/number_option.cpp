#include "ugs/cli/number_option.hpp"

#include <charconv>
#include <cmath>
#include <string>
#include <system_error>

#include <fmt/format.h>

namespace ugs::cli {

CLI::Validator number_in(double lo, double hi, Ends ends) {
  const bool lo_open = ends == Ends::OpenLow || ends == Ends::Open, hi_open = ends == Ends::OpenHigh || ends == Ends::Open;
  const std::string range = lo == -kNoLimit && hi == kNoLimit ? std::string()
                            : hi == kNoLimit ? fmt::format(" {} {}", lo_open ? ">" : ">=", lo)
                                             : fmt::format(" in {}{}, {}{}", lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]");
  auto check = [=](std::string& text) -> std::string {
    // The whole text is one number as CLI11 reads it (a leading '+' allowed); from_chars reads
    // "nan" and "inf" as such and reports 1e999 as out of range.
    const char* first = text.data() + (!text.empty() && text[0] == '+' ? 1 : 0);
    const char* last = text.data() + text.size();
    double v = 0;
    const auto [end, ec] = std::from_chars(first, last, v);
    const bool in = ec == std::errc() && end == last && std::isfinite(v) && (lo_open ? v > lo : v >= lo) &&
                    (hi_open ? v < hi : v <= hi);
    return in ? std::string() : fmt::format("{} (expected a finite number{})", text, range);
  };
  return CLI::Validator(check, "NUMBER" + range);
}

}  // namespace ugs::cli
