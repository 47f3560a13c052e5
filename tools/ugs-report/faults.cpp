// Fault safety (thesis 4.3.4, figures 4.43-4.44): chi = |tau| / (c - sigma_n tan(phi)) on each
// fault for the minimum and maximum pressure scenarios, each fault drawn in its own plane (along
// strike, elevation) with the pools' outline projected on that plane; max chi per fault against
// time with the pool pressures; and the calibration's misfit profile.
//
// One number per quantity (docs/fault-mechanics.md "Outputs"): chi lives at the node pairs. With the
// faulted solver's node field `chi`, the maps show the node values (linear on each triangle) and
// the table's "maximum chi" is the largest node value of the fault's pairs (`interpolated` = 0),
// the max_chi of ugs-solve's faults CSV at that date. Files with a cell field only (other tools)
// are drawn per cell, and their maximum is per cell.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

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


// A fault of the results with node values: its triangles (local node numbers) and its nodes in its
// own plane, s along the strike and z.
struct FaultNodes {
  std::string name;
  std::vector<std::uint32_t> nodes;                 // node indices of the file
  std::vector<std::array<std::uint32_t, 3>> tri;    // local
  std::vector<double> s, z;                         // per local node [m]
  double sx = 1, sy = 0, s0 = 0;                    // s = x sx + y sy - s0
};

// The faults of a file written by ugs-solve (triangles in fault groups, node fields). s comes from
// the node field `along_strike` when the file has it (the per-pair CSVs' coordinate), else from the
// same definition: the horizontal direction normal to the mean normal, eastwards (northwards), from
// the fault's westmost (southmost) node.
std::vector<FaultNodes> read_fault_nodes(const FieldSeriesReader& r, const Mesh* mesh) {
  const auto x = r.coordinates();
  const auto types = r.cell_types();
  const auto mats = r.materials();
  std::map<std::int32_t, FaultNodes> by_tag;
  std::map<std::int32_t, std::map<std::uint32_t, std::uint32_t>> local;
  std::size_t offset = 0;
  for (ElementType t : types) {
    const auto c = r.cells(t);
    const std::size_t npe = static_cast<std::size_t>(nodes_per_element(t)), n = c.size() / npe;
    if (t == ElementType::Triangle)
      for (std::size_t i = 0; i < n; ++i) {
        const std::int32_t tag = offset + i < mats.size() ? mats[offset + i] : 0;
        FaultNodes& f = by_tag[tag];
        auto& loc = local[tag];
        std::array<std::uint32_t, 3> tri{};
        for (int k = 0; k < 3; ++k) {
          auto [it, fresh] = loc.emplace(c[i * npe + k], static_cast<std::uint32_t>(f.nodes.size()));
          if (fresh) f.nodes.push_back(c[i * npe + k]);
          tri[k] = it->second;
        }
        f.tri.push_back(tri);
      }
    offset += n;
  }
  if (by_tag.empty()) throw InputError(r.path(), "has no fault triangles");
  const auto names = r.node_field_names(0);
  const bool have_s = std::find(names.begin(), names.end(), "along_strike") != names.end();
  const Field as = have_s ? r.node_field(0, "along_strike") : Field{};
  std::vector<FaultNodes> out;
  for (auto& [tag, f] : by_tag) {
    f.name = insar::fault_group_name(mesh, tag);
    double nx = 0, ny = 0, nz = 0;
    for (const auto& t : f.tri) {
      const Point3 &a = x[f.nodes[t[0]]], &b = x[f.nodes[t[1]]], &d = x[f.nodes[t[2]]];
      const double ax = b[0] - a[0], ay = b[1] - a[1], az = b[2] - a[2];
      const double bx = d[0] - a[0], by = d[1] - a[1], bz = d[2] - a[2];
      double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
      if (cx * nx + cy * ny + cz * nz < 0) cx = -cx, cy = -cy, cz = -cz;
      nx += cx, ny += cy, nz += cz;
    }
    const double nh = std::hypot(nx, ny), nn = std::sqrt(nh * nh + nz * nz);
    if (nh > 1e-3 * nn) {
      f.sx = -ny / nh, f.sy = nx / nh;
      if (f.sx < 0 || (f.sx == 0 && f.sy < 0)) f.sx = -f.sx, f.sy = -f.sy;
    }
    double lo = INFINITY, off = 0;
    for (auto v : f.nodes) {
      const double p = x[v][0] * f.sx + x[v][1] * f.sy;
      lo = std::min(lo, p);
      if (have_s) off += p - as.values[v];
    }
    f.s0 = have_s ? off / static_cast<double>(f.nodes.size()) : lo;
    for (auto v : f.nodes) {
      f.s.push_back(have_s ? as.values[v] : x[v][0] * f.sx + x[v][1] * f.sy - f.s0);
      f.z.push_back(x[v][2]);
    }
    out.push_back(std::move(f));
  }
  return out;
}

// Convex hull (counter-clockwise, closed) of points in a plane.
std::vector<std::array<double, 2>> convex_hull(std::vector<std::array<double, 2>> p) {
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  auto cross = [](const auto& o, const auto& a, const auto& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  std::vector<std::array<double, 2>> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k);  // the last point repeats the first: closed
  return h;
}

}  // namespace

// The nodes of each pool's materials (tetrahedra of mat:<name>), for the outlines on the faults.
PoolNodes pool_nodes(const Context& c) {
  PoolNodes out;
  if (!c.mesh || !c.cs) return out;
  for (const auto& pool : c.cs->pools) {
    std::vector<char> in(c.mesh->num_nodes(), 0);
    for (const auto& b : c.mesh->blocks) {
      if (b.type != ElementType::Tetrahedron) continue;
      const std::string g = c.mesh->physical_name_of(b.entity_dim, b.entity_tag);
      if (g.rfind("mat:", 0) != 0 ||
          std::find(pool.materials.begin(), pool.materials.end(), g.substr(4)) == pool.materials.end())
        continue;
      for (auto v : b.nodes) in[v] = 1;
    }
    std::vector<Point3> pts;
    for (std::size_t i = 0; i < in.size(); ++i)
      if (in[i]) pts.push_back(c.mesh->nodes[i]);
    if (!pts.empty()) out.emplace_back(pool.name, std::move(pts));
  }
  return out;
}

std::string write_pool_outlines(const Context& c, const PoolNodes& pools, const std::string& name, double sx, double sy, double s0) {
  if (pools.empty()) return "null";
  if (!std::filesystem::exists(c.work_file(name))) {
    CsvWriter w(c.work_file(name), {"pool", "s", "z"});
    for (const auto& [pool, pts] : pools) {
      std::vector<std::array<double, 2>> q;
      for (const auto& p : pts) q.push_back({p[0] * sx + p[1] * sy - s0, p[2]});
      for (const auto& h : convex_hull(q)) w.text(pool).number(h[0], 3).number(h[1], 3).end_row();
    }
    w.commit();
  }
  return jwork(name);
}

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
      if (p.name == wanted_stress_pool(c)) pool = &p;
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
  const std::string& field = c.opt.fault_field;
  const auto node_names = fr.node_field_names(smin);
  const bool per_node = std::find(node_names.begin(), node_names.end(), field) != node_names.end();
  const bool have_interp = std::find(node_names.begin(), node_names.end(), "interpolated") != node_names.end();
  std::vector<FaultNodes> faults_n;
  if (per_node) faults_n = read_fault_nodes(fr, mesh);
  const PoolNodes pools = per_node ? pool_nodes(c) : PoolNodes{};
  // Per fault, the largest value of `field` at a step: over the fault's node pairs (interpolated =
  // 0), as ugs-solve's statistics.
  auto node_max = [&](std::size_t step, std::vector<std::vector<double>>& values, std::vector<std::size_t>& where) {
    const Field f = fr.node_field(step, field);
    const Field in = have_interp ? fr.node_field(step, "interpolated") : Field{};
    std::vector<double> m;
    values.clear();
    where.clear();
    for (const auto& fn : faults_n) {
      std::vector<double> v;
      double best = -INFINITY, any = -INFINITY;
      std::size_t ib = 0, ia = 0;
      for (std::size_t i = 0; i < fn.nodes.size(); ++i) {
        const std::size_t n = fn.nodes[i];
        const double x = f.values[n * f.components];
        v.push_back(x);
        if (!std::isfinite(x)) continue;
        if (x > any) any = x, ia = i;
        if ((!have_interp || in.values[n] == 0) && x > best) best = x, ib = i;
      }
      m.push_back(std::isfinite(best) ? best : (std::isfinite(any) ? any : 0.0));
      where.push_back(std::isfinite(best) ? ib : ia);
      values.push_back(std::move(v));
    }
    return m;
  };
  struct Scenario {
    const char* name;
    std::size_t step;
  };
  std::map<std::pair<std::string, std::string>, double> shown;  // (fault, date) -> max chi shown
  for (const Scenario sc : {Scenario{"minimum", smin}, Scenario{"maximum", smax}}) {
    std::string panels;
    double vmax = 0;
    auto headline = [&](const std::string& name, double v) {
      c.headlines.push_back({fmt::format("faults, {} pressure ({})", sc.name, steps[sc.step].date),
                             fmt::format("maximum {} on {}", field == "chi" ? "χ" : field, name), fmt::format("{:.3f}", v),
                             field == "chi" ? "about 0.1 on the regional faults" : ""});
      // The pictured dates' chi stands for the acceptance check until the faults table (every date) is read.
      auto& m = c.measures["chi_max"];
      if (field == "chi" && (m.where.empty() || v > m.value)) m = {v, fmt::format("fault {} on {}", name, steps[sc.step].date)};
    };
    if (per_node) {
      std::vector<std::vector<double>> values;
      std::vector<std::size_t> where;
      const auto maxima = node_max(sc.step, values, where);
      std::vector<std::string> names;
      for (const auto& f : faults_n) names.push_back(f.name);
      const auto slugs = unique_slugs(names);
      for (std::size_t k = 0; k < faults_n.size(); ++k) {
        const auto& f = faults_n[k];
        const std::string stem = fmt::format("chi_{}_{}", sc.name, slugs[k]);
        std::vector<double> sz;
        for (std::size_t i = 0; i < f.nodes.size(); ++i) sz.insert(sz.end(), {f.s[i], f.z[i]});
        std::vector<std::int32_t> tri;
        for (const auto& t : f.tri)
          for (auto v : t) tri.push_back(static_cast<std::int32_t>(v));
        insar::write_npy(c.work_file(stem + "_nodes.npy"), sz, {f.nodes.size(), 2});
        insar::write_npy(c.work_file(stem + "_tri.npy"), tri, {f.tri.size(), 3});
        insar::write_npy(c.work_file(stem + ".npy"), values[k], {values[k].size()});
        const std::string outline = write_pool_outlines(c, pools, fmt::format("pools_on_{}.csv", slugs[k]), f.sx, f.sy, f.s0);
        panels += fmt::format("{}{{\"name\": {}, \"nodes\": {}, \"tri\": {}, \"values\": {}, \"max\": {}, \"at\": [{}, {}], "
                              "\"pools\": {}}}",
                              panels.empty() ? "" : ", ", jstr(f.name), jwork(stem + "_nodes.npy"), jwork(stem + "_tri.npy"),
                              jwork(stem + ".npy"), maxima[k], f.s[where[k]], f.z[where[k]], outline);
        vmax = std::max(vmax, maxima[k]);
        headline(f.name, maxima[k]);
        if (field == "chi") shown[{f.name, steps[sc.step].date}] = maxima[k];
      }
    } else {
      const auto faults = insar::read_fault_chi(fr, sc.step, mesh, field);
      std::vector<std::string> names;
      for (const auto& f : faults) names.push_back(f.name);
      const auto slugs = unique_slugs(names);
      for (std::size_t k = 0; k < faults.size(); ++k) {
        const auto& f = faults[k];
        const std::string stem = fmt::format("chi_{}_{}", sc.name, slugs[k]);
        std::vector<double> sz;
        for (const auto& q : f.sz) sz.insert(sz.end(), q.begin(), q.end());
        insar::write_npy(c.work_file(stem + "_sz.npy"), sz, {f.sz.size(), 3, 2});
        insar::write_npy(c.work_file(stem + ".npy"), f.chi, {f.chi.size()});
        panels += fmt::format("{}{{\"name\": {}, \"sz\": {}, \"values\": {}}}", panels.empty() ? "" : ", ", jstr(f.name),
                              jwork(stem + "_sz.npy"), jwork(stem + ".npy"));
        vmax = std::max(vmax, f.max_chi);
        headline(f.name, f.max_chi);
      }
    }
    Figure fig;
    fig.kind = "faults";
    fig.png = fmt::format("chi_{}_pressure.png", sc.name);
    fig.title = fmt::format("Safety factor χ, {} pressure ({})", sc.name, steps[sc.step].date);
    fig.caption = fmt::format("χ = |τ| / (c − σ_n tan φ) on the faults for the {} pressure scenario ({}; {}), each fault "
                              "in its own plane: distance along strike and elevation{}.", sc.name, steps[sc.step].date, how,
                              per_node ? (pools.empty() ? "; values at the node pairs, linear in between"
                                                        : "; values at the node pairs, linear in between; the pools' outline "
                                                          "projected on the fault's plane")
                                       : "; values per element (the file has no node field)");
    fig.json = fmt::format("\"panels\": [{}], \"vmax\": {}, \"label\": {}", panels, std::max(vmax, 1e-3),
                           jstr(field == "chi" ? "χ" : field));
    c.add(fig);
  }

  // Max chi per fault against time: ugs-solve's faults CSV (every step), with the pool pressures.
  std::string table = c.opt.fault_table;
  if (table.empty()) {
    const std::string& h = c.opt.faults;
    const std::string stem = h.size() > 3 && h.substr(h.size() - 3) == ".h5" ? h.substr(0, h.size() - 3) : h;
    if (std::filesystem::exists(stem + ".csv")) table = stem + ".csv";
  }
  if (table.empty()) {
    c.notes.push_back("no faults CSV beside the fault results (--fault-table): the plot of max χ against time was skipped");
    return;
  }
  const CsvTable t = CsvTable::read(table);
  const auto cd = t.column("date"), cf = t.column("fault"), cm = t.column("max_chi");
  CsvWriter w(c.work_file("max_chi.csv"), {"fault", "date", "value"});
  std::map<std::string, std::pair<double, std::string>> peak;
  std::vector<std::string> order;  // faults in the CSV's order
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const std::string fault(t.text(r, cf)), date(t.text(r, cd));
    const double v = t.number(r, cm);
    (void)t.date(r, cd);  // an ISO date (InputError naming the row otherwise)
    w.text(fault).text(date).number(v).end_row();
    auto& p = peak[fault];
    if (p.second.empty()) order.push_back(fault);
    if (r == 0) c.measures.erase("chi_max");
    auto& m = c.measures["chi_max"];
    if (m.where.empty() || v > m.value) m = {v, fmt::format("fault {} on {}", fault, date)};
    if (p.second.empty() || v > p.first) p = {v, date};
    // The same definition in both files: a CSV of another run would show here.
    if (const auto it = shown.find({fault, date}); it != shown.end() && std::abs(it->second - v) > 5e-7)
      c.notes.push_back(fmt::format("{}: max_chi {} of fault {} on {} differs from the fault results' {:.6f}: another run?", table,
                                    t.text(r, cm), fault, date, it->second));
  }
  w.commit();
  if (t.rows() == 0) throw InputError(table, "has no rows");
  for (const auto& fault : order)
    c.headlines.push_back({"faults, over the run", fmt::format("largest χ on {}", fault),
                           fmt::format("{:.3f} ({})", peak[fault].first, peak[fault].second), "about 0.1 on the regional faults"});
  std::string plabel;
  const bool pressures = write_pressures(c, plabel);
  Figure fig;
  fig.kind = "chi_series";
  fig.png = "chi_max_series.png";
  fig.title = "Largest χ on each fault";
  fig.caption = fmt::format("The largest χ over each fault's node pairs at every step of the run ({}){}.", table,
                            pressures ? ", with the pool pressures" : "");
  fig.json = fmt::format("\"csv\": {}, \"pressure\": {}, \"pressure_label\": {}", jwork("max_chi.csv"),
                         pressures ? jwork("pressure.csv") : std::string("null"), jstr(plabel));
  c.add(fig);
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
