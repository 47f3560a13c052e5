#include "case_toml.hpp"

#include <cmath>
#include <fstream>

#include <fmt/format.h>

namespace ugs::testcase {
namespace {

// Four decimals where they hold the value exactly (0.0100), else the shortest form (0.00981).
std::string gradient(double v) {
  const std::string four = fmt::format("{:.4f}", v);
  return std::stod(four) == v ? four : fmt::format("{}", v);
}

}  // namespace

Material linear(const std::string& name, double E_MPa, double nu) { return {.name = name, .law = "linear", .E_MPa = E_MPa, .nu = nu}; }

Material elastic(const std::string& name, double nu) { return {.name = name, .law = "elastic", .nu = nu}; }

Material hypoplastic(const std::string& name, double c_R) {
  return {.name = name, .law = "hypoplastic", .thesis_anisotropy = true, .c_R = c_R};
}

Boundary fixed_sides() { return {{"bottom", "west", "east", "south", "north"}, {}, {}}; }

std::string string_list(const std::vector<std::string>& items) {
  std::string s = "[";
  for (std::size_t i = 0; i < items.size(); ++i) s += (i ? ", \"" : "\"") + items[i] + "\"";
  return s + "]";
}

void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream f(p);
  f << text;
}

std::string toml_number(double v, Numbers numbers) {
  if (numbers == Numbers::Decimal && std::isfinite(v) && v == std::floor(v) && std::abs(v) < 1e15) return fmt::format("{:.1f}", v);
  return fmt::format("{}", v);
}

void TomlSections::section(const std::string& header) {
  if (!first_ && layout_ == Layout::Spaced) text_ += "\n";
  first_ = false;
  text_ += header + "\n";
}

CaseToml& CaseToml::initial_stress(const InitialStress& s) {
  section("[initial_stress]");
  if (s.surface_elevation_m) add("surface_elevation_m = " + number(*s.surface_elevation_m) + "\n");
  if (s.lithostatic_gradient_MPa_per_m) add("lithostatic_gradient_MPa_per_m = " + gradient(*s.lithostatic_gradient_MPa_per_m) + "\n");
  if (s.hydrostatic_gradient_MPa_per_m) add("hydrostatic_gradient_MPa_per_m = " + gradient(*s.hydrostatic_gradient_MPa_per_m) + "\n");
  if (s.k0) add("k0 = " + number(*s.k0) + "\n");
  if (s.k_Hmax) add("k_Hmax = " + number(*s.k_Hmax) + "\n");
  if (s.k_hmin) add("k_hmin = " + number(*s.k_hmin) + "\n");
  if (s.Hmax_azimuth_deg) add("Hmax_azimuth_deg = " + number(*s.Hmax_azimuth_deg) + "\n");
  const std::pair<const char*, const DepthRows*> tables[] = {{"Sv_density_kg_per_m3", &s.Sv_density_kg_per_m3},
                                                              {"Sv_gradients_MPa_per_m", &s.Sv_gradients_MPa_per_m},
                                                              {"Shmin_MPa", &s.Shmin_MPa},
                                                              {"SHmax_MPa", &s.SHmax_MPa},
                                                              {"overpressure_MPa", &s.overpressure_MPa}};
  for (const auto& [key, rows] : tables) {
    if (rows->empty()) continue;
    std::string line = std::string(key) + " = [";
    for (std::size_t i = 0; i < rows->size(); ++i)
      line += (i ? ", [" : "[") + number((*rows)[i][0]) + ", " + number((*rows)[i][1]) + "]";
    add(line + "]\n");
  }
  if (s.SHmax_over_Shmin) add("SHmax_over_Shmin = " + number(*s.SHmax_over_Shmin) + "\n");
  if (!s.regime.empty()) add("regime = \"" + s.regime + "\"\n");
  return *this;
}

CaseToml& CaseToml::material(const Material& m) {
  section("[[material]]");
  add("name = \"" + m.name + "\"\n");
  if (!m.law.empty()) add("law = \"" + m.law + "\"\n");
  if (m.E_MPa) add("E_MPa = " + number(*m.E_MPa) + "\n");
  if (m.nu) add("nu = " + number(*m.nu) + "\n");
  if (m.nu_z) add("nu_z = " + number(*m.nu_z) + "\n");
  if (m.thesis_anisotropy) add("nu_z = 0.3\nEh_over_Ez = 3.0\nnuh_over_nuz = 0.2\n");
  if (m.c_R) add("c_R = " + number(*m.c_R) + "\n");
  add(m.more);
  return *this;
}

CaseToml& CaseToml::boundary(const Boundary& b) {
  section("[boundary]");
  if (!b.fixed.empty()) add("fixed = " + string_list(b.fixed) + "\n");
  if (!b.rollers.empty()) add("rollers = " + string_list(b.rollers) + "\n");
  if (!b.free.empty()) add("free = " + string_list(b.free) + "\n");
  return *this;
}

CaseToml& CaseToml::seal(const Seal& s) {
  section("[[seal]]");
  add("material = \"" + s.material + "\"\n");
  add("cohesion_MPa = " + number(s.cohesion_MPa) + "\n");
  add("friction_deg = " + number(s.friction_deg) + "\n");
  add("tensile_strength_MPa = " + number(s.tensile_strength_MPa) + "\n");
  return *this;
}

CaseToml& CaseToml::fault(const Fault& f) {
  section("[[fault]]");
  add("name = \"" + f.name + "\"\ncohesion_MPa = " + number(f.cohesion_MPa) + "\nfriction_deg = " + number(f.friction_deg) + "\n");
  return *this;
}

CaseToml& CaseToml::pool(const Pool& p) {
  section("[[pool]]");
  add("name = \"" + p.name + "\"\nmaterials = " + string_list(p.materials) + "\n");
  if (!p.aquifer_materials.empty()) add("aquifer_materials = " + string_list(p.aquifer_materials) + "\n");
  add("schedule = \"" + p.schedule + "\"\ncolumn = \"" + p.column + "\"\n");
  if (p.gas_water_contact_m) add("gas_water_contact_m = " + number(*p.gas_water_contact_m) + "\n");
  if (p.gas_density_kg_per_m3) add("gas_density_kg_per_m3 = " + number(*p.gas_density_kg_per_m3) + "\n");
  add(p.more);
  return *this;
}

CaseToml& CaseToml::table(const std::string& name, const std::string& lines) {
  section("[" + name + "]");
  add(lines);
  return *this;
}

}  // namespace ugs::testcase
