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

}  // namespace

std::vector<FaultTrace> read_fault_traces(const std::string& path, const std::string& model_wkt) {
  const geo::VectorData data = geo::read_vector(path, model_wkt);
  std::vector<FaultTrace> out;
  std::map<std::string, std::string> seen;  // name -> where
  for (const auto& f : data.features) {
    FaultTrace t;
    t.where = fmt::format("{}: feature {}", path, f.fid);
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
    t.dip_deg = need("dip_deg");
    t.dip_dir_deg = need("dip_dir_deg");
    t.trace_z = number_field(f, "trace_z_m", t.where, who).value_or(t.top);
    if (f.lines.empty())
      throw InputError(t.where, fmt::format("{}: the feature is not a line (fault traces are (multi)line strings)", who));
    for (const auto& l : f.lines) t.parts.emplace_back(l.begin(), l.end());
    if (auto [it, fresh] = seen.emplace(t.name, t.where); !fresh)
      throw InputError(t.where, fmt::format("{} is also defined at {}", who, it->second));
    check_fault_trace(t);
    out.push_back(std::move(t));
  }
  if (out.empty()) throw InputError(path, "no fault traces in the file");
  return out;
}

}  // namespace ugs
