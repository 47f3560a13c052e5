#include "ugs/insar/misfit.hpp"

#include <cmath>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"

namespace ugs::insar {

std::vector<SeriesMisfit> series_misfits(const PsData& measured, const Samples& sim, int component,
                                         const MisfitWindow& window) {
  if (sim.dates != measured.dates)
    throw std::logic_error("series_misfits: simulated series not sampled at the measured dates");
  std::vector<SeriesMisfit> out;
  const char* name = component == 2 ? "up" : component == 0 ? "east" : "north";
  for (std::size_t p = 0; p < sim.points.size(); ++p) {
    const auto m = measured.find(sim.points[p].point.id);
    if (!m) continue;
    SeriesMisfit s;
    s.id = sim.points[p].point.id;
    s.component = name;
    std::vector<double> r;
    for (std::size_t d = 0; d < measured.dates.size(); ++d) {
      if (!window.contains(measured.dates[d])) continue;
      const double meas = measured.value_mm(*m, d), simv = sim.at(p, d)[component] * 1e3;
      if (std::isnan(meas) || std::isnan(simv)) continue;
      r.push_back(simv - meas);
    }
    s.n = r.size();
    if (s.n > 0) {
      double mean = 0;
      for (double v : r) mean += v;
      mean /= double(s.n);
      double ss = 0;
      for (double v : r) ss += (v - mean) * (v - mean);
      s.offset_mm = mean;
      s.sum_squares = ss;
      s.rms_mm = std::sqrt(ss / double(s.n));
    }
    out.push_back(std::move(s));
  }
  return out;
}

Misfit combine_misfits(std::vector<SeriesMisfit> up, std::vector<SeriesMisfit> east, double east_weight) {
  Misfit m;
  double ss = 0, w = 0;
  for (const auto& s : up) {
    ss += s.sum_squares;
    w += double(s.n);
    m.n += s.n;
  }
  if (east_weight > 0)
    for (const auto& s : east) {
      ss += east_weight * s.sum_squares;
      w += east_weight * double(s.n);
      m.n += s.n;
    }
  if (m.n == 0 || w <= 0)
    throw InputError("", "no measured value of the PS selection falls in the misfit window within the results' dates");
  m.rms_mm = std::sqrt(ss / w);
  if (!std::isfinite(m.rms_mm))
    throw ComputeError(fmt::format("the InSAR misfit is not finite (sum of squares {} mm^2 over weight {})", ss, w));
  m.series = std::move(up);
  if (east_weight > 0) m.series.insert(m.series.end(), east.begin(), east.end());
  return m;
}

MisfitWindow parse_window(const std::string& text, const std::string& option) {
  MisfitWindow w;
  if (text.empty()) return w;
  const auto slash = text.find('/');
  if (slash == std::string::npos) throw InputError(option, fmt::format("'{}' is not START/END (ISO dates)", text));
  const std::string a = text.substr(0, slash), b = text.substr(slash + 1);
  if (!a.empty()) {
    const auto t = parse_iso_date(a);
    if (!t) throw InputError(option, fmt::format("'{}' is not an ISO 8601 date", a));
    w.start = *t;
  }
  if (!b.empty()) {
    const auto t = parse_iso_date(b);
    if (!t) throw InputError(option, fmt::format("'{}' is not an ISO 8601 date", b));
    w.end = *t;
  }
  if (w.start > w.end) throw InputError(option, fmt::format("'{}': start after end", text));
  return w;
}

}  // namespace ugs::insar
