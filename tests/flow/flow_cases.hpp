// Small worked flow cases for the verification tests: a case file built in memory (no TOML),
// a "pool" slab whose nodes carry the boundary pressure, and time grids from explicit values.
#pragma once
#include <cmath>
#include <string>
#include <vector>

#include "ugs/flow/flow_model.hpp"
#include "ugs/flow/schedule.hpp"
#include "ugs/formats/case_file.hpp"

namespace ugs::test {

// Aquifer with constant specific storage: a linear material with nu = 0 has c_M = 1/E (eq. 3.23).
struct AquiferParams {
  double eta = 0.1;         // diffusivity K/S_s [m2/s]
  double c_M = 1e-9;        // 1/Pa
  double porosity = 0.2;
  double beta = 4.4e-10;    // 1/Pa
  double gamma_w = 9810;

  double s() const { return porosity * beta + c_M; }     // S_s / gamma_w [1/Pa]
  double K() const { return eta * gamma_w * s(); }        // m/s
};

inline CaseFile aquifer_case(const AquiferParams& a, std::array<double, 3> k_scale = {1, 1, 1}) {
  CaseFile c;
  c.path = "test.toml";
  c.water_unit_weight = a.gamma_w;
  c.water_compressibility = a.beta;
  MaterialSpec aq;
  aq.name = "aquifer";
  aq.where = "test.toml:10";
  aq.law = MaterialLaw::Linear;
  aq.nu_z = 0;
  aq.E_Pa = 1.0 / a.c_M;
  aq.K = std::array<double, 3>{a.K() * k_scale[0], a.K() * k_scale[1], a.K() * k_scale[2]};
  aq.porosity = a.porosity;
  MaterialSpec pool = aq;
  pool.name = "pool";
  pool.where = "test.toml:20";
  c.materials = {aq, pool};
  PoolSpec p;
  p.name = "Pool";
  p.where = "test.toml:30";
  p.materials = {"pool"};
  p.column = "p_MPa";
  c.pools = {p};
  return c;
}

// Grid of dates (seconds from 0) with the pool stepped to dp0 from the first step on.
inline flow::TimeGrid step_grid(const std::vector<std::int64_t>& dates, double dp0) {
  flow::TimeGrid g;
  g.dates = dates;
  g.is_schedule_date.assign(dates.size(), 1);
  std::vector<double> v(dates.size(), dp0);
  v[0] = 0;
  g.pool_dp = {v};
  return g;
}

// 0, dt, 2 dt, ... up to t_end (dt dividing it).
inline std::vector<std::int64_t> uniform_dates(std::int64_t dt, std::int64_t t_end, std::vector<std::int64_t> start = {0}) {
  std::int64_t t = start.back();
  while (t < t_end) start.push_back(t += dt);
  return start;
}

// Semi-infinite aquifer (VERIFICATION.md V3).
inline double erfc_profile(double x, double t, double eta) { return std::erfc(x / (2.0 * std::sqrt(eta * t))); }

// Finite aquifer of length L closed at x = L: dp/dp0.
inline double closed_profile(double x, double t, double eta, double L) {
  double sum = 0;
  for (int n = 0; n < 2000; ++n) {
    const double k = 2 * n + 1;
    const double term = std::sin(k * M_PI * x / (2 * L)) * std::exp(-k * k * M_PI * M_PI * eta * t / (4 * L * L)) / k;
    sum += term;
    if (std::abs(term) < 1e-14 && n > 10) break;
  }
  return 1.0 - 4.0 / M_PI * sum;
}

}  // namespace ugs::test
