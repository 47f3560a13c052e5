// Fault sticks in the IRAP classic lines format (formats/src/fault_sticks.cpp), the sticks of a
// fault given as a surface (docs/faults.md, "Faults as surfaces").
#include <cmath>
#include <cstdlib>

#include "fuzz_support.hpp"
#include "ugs/formats/fault_sticks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = ugs::fuzz::write_temp("fault.sticks", data, size);
  ugs::fuzz::outcome([&] {
    const ugs::FaultSticks s = ugs::read_fault_sticks(path);
    if (s.sticks.size() < 2) std::abort();  // fewer than two sticks is an InputError
    for (const auto& st : s.sticks) {
      if (st.points.size() < 2 || st.lines.size() != st.points.size()) std::abort();
      for (const auto& p : st.points)
        for (double c : p)
          if (!std::isfinite(c)) std::abort();
    }
  });
  return 0;
}
