// The ensemble's pictures, from an ugs-ensemble output folder (docs/ensemble.md): a tornado chart
// of the sensitivity indices (sobol.csv: S1 and ST with their intervals; morris.csv: mu* and sigma)
// and fan charts of the PS series (ps_series.csv: the P10-P90 band and P50 of the members against
// the InSAR series), with the exceedance probabilities of chi and the seismicity metrics' quantiles
// (P(event), expected events) as headlines, and maps of P(chi >= 1)
// and P(chi >= 0.8) on each fault plane (chi_exceedance_pairs.csv, the rows over all dates), drawn
// as ugs-report's single-run chi maps. The CSVs are copied to the work folder as they are: the
// figures plot exactly the files people read.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "report.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/insar/npy.hpp"

namespace ugs::report {

namespace fs = std::filesystem;

namespace {

void copy_table(const CsvTable& t, const std::string& to) {
  CsvWriter w(to, t.columns());
  for (std::size_t r = 0; r < t.rows(); ++r) {
    for (std::size_t k = 0; k < t.columns().size(); ++k) w.text(t.text(r, k));
    w.end_row();
  }
  w.commit();
}

// Maps of P(chi >= 1) and P(chi >= 0.8) on each fault plane: the rows of chi_exceedance_pairs.csv
// over all dates ("max"), copied as the CSV of what is drawn.
void exceedance_maps(Context& c, const CsvTable& t) {
  const auto cf = t.column("fault"), cd = t.column("date"), cx = t.column("x_m"), cy = t.column("y_m"), cz = t.column("z_m");
  const auto cs = t.column("along_strike_m"), c8 = t.column("p_chi_ge_0.8"), c1 = t.column("p_chi_ge_1");
  struct Plane {
    std::string name;
    std::vector<double> x, y, s, z, p8, p1;
  };
  std::vector<Plane> planes;
  CsvWriter w(c.work_file("ensemble_chi_exceedance.csv"), t.columns());
  for (std::size_t r = 0; r < t.rows(); ++r) {
    if (t.text(r, cd) != "max") continue;
    for (std::size_t k = 0; k < t.columns().size(); ++k) w.text(t.text(r, k));
    w.end_row();
    if (planes.empty() || planes.back().name != t.text(r, cf)) planes.push_back({std::string(t.text(r, cf)), {}, {}, {}, {}, {}, {}});
    Plane& p = planes.back();
    p.x.push_back(t.number(r, cx)), p.y.push_back(t.number(r, cy)), p.s.push_back(t.number(r, cs)), p.z.push_back(t.number(r, cz));
    p.p8.push_back(t.number(r, c8)), p.p1.push_back(t.number(r, c1));
  }
  w.commit();
  if (planes.empty()) return;
  const PoolNodes pools = pool_nodes(c);
  std::vector<std::string> names;
  for (const auto& p : planes) names.push_back(p.name);
  const auto slugs = unique_slugs(names);
  for (const auto& [tag, threshold] : {std::pair{"1", 1.0}, std::pair{"0.8", 0.8}}) {
    std::string panels;
    for (std::size_t k = 0; k < planes.size(); ++k) {
      const Plane& p = planes[k];
      if (p.s.size() < 3) {
        c.notes.push_back(fmt::format("chi_exceedance_pairs.csv: fault {} has {} node pairs, too few for a map", p.name, p.s.size()));
        continue;
      }
      const std::string stem = fmt::format("ensemble_p_chi_ge_{}_{}", tag, slugs[k]);
      std::vector<double> sz;
      for (std::size_t i = 0; i < p.s.size(); ++i) sz.insert(sz.end(), {p.s[i], p.z[i]});
      const auto& v = threshold == 1.0 ? p.p1 : p.p8;
      insar::write_npy(c.work_file(stem + "_nodes.npy"), sz, {p.s.size(), 2});
      insar::write_npy(c.work_file(stem + ".npy"), v, {v.size()});
      const auto [sx, sy, s0] = strike_of(p.x, p.y, p.s);
      const std::string outline = write_pool_outlines(c, pools, fmt::format("ensemble_pools_on_{}.csv", slugs[k]), sx, sy, s0);
      const double top = *std::max_element(v.begin(), v.end());
      panels += fmt::format("{}{{\"name\": {}, \"nodes\": {}, \"values\": {}, \"max\": {}, \"pools\": {}, \"title\": {}}}",
                            panels.empty() ? "" : ", ", jstr(p.name), jwork(stem + "_nodes.npy"), jwork(stem + ".npy"), top, outline,
                            jstr(fmt::format("{}: largest P(χ ≥ {}) {:.2f}", p.name, tag, top)));
    }
    if (panels.empty()) continue;
    Figure f;
    f.kind = "faults";
    f.png = fmt::format("ensemble_p_chi_ge_{}.png", tag);
    f.title = fmt::format("Probability that χ reaches {} at some date, over the ensemble", tag);
    f.caption = fmt::format("The fraction of the members whose χ reaches {} at the node pair at any output date, on each fault in "
                            "its own plane (distance along strike and elevation; linear between the pairs{}); "
                            "ensemble_chi_exceedance.csv, the rows 'max' of chi_exceedance_pairs.csv.", tag,
                            pools.empty() ? "" : "; the pools' outline projected on the fault's plane");
    f.json = fmt::format("\"panels\": [{}], \"vmax\": 1, \"label\": {}", panels, jstr(fmt::format("P(χ ≥ {})", tag)));
    c.add(f);
  }
}

// The seismicity metrics' spread over the members (quantiles.csv, docs/ensemble.md):
// seismic_events.<fault>.<window>, p_event.<fault>.<window> and p_event_M<m>.<fault>.<window> as
// "P50 (P10 - P90)". P(event >= M_c) for every fault, the counts and the other magnitudes for all faults.
void seismic_headlines(Context& c, const CsvTable& q) {
  const auto cm = q.column("metric"), cn = q.column("n"), c10 = q.column("p10"), c50 = q.column("p50"), c90 = q.column("p90");
  for (std::size_t r = 0; r < q.rows(); ++r) {
    const std::string metric(q.text(r, cm));
    if (q.text(r, c50).empty()) continue;  // no successful member
    const auto first = metric.find('.'), last = metric.rfind('.');
    if (first == std::string::npos || last <= first) continue;
    const std::string kind = metric.substr(0, first), fault = metric.substr(first + 1, last - first - 1), window = metric.substr(last + 1);
    std::string what;
    if (kind == "seismic_events" && fault == "all") what = "expected events M ≥ M_c, all faults";
    else if (kind == "p_event") what = fmt::format("P(event M ≥ M_c) on {}", fault == "all" ? "all faults" : fault);
    else if (kind.rfind("p_event_M", 0) == 0 && fault == "all") what = fmt::format("P(event M ≥ {}), all faults", kind.substr(9));
    else continue;
    c.headlines.push_back({fmt::format("ensemble, seismicity window {}", window),
                           fmt::format("{}: P50 (P10 - P90) of {} members", what, q.text(r, cn)),
                           fmt::format("{:.3g} ({:.3g} - {:.3g})", q.number(r, c50), q.number(r, c10), q.number(r, c90)), ""});
  }
}

}  // namespace

void build_ensemble(Context& c) {
  if (c.opt.ensemble.empty()) return;
  const fs::path dir(c.opt.ensemble);
  const CsvTable members = CsvTable::read((dir / "members.csv").string());
  std::size_t ok = 0;
  for (std::size_t r = 0; r < members.rows(); ++r) ok += members.text(r, members.column("status")) == "ok";
  c.headlines.push_back({"ensemble", "members in the statistics", fmt::format("{} of {}", ok, members.rows()), ""});
  if (fs::exists(dir / "exceedance.csv")) {
    const CsvTable ex = CsvTable::read((dir / "exceedance.csv").string());
    for (std::size_t r = 0; r < ex.rows(); ++r)
      c.headlines.push_back({"ensemble", fmt::format("P(chi >= 0.8), P(chi >= 1) on {}", ex.text(r, ex.column("fault"))),
                             fmt::format("{:.2f}, {:.2f}", ex.number(r, ex.column("p_chi_ge_0.8")), ex.number(r, ex.column("p_chi_ge_1"))),
                             ""});
  }
  if (fs::exists(dir / "quantiles.csv")) seismic_headlines(c, CsvTable::read((dir / "quantiles.csv").string()));
  if (fs::exists(dir / "chi_exceedance_pairs.csv")) exceedance_maps(c, CsvTable::read((dir / "chi_exceedance_pairs.csv").string()));
  for (const char* method : {"sobol", "morris"}) {
    const fs::path p = dir / (std::string(method) + ".csv");
    if (!fs::exists(p)) continue;
    const CsvTable t = CsvTable::read(p.string());
    if (t.rows() == 0) continue;
    copy_table(t, c.work_file(std::string("ensemble_") + method + ".csv"));
    Figure f;
    f.kind = "tornado";
    f.png = std::string("ensemble_tornado_") + method + ".png";
    f.title = std::string(method) == "sobol" ? "Which parameter decides it: Sobol' indices" : "Which parameter decides it: Morris screening";
    f.caption = std::string(method) == "sobol"
                    ? "First-order (S1) and total (ST) Sobol' indices of each metric with their 95 % intervals (sobol.csv)."
                    : "Morris mean absolute elementary effect mu* and its spread sigma of each metric (morris.csv).";
    f.json = fmt::format("\"csv\": {}, \"method\": {}", jwork(std::string("ensemble_") + method + ".csv"), jstr(method));
    c.add(f);
  }
  if (fs::exists(dir / "ps_series.csv")) {
    const CsvTable t = CsvTable::read((dir / "ps_series.csv").string());
    if (t.rows() > 0) {
      copy_table(t, c.work_file("ensemble_ps_series.csv"));
      Figure f;
      f.kind = "fan";
      f.png = "ensemble_fan_ps.png";
      f.title = "PS series: the ensemble's P10-P90 band and P50 against InSAR";
      f.caption = "Simulated vertical displacement at the PS points (relative to the first PS date; band P10-P90, line "
                  "P50) with the measured series shifted to the same zero (ps_series.csv).";
      f.json = fmt::format("\"csv\": {}", jwork("ensemble_ps_series.csv"));
      c.add(f);
    }
  }
}

}  // namespace ugs::report
