// ugs-solve / ugs-flow case files for tests and benchmark cases, composed from sections with named,
// typed fields, so that a case writer says what its case holds and not how TOML spells it. The
// text is that of the hand-written cases it replaces, byte for byte: a head (comment lines, top-level
// keys) written as given, then the sections in the order added, one blank line between them
// (Layout::Spaced) or none (Layout::Compact). strata_toml.hpp builds ugs-meshgen's strata files alike.
#pragma once
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ugs::testcase {

// How whole numbers are written: Plain "3" (fmt's shortest form), Decimal "3.0" (a TOML float).
enum class Numbers { Plain, Decimal };
std::string toml_number(double v, Numbers numbers);
enum class Layout { Spaced, Compact };

// The text both builders share: the head, then sections in the order added.
class TomlSections {
 public:
  const std::string& str() const { return text_; }

 protected:
  TomlSections(std::string head, Numbers numbers, Layout layout) : numbers_(numbers), layout_(layout), text_(std::move(head)) {}
  void section(const std::string& header);
  std::string number(double v) const { return toml_number(v, numbers_); }
  void add(const std::string& lines) { text_ += lines; }

 private:
  Numbers numbers_;
  Layout layout_;
  std::string text_;
  bool first_ = true;
};

// [initial_stress]. Gradients in MPa/m are written with four decimals where that is exact (0.0100,
// 0.0226: as the thesis gives them), otherwise in their shortest form (0.00981); a field left empty
// is not written (ugs-flow reads the surface elevation alone).
// The tables by depth of the mechanical earth model are written as arrays of [depth_m, value] rows
// (an empty table is not written); give lithostatic_gradient_MPa_per_m = std::nullopt with an S_v table.
using DepthRows = std::vector<std::array<double, 2>>;
struct InitialStress {
  std::optional<double> surface_elevation_m{};
  std::optional<double> lithostatic_gradient_MPa_per_m = 0.0226;
  std::optional<double> hydrostatic_gradient_MPa_per_m = 0.0100;
  std::optional<double> k0{};
  std::optional<double> k_Hmax{}, k_hmin{}, Hmax_azimuth_deg{};
  DepthRows Sv_density_kg_per_m3{}, Sv_gradients_MPa_per_m{}, Shmin_MPa{}, SHmax_MPa{}, overpressure_MPa{};
  std::optional<double> SHmax_over_Shmin{};
  std::string regime{};  // empty: not written
};

// [[material]]. `law` as the case file spells it (linear, elastic, hypoplastic; empty: not written,
// as for ugs-flow, which reads conductivities and porosity alone). thesis_anisotropy
// writes the hypo-plastic anisotropy of Table 4.3 (nu_z 0.3, Eh_over_Ez 3.0, nuh_over_nuz 0.2);
// `more` holds further "key = value" lines as written (conductivities, porosity).
struct Material {
  std::string name{};
  std::string law{};
  std::optional<double> E_MPa{};
  std::optional<double> nu{};
  std::optional<double> nu_z{};
  bool thesis_anisotropy = false;
  std::optional<double> c_R{};
  std::string more{};
};

// A linear-elastic material (E in MPa), an elastic one (c_M from eq. 4.1: nu only), and a
// hypo-plastic one with the thesis' anisotropy and compaction ratio c_R.
Material linear(const std::string& name, double E_MPa, double nu);
Material elastic(const std::string& name, double nu);
Material hypoplastic(const std::string& name, double c_R);

// [boundary]: the groups held fixed, on rollers and free (a list left empty is not written).
struct Boundary {
  std::vector<std::string> fixed{}, rollers{}, free{};
};
// The five sides other than the top fixed.
Boundary fixed_sides();

// [[fault]] with its Mohr-Coulomb strength.
struct Fault {
  std::string name{};
  double cohesion_MPa = 0;
  double friction_deg = 30;
};

// [[pool]] of a case (ugs-flow): the pool's materials, its aquifers, its schedule (CSV and column).
struct Pool {
  std::string name{};
  std::vector<std::string> materials{}, aquifer_materials{};
  std::string schedule{}, column = "p_MPa";
  std::optional<double> gas_water_contact_m{}, gas_density_kg_per_m3{};  // the pool's gas column
  std::string more{};  // further "key = value" lines as written
};

// [[seal]]: a material checked for caprock integrity, with the intact rock's strength.
struct Seal {
  std::string material{};
  double cohesion_MPa = 0;
  double friction_deg = 30;
  double tensile_strength_MPa = 0;
};

class CaseToml : public TomlSections {
 public:
  explicit CaseToml(std::string head = "", Numbers numbers = Numbers::Plain, Layout layout = Layout::Spaced)
      : TomlSections(std::move(head), numbers, layout) {}
  CaseToml& initial_stress(const InitialStress& s);
  CaseToml& material(const Material& m);
  CaseToml& boundary(const Boundary& b);
  CaseToml& fault(const Fault& f);
  CaseToml& pool(const Pool& p);
  CaseToml& seal(const Seal& s);
  // Any other table ([solver], [output], [scenario], [model]) with its lines as written.
  CaseToml& table(const std::string& name, const std::string& lines);
};

// Writes a case (or any) text to a file.
void write_text(const std::filesystem::path& p, const std::string& text);

// A TOML array of strings: ["a", "b"].
std::string string_list(const std::vector<std::string>& items);

}  // namespace ugs::testcase
