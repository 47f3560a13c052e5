// Fault sticks as Petrel, RMS and Move export them in the IRAP classic lines format: one point
// "x y z" per line (z elevation, up, m), each stick ended by the line "999 999 999" (any spelling of
// the number 999: 999.000000), blank lines and '#' comments skipped. The sticks are given in order
// along the fault's strike; each runs down (or up) the fault.
#pragma once
#include <array>
#include <string>
#include <vector>

namespace ugs {

struct FaultSticks {
  std::string path;
  struct Stick {
    std::vector<std::array<double, 3>> points;
    std::vector<std::size_t> lines;  // of each point
  };
  std::vector<Stick> sticks;
};

// InputError "file:line: ..." for a line that is not three finite numbers, a stick of fewer than two
// distinct points, a last stick without its 999 line when the file has any (a truncated file), or
// fewer than two sticks.
FaultSticks read_fault_sticks(const std::string& path);

}  // namespace ugs
