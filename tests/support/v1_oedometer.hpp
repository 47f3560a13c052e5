// V1 (shared/docs/VERIFICATION.md): the closed-form vertical strain of one layer of the
// hypo-plastic oedometer along the effective-stress path sigma0 + dS[k] (MPa), for each inversion
// rule, with the Po plain's virgin compressibility c_M(sigma) = a sigma^-b (thesis eq. 4.1, docs/theory.md 3).
#pragma once
#include <cmath>
#include <string>
#include <vector>

namespace ugs::test::v1 {

constexpr double a = 1.0044e-2, b = 1.1347;
inline double cM(double s) { return a * std::pow(s, -b); }
// Strain on the virgin branch from s0 to s1 (the integral of c_M).
inline double virgin(double s0, double s1) { return a * (std::pow(s1, 1 - b) - std::pow(s0, 1 - b)) / (1 - b); }

// Cumulative strain magnitude at each turn of the path (dS[0] = 0; four legs: load, unload,
// reload past the first peak, unload). Rules: "sigma-max", "sigma-inversion", "stress-dependent".
inline std::vector<double> layer_strain(const std::string& rule, double s0, double cR, const std::vector<double>& dS) {
  const double s1 = s0 + dS[1], s2 = s0 + dS[2], s3 = s0 + dS[3], s4 = s0 + dS[4];
  std::vector<double> e(5, 0.0);
  e[1] = virgin(s0, s1);
  if (rule == "sigma-max") {
    e[2] = e[1] + cM(s1) / cR * (s2 - s1);
    e[3] = e[2] + cM(s1) / cR * (s1 - s2) + virgin(s1, s3);
    e[4] = e[3] + cM(s3) / cR * (s4 - s3);
  } else if (rule == "sigma-inversion") {
    e[2] = e[1] + cM(s1) / cR * (s2 - s1);
    e[3] = e[2] + cM(s2) / cR * (s1 - s2) + virgin(s1, s3);
    e[4] = e[3] + cM(s3) / cR * (s4 - s3);
  } else {
    e[2] = e[1] + virgin(s1, s2) / cR;
    e[3] = e[2] + virgin(s2, s1) / cR + virgin(s1, s3);
    e[4] = e[3] + virgin(s3, s4) / cR;
  }
  return e;
}

}  // namespace ugs::test::v1
