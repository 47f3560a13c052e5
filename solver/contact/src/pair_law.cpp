#include "ugs/contact/pair_law.hpp"

#include <algorithm>
#include <cmath>

#include "ugs/contact/dof_mask.hpp"

namespace ugs::contact {

const char* pair_state_name(PairState s) {
  switch (s) {
    case PairState::Stick: return "stick";
    case PairState::Slip: return "slip";
    case PairState::Open: return "open";
  }
  return "?";
}

PairEquations pair_equations(const PairLaw& L, const std::array<double, 3>& lam, const std::array<double, 3>& lam0,
                             const std::array<double, 3>& lam_c, const std::array<double, 3>& g,
                             const std::array<double, 3>& gc, double p_f, PairState previous) {
  PairEquations e;
  const double A = L.area, kA = L.k * L.area;
  auto hold = [&](int j) {  // component kept at its initial traction
    e.F[j] = A * (lam[j] - lam0[j]);
    e.Jl[4 * j] = A;
  };
  // A held normal (a pair whose free directions lie in the fault plane, constraint_frame): the
  // normal traction keeps its initial value and the shear obeys friction under it.
  const bool normal = normal_active(L.active);
  const bool act[2] = {is_active(L.active, kStrike), is_active(L.active, kDip)};
  const double sn = lam[2] + p_f;
  // Hysteresis band: round-off of the stress scale of the pair.
  const double band = 1e-9 * (std::abs(lam[0]) + std::abs(lam[1]) + std::abs(lam[2]) + std::abs(p_f) + L.cohesion + 1.0);
  const double open_test = sn + L.k * g[2];
  if (normal && (previous == PairState::Open ? open_test > -band : open_test > band)) {
    e.state = PairState::Open;
    e.F[2] = A * sn;
    e.Jl[8] = A;
    for (int j = 0; j < 2; ++j) {
      if (!act[j]) {
        hold(j);
        continue;
      }
      e.F[j] = A * lam[j];
      e.Jl[4 * j] = A;
    }
    return e;
  }
  // Contact: the normal gap closes.
  if (normal) {
    e.F[2] = kA * g[2];
    e.Jg[8] = kA;
  } else {
    hold(2);
  }
  double tau_L = L.cohesion - L.mu * sn, dtau_dln = -L.mu;
  if (tau_L < 0) tau_L = 0, dtau_dln = 0;
  std::array<double, 2> eta{0, 0};
  for (int j = 0; j < 2; ++j)
    if (act[j]) eta[j] = lam[j] + L.k * (g[j] - gc[j]);
  const double ne = std::hypot(eta[0], eta[1]);
  if (previous == PairState::Slip ? ne < tau_L - band : ne <= tau_L + band) {
    e.state = PairState::Stick;
    for (int j = 0; j < 2; ++j) {
      if (!act[j]) {
        hold(j);
        continue;
      }
      e.F[j] = kA * (g[j] - gc[j]);
      e.Jg[4 * j] = kA;
    }
  } else {
    e.state = PairState::Slip;
    const double eh[2] = {eta[0] / ne, eta[1] / ne};
    const double s = tau_L / ne;
    for (int j = 0; j < 2; ++j) {
      if (!act[j]) {
        hold(j);
        continue;
      }
      e.F[j] = A * (lam[j] - tau_L * eh[j]);
      for (int i = 0; i < 2; ++i) {
        if (!act[i]) continue;
        const double P = (i == j ? 1.0 : 0.0) - eh[j] * eh[i];  // projection normal to eta
        e.Jl[3 * j + i] = A * ((i == j ? 1.0 : 0.0) - s * P);
        e.Jg[3 * j + i] = -A * s * P * L.k;
      }
      e.Jl[3 * j + 2] = -A * dtau_dln * eh[j];
    }
  }
  if (L.regularization > 0) add_regularization(e, L.regularization, A, lam, lam_c);
  return e;
}

void add_regularization(PairEquations& e, double weight, double area, const std::array<double, 3>& lam,
                        const std::array<double, 3>& lam_c) {
  for (int j = 0; j < 3; ++j)
    if (e.Jg[4 * j] != 0 && e.Jl[4 * j] == 0) {
      e.F[j] -= weight * area * (lam[j] - lam_c[j]);
      e.Jl[4 * j] = -weight * area;
    }
}

double safety_factor(double tau, double sn, double c, double mu, PairState state) {
  if (state != PairState::Stick) return 1.0;
  const double tau_L = c - sn * mu;
  if (!(tau_L > 0)) return tau > 0 ? 1.0 : 0.0;
  return tau / tau_L;
}

}  // namespace ugs::contact
