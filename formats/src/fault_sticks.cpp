// Fault sticks in the IRAP classic lines format (fault_sticks.hpp).
#include "ugs/formats/fault_sticks.hpp"

#include <fmt/format.h>

#include "text_lines.hpp"

namespace ugs {

FaultSticks read_fault_sticks(const std::string& path) {
  text::Lines in(path, "a fault sticks file (IRAP classic lines)");
  FaultSticks out;
  out.path = in.name();
  FaultSticks::Stick stick;
  std::size_t stick_line = 0;
  bool separators = false;
  auto close = [&] {
    if (stick.points.empty()) return;
    if (stick.points.size() < 2)
      throw InputError(fmt::format("{}:{}", out.path, stick.lines.front()),
                       "a stick of one point (a stick needs two or more points down the fault)");
    out.sticks.push_back(std::move(stick));
    stick = {};
  };
  while (in.next()) {
    const auto& t = in.tokens();
    if (t.empty() || t[0].starts_with("#")) continue;
    if (t.size() != 3) throw in.error(fmt::format("{} values (expected x y z, or 999 999 999 to end a stick)", t.size()));
    const std::array<double, 3> p{text::number(in, t[0], "x"), text::number(in, t[1], "y"), text::number(in, t[2], "z")};
    if (p[0] == 999 && p[1] == 999 && p[2] == 999) {
      if (stick.points.empty()) throw in.error("999 999 999 ends a stick, but no point precedes it (an empty stick)");
      separators = true;
      close();
      continue;
    }
    if (!stick.points.empty() && stick.points.back() == p) continue;  // a repeated point adds nothing
    if (stick.points.empty()) stick_line = in.line();
    stick.points.push_back(p);
    stick.lines.push_back(in.line());
  }
  if (!stick.points.empty() && separators)
    throw InputError(fmt::format("{}:{}", out.path, stick_line),
                     "the last stick has no 999 999 999 line after it (truncated file?)");
  close();
  if (out.sticks.size() < 2)
    throw InputError(fmt::format("{}:{}", out.path, in.line()),
                     fmt::format("{} stick(s): a fault surface needs two or more sticks", out.sticks.size()));
  return out;
}

}  // namespace ugs
