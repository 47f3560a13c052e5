// The seismicity forecast's pictures, from ugs-seismicity's tables (docs/seismicity.md): R/r over
// time on each fault (area-weighted and its largest value over the node pairs) beside the pool
// pressures, as chi_max_series.png; a map of the expected event density on each fault plane over a
// window (events >= M_c per km2, the difference of the per-pair table's cumulative density at the
// window's ends), as the chi maps; and headline rows: the expected events and P(at least one event
// >= M) over each window, all faults together and per fault.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "report.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/insar/npy.hpp"

namespace ugs::report {

namespace fs = std::filesystem;

namespace {

std::string stem_of(const std::string& table) {
  return table.size() > 4 && table.substr(table.size() - 4) == ".csv" ? table.substr(0, table.size() - 4) : table;
}

void rate_series(Context& c, const CsvTable& t) {
  const auto cd = t.column("date"), cf = t.column("fault"), cr = t.column("R_over_r"), cm = t.column("R_over_r_max");
  CsvWriter w(c.work_file("seismicity_rate.csv"), {"fault", "date", "value", "max"});
  std::map<std::string, std::pair<double, std::string>> peak;
  std::vector<std::string> order;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const std::string fault(t.text(r, cf)), date(t.text(r, cd));
    (void)t.date(r, cd);
    const double v = t.number(r, cr), m = t.number(r, cm);
    if (!(v > 0) || !(m > 0)) throw InputError(t.where(r), fmt::format("R/r {} / {} (expected positive rates)", v, m));
    w.text(fault).text(date).number(v).number(m).end_row();
    auto& p = peak[fault];
    if (p.second.empty()) order.push_back(fault);
    if (p.second.empty() || v > p.first) p = {v, date};
  }
  w.commit();
  if (t.rows() == 0) throw InputError(t.name(), "has no rows");
  for (const auto& fault : order)
    c.headlines.push_back({"seismicity, over the run", fmt::format("largest area-weighted R/r on {}", fault),
                           fmt::format("{:.3g} ({})", peak[fault].first, peak[fault].second), "not in the thesis"});
  std::string plabel;
  const bool pressures = write_pressures(c, plabel);
  Figure fig;
  fig.kind = "rate_series";
  fig.png = "seismicity_rate_series.png";
  fig.title = "Seismicity rate over the background rate (R/r) on each fault";
  fig.caption = fmt::format("Dieterich's rate-and-state seismicity rate R over the background rate r on each fault ({}): "
                            "area-weighted over its node pairs (solid) and the largest over the pairs (dashed), logarithmic "
                            "scale{}.", t.name(), pressures ? ", with the pool pressures" : "");
  fig.json = fmt::format("\"csv\": {}, \"pressure\": {}, \"pressure_label\": {}", jwork("seismicity_rate.csv"),
                         pressures ? jwork("pressure.csv") : std::string("null"), jstr(plabel));
  c.add(fig);
}

void window_headlines(Context& c, const CsvTable& t, std::string& first_window) {
  const auto cs = t.column("start"), ce = t.column("end"), cf = t.column("fault"), cm = t.column("magnitude");
  const auto cn = t.column("expected_events"), cp = t.column("p_at_least_one");
  std::map<std::string, double> lowest_m;  // fault -> its lowest magnitude (M_c) in the window
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const std::string window = fmt::format("{} to {}", t.text(r, cs), t.text(r, ce)), fault(t.text(r, cf));
    if (first_window.empty()) first_window = fmt::format("{}/{}", t.text(r, cs), t.text(r, ce));
    const double m = t.number(r, cm), n = t.number(r, cn), p = t.number(r, cp);
    const bool all = fault == "all";
    const auto [it, fresh] = lowest_m.try_emplace(window + "|" + fault, m);
    if (!all && !fresh) continue;  // per fault: only its M_c row; all faults: every magnitude
    c.headlines.push_back({"seismicity, " + window,
                           fmt::format("expected events M ≥ {}, {}", t.text(r, cm), all ? "all faults" : fault),
                           fmt::format("{:.3g} (P(at least one) {})", n, p > 0.999 ? std::string("> 0.999") : fmt::format("{:.3g}", p)),
                           all ? "no induced seismicity (χ about 0.1)" : ""});
  }
}

void density_map(Context& c, const CsvTable& t, const std::string& window) {
  const auto slash = std::min(window.find('/'), window.size());
  const auto start = parse_iso_date(window.substr(0, slash));
  const auto end = parse_iso_date(window.substr(std::min(slash + 1, window.size())));
  if (slash == window.size() || !start || !end || !(*end > *start))
    throw InputError("seismicity window", fmt::format("'{}' is not START/END with START before END", window));
  const std::int64_t a = start.value_or(0), b = end.value_or(0);
  const std::string from = format_iso_date(a), to = format_iso_date(b);
  const auto cd = t.column("date"), cf = t.column("fault"), cn = t.column("node"), cx = t.column("x_m"), cy = t.column("y_m");
  const auto cz = t.column("z_m"), cs = t.column("along_strike_m"), ce = t.column("events_per_km2_from_start");
  struct Plane {
    std::string name;
    std::map<std::string, std::size_t> index;  // node -> pair
    std::vector<double> x, y, s, z, at_a, at_b;
    std::vector<char> have_a, have_b;
  };
  std::vector<Plane> planes;
  std::map<std::string, std::size_t> plane_of;
  bool found_a = false, found_b = false;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const std::int64_t d = t.date(r, cd);
    if (d != a && d != b) continue;
    const std::string fault(t.text(r, cf)), node(t.text(r, cn));
    auto [pit, fresh] = plane_of.try_emplace(fault, planes.size());
    if (fresh) planes.push_back({fault, {}, {}, {}, {}, {}, {}, {}, {}, {}});
    Plane& p = planes[pit->second];
    auto [nit, new_node] = p.index.try_emplace(node, p.x.size());
    if (new_node) {
      p.x.push_back(t.number(r, cx)), p.y.push_back(t.number(r, cy)), p.s.push_back(t.number(r, cs)), p.z.push_back(t.number(r, cz));
      p.at_a.push_back(0), p.at_b.push_back(0), p.have_a.push_back(0), p.have_b.push_back(0);
    }
    const std::size_t q = nit->second;
    (d == a ? p.at_a : p.at_b)[q] = t.number(r, ce);
    (d == a ? p.have_a : p.have_b)[q] = 1;
    (d == a ? found_a : found_b) = true;
  }
  if (!found_a || !found_b) {
    c.notes.push_back(fmt::format("{}: the window {} does not start and end on dates of the per-pair table: no event density map",
                                  t.name(), window));
    return;
  }
  const PoolNodes pools = pool_nodes(c);
  std::vector<std::string> names;
  for (const auto& p : planes) names.push_back(p.name);
  const auto slugs = unique_slugs(names);
  std::string panels;
  double vmax = 0;
  CsvWriter w(c.work_file("seismicity_density.csv"), {"fault", "node", "along_strike_m", "z_m", "events_per_km2"});
  for (std::size_t k = 0; k < planes.size(); ++k) {
    const Plane& p = planes[k];
    std::vector<double> v(p.x.size()), sz;
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!p.have_a[i] || !p.have_b[i])
        throw InputError(t.name(), fmt::format("fault {}: a node pair is missing at one end of the window {}", p.name, window));
      v[i] = p.at_b[i] - p.at_a[i];
      sz.insert(sz.end(), {p.s[i], p.z[i]});
    }
    for (const auto& [node, i] : p.index) w.text(p.name).text(node).number(p.s[i]).number(p.z[i]).number(v[i]).end_row();
    if (v.size() < 3) {
      c.notes.push_back(fmt::format("{}: fault {} has {} node pairs, too few for a map", t.name(), p.name, v.size()));
      continue;
    }
    const std::string stem = fmt::format("seismicity_density_{}", slugs[k]);
    insar::write_npy(c.work_file(stem + "_nodes.npy"), sz, {v.size(), 2});
    insar::write_npy(c.work_file(stem + ".npy"), v, {v.size()});
    const auto [sx, sy, s0] = strike_of(p.x, p.y, p.s);
    const std::string outline = write_pool_outlines(c, pools, fmt::format("seismicity_pools_on_{}.csv", slugs[k]), sx, sy, s0);
    const double top = *std::max_element(v.begin(), v.end());
    vmax = std::max(vmax, top);
    panels += fmt::format("{}{{\"name\": {}, \"nodes\": {}, \"values\": {}, \"max\": {}, \"pools\": {}, \"title\": {}}}",
                          panels.empty() ? "" : ", ", jstr(p.name), jwork(stem + "_nodes.npy"), jwork(stem + ".npy"), top, outline,
                          jstr(fmt::format("{}: up to {:.3g} events per km²", p.name, top)));
  }
  w.commit();
  if (panels.empty()) return;
  Figure f;
  f.kind = "faults";
  f.png = "seismicity_density.png";
  f.title = fmt::format("Expected events ≥ M_c per km², {} to {}", from, to);
  f.caption = fmt::format("The expected number of events of magnitude M_c and above per km² of fault over {} to {} (rate-and-state "
                          "forecast, docs/seismicity.md), on each fault in its own plane (distance along strike and elevation; "
                          "linear between the node pairs{}); work/seismicity_density.csv.", from, to,
                          pools.empty() ? "" : "; the pools' outline projected on the fault's plane");
  f.json = fmt::format("\"panels\": [{}], \"vmax\": {}, \"label\": {}", panels, std::max(vmax, 1e-12),
                       jstr("expected events ≥ M_c per km²"));
  c.add(f);
}

}  // namespace

void build_seismicity(Context& c) {
  if (c.opt.seismicity.empty()) return;
  const std::string stem = stem_of(c.opt.seismicity);
  rate_series(c, CsvTable::read(c.opt.seismicity));
  std::string window = c.opt.seismicity_window;
  if (fs::exists(stem + "_windows.csv")) {
    std::string first;
    window_headlines(c, CsvTable::read(stem + "_windows.csv"), first);
    if (window.empty()) window = first;
  } else {
    c.notes.push_back(fmt::format("no {}_windows.csv beside {}: no expected events in the headlines", stem, c.opt.seismicity));
  }
  if (window.empty()) {
    c.notes.push_back("no forecast window (--seismicity-window, or a windows table beside the seismicity table): no event density map");
  } else if (fs::exists(stem + "_pairs.csv")) {
    density_map(c, CsvTable::read(stem + "_pairs.csv"), window);
  } else {
    c.notes.push_back(fmt::format("no {}_pairs.csv beside {}: no event density map", stem, c.opt.seismicity));
  }
}

}  // namespace ugs::report
