#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <tuple>

#include <fmt/format.h>

#include "report.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/insar/displacement.hpp"
#include "ugs/meshing/geodata.hpp"

namespace ugs::report {

bool write_pressures(Context& c, std::string& label) {
  if (!c.cs || c.cs->pools.empty()) return false;
  if (std::filesystem::exists(c.work_file("pressure.csv"))) {
    label = c.cs->pools.back().column == "p_norm" ? "p / p0 (pool pressure, normalized)" : "pool pressure (MPa)";
    return true;
  }
  CsvWriter w(c.work_file("pressure.csv"), {"pool", "date", "value"});
  std::string col;
  for (const auto& p : c.cs->pools) {
    const CsvTable t = CsvTable::read(p.schedule);
    const auto cd = t.column("date"), cv = t.column(p.column);
    col = p.column;
    for (std::size_t r = 0; r < t.rows(); ++r) w.text(p.name).date(t.date(r, cd)).number(t.number(r, cv)).end_row();
  }
  w.commit();
  label = col == "p_norm" ? "p / p0 (pool pressure, normalized)" : "pool pressure (MPa)";
  return true;
}

std::string wanted_stress_pool(const Context& c) {
  if (!c.opt.stress_pool.empty()) return c.opt.stress_pool;
  if (c.cs && c.cs->report && !c.cs->report->stress_pool.empty()) return c.cs->report->stress_pool;
  return "Pool C";  // the thesis' storage pool; a case without it falls back to its last pool
}

std::vector<SectionLine> section_lines(const Context& c) {
  std::vector<SectionLine> out;
  if (c.opt.sections.empty()) return out;
  const auto vec = geo::read_vector(c.opt.sections, c.crs_wkt, c.opt.sections_where);
  for (const auto& f : vec.features)
    for (const auto& line : f.lines)
      out.push_back({f.text_of("name").value_or(fmt::format("section {}", f.fid)), f.text_of("from_label").value_or(""),
                     f.text_of("to_label").value_or(""), {line.begin(), line.end()}});
  return out;
}

std::string Phase::label() const { return fmt::format("{} {} to {}", name, format_iso_date(start), format_iso_date(end)); }

std::string jstr(const std::string& s) {
  std::string q = "\"";
  for (unsigned char ch : s) {
    switch (ch) {
      case '"': q += "\\\""; break;
      case '\\': q += "\\\\"; break;
      case '\n': q += "\\n"; break;
      case '\t': q += "\\t"; break;
      default:
        if (ch < 0x20)
          q += fmt::format("\\u{:04x}", ch);
        else
          q += static_cast<char>(ch);
    }
  }
  return q + "\"";
}

std::string jwork(const std::string& name) { return jstr("work/" + name); }

std::string slug(const std::string& s) {
  std::string r;
  for (char ch : s) r += std::isalnum(static_cast<unsigned char>(ch)) ? static_cast<char>(std::tolower(ch)) : '_';
  return r;
}

std::vector<std::string> unique_slugs(const std::vector<std::string>& names) {
  std::set<std::string> plain, used;
  for (const auto& n : names) plain.insert(slug(n));
  std::map<std::string, std::string> stem;  // name -> stem, assigned in byte order of the names
  for (const auto& n : std::set<std::string>(names.begin(), names.end())) {
    const std::string base = slug(n);
    std::string s = base;
    for (int k = 1; used.count(s);)
      do s = fmt::format("{}_{}", base, ++k);
      while (plain.count(s) || used.count(s));
    used.insert(s);
    stem[n] = s;
  }
  std::vector<std::string> out;
  for (const auto& n : names) out.push_back(stem.at(n));
  return out;
}

std::string mm(double v) { return std::isfinite(v) ? fmt::format("{:.2f}", v) : "n/a"; }

std::vector<double> cell_field_at(const FieldSeriesReader& r, const std::vector<std::int64_t>& times, const std::string& name,
                                  std::int64_t t, int& components) {
  const auto b = insar::bracket_time(times, t);
  if (!b)
    throw InputError(r.path(), fmt::format("date {} lies outside the results ({} .. {})", format_iso_date(t),
                                           format_iso_date(times.front()), format_iso_date(times.back())));
  Field a = r.cell_field(b->i0, name);
  components = a.components;
  if (b->w == 0) return std::move(a.values);
  const Field c = r.cell_field(b->i1, name);
  for (std::size_t i = 0; i < a.values.size(); ++i) a.values[i] = (1 - b->w) * a.values[i] + b->w * c.values[i];
  return std::move(a.values);
}

// The fault's strike in the horizontal plane from its pairs' along_strike (= x sx + y sy - s0,
// docs/fault-mechanics.md): least squares, or along the pairs' line when they stand on one in plan
// (a vertical fault). For the pools' outlines on the fault's plane.
std::array<double, 3> strike_of(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& s) {
  const double n = static_cast<double>(x.size());
  double mx = 0, my = 0, ms = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += x[i] / n, my += y[i] / n, ms += s[i] / n;
  double xx = 0, xy = 0, yy = 0, xs = 0, ys = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double dx = x[i] - mx, dy = y[i] - my, ds = s[i] - ms;
    xx += dx * dx, xy += dx * dy, yy += dy * dy, xs += dx * ds, ys += dy * ds;
  }
  const double det = xx * yy - xy * xy;
  double sx = 1, sy = 0;
  if (det > 1e-9 * (xx + yy) * (xx + yy)) {
    sx = (yy * xs - xy * ys) / det, sy = (xx * ys - xy * xs) / det;
  } else if (xx + yy > 0) {
    std::tie(sx, sy) = xx >= yy ? std::pair{xx, xy} : std::pair{xy, yy};
    if (sx * xs + sy * ys < 0) sx = -sx, sy = -sy;
  }
  const double h = std::hypot(sx, sy);
  sx /= h, sy /= h;
  return {sx, sy, mx * sx + my * sy - ms};
}

}  // namespace ugs::report
