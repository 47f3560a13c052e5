// ugs-seismicity's readers and model (analysis/seismicity): the input as ugs-solve's per-pair fault
// CSV and as a date,dcfs_MPa table, each forecast with fixed parameters over a window inside its
// history (every value must come out finite: a non-finite one is a ComputeError, never written).
#include <cmath>
#include <cstdlib>

#include "fuzz_support.hpp"
#include "ugs/seismicity/forecast.hpp"
#include "ugs/seismicity/histories.hpp"

namespace {

void forecast_of(const ugs::seismicity::StressHistory& h) {
  ugs::seismicity::Parameters p;
  p.A_sigma = 0.01e6;
  p.stressing_rate = 1e-3 * 1e6 / ugs::kSecondsPerYear;
  p.background_rate = 0.1 / ugs::kSecondsPerYear / 1e6;
  p.M_c = 1.5;
  const std::vector<ugs::seismicity::Parameters> params(h.faults.size(), p);
  const std::int64_t a = h.dates.front(), b = h.dates.back();
  const auto fc = ugs::seismicity::forecast(h, params, a + (b - a) / 3, {{a + (b - a) / 4, b}});
  for (const auto& f : fc.faults) {
    for (double v : f.events)
      if (!std::isfinite(v)) std::abort();
    for (double v : f.window_events)
      if (!std::isfinite(v) || !std::isfinite(ugs::seismicity::events_above(v, f.params, 3.0))) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string pairs = ugs::fuzz::write_temp("run_fault_F.csv", data, size);
  ugs::fuzz::outcome([&] { forecast_of(ugs::seismicity::read_pair_csvs({pairs})); });
  const std::string dcfs = ugs::fuzz::write_temp("dcfs.csv", data, size);
  ugs::fuzz::outcome([&] { forecast_of(ugs::seismicity::read_dcfs_csv(dcfs, "patch", 1e6)); });
  return 0;
}
