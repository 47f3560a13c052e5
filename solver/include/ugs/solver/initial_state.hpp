// The initial state of a case (its mechanical earth model): total stresses and pore pressure by
// depth, and the effective stress the mechanics starts from. One definition for every tool that
// needs it: ugs-solve's continuum, its faults and boundary tractions, and ugs-flow's storage
// coefficient. Formulas: docs/theory.md ("Initial state"); keys: docs/case-file.md.
#pragma once
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "ugs/formats/case_file.hpp"

namespace ugs {

// A pool's gas column as its materials see it: above contact_elevation the pore pressure follows
// `gradient` up from the water pressure at the contact. The default holds water (no contact).
struct GasColumn {
  double contact_elevation = std::numeric_limits<double>::infinity();  // m; +inf: no gas
  double gradient = 0;                                                 // Pa/m, rho_gas g
  bool holds_gas(double z) const { return z > contact_elevation; }
};

// Geostatic initial state (in equilibrium, taken as the reference), with depth d = max(z_s - z, 0),
// stresses tension positive, pressure positive:
//   total vertical stress S_v(d): lithostatic d, or the integral of the sv_gradient table;
//   pore pressure p0: hydrostatic d + overpressure(d), in a gas column p_w(z_gwc) - gradient (z - z_gwc);
//   sigma'_v = -(S_v - alpha p0);
//   ratio form: sigma'_Hmax = k_Hmax sigma'_v, sigma'_hmin = k_hmin sigma'_v;
//   table form: sigma'_hmin = -(S_hmin(d) - alpha p0), sigma'_Hmax = -(S_Hmax(d) - alpha p0);
//   sigma'_0 = sigma'_Hmax s s^T + sigma'_hmin h h^T + sigma'_v e_z e_z^T,
// s = (sin a, cos a, 0) the direction of S_Hmax (a clockwise from +y, north), h = (cos a, -sin a, 0).
// With the gradients alone (no table, no overpressure, water) sigma'_v = -(gamma_lith - alpha gamma_hyd) d,
// the formula (and the bytes) of the gradient form.
struct InitialState {
  double surface_elevation = 0;  // m
  double lithostatic = 0.0226e6; // Pa/m
  double hydrostatic = 0.0100e6; // Pa/m
  double k_Hmax = 1.0;           // sigma'_Hmax / sigma'_v (ratio form)
  double k_hmin = 1.0;           // sigma'_hmin / sigma'_v (ratio form)
  double Hmax_azimuth_deg = 0.0; // degrees clockwise from +y
  // Tables by depth (InitialStressSpec; empty: not given). sv_total[i] is S_v at sv_gradient[i].depth.
  std::vector<DepthValue> sv_gradient;
  std::vector<double> sv_total;
  std::vector<DepthValue> shmin, sHmax, overpressure;
  double sHmax_over_shmin = 1.0;  // table form without an S_Hmax table

  using Stress = std::array<double, 6>;  // thesis Voigt order xx yy zz yz xz xy, Pa

  double depth(double z) const { return z < surface_elevation ? surface_elevation - z : 0.0; }
  // Total principal stresses (compression positive, Pa) at elevation z. The horizontal ones of the
  // table form only (horizontal_table()).
  double vertical_stress(double z) const;
  double hmin_stress(double z) const;
  double Hmax_stress(double z) const;
  bool horizontal_table() const { return !shmin.empty(); }
  // Initial pore pressure at elevation z in rock of the given gas column (water by default).
  double pore_pressure(double z, const GasColumn& gas = {}) const;
  // Initial effective stress (tension positive) at elevation z, with the global ratios in water or
  // with a material's own k = {k_Hmax, k_hmin} (ratio form; the table form ignores k) and gas column.
  Stress effective_stress(double z, double biot) const;
  Stress effective_stress(double z, double biot, const std::array<double, 2>& k, const GasColumn& gas = {}) const;
  // The initial effective vertical stress, compression positive (c_M of the compressibility law).
  double effective_vertical_stress(double z, double biot, const GasColumn& gas = {}) const;
};

// The state a case describes (its [initial_stress]). InputError (at the key's line) for a regime
// named but not honoured: checked on [0, max_depth] exactly (between the tables' rows the
// stresses are linear or quadratic in depth) when the horizontal stresses are tables, and by the
// ratios (k <= 1 or k >= 1) in the ratio form.
InitialState initial_state_of(const CaseFile& cs, double max_depth);
// The gas column of a material: that of the pool listing it in `materials` (water if none, or if
// that pool has no gas_water_contact_m).
GasColumn gas_column_of(const CaseFile& cs, const std::string& material);
// InputError at the pool's line when its contact lies at or above the top of its materials (a gas
// column above the pool's top: the pool holds no gas), or when the gas pressure reaches S_v at that
// top (where p0 - S_v is largest: S_v falls faster upwards than the gas pressure). `top` is the
// highest elevation of the pool's rock.
void check_gas_contact(const PoolSpec& pool, double top, const InitialState& state);

}  // namespace ugs
