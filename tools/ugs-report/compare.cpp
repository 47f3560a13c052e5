// Comparison of runs (--compare LABEL=FILE): the vertical displacement over the reservoir trace from
// this run and from others on the same mesh, e.g. a reservoir simulator's pressures against the
// schedule-driven flow model (docs/eclipse.md). Changes are taken from the first date the runs share,
// so runs that start at different dates still compare.
#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "report.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/insar/displacement.hpp"
#include "ugs/meshing/submesh.hpp"

namespace ugs::report {

namespace {

struct Run {
  std::string label, path;
};

// LABEL=FILE; InputError naming the option otherwise.
Run parse_run(const std::string& s) {
  const auto eq = s.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == s.size())
    throw InputError("--compare", fmt::format("'{}' is not LABEL=FILE (e.g. \"flow model=solve_flow_top.h5\")", s));
  return {s.substr(0, eq), s.substr(eq + 1)};
}

// Surface nodes inside the trace's polygons (every node when the trace has none).
std::vector<std::size_t> nodes_over_trace(const Context& c, bool& all) {
  std::vector<std::vector<std::array<double, 2>>> rings;
  for (const auto& l : c.trace_lines)
    if (l.size() >= 4 && l.front() == l.back()) rings.push_back(l);
  std::vector<std::size_t> sel;
  for (std::size_t i = 0; i < c.top->points.size(); ++i)
    if (rings.empty() || inside_rings(rings, c.top->points[i][0], c.top->points[i][1])) sel.push_back(i);
  all = rings.empty();
  return sel;
}

struct Change {
  double mean_mm = 0, peak_mm = 0;  // peak: the signed value of largest magnitude
};

Change change_since(const std::vector<double>& u, const std::vector<double>& u0, const std::vector<std::size_t>& nodes) {
  Change ch;
  double sum = 0;
  for (std::size_t i : nodes) {
    const double d = (u[3 * i + 2] - u0[3 * i + 2]) * 1e3;
    sum += d;
    if (std::abs(d) > std::abs(ch.peak_mm)) ch.peak_mm = d;
  }
  ch.mean_mm = sum / static_cast<double>(nodes.size());
  return ch;
}

}  // namespace

void build_comparison(Context& c) {
  if (c.opt.compare.empty()) return;
  if (!c.top) throw InputError("--compare", "no top surface to compare the runs on (give --mesh with bnd:top)");
  std::vector<Run> runs{{"this run", c.surface_results}};
  for (const auto& s : c.opt.compare) runs.push_back(parse_run(s));
  std::set<std::string> labels;
  for (const auto& r : runs)
    if (!labels.insert(r.label).second) throw InputError("--compare", fmt::format("the label '{}' is given twice", r.label));
  bool all = false;
  const auto nodes = nodes_over_trace(c, all);
  if (nodes.empty()) throw InputError(c.opt.trace, "no top-surface node lies inside the trace: nothing to compare");

  // Every run on this run's top surface (InputError when a file is of another mesh), and the dates
  // they all hold.
  std::vector<std::unique_ptr<insar::SurfaceDisplacement>> disp;
  for (const auto& r : runs) disp.push_back(std::make_unique<insar::SurfaceDisplacement>(r.path, *c.top, ""));
  auto sorted_times = [](const insar::SurfaceDisplacement& d) {
    std::vector<std::int64_t> t = d.times();
    std::sort(t.begin(), t.end());
    return t;
  };
  std::vector<std::int64_t> common = sorted_times(*disp.front());
  for (const auto& d : disp) {
    const auto t = sorted_times(*d);
    std::vector<std::int64_t> keep;
    std::set_intersection(common.begin(), common.end(), t.begin(), t.end(), std::back_inserter(keep));
    common = std::move(keep);
  }
  if (!c.opt.compare_since.empty()) {
    const auto since = parse_iso_date(c.opt.compare_since);
    if (!since) throw InputError("--compare-since", fmt::format("'{}' is not a date (YYYY-MM-DD)", c.opt.compare_since));
    if (!std::binary_search(common.begin(), common.end(), *since))
      throw InputError("--compare-since", fmt::format("{} is not a date every compared run holds", c.opt.compare_since));
    common.erase(common.begin(), std::lower_bound(common.begin(), common.end(), *since));
  }
  if (common.size() < 2)
    throw InputError(runs.back().path, fmt::format("shares {} dates with {}{} (--compare needs at least two)", common.size(),
                                                   c.surface_results, c.opt.compare_since.empty() ? "" : " from --compare-since on"));
  auto step_of = [](const insar::SurfaceDisplacement& d, std::int64_t t) {
    return static_cast<std::size_t>(std::find(d.times().begin(), d.times().end(), t) - d.times().begin());
  };

  // The table people read and plots.py draws: one row per run and date.
  const std::string csv = "comparison.csv";
  std::vector<std::vector<Change>> ch(runs.size(), std::vector<Change>(common.size()));
  {
    CsvWriter w(c.out + "/" + csv, {"run", "date", "uz_mean_mm", "uz_peak_mm"});
    for (std::size_t r = 0; r < runs.size(); ++r) {
      auto& d = *disp[r];
      const std::vector<double> u0 = d.at_step(step_of(d, common.front()));
      for (std::size_t k = 0; k < common.size(); ++k) {
        ch[r][k] = change_since(d.at_step(step_of(d, common[k])), u0, nodes);
        w.text(runs[r].label).date(common[k]).number(ch[r][k].mean_mm, 4).number(ch[r][k].peak_mm, 4).end_row();
      }
    }
    w.commit();
  }
  c.written.push_back(csv);

  const std::string where = all ? fmt::format("the {} top-surface nodes", nodes.size())
                                : fmt::format("the {} top-surface nodes inside the trace", nodes.size());
  Figure f;
  f.kind = "compare";
  f.png = "comparison.png";
  f.title = "Vertical displacement: " + [&] {
    std::string s;
    for (std::size_t r = 0; r < runs.size(); ++r) s += (r ? " vs " : "") + runs[r].label;
    return s;
  }();
  f.caption = fmt::format("Change of the vertical displacement since {} over {}: mean (solid) and the value of largest "
                          "magnitude (dashed) of each run, at the {} dates they share; the numbers are in {}.",
                          format_iso_date(common.front()), where, common.size(), csv);
  f.json = fmt::format("\"data\": {}, \"label\": {}", jstr(csv), jstr("u_z change (mm)"));
  c.add(f);

  // Headlines: how far each run is from this one, and their ratio where the swing is clear.
  for (std::size_t r = 1; r < runs.size(); ++r) {
    double worst = 0, swing = 0;
    std::int64_t at = common.front();
    for (std::size_t k = 0; k < common.size(); ++k) {
      const double diff = ch[0][k].mean_mm - ch[r][k].mean_mm;
      if (std::abs(diff) > std::abs(worst)) worst = diff, at = common[k];
      swing = std::max(swing, std::abs(ch[r][k].mean_mm));
    }
    c.headlines.push_back({"Run comparison", fmt::format("mean u_z change, this run minus '{}' (largest)", runs[r].label),
                           fmt::format("{} mm on {}", mm(worst), format_iso_date(at)), ""});
    double lo = INFINITY, hi = -INFINITY;
    for (std::size_t k = 0; k < common.size(); ++k)
      if (std::abs(ch[r][k].mean_mm) > 0.1 * swing && swing > 0) {
        const double ratio = ch[0][k].mean_mm / ch[r][k].mean_mm;
        lo = std::min(lo, ratio), hi = std::max(hi, ratio);
      }
    if (lo <= hi)
      c.headlines.push_back({"Run comparison", fmt::format("mean u_z change, this run / '{}'", runs[r].label),
                             fmt::format("{:.2f} .. {:.2f} (dates with more than 10 % of its largest change)", lo, hi), ""});
  }
}

}  // namespace ugs::report
