#include "case_toml.hpp"

#include <cmath>
#include <string_view>

#include <fmt/format.h>

namespace ugs::testcase {
namespace {

// Four decimals where they hold the value exactly (0.0100), else the shortest form (0.00981).
std::string gradient(double v) {
  const std::string four = fmt::format("{:.4f}", v);
  return std::stod(four) == v ? four : fmt::format("{}", v);
}

}  // namespace

Material linear(const std::string& name, double E_MPa, double nu) {
  Material m;
  m.name = name;
  m.law = "linear";
  m.E_MPa = E_MPa;
  m.nu = nu;
  return m;
}

Material elastic(const std::string& name, double nu) {
  Material m;
  m.name = name;
  m.law = "elastic";
  m.nu = nu;
  return m;
}

Material hypoplastic(const std::string& name, double c_R) {
  Material m;
  m.name = name;
  m.law = "hypoplastic";
  m.thesis_anisotropy = true;
  m.c_R = c_R;
  return m;
}

Boundary fixed_sides() { return {{"bottom", "west", "east", "south", "north"}, {}, {}}; }

std::string string_list(const std::vector<std::string>& items) {
  std::string s = "[";
  for (std::size_t i = 0; i < items.size(); ++i) s += (i ? ", \"" : "\"") + items[i] + "\"";
  return s + "]";
}

CaseToml::CaseToml(std::string head, Numbers numbers) : numbers_(numbers), text_(std::move(head)) {}

std::string CaseToml::number(double v) const {
  if (numbers_ == Numbers::Decimal && std::isfinite(v) && v == std::floor(v) && std::abs(v) < 1e15) return fmt::format("{:.1f}", v);
  return fmt::format("{}", v);
}

void CaseToml::section(const std::string& header) {
  if (!first_) text_ += "\n";
  first_ = false;
  text_ += header + "\n";
}

CaseToml& CaseToml::initial_stress(const InitialStress& s) {
  section("[initial_stress]");
  if (s.surface_elevation_m) text_ += "surface_elevation_m = " + number(*s.surface_elevation_m) + "\n";
  text_ += "lithostatic_gradient_MPa_per_m = " + gradient(s.lithostatic_gradient_MPa_per_m) + "\n";
  text_ += "hydrostatic_gradient_MPa_per_m = " + gradient(s.hydrostatic_gradient_MPa_per_m) + "\n";
  if (s.k0) text_ += "k0 = " + number(*s.k0) + "\n";
  return *this;
}

CaseToml& CaseToml::material(const Material& m) {
  section("[[material]]");
  text_ += "name = \"" + m.name + "\"\nlaw = \"" + m.law + "\"\n";
  if (m.E_MPa) text_ += "E_MPa = " + number(*m.E_MPa) + "\n";
  if (m.nu) text_ += "nu = " + number(*m.nu) + "\n";
  if (m.nu_z) text_ += "nu_z = " + number(*m.nu_z) + "\n";
  if (m.thesis_anisotropy) text_ += "nu_z = 0.3\nEh_over_Ez = 3.0\nnuh_over_nuz = 0.2\n";
  if (m.c_R) text_ += "c_R = " + number(*m.c_R) + "\n";
  text_ += m.more;
  return *this;
}

CaseToml& CaseToml::boundary(const Boundary& b) {
  section("[boundary]");
  if (!b.fixed.empty()) text_ += "fixed = " + string_list(b.fixed) + "\n";
  if (!b.rollers.empty()) text_ += "rollers = " + string_list(b.rollers) + "\n";
  if (!b.free.empty()) text_ += "free = " + string_list(b.free) + "\n";
  return *this;
}

CaseToml& CaseToml::fault(const Fault& f) {
  section("[[fault]]");
  text_ += "name = \"" + f.name + "\"\ncohesion_MPa = " + number(f.cohesion_MPa) + "\nfriction_deg = " + number(f.friction_deg) + "\n";
  return *this;
}

CaseToml& CaseToml::pool(const Pool& p) {
  section("[[pool]]");
  text_ += "name = \"" + p.name + "\"\nmaterials = " + string_list(p.materials) + "\n";
  if (!p.aquifer_materials.empty()) text_ += "aquifer_materials = " + string_list(p.aquifer_materials) + "\n";
  text_ += "schedule = \"" + p.schedule + "\"\ncolumn = \"" + p.column + "\"\n";
  text_ += p.more;
  return *this;
}

CaseToml& CaseToml::table(const std::string& name, const std::string& lines) {
  section("[" + name + "]");
  text_ += lines;
  return *this;
}

}  // namespace ugs::testcase
