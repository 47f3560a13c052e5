#include "ugs/formats/case_file.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/toml_reader.hpp"

namespace ugs {
namespace {

constexpr double kMPa = 1e6;

MaterialLaw parse_law(const TomlTable& t) {
  const std::string s = t.string("law");
  if (s == "linear") return MaterialLaw::Linear;
  if (s == "elastic") return MaterialLaw::ElasticDepth;
  if (s == "hypoplastic") return MaterialLaw::Hypoplastic;
  throw t.error("law", fmt::format("'{}' is not one of linear, elastic, hypoplastic", s));
}

// An integer key in [lo, hi], checked before it is narrowed to int (4294967297 must not become 1).
int integer_in(const TomlTable& t, const std::string& key, long long fallback, long long lo, long long hi) {
  const long long v = t.integer_opt(key).value_or(fallback);
  if (v < lo || v > hi) throw t.error(key, fmt::format("must lie in [{}, {}], got {}", lo, hi, v));
  return static_cast<int>(v);
}

double positive(const TomlTable& t, const std::string& key, double v) {
  if (!(v > 0) || !std::isfinite(v)) throw t.error(key, fmt::format("must be positive, got {}", v));
  return v;
}

// Runs one check; a bad value is added to the list and the reading goes on (GMT's n_errors), so a
// case file with several problems names them all. A value that failed keeps its default, and the
// checks that depend on it are skipped, so one mistake gives one line.
struct Collect {
  ErrorList& errors;
  template <class F>
  bool operator()(F&& check) const {
    try {
      check();
      return true;
    } catch (const InputError& e) {
      errors.add(e);
      return false;
    }
  }
};

// k0 / k_Hmax / k_hmin of [initial_stress] or of a material: positive and finite, k0 not with the others.
void read_ratios(const TomlTable& t, std::optional<double>& kH, std::optional<double>& kh, const Collect& ok,
                 bool check_k0) {
  bool fine = true;
  for (const char* key : {"k0", "k_Hmax", "k_hmin"})
    if (t.has(key) && (check_k0 || std::string(key) != "k0")) fine = ok([&] { positive(t, key, t.number(key)); }) && fine;
  // k0 is the shorthand for k_Hmax = k_hmin = k0: both forms at once would leave one unused.
  for (const char* key : {"k_Hmax", "k_hmin"})
    if (t.has(key) && t.has("k0"))
      fine = ok([&] {
        throw t.error(key, fmt::format("{} given together with k0 = {} (k0 is the shorthand for k_Hmax = k_hmin; give one "
                                       "form)", t.number(key), t.number("k0")));
      }) && fine;
  if (!fine) return;
  ok([&] {
    if (t.has("k0")) kH = kh = t.number("k0");
    if (t.has("k_Hmax")) kH = t.number("k_Hmax");
    if (t.has("k_hmin")) kh = t.number("k_hmin");
  });
}

// The [[material]] keys whose value may be a field, with the SI factor of their unit.
double field_key_si(const std::string& key) { return key == "E_MPa" ? kMPa : 1.0; }

// `key = { grdecl = ..., keyword = ... }` (or init, elevation_table, depth_table, map, cells): a
// constant that varies in space. The file is checked to exist here, so that a missing one names
// its line; the rest (keyword, coverage, values) when the mesh is known.
MaterialField parse_field(const TomlTable& f, const std::string& key, const std::string& case_path) {
  MaterialField m;
  m.key = key;
  m.where = f.where();
  m.si = field_key_si(key.substr(0, key.find('[')));
  f.reject_unknown({"grdecl", "init", "elevation_table", "depth_table", "map", "cells", "keyword", "field", "grid", "date",
                    "offset_m", "scale"});
  static const std::vector<std::pair<const char*, MaterialField::Source>> sources = {
      {"grdecl", MaterialField::Source::Grdecl},       {"init", MaterialField::Source::Init},
      {"elevation_table", MaterialField::Source::Table}, {"depth_table", MaterialField::Source::Table},
      {"map", MaterialField::Source::Map},             {"cells", MaterialField::Source::Cells}};
  std::vector<std::string> given;
  for (const auto& [name, source] : sources)
    if (f.has(name)) given.push_back(name), m.source = source;
  if (given.size() != 1)
    throw f.error(given.empty() ? "grdecl" : given[1],
                  given.empty() ? "a field needs its source: one of grdecl, init, elevation_table, depth_table, map, cells"
                                : fmt::format("two sources ({} and {}): give one", given[0], given[1]));
  const std::string& source = given[0];
  const auto need = [&](const std::string& k, bool wanted) {
    if (f.has(k) != wanted)
      throw f.error(k, wanted ? fmt::format("is required with {}", source) : fmt::format("does not go with {}", source));
  };
  const bool grid_source = m.source == MaterialField::Source::Grdecl || m.source == MaterialField::Source::Init;
  need("keyword", grid_source);
  need("field", m.source == MaterialField::Source::Cells);
  if (f.has("grid") && !grid_source) need("grid", false);
  if (f.has("offset_m") && !grid_source) need("offset_m", false);
  if (f.has("date") && m.source != MaterialField::Source::Cells) need("date", false);
  const auto existing = [&](const std::string& k) {
    const std::string path = resolve_relative(case_path, f.string(k));
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw f.error(k, fmt::format("no such file: {}", path));
    return path;
  };
  if (m.source == MaterialField::Source::Table) {
    m.by_depth = source == "depth_table";
    std::vector<std::string> row_where;
    const auto rows = f.number_rows(source, 2, &row_where);
    for (std::size_t r = 0; r < rows.size(); ++r) {
      if (r > 0 && !(rows[r][0] > rows[r - 1][0]))
        throw InputError(row_where[r], fmt::format("'{}' row {}: {} m after {} m (expected rows in increasing {})", key, r + 1,
                                                   rows[r][0], rows[r - 1][0], m.by_depth ? "depth" : "elevation"));
      m.rows.push_back({rows[r][0], rows[r][1]});
    }
  } else {
    m.file = existing(source);
  }
  if (grid_source) {
    m.keyword = f.string("keyword");
    if (f.has("grid")) m.grid = existing("grid");
    if (f.has("offset_m")) {
      const auto o = f.numbers("offset_m");
      if (o.size() != 3) throw f.error("offset_m", fmt::format("has {} numbers (expected [dx, dy, dz] in m)", o.size()));
      m.offset_m = {o[0], o[1], o[2]};
    }
  }
  if (m.source == MaterialField::Source::Cells) {
    m.keyword = f.string("field");
    m.date = f.string_opt("date").value_or("");
  }
  m.scale = positive(f, "scale", f.number_or("scale", 1.0));
  // A table's values are known now: each checked as the number would be.
  for (std::size_t r = 0; r < m.rows.size(); ++r)
    if (const std::string why = material_value_problem(key, m.scale * m.si * m.rows[r].value); !why.empty())
      throw f.error(source, fmt::format("row {}: {}", r + 1, why));
  return m;
}

MaterialSpec parse_material(const TomlTable& t, const Collect& ok, bool& named) {
  MaterialSpec m;
  m.where = t.where();
  ok([&] {
    if (t.has("Hmax_azimuth_deg"))
      throw t.error("Hmax_azimuth_deg", "the azimuth of sigma'_Hmax is global: set it in [initial_stress] (a material may "
                                        "set only its own k0, k_Hmax, k_hmin)");
  });
  t.reject_unknown({"name", "law", "biot", "nu", "nu_z", "Eh_over_Ez", "nuh_over_nuz", "Gh_over_Gz", "cm_a", "cm_b", "c_R",
                    "E_MPa", "K_m_per_s", "porosity", "sigma_z_min_MPa", "k0", "k_Hmax", "k_hmin", "Hmax_azimuth_deg"},
                   ok.errors);
  // Constants given as fields: read here, their members NaN; the number checks below skip them.
  std::set<std::string> fields;
  for (const std::string& key : t.keys()) {
    static const std::set<std::string> known = {"name", "law", "biot", "nu", "nu_z", "Eh_over_Ez", "nuh_over_nuz", "Gh_over_Gz",
                                                "cm_a", "cm_b", "c_R", "E_MPa", "porosity", "sigma_z_min_MPa", "k0", "k_Hmax", "k_hmin"};
    if (!known.count(key) || !t.is_table(key)) continue;  // (unknown keys: reported above)
    ok([&] {
      if (!material_key_may_vary(key))
        throw t.error(key, "cannot vary in space (a number; the constants that may be fields: biot, nu, nu_z, Eh_over_Ez, "
                           "nuh_over_nuz, Gh_over_Gz, cm_a, cm_b, c_R, E_MPa, K_m_per_s, porosity)");
      m.fields.push_back(parse_field(t.table(key), key, t.file()));
      m.set_value(key, std::numeric_limits<double>::quiet_NaN());
    });
    fields.insert(key);
  }
  const auto number = [&](const std::string& key) { return t.has(key) && !fields.count(key); };
  named = ok([&] { m.name = t.string("name"); });
  ok([&] { m.law = t.has("law") ? parse_law(t) : MaterialLaw::ElasticDepth; });
  ok([&] {
    if (fields.count("biot")) return;
    m.biot = t.number_or("biot", 1.0);
    if (m.biot < 0 || m.biot > 1) throw t.error("biot", "must lie in [0, 1]");
  });
  const bool nu_read = ok([&] {
    if (t.has("nu") && t.has("nu_z")) throw t.error("nu", "give either nu (isotropic) or nu_z, not both");
    if (fields.count("nu") || fields.count("nu_z")) return;
    const double nu = t.has("nu") ? t.number("nu") : t.number_or("nu_z", 0.3);
    const std::string nu_key = t.has("nu") ? "nu" : "nu_z";
    if (!(nu > -1 && nu < 0.5)) throw t.error(nu_key, fmt::format("Poisson ratio {} outside (-1, 0.5)", nu));
    m.nu_z = nu;
  }) && !fields.count("nu") && !fields.count("nu_z");
  ok([&] {
    if (!fields.count("Eh_over_Ez")) m.Eh_over_Ez = positive(t, "Eh_over_Ez", t.number_or("Eh_over_Ez", 1.0));
  });
  ok([&] {
    if (fields.count("nuh_over_nuz")) return;
    m.nuh_over_nuz = t.number_or("nuh_over_nuz", 1.0);
    const double nu_h = m.nu_z * m.nuh_over_nuz;
    if (nu_read && !(nu_h > -1 && nu_h < 1))
      throw t.error("nuh_over_nuz", fmt::format("horizontal Poisson ratio {} outside (-1, 1)", nu_h));
  });
  ok([&] {
    if (!fields.count("Gh_over_Gz")) m.Gh_over_Gz = positive(t, "Gh_over_Gz", t.number_or("Gh_over_Gz", 1.0));
  });
  ok([&] {
    if (!fields.count("cm_a")) m.cm_a = positive(t, "cm_a", t.number_or("cm_a", 1.0044e-2));
  });
  ok([&] {
    if (fields.count("cm_b")) return;
    m.cm_b = t.number_or("cm_b", 1.1347);
    if (!(m.cm_b >= 0))  // (non-finite numbers are refused by the TOML reader)
      throw t.error("cm_b",
                    fmt::format("must not be negative (c_M = cm_a sigma^-cm_b decreases with stress), got {}", m.cm_b));
  });
  ok([&] {
    if (number("c_R")) m.c_R = positive(t, "c_R", t.number("c_R"));
  });
  ok([&] {
    if (t.is_table("sigma_z_min_MPa")) return;  // (refused above)
    m.sigma_z_min_MPa = positive(t, "sigma_z_min_MPa", t.number_or("sigma_z_min_MPa", 0.1));
  });
  ok([&] {
    if (number("E_MPa")) m.E_Pa = positive(t, "E_MPa", t.number("E_MPa")) * kMPa;
  });
  // (A value given but refused above is one problem, not also a missing one.)
  ok([&] {
    if (m.law == MaterialLaw::Linear && !t.has("E_MPa")) throw t.error("E_MPa", "is required for law = \"linear\"");
  });
  ok([&] {
    if (m.law == MaterialLaw::Hypoplastic && !t.has("c_R")) throw t.error("c_R", "is required for law = \"hypoplastic\"");
  });
  ok([&] {
    if (!t.has("K_m_per_s")) return;
    // [Kx, Ky, Kz], each a number or a field.
    const auto items = t.items("K_m_per_s");
    if (items.size() != 3) throw t.error("K_m_per_s", "expected [Kx, Ky, Kz]");
    std::array<double, 3> k{};
    for (std::size_t d = 0; d < 3; ++d) {
      const std::string key = fmt::format("K_m_per_s[{}]", d);
      if (items[d].is_table()) {
        m.fields.push_back(parse_field(items[d], key, t.file()));
        k[d] = std::numeric_limits<double>::quiet_NaN();
        continue;
      }
      const auto v = items[d].as_number();
      if (!v) throw t.error("K_m_per_s", "expected [Kx, Ky, Kz], each a number or a field { ... }");
      if (!(*v > 0)) throw t.error("K_m_per_s", fmt::format("conductivities must be positive, got {}", *v));
      k[d] = *v;
    }
    m.K = k;
  });
  ok([&] {
    if (!number("porosity")) return;
    const double n = t.number("porosity");
    if (!(n > 0 && n < 1)) throw t.error("porosity", "must lie in (0, 1)");
    m.porosity = n;
  });
  for (const char* key : {"k0", "k_Hmax", "k_hmin"})
    if (t.is_table(key)) return m;  // (refused above; read_ratios would say it again)
  read_ratios(t, m.k_Hmax, m.k_hmin, ok, true);
  return m;
}

// A pool's gas column: the contact (an elevation) with the gas density or gradient, lighter than water.
void read_gas_column(const TomlTable& t, PoolSpec& p, double hydrostatic_gradient, const Collect& ok) {
  const bool contact = t.has("gas_water_contact_m");
  const int weights = t.has("gas_density_kg_per_m3") + t.has("gas_gradient_MPa_per_m");
  ok([&] {
    if (weights > 1) throw t.error("gas_gradient_MPa_per_m", "given together with gas_density_kg_per_m3 (give one)");
    if (contact && weights == 0)
      throw t.error("gas_water_contact_m", "needs the gas weight (gas_density_kg_per_m3 or gas_gradient_MPa_per_m)");
    if (!contact && weights > 0)
      throw t.error(t.has("gas_density_kg_per_m3") ? "gas_density_kg_per_m3" : "gas_gradient_MPa_per_m",
                    "needs gas_water_contact_m (the elevation of the gas-water contact, m)");
  });
  if (!contact || weights != 1) return;
  ok([&] {
    const std::string key = t.has("gas_density_kg_per_m3") ? "gas_density_kg_per_m3" : "gas_gradient_MPa_per_m";
    const double v = t.number(key), g = key == "gas_density_kg_per_m3" ? v * kGravity : v * kMPa;
    if (!(g >= 0) || !(g < hydrostatic_gradient))
      throw t.error(key, fmt::format("{} gives a gas gradient of {:.6g} MPa/m, outside [0, {:.6g}) (gas is lighter than the "
                                     "pore water's hydrostatic gradient)", v, g / kMPa, hydrostatic_gradient / kMPa));
    p.gas_gradient_Pa_per_m = g;
    p.gas_water_contact_m = t.number("gas_water_contact_m");
  });
}

PoolSpec parse_pool(const TomlTable& t, double hydrostatic_gradient, const Collect& ok) {
  t.reject_unknown({"name", "materials", "aquifer_materials", "schedule", "column", "reference_pressure_MPa", "gas_water_contact_m",
                    "gas_density_kg_per_m3", "gas_gradient_MPa_per_m"},
                   ok.errors);
  PoolSpec p;
  p.where = t.where();
  ok([&] { p.name = t.string("name"); });
  ok([&] {
    const auto materials = t.strings("materials");
    if (materials.empty()) throw t.error("materials", "needs at least one material");
    p.materials = materials;
  });
  ok([&] {
    if (t.has("aquifer_materials")) p.aquifer_materials = t.strings("aquifer_materials");
  });
  ok([&] { p.schedule = resolve_relative(t.file(), t.string("schedule")); });
  const bool column_read = ok([&] {
    const std::string column = t.has("column") ? t.string("column") : "p_norm";
    if (column != "p_norm" && column != "p_MPa") throw t.error("column", "must be p_norm or p_MPa");
    p.column = column;
  });
  ok([&] {
    if (t.has("reference_pressure_MPa"))
      p.reference_pressure_Pa = positive(t, "reference_pressure_MPa", t.number("reference_pressure_MPa")) * kMPa;
  });
  ok([&] {
    if (column_read && p.column == "p_norm" && !t.has("reference_pressure_MPa"))
      throw t.error("reference_pressure_MPa", "is required for a normalized schedule (column = \"p_norm\")");
  });
  read_gas_column(t, p, hydrostatic_gradient, ok);
  return p;
}

FaultSpec parse_fault(const TomlTable& t, const Collect& ok) {
  t.reject_unknown({"name", "cohesion_MPa", "friction_deg"}, ok.errors);
  FaultSpec f;
  f.where = t.where();
  ok([&] { f.name = t.string("name"); });
  ok([&] {
    f.cohesion_Pa = t.number_or("cohesion_MPa", 0.0) * kMPa;
    if (f.cohesion_Pa < 0) throw t.error("cohesion_MPa", "must not be negative");
  });
  ok([&] {
    f.friction_deg = t.number_or("friction_deg", 30.0);
    if (!(f.friction_deg > 0 && f.friction_deg < 90)) throw t.error("friction_deg", "must lie in (0, 90) degrees");
  });
  return f;
}

SealSpec parse_seal(const TomlTable& t, const Collect& ok) {
  t.reject_unknown({"material", "cohesion_MPa", "friction_deg", "tensile_strength_MPa"}, ok.errors);
  SealSpec s;
  s.where = t.where();
  ok([&] { s.material = t.string("material"); });
  ok([&] {
    s.cohesion_Pa = t.number_or("cohesion_MPa", 0.0) * kMPa;
    if (!(s.cohesion_Pa >= 0 && std::isfinite(s.cohesion_Pa))) throw t.error("cohesion_MPa", "must be finite and not negative");
  });
  ok([&] {
    s.friction_deg = t.number_or("friction_deg", 30.0);
    if (!(s.friction_deg > 0 && s.friction_deg < 90)) throw t.error("friction_deg", "must lie in (0, 90) degrees");
  });
  ok([&] {
    s.tensile_strength_Pa = t.number_or("tensile_strength_MPa", 0.0) * kMPa;
    if (!(s.tensile_strength_Pa >= 0 && std::isfinite(s.tensile_strength_Pa)))
      throw t.error("tensile_strength_MPa", "must be finite and not negative");
  });
  return s;
}

// The entry, or nothing when its group cannot be read (then it loads nothing and is not compared).
std::optional<TractionSpec> parse_traction(const TomlTable& t, const Collect& ok) {
  t.reject_unknown({"group", "traction_MPa", "in_situ"}, ok.errors);
  TractionSpec s;
  s.where = t.where();
  const bool named = ok([&] {
    s.group = t.string("group");
    if (s.group.rfind("bnd:", 0) == 0) s.group = s.group.substr(4);
    if (s.group.empty()) throw t.error("group", "is empty (expected the name of a mesh group bnd:<name>, e.g. \"east\")");
  });
  const bool kind_read = ok([&] { s.in_situ = t.boolean_or("in_situ", false); });
  ok([&] {
    if (!kind_read) return;
    if (s.in_situ && t.has("traction_MPa"))
      throw t.error("traction_MPa", "given together with in_situ = true (give one: a constant traction or the in-situ one)");
    if (!s.in_situ && !t.has("traction_MPa"))
      throw InputError(s.where, fmt::format("boundary_traction on '{}' has no value (expected traction_MPa = [tx, ty, tz] or "
                                            "in_situ = true)", s.group));
  });
  ok([&] {
    if (!t.has("traction_MPa")) return;
    const auto v = t.numbers("traction_MPa");
    if (v.size() != 3) throw t.error("traction_MPa", fmt::format("has {} values (expected [tx, ty, tz] in MPa)", v.size()));
    for (int k = 0; k < 3; ++k) s.traction_Pa[k] = v[k] * kMPa;
  });
  if (!named) return std::nullopt;
  return s;
}

const std::set<std::string> kBoundaryNames{"west", "east", "south", "north", "bottom", "top"};

// Boundary names as in the mesh group without its prefix: "west" or "bnd:west".
std::vector<std::string> boundary_list(const TomlTable& t, const std::string& key) {
  auto v = t.strings(key);
  for (auto& b : v)
    if (b.rfind("bnd:", 0) == 0) b = b.substr(4);
  for (const auto& b : v)
    if (!kBoundaryNames.count(b)) throw t.error(key, fmt::format("unknown boundary '{}' (west, east, south, north, bottom, top)", b));
  return v;
}

}  // namespace

bool material_key_may_vary(const std::string& key) {
  static const std::set<std::string> keys = {"biot", "nu", "nu_z", "Eh_over_Ez", "nuh_over_nuz", "Gh_over_Gz", "cm_a", "cm_b",
                                             "c_R", "E_MPa", "porosity", "K_m_per_s[0]", "K_m_per_s[1]", "K_m_per_s[2]"};
  return keys.count(key) > 0;
}

std::string material_value_problem(const std::string& key, double v) {
  if (!std::isfinite(v)) return fmt::format("{} = {} (expected a finite number)", key, v);
  if (key == "biot") return v >= 0 && v <= 1 ? "" : fmt::format("biot = {} outside [0, 1]", v);
  if (key == "porosity") return v > 0 && v < 1 ? "" : fmt::format("porosity = {} outside (0, 1)", v);
  if (key == "nu" || key == "nu_z") return v > -1 && v < 0.5 ? "" : fmt::format("Poisson ratio {} = {} outside (-1, 0.5)", key, v);
  if (key == "cm_b") return v >= 0 ? "" : fmt::format("cm_b = {} is negative (expected >= 0)", v);
  if (key == "nuh_over_nuz") return "";  // nu_h = nu_z nuh_over_nuz in (-1, 1) is checked with nu_z
  return v > 0 ? "" : fmt::format("{} = {:g} (expected a positive number)", key, v);
}

const MaterialField* MaterialSpec::field(const std::string& key) const {
  for (const auto& f : fields)
    if (f.key == key) return &f;
  return nullptr;
}

void MaterialSpec::set_value(const std::string& key, double v) {
  if (key == "biot") biot = v;
  else if (key == "nu" || key == "nu_z") nu_z = v;
  else if (key == "Eh_over_Ez") Eh_over_Ez = v;
  else if (key == "nuh_over_nuz") nuh_over_nuz = v;
  else if (key == "Gh_over_Gz") Gh_over_Gz = v;
  else if (key == "cm_a") cm_a = v;
  else if (key == "cm_b") cm_b = v;
  else if (key == "c_R") c_R = v;
  else if (key == "E_MPa") E_Pa = v;
  else if (key == "porosity") porosity = v;
  else if (key.rfind("K_m_per_s[", 0) == 0 && key.size() == 12 && key[10] >= '0' && key[10] <= '2') {
    if (!K) K = std::array<double, 3>{};
    (*K)[static_cast<std::size_t>(key[10] - '0')] = v;
  } else {
    throw std::logic_error("MaterialSpec::set_value: '" + key + "' cannot vary");
  }
}

const MaterialSpec* CaseFile::material(const std::string& name) const {
  for (const auto& m : materials)
    if (m.name == name) return &m;
  return nullptr;
}

namespace {

void read_model_and_water(const TomlTable& root, CaseFile& c, const Collect& ok) {
  ok([&] { c.crs = root.string_opt("crs").value_or(""); });
  std::optional<TomlTable> m, w;
  ok([&] { m = root.table_opt("model"); });
  if (m) {
    m->reject_unknown({"name", "start", "end"}, ok.errors);
    ok([&] { c.start_date = m->string_opt("start").value_or(""); });
    ok([&] { c.end_date = m->string_opt("end").value_or(""); });
  }
  ok([&] { w = root.table_opt("water"); });
  if (w) {
    w->reject_unknown({"unit_weight_N_per_m3", "compressibility_per_MPa"}, ok.errors);
    ok([&] { c.water_unit_weight = positive(*w, "unit_weight_N_per_m3", w->number_or("unit_weight_N_per_m3", 9810.0)); });
    ok([&] {
      const double per_Pa = w->number_or("compressibility_per_MPa", 4.4e-4) / kMPa;
      if (!(per_Pa >= 0))
        throw w->error("compressibility_per_MPa", fmt::format("must not be negative, got {}", per_Pa * kMPa));
      c.water_compressibility = per_Pa;
    });
  }
}

// A table by depth of [initial_stress]: rows [depth_m, value], depths strictly increasing from 0
// (from above 0 unless `depth_zero_allowed`), each value checked by `value_ok` (empty: fine, else
// what is wrong with it) and scaled by `unit` to SI. Errors name the row's line.
template <class ValueOk>
std::vector<DepthValue> depth_table(const TomlTable& t, const std::string& key, bool depth_zero_allowed, double unit,
                                    ValueOk value_ok) {
  std::vector<std::string> where;
  const auto rows = t.number_rows(key, 2, &where);
  std::vector<DepthValue> table;
  const std::string name = "'initial_stress." + key + "'";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double d = rows[i][0], v = rows[i][1];
    if (!(d >= 0) || (!depth_zero_allowed && !(d > 0)))
      throw InputError(where[i], fmt::format("{} row {}: depth {} m is {} (depths are metres below surface_elevation_m)", name,
                                             i + 1, d, depth_zero_allowed ? "negative" : "not below the surface (expected > 0)"));
    if (i > 0 && !(d > rows[i - 1][0]))
      throw InputError(where[i], fmt::format("{} row {}: depth {} m does not follow {} m (the table must go down in depth, "
                                             "strictly increasing)", name, i + 1, d, rows[i - 1][0]));
    if (const std::string bad = value_ok(v); !bad.empty())
      throw InputError(where[i], fmt::format("{} row {}: {} {}", name, i + 1, v, bad));
    table.push_back({d, v * unit});
  }
  return table;
}

// S_v as a table (InitialStressSpec::sv_gradient): a density log or gradients per interval, not
// with the gradient; every gradient above the hydrostatic one (`hydro`: that one was read).
void read_sv_table(const TomlTable& t, InitialStressSpec& is, bool hydro, const Collect& ok) {
  // S_v: one of the gradient, a density log, gradients per interval.
  const int sv_forms = t.has("lithostatic_gradient_MPa_per_m") + t.has("Sv_density_kg_per_m3") + t.has("Sv_gradients_MPa_per_m");
  const bool sv_one = ok([&] {
    if (sv_forms > 1)
      throw t.error(t.has("Sv_gradients_MPa_per_m") ? "Sv_gradients_MPa_per_m" : "Sv_density_kg_per_m3",
                     "S_v is given twice (give one of lithostatic_gradient_MPa_per_m, Sv_density_kg_per_m3, Sv_gradients_MPa_per_m)");
  });
  // A gradient of S_v at or below the hydrostatic one leaves no effective vertical stress.
  auto above_water = [&](double gradient_Pa_per_m) -> std::string {
    if (!(gradient_Pa_per_m > 0)) return "is not positive";
    if (hydro && gradient_Pa_per_m <= is.hydrostatic_gradient)
      return fmt::format("gives a gradient of S_v of {:.6g} MPa/m, not above the hydrostatic {:.6g} MPa/m", gradient_Pa_per_m / kMPa,
                         is.hydrostatic_gradient / kMPa);
    return {};
  };
  if (sv_one && t.has("Sv_density_kg_per_m3"))
    ok([&] {
      // rho g by depth: linear between the log's samples, as the log.
      is.sv_gradient = depth_table(t, "Sv_density_kg_per_m3", true, kGravity, [&](double rho) {
        const std::string bad = above_water(rho * kGravity);
        return bad.empty() ? bad : "kg/m3 " + bad;
      });
    });
  if (sv_one && t.has("Sv_gradients_MPa_per_m"))
    ok([&] {
      // [top of the interval, its gradient]: a step at each top.
      const auto rows = depth_table(t, "Sv_gradients_MPa_per_m", true, kMPa, [&](double g) {
        const std::string bad = above_water(g * kMPa);
        return bad.empty() ? bad : "MPa/m " + bad;
      });
      if (rows.front().depth != 0)
        throw t.error("Sv_gradients_MPa_per_m", fmt::format("the first interval starts at depth {} m (expected 0: the intervals "
                                                             "cover the column from the surface down)", rows.front().depth));
      for (std::size_t i = 0; i < rows.size(); ++i) {
        if (i > 0) is.sv_gradient.push_back({rows[i].depth, rows[i - 1].value});
        is.sv_gradient.push_back(rows[i]);
      }
    });
}

// The tables of total horizontal stress and of the overpressure.
void read_stress_tables(const TomlTable& t, InitialStressSpec& is, const Collect& ok) {
  const bool table_h = t.has("Shmin_MPa");
  auto stress_ok = [](double v) { return v > 0 ? std::string() : std::string("MPa is not positive (a total stress, compression positive)"); };
  if (table_h) ok([&] { is.shmin = depth_table(t, "Shmin_MPa", false, kMPa, stress_ok); });
  for (const char* key : {"SHmax_MPa", "SHmax_over_Shmin"})
    if (t.has(key) && !table_h)
      ok([&] { throw t.error(key, "needs Shmin_MPa (S_Hmax is given relative to, or beside, the S_hmin table)"); });
  ok([&] {
    if (t.has("SHmax_MPa") && t.has("SHmax_over_Shmin"))
      throw t.error("SHmax_over_Shmin", "given together with SHmax_MPa (give S_Hmax one way)");
  });
  if (table_h && t.has("SHmax_MPa")) ok([&] { is.sHmax = depth_table(t, "SHmax_MPa", false, kMPa, stress_ok); });
  if (table_h && t.has("SHmax_over_Shmin"))
    ok([&] {
      const double r = t.number("SHmax_over_Shmin");
      if (!(r >= 1)) throw t.error("SHmax_over_Shmin", fmt::format("{} is below 1 (S_Hmax is the larger horizontal stress)", r));
      is.sHmax_over_shmin = r;
    });
  if (t.has("overpressure_MPa"))
    ok([&] { is.overpressure = depth_table(t, "overpressure_MPa", true, kMPa, [](double) { return std::string(); }); });
}

void read_initial_stress(const TomlTable& root, CaseFile& c, const Collect& ok) {
  std::optional<TomlTable> s;
  ok([&] { s = root.table_opt("initial_stress"); });
  if (!s) return;
  s->reject_unknown({"surface_elevation_m", "lithostatic_gradient_MPa_per_m", "hydrostatic_gradient_MPa_per_m", "k0", "k_Hmax",
                     "k_hmin", "Hmax_azimuth_deg", "Sv_density_kg_per_m3", "Sv_gradients_MPa_per_m", "Shmin_MPa", "SHmax_MPa",
                     "SHmax_over_Shmin", "overpressure_MPa", "regime"},
                    ok.errors);
  auto& is = c.initial_stress;
  for (const char* key : {"regime", "Shmin_MPa", "SHmax_MPa", "SHmax_over_Shmin", "overpressure_MPa", "Sv_density_kg_per_m3",
                          "Sv_gradients_MPa_per_m", "k0", "k_Hmax", "k_hmin"})
    if (s->has(key)) c.key_lines[std::string("initial_stress.") + key] = s->where(key);
  ok([&] { is.surface_elevation = s->number_or("surface_elevation_m", 0.0); });
  const bool litho = ok([&] {
    is.lithostatic_gradient =
        positive(*s, "lithostatic_gradient_MPa_per_m", s->number_or("lithostatic_gradient_MPa_per_m", 0.0226)) * kMPa;
  });
  const bool hydro = ok([&] {
    is.hydrostatic_gradient = s->number_or("hydrostatic_gradient_MPa_per_m", 0.0100) * kMPa;
    if (is.hydrostatic_gradient < 0 || (litho && !s->has("Sv_density_kg_per_m3") && !s->has("Sv_gradients_MPa_per_m") &&
                                        is.hydrostatic_gradient >= is.lithostatic_gradient))
      throw s->error("hydrostatic_gradient_MPa_per_m", "must lie in [0, lithostatic gradient)");
  });
  read_sv_table(*s, is, hydro, ok);
  const bool table_h = s->has("Shmin_MPa");
  ok([&] { is.k0 = positive(*s, "k0", s->number_or("k0", 1.0)); });
  // k0 is the shorthand for k_Hmax = k_hmin = k0 (kH(), kh()): the optionals stay empty with k0,
  // and k0 with either of them is refused by read_ratios.
  if (s->has("k_Hmax") || s->has("k_hmin")) read_ratios(*s, is.k_Hmax, is.k_hmin, ok, false);
  for (const char* key : {"k0", "k_Hmax", "k_hmin"})
    if (table_h && s->has(key))
      ok([&] {
        throw s->error(key, "given together with Shmin_MPa (the horizontal stresses come from the S_hmin table, or from k "
                            "ratios: give one form)");
      });
  read_stress_tables(*s, is, ok);
  ok([&] {
    if (!s->has("regime")) return;
    const std::string r = s->string("regime");
    if (r != "normal" && r != "strike-slip" && r != "reverse")
      throw s->error("regime", fmt::format("'{}' is not one of normal, strike-slip, reverse", r));
    is.regime = r;
  });
  ok([&] {
    is.Hmax_azimuth_deg = s->number_or("Hmax_azimuth_deg", 0.0);
    if (!(is.Hmax_azimuth_deg >= 0 && is.Hmax_azimuth_deg < 360))
      throw s->error("Hmax_azimuth_deg", fmt::format("{} is outside [0, 360) degrees (clockwise from north, the mesh's +y axis)",
                                                     is.Hmax_azimuth_deg));
  });
}

void read_materials_and_pools(const TomlTable& root, CaseFile& c, const Collect& ok) {
  std::vector<TomlTable> materials, pools;
  ok([&] { materials = root.tables("material"); });
  std::set<std::string> names;
  bool all_named = true;  // a pool's material is compared only with a complete list of names
  for (const auto& t : materials) {
    bool named = false;
    c.materials.push_back(parse_material(t, ok, named));
    all_named = all_named && named;
    if (named && !names.insert(c.materials.back().name).second)
      ok([&] { throw t.error("name", "material defined twice"); });
  }
  ok([&] { pools = root.tables("pool"); });
  for (const auto& t : pools) c.pools.push_back(parse_pool(t, c.initial_stress.hydrostatic_gradient, ok));
  // The table form's horizontal stresses are the table's in every rock: a material's own ratios
  // would have nothing to scale.
  if (c.initial_stress.horizontal_table())
    for (std::size_t i = 0; i < materials.size(); ++i)
      for (const char* key : {"k0", "k_Hmax", "k_hmin"})
        if (materials[i].has(key))
          ok([&] {
            throw materials[i].error(key, "a material's own stress ratio with [initial_stress] Shmin_MPa (the horizontal "
                                          "stresses come from the S_hmin table in every rock; give the ratios or the table)");
          });
  if (!all_named) return;
  // A material holds one pore fluid at the initial state: at most one pool with a gas column lists it.
  std::map<std::string, const PoolSpec*> gas_pool;
  for (const auto& p : c.pools)
    if (p.gas_water_contact_m)
      for (const auto& m : p.materials)
        if (const auto placed = gas_pool.emplace(m, &p); !placed.second) {
          const std::string other = placed.first->second->name;  // (a structured binding: not capturable in C++17 clang)
          ok([&] {
            throw InputError(p.where, fmt::format("pool '{}': material '{}' is also in pool '{}', and both have a gas column (a "
                                                  "rock has one gas-water contact)", p.name, m, other));
          });
        }
  for (const auto& p : c.pools)
    for (const auto& list : {p.materials, p.aquifer_materials})
      for (const auto& m : list)
        if (!c.material(m))
          ok([&] { throw InputError(p.where, fmt::format("pool '{}': material '{}' is not defined", p.name, m)); });
}

void read_boundaries(const TomlTable& root, CaseFile& c, const Collect& ok) {
  std::optional<TomlTable> b;
  ok([&] { b = root.table_opt("boundary"); });
  const bool explicit_fixed = b && b->has("fixed");
  if (b) {
    b->reject_unknown({"fixed", "rollers", "free"}, ok.errors);
    const bool fixed = ok([&] {
      if (b->has("fixed")) c.fixed_boundaries = boundary_list(*b, "fixed");
    });
    const bool rollers = ok([&] {
      if (b->has("rollers")) c.roller_boundaries = boundary_list(*b, "rollers");
    });
    const bool free = ok([&] {
      if (b->has("free")) c.free_boundaries = boundary_list(*b, "free");
    });
    if (fixed && rollers)
      for (const auto& r : c.roller_boundaries)
        for (const auto& f : c.fixed_boundaries)
          if (r == f) ok([&] { throw b->error("rollers", fmt::format("boundary '{}' is also in fixed", r)); });
    if (fixed && free)
      for (const auto& r : c.free_boundaries)
        for (const auto& f : c.fixed_boundaries)
          if (r == f) ok([&] { throw b->error("free", fmt::format("boundary '{}' is also in fixed", r)); });
    if (rollers && free)
      for (const auto& r : c.free_boundaries)
        for (const auto& f : c.roller_boundaries)
          if (r == f) ok([&] { throw b->error("free", fmt::format("boundary '{}' is also in rollers", r)); });
  }
  std::vector<TomlTable> entries;
  ok([&] { entries = root.tables("boundary_traction"); });
  for (const auto& t : entries) {
    const auto spec = parse_traction(t, ok);
    if (!spec) continue;
    const std::string& g = spec->group;
    bool fine = true;
    for (const auto& earlier : c.tractions)
      if (earlier.group == g)
        fine = ok([&] {
          throw t.error("group", fmt::format("boundary '{}' is already loaded by the entry at {}", g, earlier.where));
        }) && fine;
    // A group is held or loaded, not both (`free` states that a side carries no load beyond the initial state).
    for (const auto& [list, name] : {std::pair{&c.fixed_boundaries, "fixed"}, std::pair{&c.roller_boundaries, "rollers"},
                                     std::pair{&c.free_boundaries, "free"}})
      if (std::find(list->begin(), list->end(), g) != list->end()) {
        const char* what = name;  // (clang 14 cannot capture a structured binding)
        fine = ok([&] {
          throw t.error("group", fmt::format("boundary '{}' is also in [boundary] {}{} (a group is either held or loaded: "
                                             "take it out of {})", g, what,
                                             std::string(what) == "fixed" && !explicit_fixed
                                                 ? " (the default: fixed = [\"west\", \"east\", \"south\", \"north\", \"bottom\"])"
                                                 : "",
                                             what));
        }) && fine;
      }
    if (fine) c.tractions.push_back(*spec);
  }
}

void read_faults(const TomlTable& root, CaseFile& c, const Collect& ok) {
  std::vector<TomlTable> faults;
  ok([&] { faults = root.tables("fault"); });
  for (const auto& t : faults) c.faults.push_back(parse_fault(t, ok));
}

// [[seal]]: one entry per material, each naming a [[material]].
void read_seals(const TomlTable& root, CaseFile& c, const Collect& ok) {
  std::vector<TomlTable> seals;
  ok([&] { seals = root.tables("seal"); });
  std::set<std::string> named;
  for (const auto& t : seals) {
    SealSpec s = parse_seal(t, ok);
    if (!s.material.empty()) {
      if (!c.material(s.material))
        ok([&] { throw t.error("material", fmt::format("'{}' is not a [[material]] of the case", s.material)); });
      else if (!named.insert(s.material).second)
        ok([&] { throw t.error("material", fmt::format("'{}' is a seal twice (one [[seal]] per material)", s.material)); });
    }
    c.seals.push_back(std::move(s));
  }
}

// The numbers of [solver], each with the range ugs-solve can use and why, checked here and nowhere
// else: "case.toml:21: [solver] tolerance = 1: outside [1e-14, 1) (a relative residual ...)".
// Integers are checked before they are narrowed to int (2^32 + 1 would read as 1).
struct SolverNumber {
  const char* key;
  double fallback, lo, hi;  // hi = infinity: no upper limit
  bool lo_open, hi_open, integer;
  const char* why;
};
constexpr double kNoUpper = std::numeric_limits<double>::infinity();
constexpr SolverNumber kSolverNumbers[] = {
    // A tolerance of 1 or more accepts the first iterate of every step (no equilibrium, exit 0);
    // one below 1e-14 is beyond double precision (every step would fail after all its sub-steps).
    {"tolerance", 1e-8, 1e-14, 1, false, true, false, "a relative residual ||r|| / ||r_0||"},
    // 10^9 Newton iterations per sub-step never end.
    {"max_newton_iterations", 25, 1, 1000, false, false, true, "a step takes 2-25"},
    {"max_substeps", 64, 1, 4096, false, false, true, "sub-steps of a step that does not converge whole"},
    {"turning_point_tolerance_MPa", 1e-2, 0, kNoUpper, true, false, false, "a pressure change in MPa"},
};

void read_solver_numbers(const TomlTable& s, CaseFile& c, const Collect& ok) {
  for (const SolverNumber& n : kSolverNumbers) {
    double v = n.fallback;
    std::string text;
    const bool read = ok([&] {
      if (n.integer) {
        const long long i = s.integer_opt(n.key).value_or(static_cast<long long>(n.fallback));
        v = static_cast<double>(i);
        text = fmt::format("{}", i);
      } else {
        v = s.number_or(n.key, n.fallback);
        text = fmt::format("{}", v);
      }
    });
    if (!read) continue;
    const bool in = std::isfinite(v) && (n.lo_open ? v > n.lo : v >= n.lo) && (n.hi_open ? v < n.hi : v <= n.hi);
    if (!in) {
      const std::string range = n.hi == kNoUpper ? fmt::format("must be {} {}", n.lo_open ? ">" : ">=", n.lo)
                                                 : fmt::format("outside {}{}, {}{}", n.lo_open ? "(" : "[", n.lo, n.hi,
                                                               n.hi_open ? ")" : "]");
      ok.errors.add(s.where(n.key), fmt::format("[solver] {} = {}: {} ({})", n.key, text, range, n.why));
      continue;
    }
    const std::string key = n.key;
    if (key == "tolerance") c.newton_tolerance = v;
    else if (key == "max_newton_iterations") c.max_newton_iterations = static_cast<int>(v);
    else if (key == "max_substeps") c.max_substeps = static_cast<int>(v);
    else c.turning_point_tolerance = 1e6 * v;
  }
}

void read_solver(const TomlTable& root, CaseFile& c, const Collect& ok) {
  std::optional<TomlTable> s;
  ok([&] { s = root.table_opt("solver"); });
  if (!s) return;
  s->reject_unknown({"tolerance", "tolerance_of", "max_newton_iterations", "linear_solver", "inversion_rule", "max_substeps",
                     "reuse_preconditioner", "fault_solver", "steps", "turning_point_tolerance_MPa"},
                    ok.errors);
  for (const char* key : {"linear_solver", "fault_solver"})
    if (s->has(key)) c.key_lines[std::string("solver.") + key] = s->where(key);
  read_solver_numbers(*s, c, ok);
  // The names are checked by the solver libraries that own them (ugs/mechanics/case_section.hpp).
  ok([&] { c.linear_solver = s->string_opt("linear_solver").value_or("cg-hypre"); });
  const bool rule_read = ok([&] {
    const std::string rule = s->string_opt("inversion_rule").value_or("sigma-max");
    if (!std::set<std::string>{"sigma-max", "sigma-inversion", "stress-dependent"}.count(rule))
      throw s->error("inversion_rule", "must be one of sigma-max, sigma-inversion, stress-dependent");
    c.inversion_rule = rule;
  });
  ok([&] { c.reuse_preconditioner = s->boolean_or("reuse_preconditioner", true); });
  ok([&] {
    const std::string of = s->string_opt("tolerance_of").value_or("step");
    if (of != "step" && of != "total-load") throw s->error("tolerance_of", "must be one of step, total-load");
    c.tolerance_of = of;
  });
  ok([&] {
    const std::string steps = s->string_opt("steps").value_or("every-date");
    if (steps != "every-date" && steps != "turning-points" && steps != "turning-windows")
      throw s->error("steps", "must be one of every-date, turning-points, turning-windows");
    c.steps = steps;
    if (rule_read && c.steps != "every-date" && c.inversion_rule != "sigma-max")
      throw s->error("steps", c.steps + " needs inversion_rule = \"sigma-max\" (the other rules depend on the whole path)");
  });
  ok([&] { c.fault_solver = s->string_opt("fault_solver").value_or("auto"); });  // checked by ugs/contact/case_section.hpp
}

void read_scenario(const TomlTable& root, CaseFile& c, const Collect& ok) {
  std::optional<TomlTable> sc;
  ok([&] { sc = root.table_opt("scenario"); });
  if (!sc) return;
  sc->reject_unknown({"pressure_scale", "reference_date", "max_scale", "scale_tolerance"}, ok.errors);
  ok([&] {
    c.scenario_scale = sc->number_or("pressure_scale", 1.0);
    if (!(c.scenario_scale >= 0) || !std::isfinite(c.scenario_scale)) throw sc->error("pressure_scale", "must not be negative");
  });
  ok([&] {
    const std::string date = sc->string_opt("reference_date").value_or("");
    if (!date.empty() && !parse_iso_date(date))
      throw sc->error("reference_date", fmt::format("'{}' is not an ISO 8601 date", date));
    c.scenario_reference_date = date;
  });
  ok([&] { c.scenario_max_scale = positive(*sc, "max_scale", sc->number_or("max_scale", 10.0)); });
  ok([&] {
    c.scenario_tolerance = positive(*sc, "scale_tolerance", sc->number_or("scale_tolerance", 0.01));
    if (c.scenario_tolerance >= 1) throw sc->error("scale_tolerance", "must be below 1 (a relative width)");
  });
}

// The values of [seismicity] or of one [seismicity.fault.<name>]: each checked where given.
SeismicityValues read_seismicity_values(const TomlTable& t, const Collect& ok) {
  SeismicityValues v;
  v.where = t.where();
  ok([&] {
    if (!t.has("A_sigma_MPa")) return;
    const double a = positive(t, "A_sigma_MPa", t.number("A_sigma_MPa"));
    if (!(a >= 1e-6 && a <= 1e3)) throw t.error("A_sigma_MPa", fmt::format("{} is outside [1e-6, 1000] MPa", a));
    v.A_sigma_Pa = a * kMPa;
  });
  ok([&] {
    if (!t.has("stressing_rate_MPa_per_yr")) return;
    const double r = positive(t, "stressing_rate_MPa_per_yr", t.number("stressing_rate_MPa_per_yr"));
    if (!(r >= 1e-9 && r <= 1e3)) throw t.error("stressing_rate_MPa_per_yr", fmt::format("{} is outside [1e-9, 1000] MPa/yr", r));
    v.stressing_rate_Pa_per_s = r * kMPa / kSecondsPerYear;
  });
  ok([&] {
    if (!t.has("background_rate_per_yr_km2")) return;
    const double r = positive(t, "background_rate_per_yr_km2", t.number("background_rate_per_yr_km2"));
    if (!(r <= 1e6)) throw t.error("background_rate_per_yr_km2", fmt::format("{} is above 1e6 events per year per km2", r));
    v.background_rate_per_s_m2 = r / kSecondsPerYear / 1e6;
  });
  ok([&] {
    if (!t.has("M_c")) return;
    const double m = t.number("M_c");
    if (!(m >= -3 && m <= 10)) throw t.error("M_c", fmt::format("{} is outside [-3, 10] (a magnitude)", m));
    v.M_c = m;
  });
  ok([&] {
    if (!t.has("b_value")) return;
    const double b = t.number("b_value");
    if (!(b > 0 && b <= 5)) throw t.error("b_value", fmt::format("{} is outside (0, 5] (Gutenberg-Richter b, about 1)", b));
    v.b_value = b;
  });
  return v;
}

void read_report(const TomlTable& root, CaseFile& c, const Collect& ok) {
  std::optional<TomlTable> s;
  ok([&] { s = root.table_opt("report"); });
  if (!s) return;
  s->reject_unknown({"stress_pool", "phase", "chi_max", "uplift_max_mm", "settlement_max_mm", "tensile_margin_min_MPa",
                     "shear_margin_min_MPa"},
                    ok.errors);
  ReportSpec r;
  r.where = s->where();
  ok([&] {
    r.stress_pool = s->has("stress_pool") ? s->string("stress_pool") : "";
    if (r.stress_pool.empty() || c.pools.empty()) return;
    for (const auto& p : c.pools)
      if (p.name == r.stress_pool) return;
    throw s->error("stress_pool", fmt::format("'{}' is not a [[pool]] of the case", r.stress_pool));
  });
  auto limit = [&](const char* key, std::optional<double>& v, double lo, bool lo_open, double hi, const char* what) {
    ok([&] {
      if (!s->has(key)) return;
      const double x = s->number(key);
      if (!std::isfinite(x) || (lo_open ? x <= lo : x < lo) || x > hi)
        throw s->error(key, fmt::format("{} is outside {}{}, {}] ({})", x, lo_open ? "(" : "[", lo, hi, what));
      v = x;
    });
  };
  const double inf = std::numeric_limits<double>::max();
  limit("chi_max", r.chi_max, 0, true, 1, "a fault safety factor");
  limit("uplift_max_mm", r.uplift_max_mm, 0, true, inf, "mm of uplift over a phase");
  limit("settlement_max_mm", r.settlement_max_mm, 0, true, inf, "mm of settlement over a phase");
  limit("tensile_margin_min_MPa", r.tensile_margin_min_MPa, 0, false, inf, "MPa between the fracture and the pore pressure");
  limit("shear_margin_min_MPa", r.shear_margin_min_MPa, 0, false, inf, "MPa of shear stress below the Mohr-Coulomb line");
  std::vector<TomlTable> phases;
  ok([&] {
    if (s->has("phase")) phases = s->tables("phase");
  });
  std::set<std::string> names;
  for (const auto& t : phases) {
    t.reject_unknown({"name", "start", "end"}, ok.errors);
    ReportPhaseSpec p;
    ok([&] {
      p.name = t.string("name");
      if (p.name.empty()) throw t.error("name", "is empty");
      if (!names.insert(p.name).second) throw t.error("name", fmt::format("phase '{}' given twice", p.name));
    });
    const bool dates = ok([&] {
      p.start = t.string("start");
      if (!parse_iso_date(p.start)) throw t.error("start", fmt::format("'{}' is not an ISO 8601 date", p.start));
    }) && ok([&] {
      p.end = t.string("end");
      if (!parse_iso_date(p.end)) throw t.error("end", fmt::format("'{}' is not an ISO 8601 date", p.end));
    });
    if (dates && *parse_iso_date(p.start) >= *parse_iso_date(p.end))
      ok([&] { throw t.error("end", fmt::format("{} is not after the start {}", p.end, p.start)); });
    r.phases.push_back(std::move(p));
  }
  c.report = std::move(r);
}

void read_seismicity(const TomlTable& root, CaseFile& c, const Collect& ok) {
  std::optional<TomlTable> s;
  ok([&] { s = root.table_opt("seismicity"); });
  if (!s) return;
  static const std::set<std::string> value_keys{"A_sigma_MPa", "stressing_rate_MPa_per_yr", "background_rate_per_yr_km2", "M_c",
                                                "b_value"};
  std::set<std::string> keys = value_keys;
  keys.insert({"magnitudes", "fault"});
  s->reject_unknown(keys, ok.errors);
  SeismicitySpec spec;
  spec.values = read_seismicity_values(*s, ok);
  for (const char* key : {"A_sigma_MPa", "stressing_rate_MPa_per_yr", "background_rate_per_yr_km2", "M_c"})
    if (!s->has(key))
      ok([&] { throw InputError(s->where(), fmt::format("'seismicity.{}' is required in [seismicity] (docs/seismicity.md)", key)); });
  if (!spec.values.b_value && !s->has("b_value")) spec.values.b_value = 1.0;
  ok([&] {
    if (!s->has("magnitudes")) return;
    for (double m : s->numbers("magnitudes"))
      if (!(m >= -3 && m <= 10)) throw s->error("magnitudes", fmt::format("{} is outside [-3, 10] (a magnitude)", m));
    spec.magnitudes = s->numbers("magnitudes");
  });
  std::optional<TomlTable> faults;
  ok([&] {
    if (s->has("fault")) faults = s->table("fault");
  });
  if (faults)
    for (const auto& name : faults->keys()) {
      std::optional<TomlTable> f;
      ok([&] { f = faults->table(name); });
      if (!f) continue;
      f->reject_unknown(value_keys, ok.errors);
      spec.faults[name] = read_seismicity_values(*f, ok);
    }
  c.seismicity = std::move(spec);
}

void read_output(const TomlTable& root, CaseFile& c, const Collect& ok) {
  std::optional<TomlTable> o;
  ok([&] { o = root.table_opt("output"); });
  if (!o) return;
  o->reject_unknown({"dates", "fields", "checkpoint_every"}, ok.errors);
  ok([&] {
    if (o->has("dates")) c.output_dates = o->strings("dates");
  });
  for (const auto& d : c.output_dates)
    if (!parse_iso_date(d)) ok([&] { throw o->error("dates", fmt::format("'{}' is not an ISO 8601 date", d)); });
  ok([&] {
    if (o->has("fields")) c.output_fields = o->strings("fields");
  });
  static const std::set<std::string> known{"displacement", "strain", "stress", "stress_change", "cm", "state", "pressure"};
  for (const auto& f : c.output_fields)
    if (!known.count(f))
      ok([&] {
        throw o->error("fields", fmt::format("unknown field '{}' (displacement, strain, stress, stress_change, cm, state, "
                                             "pressure)", f));
      });
  ok([&] { c.checkpoint_every = integer_in(*o, "checkpoint_every", 0, 0, 1000000); });
}

}  // namespace

CaseFile read_case_file(const std::string& path, ErrorList& errors) {
  const TomlTable root = TomlTable::parse_file(path);  // (a file that cannot be read or parsed stops here)
  const Collect ok{errors};
  root.reject_unknown({"crs", "model", "water", "initial_stress", "material", "pool", "boundary", "boundary_traction", "fault",
                       "solver", "output", "scenario", "seismicity", "seal", "report"},
                      errors);
  CaseFile c;
  c.path = path;
  read_model_and_water(root, c, ok);
  read_initial_stress(root, c, ok);
  read_materials_and_pools(root, c, ok);
  read_boundaries(root, c, ok);
  read_faults(root, c, ok);
  read_seals(root, c, ok);
  read_solver(root, c, ok);
  read_scenario(root, c, ok);
  read_output(root, c, ok);
  read_seismicity(root, c, ok);
  read_report(root, c, ok);
  return c;
}

CaseFile read_case_file(const std::string& path) {
  ErrorList errors;
  CaseFile c = read_case_file(path, errors);
  errors.throw_if_any();
  return c;
}

}  // namespace ugs
