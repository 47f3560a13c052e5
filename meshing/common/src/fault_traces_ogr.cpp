// Fault traces from any OGR vector file (GeoJSON, GeoPackage, Shapefile, ...), through geodata.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/meshing/fault_traces.hpp"
#include "ugs/meshing/geodata.hpp"

namespace ugs {
namespace {

// A numeric field, also when the file stores it as text ("35").
std::optional<double> number_field(const geo::Feature& f, const std::string& field, const std::string& where,
                                   const std::string& who) {
  if (auto v = f.number_of(field)) return v;
  auto t = f.text_of(field);
  if (!t) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(t->c_str(), &end);
  if (t->empty() || end != t->c_str() + t->size())
    throw InputError(where, fmt::format("{}: field '{}' is not a number: \"{}\"", who, field, *t));
  return v;
}

// A list of numbers: OGR's text of a list field "(3:60,45,30)", or "60, 45, 30".
std::optional<std::vector<double>> number_list(const geo::Feature& f, const std::string& field, const std::string& where,
                                               const std::string& who) {
  auto t = f.text_of(field);
  if (!t) {
    if (auto v = f.number_of(field)) return std::vector<double>{*v};
    return std::nullopt;
  }
  std::string s = *t;
  if (!s.empty() && s.front() == '(') {
    const auto colon = s.find(':');
    s = s.substr(colon == std::string::npos ? 1 : colon + 1);
    if (!s.empty() && s.back() == ')') s.pop_back();
  }
  if (!s.empty() && s.front() == '[') s = s.substr(1);
  if (!s.empty() && s.back() == ']') s.pop_back();
  std::vector<double> out;
  std::size_t start = 0;
  while (start <= s.size()) {
    auto end = s.find(',', start);
    if (end == std::string::npos) end = s.size();
    std::string item = s.substr(start, end - start);
    const auto b = item.find_first_not_of(" \t"), e = item.find_last_not_of(" \t");
    item = b == std::string::npos ? "" : item.substr(b, e - b + 1);
    char* stop = nullptr;
    const double v = std::strtod(item.c_str(), &stop);
    if (item.empty() || stop != item.c_str() + item.size())
      throw InputError(where, fmt::format("{}: field '{}' is not a list of numbers: \"{}\"", who, field, *t));
    out.push_back(v);
    start = end + 1;
  }
  return out;
}

}  // namespace

std::vector<FaultRecord> read_fault_file(const std::string& path, const std::string& model_wkt,
                                         const std::string& name_field) {
  const geo::VectorData data = geo::read_vector(path, model_wkt);
  std::vector<FaultRecord> out;
  std::map<std::string, std::string> seen;  // name -> where
  for (const auto& f : data.features) {
    FaultRecord r;
    r.where = fmt::format("{}: feature {}", path, f.fid);
    r.name = f.text_of(name_field).value_or("");
    if (r.name.rfind("fault:", 0) == 0) r.name = r.name.substr(6);
    if (r.name.empty()) throw InputError(r.where, fmt::format("a fault has no '{}'", name_field));
    const std::string who = fmt::format("fault '{}'", r.name);
    auto number = [&](const char* field) -> std::optional<double> {
      auto v = number_field(f, field, r.where, who);
      if (v && !std::isfinite(*v)) throw InputError(r.where, fmt::format("{}: {} = {} is not a finite number", who, field, *v));
      return v;
    };
    r.top = number("top_m");
    r.bottom = number("bottom_m");
    r.dip_deg = number("dip_deg");
    r.dip_dir_deg = number("dip_dir_deg");
    r.trace_z = number("trace_z_m");
    r.size = number("size_m");
    if (r.top && r.bottom && !(*r.top >= *r.bottom))
      throw InputError(r.where, fmt::format("{}: bottom_m {} lies above top_m {}", who, *r.bottom, *r.top));
    if (r.dip_deg && !(*r.dip_deg > 0 && *r.dip_deg <= 90))
      throw InputError(r.where, fmt::format("{}: dip_deg {} is outside (0, 90]", who, *r.dip_deg));
    if (r.size && !(*r.size > 0)) throw InputError(r.where, fmt::format("{}: size_m must be > 0 (got {})", who, *r.size));
    const auto lb = number_list(f, "listric_bottom_m", r.where, who);
    const auto ld = number_list(f, "listric_dip_deg", r.where, who);
    if (lb.has_value() != ld.has_value())
      throw InputError(r.where, fmt::format("{}: listric_bottom_m and listric_dip_deg go together", who));
    if (lb) {
      if (lb->size() != ld->size())
        throw InputError(r.where, fmt::format("{}: listric_bottom_m has {} values, listric_dip_deg {}", who, lb->size(),
                                              ld->size()));
      for (double v : *lb)
        if (!std::isfinite(v)) throw InputError(r.where, fmt::format("{}: listric_bottom_m holds {}", who, v));
      for (double v : *ld)
        if (!(v > 0 && v <= 90)) throw InputError(r.where, fmt::format("{}: listric_dip_deg {} is outside (0, 90]", who, v));
      r.listric_bottom = *lb;
      r.listric_dip = *ld;
    }
    if (auto e = f.text_of("ends_against"); e && !e->empty()) r.ends_against = e->rfind("fault:", 0) == 0 ? e->substr(6) : *e;
    if (auto sf = f.text_of("surface"); sf && !sf->empty()) {
      // The surface is the fault: the fields that build one from the trace would contradict it.
      for (const auto& [given, field] : {std::pair{r.top.has_value(), "top_m"}, std::pair{r.bottom.has_value(), "bottom_m"},
                                         std::pair{r.dip_deg.has_value(), "dip_deg"},
                                         std::pair{r.dip_dir_deg.has_value(), "dip_dir_deg"},
                                         std::pair{r.trace_z.has_value(), "trace_z_m"}, std::pair{lb.has_value(), "listric_bottom_m"},
                                         std::pair{!r.ends_against.empty(), "ends_against"}})
        if (given)
          throw InputError(r.where, fmt::format("{}: {} and surface exclude each other (the surface {} is the fault's "
                                                "geometry: drop {})",
                                                who, field, *sf, field));
      const std::filesystem::path sp(*sf);
      r.surface = sp.is_absolute() ? sp.string() : (std::filesystem::path(path).parent_path() / sp).string();
    }
    if (f.lines.empty())
      throw InputError(r.where, fmt::format("{}: the feature is not a line (fault traces are (multi)line strings)", who));
    for (const auto& l : f.lines) r.lines.emplace_back(l.begin(), l.end());
    if (auto [it, fresh] = seen.emplace(r.name, r.where); !fresh)
      throw InputError(r.where, fmt::format("fault '{}' is also defined at {}", r.name, it->second));
    out.push_back(std::move(r));
  }
  if (out.empty()) throw InputError(path, "no fault traces in the file");
  return out;
}

FaultTrace fault_trace_from_record(const FaultRecord& r, const std::string& why) {
  FaultTrace t;
  t.where = r.where;
  t.name = r.name;
  if (!r.surface.empty()) {
    std::shared_ptr<FaultSurfaceInput> s;
    try {
      s = std::make_shared<FaultSurfaceInput>(read_fault_surface(r.surface));
    } catch (const InputError& e) {
      // The surface file's own "file:line" stays first: the line at fault is there.
      std::string what = e.what();
      if (!e.where().empty()) what = what.substr(e.where().size() + 2);
      throw InputError(e.where(), fmt::format("{} (the surface of fault '{}')", what, r.name));
    }
    t.top = -std::numeric_limits<double>::infinity();
    t.bottom = std::numeric_limits<double>::infinity();
    for (const auto& p : s->mesh.vertices) {
      t.top = std::max(t.top, p[2]);
      t.bottom = std::min(t.bottom, p[2]);
    }
    t.trace_z = t.top;
    t.parts = r.lines;
    t.surface = std::move(s);
    check_fault_trace(t);
    return t;
  }
  auto need = [&](const std::optional<double>& v, const char* field) {
    if (!v)
      throw InputError(t.where, fmt::format("fault '{}': missing field '{}' ({} name, top_m, bottom_m, dip_deg, dip_dir_deg)",
                                            r.name, field, why));
    return *v;
  };
  t.top = need(r.top, "top_m");
  t.bottom = need(r.bottom, "bottom_m");
  for (std::size_t i = 0; i < r.listric_bottom.size(); ++i) t.pieces.push_back({r.listric_bottom[i], r.listric_dip[i]});
  t.dip_deg = t.pieces.empty() ? need(r.dip_deg, "dip_deg") : r.dip_deg.value_or(t.pieces.front().dip_deg);
  t.dip_dir_deg = need(r.dip_dir_deg, "dip_dir_deg");
  t.trace_z = r.trace_z.value_or(t.top);
  t.ends_against = r.ends_against;
  t.parts = r.lines;
  check_fault_trace(t);
  return t;
}

std::optional<Point3> record_reference_normal(const FaultRecord& r) {
  if (!r.dip_dir_deg) return std::nullopt;
  constexpr double deg = 3.14159265358979323846 / 180.0;
  const double dip = (r.dip_deg ? *r.dip_deg : r.listric_dip.empty() ? 90.0 : r.listric_dip.front()) * deg;
  const double az = *r.dip_dir_deg * deg;
  return Point3{-std::sin(dip) * std::sin(az), -std::sin(dip) * std::cos(az), -std::cos(dip)};
}

std::vector<FaultTrace> read_fault_traces(const std::string& path, const std::string& model_wkt) {
  std::vector<FaultTrace> out;
  for (const auto& r : read_fault_file(path, model_wkt)) out.push_back(fault_trace_from_record(r));
  return out;
}

}  // namespace ugs
