// The ensemble file of ugs-ensemble (analysis/ensemble/src/spec.cpp over formats/src/toml_reader.cpp),
// then what the tool does with a valid file before any solver runs: the parameters' ends against a
// fixed case (check_against_case: the 0.1 % and 99.9 % quantiles of unbounded laws, a rendered case
// read at each end) and the design (design.cpp, morris.cpp: the OpenTURNS distributions, LHS,
// Sobol' and Morris rows) for at most 32 members. Every design value must be finite and inside its
// law's support: a NaN or an out-of-range member would be rendered into a member's case.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "fuzz_support.hpp"
#include "ugs/ensemble/design.hpp"
#include "ugs/ensemble/spec.hpp"
#include "ugs/runner/case_params.hpp"

namespace {

// The paths of docs/ensemble.md's example and of tests/ensemble exist in it.
const char* kCase = R"(crs = "EPSG:32632"
[model]
name = "fuzz"
start = "1950-01-01"
end = "1951-01-01"
[water]
unit_weight_N_per_m3 = 9810.0
compressibility_per_MPa = 4.4e-4
[initial_stress]
surface_elevation_m = 50.0
lithostatic_gradient_MPa_per_m = 0.0226
hydrostatic_gradient_MPa_per_m = 0.00981
k_Hmax = 1.2
k_hmin = 0.9
[[material]]
name = "rock"
law = "elastic"
biot = 1.0
nu_z = 0.3
cm_a = 1.0044e-2
cm_b = 1.1347
[[material]]
name = "pool_c"
law = "hypoplastic"
biot = 1.0
nu_z = 0.3
cm_a = 1.0044e-2
cm_b = 1.1347
c_R = 3.0
K_m_per_s = [2.04e-7, 2.04e-7, 2.04e-8]
porosity = 0.20
[[material]]
name = "aquifer_pool_c"
law = "hypoplastic"
biot = 1.0
nu_z = 0.3
cm_a = 1.0044e-2
cm_b = 1.1347
c_R = 3.0
K_m_per_s = [2.04e-7, 2.04e-7, 2.04e-8]
porosity = 0.20
[[pool]]
name = "Pool C"
materials = ["pool_c"]
aquifer_materials = ["aquifer_pool_c"]
schedule = "pressure_pool_c.csv"
column = "p_MPa"
[boundary]
fixed = ["bottom", "west", "east", "south", "north"]
[[fault]]
name = "backthrust_south"
cohesion_MPa = 0.0
friction_deg = 30.0
[scenario]
reference_date = "1950-06-01"
max_scale = 4.0
scale_tolerance = 0.02
)";

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_ensemble_spec: %s\n", what.c_str());
  std::abort();
}

void check_design(const ugs::ensemble::EnsembleSpec& s, const ugs::ensemble::Design& d) {
  using namespace ugs::ensemble;
  const std::size_t n = s.parameters.size();
  const std::size_t rows = s.method == DesignMethod::lhs     ? s.members
                           : s.method == DesignMethod::sobol ? s.members / (n + 2) * (n + 2)
                                                             : s.members / (n + 1) * (n + 1);
  if (d.x.size() != rows) finding("design has " + std::to_string(d.x.size()) + " rows, expected " + std::to_string(rows));
  for (std::size_t j = 0; j < n; ++j) {
    const Distribution& law = s.parameters[j].distribution;
    double lo = -INFINITY, hi = INFINITY;
    if (law.kind == DistributionKind::uniform || law.kind == DistributionKind::triangular) lo = law.a, hi = law.b;
    if (law.kind == DistributionKind::lognormal) lo = 0;
    if (law.lower) lo = std::max(lo, *law.lower);
    if (law.upper) hi = std::min(hi, *law.upper);
    // OpenTURNS maps [0, 1] to [lower, upper] with rounding: a value may leave by an ulp or so.
    const double slack = 1e-12 * std::max(std::isfinite(lo) ? std::abs(lo) : 0.0, std::isfinite(hi) ? std::abs(hi) : 0.0);
    for (std::size_t i = 0; i < d.x.size(); ++i) {
      const double v = d.x[i].at(j);
      if (!std::isfinite(v) || v < lo - slack || v > hi + slack) {
        char text[64];
        std::snprintf(text, sizeof text, "%.17g", v);
        finding("member " + std::to_string(i + 1) + ", " + s.parameters[j].name + " of " + law.describe() + ": " + text);
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string case_path = [] {
    return ugs::fuzz::write_temp("case.toml", reinterpret_cast<const std::uint8_t*>(kCase), std::strlen(kCase));
  }();
  static const ugs::runner::CaseTemplate tmpl(case_path);
  const std::string path = ugs::fuzz::write_temp("ensemble.toml", data, size);
  ugs::fuzz::outcome([&] {
    ugs::ensemble::EnsembleSpec s = ugs::ensemble::read_spec(path);
    ugs::fuzz::outcome([&] { ugs::ensemble::check_against_case(s, tmpl); });
    // A small design (the file may ask for up to 10^7 members): at most 32, or the design's minimum.
    s.members = std::min(s.members, std::max<std::size_t>(32, ugs::ensemble::minimum_members(s.method, s.parameters.size())));
    check_design(s, ugs::ensemble::make_design(s));
  });
  return 0;
}
