#include "ugs/solver/initial_state.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs {
namespace {

// Index of the last row at or above depth d (rows sorted by depth; -1 above the first).
std::ptrdiff_t row_above(const std::vector<DepthValue>& t, double d) {
  const auto it = std::upper_bound(t.begin(), t.end(), d, [](double x, const DepthValue& r) { return x < r.depth; });
  return (it - t.begin()) - 1;
}

// Linear between rows, the end rows' values beyond them (overpressure).
double linear_clamped(const std::vector<DepthValue>& t, double d) {
  const std::ptrdiff_t i = row_above(t, d);
  if (i < 0) return t.front().value;
  if (i + 1 >= static_cast<std::ptrdiff_t>(t.size())) return t.back().value;
  const DepthValue &a = t[i], &b = t[i + 1];
  return a.value + (b.value - a.value) * (d - a.depth) / (b.depth - a.depth);
}

// Linear between rows, the end rows' own gradient value / depth beyond them (stress points).
double linear_through_surface(const std::vector<DepthValue>& t, double d) {
  const std::ptrdiff_t i = row_above(t, d);
  if (i < 0) return t.front().value * (d / t.front().depth);
  if (i + 1 >= static_cast<std::ptrdiff_t>(t.size())) return t.back().value * (d / t.back().depth);
  const DepthValue &a = t[i], &b = t[i + 1];
  return a.value + (b.value - a.value) * (d - a.depth) / (b.depth - a.depth);
}

InitialState::Stress rotate(double sH, double sh, double sv, double azimuth_deg) {
  const double a = azimuth_deg * M_PI / 180.0, sa = std::sin(a), ca = std::cos(a);
  return {sH * sa * sa + sh * ca * ca, sH * ca * ca + sh * sa * sa, sv, 0, 0, (sH - sh) * sa * ca};
}

// The largest value of f on [lo, hi] where f is quadratic between consecutive breakpoints: the
// ends of each piece and its vertex when that lies inside (a quadratic through three points).
// Returns the depth where it is reached.
double argmax_piecewise_quadratic(const std::function<double(double)>& f, std::vector<double> breaks, double lo, double hi) {
  breaks.push_back(lo);
  breaks.push_back(hi);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  double best_d = lo, best = f(lo);
  auto consider = [&](double d) {
    if (const double v = f(d); v > best) best = v, best_d = d;
  };
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double a = breaks[i], b = breaks[i + 1];
    if (b <= lo || a >= hi) continue;
    const double m = 0.5 * (a + b), fa = f(a), fm = f(m), fb = f(b);
    consider(b);
    // f = fm + c1 t + c2 t^2 with t = (d - m) / h, h = (b - a) / 2.
    const double c2 = 0.5 * (fa + fb) - fm, c1 = 0.5 * (fb - fa);
    if (c2 < 0) {
      const double t = -c1 / (2 * c2);
      if (t > -1 && t < 1) consider(m + t * 0.5 * (b - a));
    }
  }
  return best_d;
}

}  // namespace

double InitialState::vertical_stress(double z) const {
  const double d = depth(z);
  if (sv_gradient.empty()) return lithostatic * d;
  const std::ptrdiff_t i = row_above(sv_gradient, d);
  if (i < 0) return sv_gradient.front().value * d;
  const std::size_t n = sv_gradient.size();
  const DepthValue& a = sv_gradient[i];
  const double t = d - a.depth;
  if (static_cast<std::size_t>(i) + 1 >= n) return sv_total[i] + a.value * t;
  const DepthValue& b = sv_gradient[i + 1];  // (b.depth > d >= a.depth: not a step)
  return sv_total[i] + a.value * t + 0.5 * (b.value - a.value) * t * t / (b.depth - a.depth);
}

double InitialState::hmin_stress(double z) const { return linear_through_surface(shmin, depth(z)); }

double InitialState::Hmax_stress(double z) const {
  return sHmax.empty() ? sHmax_over_shmin * hmin_stress(z) : linear_through_surface(sHmax, depth(z));
}

double InitialState::pore_pressure(double z, const GasColumn& gas) const {
  if (gas.holds_gas(z)) return pore_pressure(gas.contact_elevation) - gas.gradient * (z - gas.contact_elevation);
  const double d = depth(z);
  return overpressure.empty() ? hydrostatic * d : hydrostatic * d + linear_clamped(overpressure, d);
}

InitialState::Stress InitialState::effective_stress(double z, double biot) const {
  return effective_stress(z, biot, {k_Hmax, k_hmin});
}

double InitialState::effective_vertical_stress(double z, double biot, const GasColumn& gas) const {
  // The gradient form in water: the former formula, to the byte.
  if (sv_gradient.empty() && overpressure.empty() && !gas.holds_gas(z)) return (lithostatic - biot * hydrostatic) * depth(z);
  return vertical_stress(z) - biot * pore_pressure(z, gas);
}

InitialState::Stress InitialState::effective_stress(double z, double biot, const std::array<double, 2>& k, const GasColumn& gas) const {
  const double sv = -effective_vertical_stress(z, biot, gas);
  if (horizontal_table()) {
    const double ap = biot * pore_pressure(z, gas);
    return rotate(-(Hmax_stress(z) - ap), -(hmin_stress(z) - ap), sv, Hmax_azimuth_deg);
  }
  if (k[0] == k[1]) return {k[1] * sv, k[1] * sv, sv, 0, 0, 0};  // isotropic horizontally (k0): exactly as before
  return rotate(k[0] * sv, k[1] * sv, sv, Hmax_azimuth_deg);
}

InitialState initial_state_of(const CaseFile& cs, double max_depth) {
  const InitialStressSpec& is = cs.initial_stress;
  InitialState s;
  s.surface_elevation = is.surface_elevation;
  s.lithostatic = is.lithostatic_gradient;
  s.hydrostatic = is.hydrostatic_gradient;
  s.k_Hmax = is.kH();
  s.k_hmin = is.kh();
  s.Hmax_azimuth_deg = is.Hmax_azimuth_deg;
  s.sv_gradient = is.sv_gradient;
  s.shmin = is.shmin;
  s.sHmax = is.sHmax;
  s.sHmax_over_shmin = is.sHmax_over_shmin.value_or(1.0);
  s.overpressure = is.overpressure;
  // S_v at each row: the integral of the gradient, linear between rows.
  for (std::size_t i = 0; i < s.sv_gradient.size(); ++i) {
    const DepthValue& r = s.sv_gradient[i];
    if (i == 0) {
      s.sv_total.push_back(r.value * r.depth);
      continue;
    }
    const DepthValue& p = s.sv_gradient[i - 1];
    s.sv_total.push_back(s.sv_total.back() + 0.5 * (p.value + r.value) * (r.depth - p.depth));
  }

  auto at_depth = [&](double d) { return s.surface_elevation - d; };
  std::vector<double> breaks;
  for (const auto* t : {&s.sv_gradient, &s.shmin, &s.sHmax, &s.overpressure})
    for (const auto& r : *t) breaks.push_back(r.depth);
  const double D = std::max(max_depth, 0.0);

  // The water pressure stays below S_v (an overpressure that lifts the rock is no initial state).
  if (!s.overpressure.empty() && D > 0) {
    const auto excess = [&](double d) { return s.pore_pressure(at_depth(d)) - s.vertical_stress(at_depth(d)); };
    const double d = argmax_piecewise_quadratic(excess, breaks, 0, D);
    if (d > 0 && excess(d) >= 0)
      throw InputError(cs.where("initial_stress.overpressure_MPa"),
                       fmt::format("the pore pressure {:.4g} MPa reaches S_v {:.4g} MPa at depth {:.1f} m (the overpressure "
                                   "leaves no effective vertical stress)", s.pore_pressure(at_depth(d)) * 1e-6,
                                   s.vertical_stress(at_depth(d)) * 1e-6, d));
  }
  if (s.horizontal_table() && D > 0) {
    const auto excess = [&](double d) { return s.hmin_stress(at_depth(d)) - s.Hmax_stress(at_depth(d)); };
    const double d = argmax_piecewise_quadratic(excess, breaks, 0, D);
    if (d > 0 && excess(d) > 0)
      throw InputError(cs.where("initial_stress.SHmax_MPa"),
                       fmt::format("S_Hmax {:.4g} MPa is below S_hmin {:.4g} MPa at depth {:.1f} m (S_Hmax is the larger "
                                   "horizontal stress)", s.Hmax_stress(at_depth(d)) * 1e-6, s.hmin_stress(at_depth(d)) * 1e-6, d));
  }
  if (is.regime.empty()) return s;

  // The regime: the order of S_v among the horizontal stresses.
  const bool normal = is.regime == "normal", reverse = is.regime == "reverse";
  const std::string where = cs.where("initial_stress.regime");
  if (s.horizontal_table()) {
    if (D <= 0) return s;
    // normal: S_Hmax <= S_v; strike-slip: S_hmin <= S_v <= S_Hmax; reverse: S_v <= S_hmin.
    struct Bound {
      const char* name;
      std::function<double(double)> excess;  // > 0: violated
      bool applies;
    };
    const Bound bounds[] = {
        {"S_hmin above S_v", [&](double d) { return s.hmin_stress(at_depth(d)) - s.vertical_stress(at_depth(d)); }, !reverse},
        {"S_Hmax above S_v", [&](double d) { return s.Hmax_stress(at_depth(d)) - s.vertical_stress(at_depth(d)); }, normal},
        {"S_Hmax below S_v", [&](double d) { return s.vertical_stress(at_depth(d)) - s.Hmax_stress(at_depth(d)); }, !normal},
        {"S_hmin below S_v", [&](double d) { return s.vertical_stress(at_depth(d)) - s.hmin_stress(at_depth(d)); }, reverse},
    };
    for (const Bound& b : bounds) {
      if (!b.applies) continue;
      const double d = argmax_piecewise_quadratic(b.excess, breaks, 0, D);
      if (d > 0 && b.excess(d) > 1e-9 * s.vertical_stress(at_depth(d)))
        throw InputError(where, fmt::format("regime = \"{}\" but {} at depth {:.1f} m (S_v {:.4g}, S_hmin {:.4g}, S_Hmax {:.4g} MPa)",
                                            is.regime, b.name, d, s.vertical_stress(at_depth(d)) * 1e-6,
                                            s.hmin_stress(at_depth(d)) * 1e-6, s.Hmax_stress(at_depth(d)) * 1e-6));
    }
    return s;
  }
  // Ratio form: S_h - S_v = (1 - k) sigma'_v = (k - 1) |sigma'_v|, so the regime orders the ratios about 1.
  auto check_ratios = [&](double kH, double kh, const std::string& who, const std::string& at) {
    const char* bad = nullptr;
    if (normal && (kh > 1 || kH > 1)) bad = "k_Hmax and k_hmin at most 1 (S_hmin <= S_Hmax <= S_v)";
    if (is.regime == "strike-slip" && (kh > 1 || kH < 1)) bad = "k_hmin <= 1 <= k_Hmax (S_hmin <= S_v <= S_Hmax)";
    if (reverse && (kh < 1 || kH < 1)) bad = "k_hmin and k_Hmax at least 1 (S_v <= S_hmin <= S_Hmax)";
    if (bad)
      throw InputError(at, fmt::format("regime = \"{}\" but {}k_Hmax = {}, k_hmin = {} (expected {})", is.regime, who, kH, kh, bad));
  };
  check_ratios(s.k_Hmax, s.k_hmin, "", where);
  for (const auto& m : cs.materials)
    if (m.own_stress_ratios())
      check_ratios(m.k_Hmax.value_or(s.k_Hmax), m.k_hmin.value_or(s.k_hmin), fmt::format("material '{}' has ", m.name), m.where);
  return s;
}

GasColumn gas_column_of(const CaseFile& cs, const std::string& material) {
  for (const auto& p : cs.pools)
    if (p.gas_water_contact_m && std::find(p.materials.begin(), p.materials.end(), material) != p.materials.end())
      return {*p.gas_water_contact_m, p.gas_gradient_Pa_per_m};
  return {};
}

void check_gas_contact(const PoolSpec& pool, double top, const InitialState& state) {
  if (!pool.gas_water_contact_m) return;
  if (*pool.gas_water_contact_m >= top)
    throw InputError(pool.where, fmt::format("pool '{}': gas_water_contact_m = {} m lies at or above the pool's top ({:.6g} m, "
                                             "the highest node of its materials): a gas column above the pool's top (expected "
                                             "a contact below {:.6g} m)", pool.name, *pool.gas_water_contact_m, top, top));
  const GasColumn gas{*pool.gas_water_contact_m, pool.gas_gradient_Pa_per_m};
  if (const double p = state.pore_pressure(top, gas), sv = state.vertical_stress(top); p >= sv)
    throw InputError(pool.where, fmt::format("pool '{}': the gas pressure {:.4g} MPa at the pool's top ({:.6g} m) reaches S_v "
                                             "{:.4g} MPa there (a gas column of {:.6g} m leaves no effective vertical stress)",
                                             pool.name, p * 1e-6, top, sv * 1e-6, top - *pool.gas_water_contact_m));
}

}  // namespace ugs
