// The calibration misfit (thesis 4.2.2): at each chosen point, the residual r(t) = simulated -
// measured over the dates of a window where both exist; each series' offset (the mean residual)
// is removed, since InSAR series and simulations have different zeros; the misfit is the RMS of
// the remaining residuals pooled over points (vertical, optionally east-west with a weight):
//   RMS = sqrt( (sum_up (r - mean r)^2 + w_e sum_east (r - mean r)^2) / (n_up + w_e n_east) ).
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "ugs/insar/ps_data.hpp"
#include "ugs/insar/sampling.hpp"

namespace ugs::insar {

struct MisfitWindow {
  std::int64_t start = std::numeric_limits<std::int64_t>::min();
  std::int64_t end = std::numeric_limits<std::int64_t>::max();
  bool contains(std::int64_t t) const { return t >= start && t <= end; }
};

struct SeriesMisfit {
  std::string id;
  std::string component;       // "up" or "east"
  std::size_t n = 0;           // dates used
  double offset_mm = 0;        // mean(simulated - measured), removed
  double sum_squares = 0;      // sum (r - offset)^2, mm^2
  double rms_mm = std::numeric_limits<double>::quiet_NaN();
};

struct Misfit {
  double rms_mm = std::numeric_limits<double>::quiet_NaN();
  std::size_t n = 0;
  std::vector<SeriesMisfit> series;
};

// Residuals of one component (0 east, 1 north, 2 up) at the measured points found in `simulated`
// (by id). `simulated` must have been sampled at `measured.dates`.
std::vector<SeriesMisfit> series_misfits(const PsData& measured, const Samples& simulated, int component,
                                         const MisfitWindow& window);

// START/END (ISO dates, either may be empty; "" = all dates); InputError at `option` otherwise.
MisfitWindow parse_window(const std::string& text, const std::string& option);

// Pools the series; InputError when no residual falls in the window.
Misfit combine_misfits(std::vector<SeriesMisfit> up, std::vector<SeriesMisfit> east, double east_weight);

}  // namespace ugs::insar
