// GRDECL decks (formats/src/grdecl_reader.cpp) and the corner-point grid built from them
// (formats/src/corner_point_grid.cpp): the reader of material fields given as ECLIPSE arrays
// (docs/case-file.md, "Properties that vary in space").
#include <cmath>
#include <cstdlib>

#include "fuzz_support.hpp"
#include "ugs/formats/corner_point_grid.hpp"
#include "ugs/formats/grdecl.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = ugs::fuzz::write_temp("deck.grdecl", data, size);
  ugs::fuzz::outcome([&] {
    const ugs::GrdeclFile f = ugs::read_grdecl(path);
    for (const auto& k : f.keywords)
      for (double v : k.values)
        if (!std::isfinite(v)) std::abort();  // the reader refuses what is not a finite number
    const ugs::CornerPointGrid g = ugs::corner_point_grid(f);
    (void)g;
  });
  return 0;
}
