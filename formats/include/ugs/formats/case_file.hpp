// The case file (TOML): one file describes a model — materials, initial stress, pools and their
// pressure schedules, boundary conditions, faults, solver and output settings. Schema and an
// example for every key: docs/case-file.md. Unknown keys are errors.
// Values are converted to SI on reading (MPa -> Pa, degrees stay degrees where named *_deg).
#pragma once
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ugs/formats/error.hpp"  // ErrorList; not toml_reader.hpp: toml11 costs every includer ~2 s of compiling

namespace ugs {

enum class MaterialLaw {
  Linear,       // constant E, nu (isotropic) or E_z with ratios (transversely isotropic)
  ElasticDepth, // c_M from the compressibility law at the initial effective vertical stress
  Hypoplastic,  // c_M from the law on virgin loading, c_M(sigma_max)/c_R on unloading/reloading
};

// One row of a table by depth of [initial_stress]: depth below surface_elevation_m [m], value (SI).
struct DepthValue {
  double depth = 0;
  double value = 0;
};

// A material constant given as a field instead of a number (docs/case-file.md, "Properties that
// vary in space"): its value in each tetrahedron of the material is scale x (the source's value at
// the tetrahedron's centroid, or of the tetrahedron itself) x si. The sources:
//   grdecl   an array of a GRDECL file by grid cell, located through the corner-point grid
//            (SPECGRID/COORD/ZCORN/ACTNUM of `grid`, default the same file)
//   init     an array of an ECLIPSE INIT file by active cell, located through the EGRID (`grid`,
//            default CASE.EGRID beside CASE.INIT)
//   table    rows (elevation or depth, value), linear between rows, at the centroid's elevation
//   map      a map (IRAP classic or CPS-3 ASCII grid), bilinear at the centroid's x, y
//   cells    a cell field of a ugs-fields HDF5 file, by element tag
struct MaterialField {
  enum class Source { Grdecl, Init, Table, Map, Cells };
  Source source = Source::Table;
  std::string key;                  // the material key it gives: "c_R", "K_m_per_s[2]"
  std::string where;                // file:line of the value in the case
  std::string file;                 // grdecl / init / map / cells file, resolved against the case
  std::string grid;                 // grdecl: file with the grid; init: the EGRID ("" = the default)
  std::string keyword;              // grdecl / init: the array; cells: the cell field
  std::string date;                 // cells: the step's date ("" = the file's first step)
  std::array<double, 3> offset_m{}; // grdecl / init: added to the grid's map coordinates
  std::vector<DepthValue> rows;     // table: (elevation or depth [m], value), ascending
  bool by_depth = false;            // table: rows by depth below [initial_stress] surface_elevation_m
  double scale = 1.0;               // the factor ugs-calibrate and ugs-ensemble vary
  double si = 1.0;                  // SI per unit of the source's values (E_MPa: 1e6)
};

// The keys of a [[material]] that may be fields ("K_m_per_s[0]" .. "[2]" for the conductivity).
bool material_key_may_vary(const std::string& key);
// Why `value` (SI) is not valid for the material key, or "" when it is (the ranges of the
// numbers: biot in [0, 1], porosity in (0, 1), nu_z in (-1, 0.5), cm_b >= 0, the others > 0).
std::string material_value_problem(const std::string& key, double value);

struct MaterialSpec {
  std::string name;           // matches the mesh group mat:<name>
  std::string where;          // file:line, for later error messages
  MaterialLaw law = MaterialLaw::ElasticDepth;
  double biot = 1.0;
  // Transverse isotropy (eq. 3.22), vertical axis of symmetry.
  double nu_z = 0.3, Eh_over_Ez = 1.0, nuh_over_nuz = 1.0, Gh_over_Gz = 1.0;
  // Compressibility law c_M = a sigma_z^-b [1/MPa, sigma_z in MPa] and c_R.
  double cm_a = 1.0044e-2, cm_b = 1.1347;
  std::optional<double> c_R;
  double sigma_z_min_MPa = 0.1;  // floor of sigma_z in the law (c_M is singular at 0); mechanics
  // Linear law: vertical Young's modulus [Pa] (E for isotropic).
  std::optional<double> E_Pa;
  // Flow: hydraulic conductivity [m/s] along x, y, z and porosity; absent for non-flow units.
  std::optional<std::array<double, 3>> K;
  std::optional<double> porosity;
  // Own in-situ stress ratios (docs/case-file.md): sigma'_Hmax / sigma'_v and sigma'_hmin / sigma'_v of
  // this material's elements; a ratio not given is the [initial_stress] one (k0 sets both). The
  // azimuth and sigma'_v(z) stay global.
  std::optional<double> k_Hmax, k_hmin;
  bool own_stress_ratios() const { return k_Hmax || k_hmin; }
  // Constants given as fields (docs/case-file.md); the member of a field-valued key holds NaN
  // (its optional is set) until material_field_values (ugs/meshing/material_fields.hpp) gives
  // each tetrahedron its own copy with numbers.
  std::vector<MaterialField> fields;
  const MaterialField* field(const std::string& key) const;
  // Sets the member of `key` (material_key_may_vary) to `value` in SI.
  void set_value(const std::string& key, double value);
};

struct PoolSpec {
  std::string name;
  std::string where;
  std::vector<std::string> materials;  // materials whose nodes follow the schedule
  std::vector<std::string> aquifer_materials;  // hydraulically connected materials (flow sub-mesh)
  std::string schedule;                // CSV path, resolved against the case file
  std::string column = "p_norm";       // p_norm (normalized) or p_MPa
  std::optional<double> reference_pressure_Pa;  // needed for normalized schedules
  // Gas column (docs/case-file.md): above the gas-water contact (an elevation, m), inside this
  // pool's materials, the initial pore pressure follows the gas gradient up from the water
  // pressure at the contact. Absent: the pool's rock holds water at the initial state.
  std::optional<double> gas_water_contact_m;
  double gas_gradient_Pa_per_m = 0.0;  // rho_gas g (gas_density_kg_per_m3 or gas_gradient_MPa_per_m)
};

// The acceleration of gravity [m/s2] that turns densities (kg/m3) into gradients (Pa/m): the value
// behind the default water unit weight, 9810 N/m3 = 1000 kg/m3 x 9.81 m/s2.
inline constexpr double kGravity = 9.81;

struct InitialStressSpec {
  double surface_elevation = 0.0;         // m, where total stress and pore pressure vanish
  double lithostatic_gradient = 0.0226e6; // Pa/m (total vertical stress)
  double hydrostatic_gradient = 0.0100e6; // Pa/m (pore pressure)
  double k0 = 1.0;                        // sigma'_h / sigma'_v, both horizontal directions (shorthand)
  // General in-situ state (docs/case-file.md): effective sigma'_Hmax / sigma'_v and sigma'_hmin / sigma'_v
  // (each k0 when not given), sigma'_Hmax along (sin a, cos a, 0), a = Hmax_azimuth_deg clockwise from +y.
  std::optional<double> k_Hmax, k_hmin;
  double Hmax_azimuth_deg = 0.0;
  double kH() const { return k_Hmax.value_or(k0); }
  double kh() const { return k_hmin.value_or(k0); }

  // Mechanical earth model: tables by depth (docs/case-file.md, "Tables by depth"; formulas in
  // docs/theory.md). Each is empty when not given, and the gradients above then hold.
  // Total vertical stress gradient [Pa/m] by depth, linear between rows (two rows at one depth: a
  // step), the first row's value above it, the last row's below it; S_v is its integral from the
  // surface. From Sv_density_kg_per_m3 (rho g) or Sv_gradients_MPa_per_m (a step per interval).
  std::vector<DepthValue> sv_gradient;
  // Total S_hmin [Pa] at depths (leak-off tests, minifracs), linear between rows, S d / d_row (the
  // row's own gradient) above the first row and below the last. Given: the horizontal stresses
  // are the table's, not k ratios.
  std::vector<DepthValue> shmin;
  // Total S_Hmax: a table like shmin, or the ratio S_Hmax / S_hmin (1 when neither is given).
  std::vector<DepthValue> sHmax;
  std::optional<double> sHmax_over_shmin;
  // Overpressure [Pa] added to the hydrostatic pore pressure, linear between rows, the first row's
  // value above it and the last row's below it.
  std::vector<DepthValue> overpressure;
  // Stress regime the tables must honour at every depth of the model: "" (not checked), "normal"
  // (S_hmin <= S_Hmax <= S_v), "strike-slip" (S_hmin <= S_v <= S_Hmax), "reverse" (S_v <= S_hmin <= S_Hmax).
  std::string regime;
  bool horizontal_table() const { return !shmin.empty(); }
};

// [[boundary_traction]]: the total traction (sigma n, n the outward normal, tension positive) on the
// triangles of the mesh group bnd:<group>, constant in time (docs/case-file.md).
struct TractionSpec {
  std::string group;                      // without the bnd: prefix
  std::string where;                      // file:line of the entry
  bool in_situ = false;                   // t = sigma_0(x) n, the initial total stress on the face
  std::array<double, 3> traction_Pa{};    // else this constant traction, Pa, mesh axes
};

struct FaultSpec {
  std::string name;
  std::string where;
  double cohesion_Pa = 0.0;
  double friction_deg = 30.0;
};

// [[seal]]: a material whose elements are checked as a seal (caprock integrity, docs/caprock.md):
// the tensile margin against its fracture pressure and a Mohr-Coulomb shear margin with the rock's
// own strength. SI inside.
struct SealSpec {
  std::string material;              // a [[material]] name
  std::string where;                 // file:line of the entry
  double cohesion_Pa = 0.0;          // Mohr-Coulomb cohesion of the intact rock (>= 0)
  double friction_deg = 30.0;        // its friction angle, (0, 90)
  double tensile_strength_Pa = 0.0;  // T0: fracture pressure = S3 + T0 (>= 0)
};

// [report] (ugs-report, docs/insar-and-reports.md "A report for the field"): the study's own phases,
// the pool the stress pictures look at, and the acceptance thresholds its headlines are checked
// against (pass / fail). A threshold not given is not checked.
struct ReportPhaseSpec {
  std::string name;
  std::string start, end;  // ISO 8601, start before end
};
struct ReportSpec {
  std::string where;                       // file:line of the table
  std::string stress_pool;                 // a [[pool]] name; empty: the first pool
  std::vector<ReportPhaseSpec> phases;     // [[report.phase]]
  std::optional<double> chi_max;           // largest acceptable fault chi (0, 1]
  std::optional<double> uplift_max_mm;     // largest acceptable uplift over a phase (> 0)
  std::optional<double> settlement_max_mm; // largest acceptable settlement over a phase (> 0)
  std::optional<double> tensile_margin_min_MPa;  // smallest acceptable seal tensile margin (>= 0)
  std::optional<double> shear_margin_min_MPa;    // smallest acceptable seal shear margin (>= 0)
};

// [seismicity] and its per-fault overrides [seismicity.fault.<name>] (docs/seismicity.md): the
// rate-and-state seismicity parameters, SI inside. A value an override does not give is the
// section's; the section gives A_sigma, the stressing rate, the background rate and M_c.
struct SeismicityValues {
  std::string where;                          // file:line of the table
  std::optional<double> A_sigma_Pa;           // A sigma, Pa (> 0)
  std::optional<double> stressing_rate_Pa_per_s;   // background Coulomb stressing rate s_r, Pa/s (> 0)
  std::optional<double> background_rate_per_s_m2;  // background rate r of events >= M_c, per s per m2 (> 0)
  std::optional<double> M_c;                  // magnitude of completeness (the magnitude r counts)
  std::optional<double> b_value;              // Gutenberg-Richter b (> 0)
};

struct SeismicitySpec {
  SeismicityValues values;                    // [seismicity]; b_value defaults to 1
  std::vector<double> magnitudes;             // magnitudes whose exceedance probability is reported
  std::map<std::string, SeismicityValues> faults;  // [seismicity.fault.<name>]
};

// One year in the seismicity parameters' units (MPa/yr, per yr per km2): the Julian year, 365.25 days.
inline constexpr double kSecondsPerYear = 365.25 * 86400.0;

struct CaseFile {
  std::string path;
  std::string crs;
  std::string start_date, end_date;
  double water_unit_weight = 9810.0;       // N/m3
  double water_compressibility = 4.4e-10;  // 1/Pa
  InitialStressSpec initial_stress;
  std::vector<MaterialSpec> materials;
  std::vector<PoolSpec> pools;
  std::vector<std::string> fixed_boundaries{"west", "east", "south", "north", "bottom"};
  std::vector<std::string> roller_boundaries;  // zero normal displacement only
  std::vector<std::string> free_boundaries;    // traction-free (stated for clarity; the default)
  std::vector<TractionSpec> tractions;         // [[boundary_traction]], on groups in none of the lists above
  std::vector<FaultSpec> faults;
  std::vector<SealSpec> seals;                 // [[seal]]
  // Solver settings (docs/case-file.md).
  double newton_tolerance = 1e-8;
  // What newton_tolerance is relative to: "step" (the step's load increment, ||r_0||) or
  // "total-load" (the larger of ||r_0|| and the whole load ||f_ext|| at the step's date).
  std::string tolerance_of = "step";
  int max_newton_iterations = 25;
  std::string linear_solver = "cg-hypre";       // ugs-solve; named in ugs/mechanics/case_section.hpp
  std::string inversion_rule = "sigma-max";     // sigma-max | sigma-inversion | stress-dependent
  int max_substeps = 64;                        // a step that fails may be split into up to this many
  std::string steps = "every-date";             // every-date | turning-points (docs/mechanics.md)
  double turning_point_tolerance = 1e4;         // Pa: a new low of the pressure change smaller than this is none
  bool reuse_preconditioner = true;             // keep the AMG hierarchy while it converges well
  // Output dates (ISO 8601); empty means every schedule date.
  std::vector<std::string> output_dates;
  // Fields written at output dates (ugs-solve); empty means all (docs/case-file.md).
  std::vector<std::string> output_fields;
  int checkpoint_every = 0;  // ugs-solve: also save the restart state every N steps (0: output dates only)
  // Faulted runs of ugs-solve (docs/fault-mechanics.md).
  std::string fault_solver = "auto";       // [solver] fault_solver, named in ugs/contact/case_section.hpp
  // [scenario]: the pressure change after reference_date is scaled about its value there,
  // dp_s(t) = dp(t_ref) + scale (dp(t) - dp(t_ref)); ugs-solve --find-safe-scale searches the
  // smallest scale at which a fault patch reaches chi = 1, up to max_scale, to scale_tolerance.
  double scenario_scale = 1.0;
  std::string scenario_reference_date;     // empty: the first date of the pressure history
  double scenario_max_scale = 10.0;
  double scenario_tolerance = 0.01;        // relative width of the final bracket
  // [report] (ugs-report); absent when the file has no such section.
  std::optional<ReportSpec> report;
  // [seismicity] (ugs-seismicity, docs/seismicity.md); absent when the file has no such section.
  std::optional<SeismicitySpec> seismicity;

  // "file:line" of a key given in the file, by its path ("solver.linear_solver"); the file alone
  // for a key not given. The libraries that check their settings after reading name the line.
  std::map<std::string, std::string> key_lines;
  std::string where(const std::string& key_path) const {
    const auto it = key_lines.find(key_path);
    return it == key_lines.end() ? path : it->second;
  }

  const MaterialSpec* material(const std::string& name) const;
};

// Throws one InputError naming every problem of the file (one "file:line: 'key': what" line each,
// in file order).
CaseFile read_case_file(const std::string& path);
// Adds every problem to `errors` instead, so that the libraries' own checks of their sections
// (e.g. ugs/mechanics/case_section.hpp) join the same report; throws only when the file cannot be
// read or is not TOML.
CaseFile read_case_file(const std::string& path, ErrorList& errors);

}  // namespace ugs
