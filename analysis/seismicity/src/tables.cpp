#include "ugs/seismicity/tables.hpp"

#include <algorithm>
#include <set>
#include <stdexcept>

namespace ugs::seismicity {

namespace {
constexpr double kYear = kSecondsPerYear;
constexpr double kKm2 = 1e6;
}  // namespace

std::unique_ptr<CsvWriter> fault_table(const std::string& path, const Forecast& fc, const std::vector<std::string>& comments) {
  auto w = std::make_unique<CsvWriter>(
      path, std::vector<std::string>{"date", "fault", "cfs_change_mean_MPa", "R_over_r", "R_over_r_max", "rate_per_yr", "events_from_start"},
      comments);
  for (std::size_t k = 0; k < fc.dates.size(); ++k)
    for (const auto& f : fc.faults) {
      w->date(fc.dates[k]).text(f.name).number(f.cfs_mean[k] / 1e6).number(f.rate_ratio[k]).number(f.rate_ratio_max[k]);
      w->number(f.rate[k] * kYear).number(f.events[k]).end_row();
    }
  return w;
}

std::unique_ptr<CsvWriter> window_table(const std::string& path, const Forecast& fc, const std::vector<double>& magnitudes,
                                        const std::vector<std::string>& comments) {
  auto w = std::make_unique<CsvWriter>(
      path, std::vector<std::string>{"start", "end", "fault", "magnitude", "expected_events", "p_at_least_one"}, comments);
  std::set<double> all_m(magnitudes.begin(), magnitudes.end());
  for (const auto& f : fc.faults) all_m.insert(f.params.M_c);
  for (std::size_t i = 0; i < fc.windows.size(); ++i) {
    auto row = [&](const std::string& fault, double m, double n) {
      w->date(fc.windows[i].start).date(fc.windows[i].end).text(fault).number(m).number(n).number(probability_at_least_one(n));
      w->end_row();
    };
    for (const auto& f : fc.faults) {
      std::set<double> ms(magnitudes.begin(), magnitudes.end());
      ms.insert(f.params.M_c);
      for (double m : ms) row(f.name, m, events_above(f.window_events[i], f.params, m));
    }
    for (double m : all_m) {
      double n = 0;
      for (const auto& f : fc.faults) n += events_above(f.window_events[i], f.params, m);
      row("all", m, n);
    }
  }
  return w;
}

std::unique_ptr<CsvWriter> pair_table(const std::string& path, const StressHistory& h, const Forecast& fc,
                                      const std::vector<std::string>& comments) {
  auto w = std::make_unique<CsvWriter>(
      path,
      std::vector<std::string>{"date", "fault", "node", "x_m", "y_m", "z_m", "along_strike_m", "down_dip_m", "area_m2", "interpolated",
                               "cfs_change_MPa", "R_over_r", "rate_per_yr_km2", "events_per_km2_from_start"},
      comments);
  for (std::size_t k = 0; k < fc.dates.size(); ++k)
    for (std::size_t f = 0; f < fc.faults.size(); ++f) {
      const auto& ff = fc.faults[f];
      for (std::size_t q = 0; q < ff.pairs.size(); ++q) {
        const PairHistory& p = h.faults[f].pairs[q];
        const PairForecast& pf = ff.pairs[q];
        w->date(fc.dates[k]).text(ff.name).integer(static_cast<std::int64_t>(p.node));
        w->number(p.x[0]).number(p.x[1]).number(p.x[2]).number(p.along_strike).number(p.down_dip).number(p.area);
        w->integer(p.interpolated ? 1 : 0).number(p.dcfs[k] / 1e6).number(pf.rate_ratio[k]);
        w->number(ff.params.background_rate * pf.rate_ratio[k] * kYear * kKm2).number(pf.events_per_m2[k] * kKm2).end_row();
      }
    }
  return w;
}

std::unique_ptr<FieldSeriesWriter> pair_fields(const std::string& h5_path, const StressHistory& h, const Forecast& fc) {
  if (!h.surface) throw std::logic_error("pair_fields: the stress history has no fault surface");
  FieldSeriesOptions o;
  o.cell_types = {ElementType::Triangle};
  auto w = std::make_unique<FieldSeriesWriter>(h5_path, *h.surface, o);
  const std::size_t nn = h.surface->num_nodes();
  for (std::size_t k = 0; k < fc.dates.size(); ++k) {
    std::vector<Field> nf{{"R_over_r", 1, std::vector<double>(nn, 0.0)},
                          {"rate_per_yr_km2", 1, std::vector<double>(nn, 0.0)},
                          {"events_per_km2", 1, std::vector<double>(nn, 0.0)}};
    for (std::size_t f = 0; f < fc.faults.size(); ++f)
      for (std::size_t q = 0; q < fc.faults[f].pairs.size(); ++q) {
        const std::uint32_t n = h.faults[f].pairs[q].surface_node;
        const PairForecast& pf = fc.faults[f].pairs[q];
        nf[0].values[n] = pf.rate_ratio[k];
        nf[1].values[n] = fc.faults[f].params.background_rate * pf.rate_ratio[k] * kYear * kKm2;
        nf[2].values[n] = pf.events_per_m2[k] * kKm2;
      }
    w->add_step(format_iso_date(fc.dates[k]), static_cast<double>(fc.dates[k]), nf);
  }
  return w;
}

}  // namespace ugs::seismicity
