// Time series at the PS points (thesis figures 4.15-4.20): the simulated displacement (from a
// ugs-sample table, or sampled here on the top-surface results) against the measured InSAR series,
// the simulated one shifted by the mean difference over the common dates (InSAR series have their
// own zero), with the pool pressures on a second axis.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "report.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/insar/displacement.hpp"
#include "ugs/insar/sampling.hpp"

namespace ugs::report {

namespace {

}  // namespace

void build_series(Context& c) {
  if (!c.measured_up && c.opt.samples.empty()) {
    c.notes.push_back("no measured series (--measured) and no samples (--samples): PS time series skipped");
    return;
  }
  // Simulated series at their own dates, absolute or relative (only differences matter here).
  insar::Samples sim;
  if (!c.opt.samples.empty()) {
    sim = insar::read_samples_csv(c.opt.samples);
  } else {
    if (!c.top) {
      c.notes.push_back("no top surface: PS time series skipped");
      return;
    }
    const insar::SurfaceLocator loc(*c.top);
    const auto located = insar::locate_points(loc, c.measured_up->points, false);
    for (const auto& p : located.outside)
      c.notes.push_back(fmt::format("PS '{}' lies {:.0f} m outside the top surface: no time series", p.point.id, p.hit.distance));
    if (located.sampled.empty()) insar::require_some_on_surface(*c.top, *c.measured_up);  // throws
    insar::SurfaceDisplacement disp(c.surface_results, *c.top, "");
    sim = insar::sample_displacement(disp, located.sampled, {}, std::nullopt);
  }
  std::string plabel;
  const bool pressures = write_pressures(c, plabel);
  {
    CsvWriter w(c.work_file("ps_points.csv"), {"pid", "x", "y"});
    for (const auto& p : sim.points) w.text(p.point.id).number(p.point.x, 2).number(p.point.y, 2).end_row();
    w.commit();
  }
  struct Comp {
    const char* name;
    int index;
    const std::optional<insar::PsData>* measured;
  };
  const Comp comps[] = {{"up", 2, &c.measured_up}, {"east", 0, &c.measured_east}};
  // Work-file stems unique per point even when ids differ only in case or punctuation (P1, p1).
  std::vector<std::string> ids;
  for (const auto& p : sim.points) ids.push_back(p.point.id);
  const auto stems = unique_slugs(ids);
  for (const auto& comp : comps) {
    if (comp.index == 0 && !c.measured_east) continue;
    for (std::size_t p = 0; p < sim.points.size(); ++p) {
      const std::string& id = sim.points[p].point.id;
      const insar::PsData* meas = comp.measured->has_value() ? &**comp.measured : nullptr;
      std::size_t mrow = 0;
      bool has_meas = false;
      if (meas)
        if (const auto i = meas->find(id)) mrow = *i, has_meas = true;
      // Offset: mean(simulated - measured) over the measured dates the simulation covers.
      double offset = 0, ss = 0;
      std::size_t n = 0;
      std::vector<double> resid;
      if (has_meas) {
        for (std::size_t d = 0; d < meas->dates.size(); ++d) {
          const double mv = meas->value_mm(mrow, d);
          const auto b = insar::bracket_time(sim.dates, meas->dates[d]);
          if (std::isnan(mv) || !b) continue;
          const double s0 = sim.at(p, b->i0)[comp.index], s1 = sim.at(p, b->i1)[comp.index];
          if (std::isnan(s0) || std::isnan(s1)) continue;
          resid.push_back(((1 - b->w) * s0 + b->w * s1) * 1e3 - mv);
        }
        n = resid.size();
        for (double r : resid) offset += r;
        if (n) offset /= double(n);
        for (double r : resid) ss += (r - offset) * (r - offset);
      }
      const std::string stem = fmt::format("series_{}_{}", comp.name, stems[p]);
      {
        CsvWriter w(c.work_file(stem + "_sim.csv"), {"date", "value_mm"});
        for (std::size_t d = 0; d < sim.dates.size(); ++d) {
          const double v = sim.at(p, d)[comp.index];
          if (!std::isnan(v)) w.date(sim.dates[d]).number(v * 1e3 - offset, 4).end_row();
        }
        w.commit();
      }
      if (has_meas) {
        CsvWriter w(c.work_file(stem + "_meas.csv"), {"date", "value_mm"});
        for (std::size_t d = 0; d < meas->dates.size(); ++d) {
          const double v = meas->value_mm(mrow, d);
          if (!std::isnan(v)) w.date(meas->dates[d]).number(v, 3).end_row();
        }
        w.commit();
      }
      const double rms = n ? std::sqrt(ss / double(n)) : NAN;
      Figure f;
      f.kind = "series";
      f.png = stem + ".png";
      f.title = fmt::format("{}: {} displacement", id, comp.index == 2 ? "vertical" : "east-west");
      f.caption = fmt::format("Simulated {} displacement at PS {}{}{}.", comp.index == 2 ? "vertical" : "east-west", id,
                              has_meas ? fmt::format(" against the InSAR series (simulation shifted by {:.2f} mm; RMS difference "
                                               "{:.2f} mm over {} dates)", -offset, rms, n)
                                 : std::string(""),
                              pressures ? ", with the pool pressures" : "");
      f.json = fmt::format("\"sim\": {}, \"meas\": {}, \"pressure\": {}, \"pressure_label\": {}, \"label\": {}", jwork(stem + "_sim.csv"),
                           has_meas ? jwork(stem + "_meas.csv") : std::string("null"), pressures ? jwork("pressure.csv") : std::string("null"),
                           jstr(plabel), jstr(comp.index == 2 ? "u_z (mm)" : "u_x, east (mm)"));
      c.add(f);
      if (has_meas && n)
        c.headlines.push_back({"InSAR comparison (offset removed)", fmt::format("RMS difference at {} ({})", id, comp.name),
                               fmt::format("{} mm over {} dates", mm(rms), n),
                               comp.index == 2 ? "good match inside the trace; outside, InSAR noise" : ""});
    }
  }
}

}  // namespace ugs::report
