// Fault safety (thesis 4.3.4, figures 4.43-4.44): chi = |tau| / (c - sigma_n tan(phi)) on each
// fault for the minimum and maximum pressure scenarios, each fault drawn in its own plane (along
// strike, depth); and the calibration's misfit profile.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "report.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/insar/displacement.hpp"
#include "ugs/insar/fault_results.hpp"
#include "ugs/insar/npy.hpp"

namespace ugs::report {

namespace {

// The pool pressure at t from its schedule (linear between rows); NaN outside.
double schedule_value(const CsvTable& t, std::size_t cd, std::size_t cv, std::int64_t when) {
  for (std::size_t r = 0; r + 1 < t.rows(); ++r) {
    const auto a = t.date(r, cd), b = t.date(r + 1, cd);
    if (when >= a && when <= b) {
      const double w = b > a ? double(when - a) / double(b - a) : 0.0;
      return (1 - w) * t.number(r, cv) + w * t.number(r + 1, cv);
    }
  }
  return NAN;
}

}  // namespace

void build_faults(Context& c) {
  if (c.opt.faults.empty()) {
    c.notes.push_back("no fault results (--faults): the chi pictures (figures 4.43-4.44) need the output of the faulted "
                      "solver and were skipped");
    return;
  }
  const FieldSeriesReader fr(c.opt.faults);
  const auto& steps = fr.steps();
  if (steps.empty()) throw InputError(c.opt.faults, "has no steps");
  std::vector<std::int64_t> times;
  for (const auto& s : steps) times.push_back(insar::step_time(s));
  std::size_t smin = 0, smax = steps.size() - 1;
  std::string how = "first and last dates of the fault results";
  if (!c.opt.fault_dates.empty()) {
    const auto comma = c.opt.fault_dates.find(',');
    if (comma == std::string::npos) throw InputError("--fault-dates", "expected MIN_DATE,MAX_DATE");
    smin = fr.step(c.opt.fault_dates.substr(0, comma));
    smax = fr.step(c.opt.fault_dates.substr(comma + 1));
    how = "dates given with --fault-dates";
  } else if (c.cs && !c.cs->pools.empty() && steps.size() > 1) {
    const PoolSpec* pool = &c.cs->pools.back();
    for (const auto& p : c.cs->pools)
      if (p.name == (c.opt.stress_pool.empty() ? "Pool C" : c.opt.stress_pool)) pool = &p;
    const CsvTable t = CsvTable::read(pool->schedule);
    const auto cd = t.column("date"), cv = t.column(pool->column);
    double lo = 1e300, hi = -1e300;
    for (std::size_t i = 0; i < times.size(); ++i) {
      const double p = schedule_value(t, cd, cv, times[i]);
      if (std::isnan(p)) continue;
      if (p < lo) lo = p, smin = i;
      if (p > hi) hi = p, smax = i;
    }
    how = fmt::format("dates of the lowest and highest {} pressure among the fault results' dates", pool->name);
  }
  const Mesh* mesh = c.mesh ? &*c.mesh : nullptr;
  struct Scenario {
    const char* name;
    std::size_t step;
  };
  for (const Scenario sc : {Scenario{"minimum", smin}, Scenario{"maximum", smax}}) {
    const auto faults = insar::read_fault_chi(fr, sc.step, mesh, c.opt.fault_field);
    std::string panels;
    double vmax = 0;
    for (const auto& f : faults) {
      const std::string stem = fmt::format("chi_{}_{}", sc.name, slug(f.name));
      std::vector<double> sz;
      for (const auto& q : f.sz) sz.insert(sz.end(), q.begin(), q.end());
      insar::write_npy(c.work_file(stem + "_sz.npy"), sz, {f.sz.size(), 3, 2});
      insar::write_npy(c.work_file(stem + ".npy"), f.chi, {f.chi.size()});
      panels += fmt::format("{}{{\"name\": {}, \"sz\": {}, \"values\": {}}}", panels.empty() ? "" : ", ", jstr(f.name),
                            jwork(stem + "_sz.npy"), jwork(stem + ".npy"));
      vmax = std::max(vmax, f.max_chi);
      c.headlines.push_back({fmt::format("faults, {} pressure ({})", sc.name, steps[sc.step].date),
                             fmt::format("maximum χ on {}", f.name), fmt::format("{:.3f}", f.max_chi),
                             "about 0.1 on the regional faults"});
    }
    Figure fig;
    fig.kind = "faults";
    fig.png = fmt::format("chi_{}_pressure.png", sc.name);
    fig.title = fmt::format("Safety factor χ, {} pressure ({})", sc.name, steps[sc.step].date);
    fig.caption = fmt::format("χ = |τ| / (c − σ_n tan φ) on the faults for the {} pressure scenario ({}; {}), each fault "
                              "in its own plane: distance along strike and elevation.", sc.name, steps[sc.step].date, how);
    fig.json = fmt::format("\"panels\": [{}], \"vmax\": {}, \"label\": \"χ\"", panels, std::max(vmax, 1e-3));
    c.add(fig);
  }
}

void build_calibration(Context& c) {
  if (c.opt.calibration.empty()) return;
  const std::string dir = c.opt.calibration;
  const CsvTable prof = CsvTable::read(dir + "/profile.csv");
  const CsvTable pars = CsvTable::read(dir + "/parameters.csv");
  std::string names;
  for (std::size_t r = 0; r < pars.rows(); ++r) {
    const std::string n(pars.text(r, pars.column("parameter")));
    names += fmt::format("{}{}", names.empty() ? "" : ", ", jstr(n));
    c.headlines.push_back({"calibration", n,
                           fmt::format("{:.4g} (bounds {} .. {}; case value {})", pars.number(r, pars.column("best")),
                                       pars.text(r, pars.column("lower")), pars.text(r, pars.column("upper")),
                                       pars.text(r, pars.column("case_value"))),
                           n.find("c_R") != std::string::npos ? "c_R = 3 in Pool C, 5 in Pool A and the interlayer" : ""});
  }
  double best = 1e300;
  for (double v : prof.numbers("rms_mm")) best = std::min(best, v);
  c.headlines.push_back({"calibration", "RMS misfit of the best evaluation", fmt::format("{:.3f} mm over {} evaluations", best, prof.rows()), ""});
  {
    CsvWriter w(c.work_file("profile.csv"), prof.columns());
    for (std::size_t r = 0; r < prof.rows(); ++r) {
      for (std::size_t k = 0; k < prof.columns().size(); ++k) w.text(prof.text(r, k));
      w.end_row();
    }
    w.commit();
  }
  Figure f;
  f.kind = "profile";
  f.png = "calibration_profile.png";
  f.title = "Calibration: RMS misfit of every evaluation";
  f.caption = "RMS misfit (offset-free, mm) of every solver run of the calibration against each parameter; the best run is marked.";
  f.json = fmt::format("\"csv\": {}, \"params\": [{}]", jwork("profile.csv"), names);
  c.add(f);
}

}  // namespace ugs::report
