// The stratigraphy file of ugs-meshgen (meshing/layers/src/strata.cpp over formats/src/toml_reader.cpp),
// then its evaluation on a small fixed plan (constant surfaces, units, material rules, fault depth
// ranges; files it names are looked for beside it and are absent unless the input names itself).
#include "fuzz_support.hpp"
#include "ugs/meshing/strata.hpp"

namespace {

// A 3 x 3 column square plan in UTM 32N, 1 km cells, with a fault line across it.
ugs::Plan small_plan() {
  ugs::Plan p;
  p.source = "plan.msh";
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      p.node_tags.push_back(p.xy.size() + 1);
      p.xy.push_back({500000.0 + 1000.0 * i, 5000000.0 + 1000.0 * j});
    }
  for (std::uint32_t j = 0; j < 2; ++j)
    for (std::uint32_t i = 0; i < 2; ++i) {
      const std::uint32_t a = 3 * j + i;
      p.triangles.push_back({a, a + 1, a + 4});
      p.triangles.push_back({a, a + 4, a + 3});
    }
  for (std::size_t t = 0; t < p.triangles.size(); ++t) p.triangle_tags.push_back(t + 1);
  p.lines.push_back({"fault:f1", {{{3, 4}}, {{4, 5}}}});
  return p;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const ugs::Plan plan = small_plan();
  const std::string path = ugs::fuzz::write_temp("strata.toml", data, size);
  ugs::fuzz::outcome([&] {
    const ugs::Strata s = ugs::read_strata(path);
    ugs::fuzz::outcome([&] { (void)ugs::prepare_model(s, plan); });
  });
  return 0;
}
