// The safety answer as headlines (docs/caprock.md, docs/fault-mechanics.md "Maximum safe storage
// pressure"): from ugs-solve's safe-scale table, the maximum safe scale of the swing, what limits it
// (a fault at chi = 1, caprock tensile or shear failure) and, per pool, the largest pressure of its
// schedule at that scale in MPa with its excess over the pool's initial pressure; from the caprock
// table, the seals' smallest tensile and shear margins over the run and when.
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "report.hpp"
#include "ugs/formats/csv.hpp"

namespace ugs::report {

namespace {

// A pool's pressure schedule in MPa: dates and values (p_norm times the reference pressure).
struct Schedule {
  std::vector<std::int64_t> t;
  std::vector<double> p;
  double at(std::int64_t when) const {
    if (when <= t.front()) return p.front();
    if (when >= t.back()) return p.back();
    const auto k = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), when) - t.begin());
    const double w = static_cast<double>(when - t[k - 1]) / static_cast<double>(t[k] - t[k - 1]);
    return p[k - 1] + w * (p[k] - p[k - 1]);
  }
};

Schedule schedule_MPa(const PoolSpec& pool) {
  const CsvTable t = CsvTable::read(pool.schedule);
  const auto cd = t.column("date"), cv = t.column(pool.column);
  const bool normalized = pool.column == "p_norm";
  if (normalized && !pool.reference_pressure_Pa)
    throw InputError(pool.where, fmt::format("pool '{}': p_norm schedule without reference_pressure_MPa", pool.name));
  Schedule s;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    s.t.push_back(t.date(r, cd));
    s.p.push_back(normalized ? t.number(r, cv) * *pool.reference_pressure_Pa * 1e-6 : t.number(r, cv));
  }
  if (s.t.empty()) throw InputError(pool.schedule, "has no rows");
  return s;
}

struct Search {
  bool tried = true;  // false: the table has no trial (an older ugs-solve, something failed before the reference date)
  bool found = false;
  bool any_safe = false;  // some trial below the critical scale was safe
  double safe = 0, critical = std::numeric_limits<double>::infinity();
  std::string limiter, who, date;
  double x = 0, y = 0, z = 0;  // where the critical trial fails first
  std::string seal_margins;  // "tensile 4.37 MPa, shear 3.96 MPa" at the safe scale (tables with seals)
};

Search read_search(const std::string& path) {
  const CsvTable t = CsvTable::read(path);
  const auto cs = t.column("scale"), cc = t.column("critical"), cf = t.column("fault"), cd = t.column("date");
  const auto cl = t.find_column("limiter"), cseal = t.find_column("seal");
  Search s;
  s.tried = t.rows() > 0;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    if (t.integer(r, cc) == 0 || t.number(r, cs) >= s.critical) continue;
    s.found = true;
    s.critical = t.number(r, cs);
    s.limiter = cl ? std::string(t.text(r, *cl)) : std::string("fault chi = 1");  // tables from before the seals
    if (s.limiter.empty()) s.limiter = "Newton failed";
    s.who = s.limiter == "fault chi = 1" || !cseal ? std::string(t.text(r, cf)) : std::string(t.text(r, *cseal));
    s.date = std::string(t.text(r, cd));
    s.x = t.number(r, t.column("x_m")), s.y = t.number(r, t.column("y_m")), s.z = t.number(r, t.column("z_m"));
    const auto cn = t.find_column("note");
    if (cn && t.text(r, *cn).find("before or at the reference date") != std::string_view::npos)
      s.date += " (before or at the reference date)";
  }
  std::size_t safe_row = t.rows();
  for (std::size_t r = 0; r < t.rows(); ++r)
    if (t.integer(r, cc) == 0 && t.number(r, cs) < s.critical && (safe_row == t.rows() || t.number(r, cs) > s.safe))
      s.safe = t.number(r, cs), safe_row = r, s.any_safe = true;
  const auto ct = t.find_column("min_tensile_margin_MPa"), csh = t.find_column("min_shear_margin_MPa");
  if (safe_row < t.rows() && ct && csh && !t.text(safe_row, *ct).empty())
    s.seal_margins = fmt::format("tensile {:.2f} MPa, shear {:.2f} MPa", t.number(safe_row, *ct), t.number(safe_row, *csh));
  return s;
}

// Plan distance from (x, y) to the nearest segment of the reservoir trace.
double distance_to_trace(const std::vector<std::vector<std::array<double, 2>>>& lines, double x, double y) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& l : lines)
    for (std::size_t k = 0; k + 1 < l.size(); ++k) {
      const double ax = l[k][0], ay = l[k][1], dx = l[k + 1][0] - ax, dy = l[k + 1][1] - ay;
      const double len2 = dx * dx + dy * dy;
      const double w = len2 > 0 ? std::clamp(((x - ax) * dx + (y - ay) * dy) / len2, 0.0, 1.0) : 0.0;
      best = std::min(best, std::hypot(x - ax - w * dx, y - ay - w * dy));
    }
  return best;
}

// Where a fault decides the safe scale: a fault patch at the edge of a depleted or pressurized
// reservoir sits where the stress change concentrates (the fault meets the reservoir's boundary),
// and chi there grows as the mesh is refined (docs/fault-convergence.md): the headline says so.
void corner_headline(Context& c, const Search& s) {
  const double d = distance_to_trace(c.trace_lines, s.x, s.y);
  if (!std::isfinite(d)) return;
  const bool at_edge = d <= c.opt.edge_distance;
  c.headlines.push_back(
      {"safety", "where it is decided",
       fmt::format("fault {} at ({:.0f}, {:.0f}, {:.0f}), {:.0f} m from the reservoir trace{}", s.who, s.x, s.y, s.z, d,
                   at_edge ? fmt::format(" (within {:.0f} m): at the reservoir's edge, where chi concentrates and grows as the "
                                         "mesh is refined; this answer depends on the fault mesh there (docs/fault-convergence.md)",
                                         c.opt.edge_distance)
                           : ""),
       ""});
}

void search_headlines(Context& c) {
  const Search s = read_search(c.opt.scenario);
  const std::string group = "safety";
  if (!s.tried) {  // ugs-solve writes no trial when a fault or a seal fails before the reference date
    c.headlines.push_back({group, "maximum safe scale of the swing",
                           "none: a fault patch reaches chi = 1 or a seal fails before or at the reference date", ""});
    return;
  }
  if (!s.found) {
    c.headlines.push_back({group, "maximum safe scale of the swing", fmt::format("above {:.4g} (nothing fails up to it)", s.safe), ""});
    return;
  }
  c.headlines.push_back({group, "maximum safe scale of the swing",
                         s.any_safe ? fmt::format("{:.4g} (critical at {:.4g})", s.safe, s.critical)
                                    : fmt::format("none (critical at {:.4g}, the smallest scale tried)", s.critical),
                         ""});
  const std::string what = s.limiter == "fault chi = 1"    ? fmt::format("fault {} reaches chi = 1 on {}", s.who, s.date)
                           : s.limiter == "Newton failed" ? fmt::format("the solver failed on {} (counted as critical)", s.date)
                                                          : fmt::format("seal {}: {} on {}", s.who, s.limiter, s.date);
  c.headlines.push_back({group, "what limits it", what, ""});
  if (s.limiter == "fault chi = 1" && !c.trace_lines.empty()) corner_headline(c, s);
  if (!s.seal_margins.empty())
    c.headlines.push_back({group, "smallest seal margins at the maximum safe scale", s.seal_margins, ""});
  if (!c.cs || !s.any_safe) return;
  // The scenario scales each pool's swing about its pressure at the reference date.
  for (const PoolSpec& pool : c.cs->pools) {
    const Schedule p = schedule_MPa(pool);
    const std::int64_t ref = c.cs->scenario_reference_date.empty() ? p.t.front()
                                                                   : parse_iso_date(c.cs->scenario_reference_date).value_or(p.t.front());
    const double p_ref = p.at(ref);
    double peak = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < p.t.size(); ++k)
      if (p.t[k] > ref) peak = std::max(peak, p_ref + s.safe * (p.p[k] - p_ref));
    if (!std::isfinite(peak)) continue;
    c.headlines.push_back({group, fmt::format("maximum safe pressure, {}", pool.name),
                           fmt::format("{:.2f} MPa ({:+.2f} MPa over its initial {:.2f} MPa)", peak, peak - p.p.front(), p.p.front()),
                           ""});
  }
}

void caprock_headlines(Context& c) {
  const CsvTable t = CsvTable::read(c.opt.caprock);
  const auto cd = t.column("date"), cs = t.column("seal"), ct = t.column("min_tensile_margin_MPa"), csh = t.column("min_shear_margin_MPa");
  const auto cp = t.column("pore_pressure_MPa");
  std::size_t wt = t.rows(), ws = t.rows();
  for (std::size_t r = 0; r < t.rows(); ++r) {
    if (wt == t.rows() || t.number(r, ct) < t.number(wt, ct)) wt = r;
    if (ws == t.rows() || t.number(r, csh) < t.number(ws, csh)) ws = r;
  }
  if (wt == t.rows()) throw InputError(c.opt.caprock, "has no rows (expected ugs-solve's caprock table)");
  c.measures["tensile_margin_min_MPa"] = {t.number(wt, ct), fmt::format("seal {}, {}", t.text(wt, cs), t.text(wt, cd))};
  c.measures["shear_margin_min_MPa"] = {t.number(ws, csh), fmt::format("seal {}, {}", t.text(ws, cs), t.text(ws, cd))};
  c.headlines.push_back({"safety", "caprock: smallest tensile margin (fracture pressure - pore pressure)",
                         fmt::format("{:.2f} MPa (seal {}, {}, pore pressure {:.2f} MPa){}", t.number(wt, ct), t.text(wt, cs),
                                     t.text(wt, cd), t.number(wt, cp), t.number(wt, ct) <= 0 ? ": FAILS" : ""),
                         ""});
  c.headlines.push_back({"safety", "caprock: smallest Mohr-Coulomb shear margin",
                         fmt::format("{:.2f} MPa (seal {}, {}){}", t.number(ws, csh), t.text(ws, cs), t.text(ws, cd),
                                     t.number(ws, csh) <= 0 ? ": FAILS" : ""),
                         ""});
}

}  // namespace

void build_safety(Context& c) {
  if (!c.opt.scenario.empty()) search_headlines(c);
  if (!c.opt.caprock.empty()) caprock_headlines(c);
}

}  // namespace ugs::report
