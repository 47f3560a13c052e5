// Fault traces from any OGR vector file (GeoJSON, GeoPackage, Shapefile, ...), through geodata.
#include <cstdlib>
#include <optional>
#include <map>

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

bool feature_has_dip(const geo::Feature& f) {
  return f.text_of("dip_deg").has_value() || f.text_of("listric_dip_deg").has_value();
}

FaultTrace fault_trace_from_feature(const geo::Feature& f, const std::string& where) {
  FaultTrace t;
  t.where = where;
  t.name = f.text_of("name").value_or("");
  if (t.name.rfind("fault:", 0) == 0) t.name = t.name.substr(6);
  if (t.name.empty()) throw InputError(t.where, "a fault trace has no 'name'");
  const std::string who = fmt::format("fault '{}'", t.name);
  auto need = [&](const char* field) {
    auto v = number_field(f, field, t.where, who);
    if (!v)
      throw InputError(t.where, fmt::format("{}: missing field '{}' (a trace needs name, top_m, bottom_m, dip_deg, "
                                            "dip_dir_deg)",
                                            who, field));
    return *v;
  };
  t.top = need("top_m");
  t.bottom = need("bottom_m");
  const auto lb = number_list(f, "listric_bottom_m", t.where, who);
  const auto ld = number_list(f, "listric_dip_deg", t.where, who);
  if (lb.has_value() != ld.has_value())
    throw InputError(t.where, fmt::format("{}: listric_bottom_m and listric_dip_deg go together", who));
  if (lb) {
    if (lb->size() != ld->size())
      throw InputError(t.where, fmt::format("{}: listric_bottom_m has {} values, listric_dip_deg {}", who, lb->size(),
                                            ld->size()));
    for (std::size_t i = 0; i < lb->size(); ++i) t.pieces.push_back({(*lb)[i], (*ld)[i]});
    t.dip_deg = number_field(f, "dip_deg", t.where, who).value_or(t.pieces.front().dip_deg);
  } else {
    t.dip_deg = need("dip_deg");
  }
  t.dip_dir_deg = need("dip_dir_deg");
  t.trace_z = number_field(f, "trace_z_m", t.where, who).value_or(t.top);
  if (auto e = f.text_of("ends_against"); e && !e->empty()) t.ends_against = e->rfind("fault:", 0) == 0 ? e->substr(6) : *e;
  if (f.lines.empty())
    throw InputError(t.where, fmt::format("{}: the feature is not a line (fault traces are (multi)line strings)", who));
  for (const auto& l : f.lines) t.parts.emplace_back(l.begin(), l.end());
  check_fault_trace(t);
  return t;
}

std::vector<FaultTrace> read_fault_traces(const std::string& path, const std::string& model_wkt) {
  const geo::VectorData data = geo::read_vector(path, model_wkt);
  std::vector<FaultTrace> out;
  std::map<std::string, std::string> seen;  // name -> where
  for (const auto& f : data.features) {
    FaultTrace t = fault_trace_from_feature(f, fmt::format("{}: feature {}", path, f.fid));
    if (auto [it, fresh] = seen.emplace(t.name, t.where); !fresh)
      throw InputError(t.where, fmt::format("fault '{}' is also defined at {}", t.name, it->second));
    out.push_back(std::move(t));
  }
  if (out.empty()) throw InputError(path, "no fault traces in the file");
  return out;
}

}  // namespace ugs
