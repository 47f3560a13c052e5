// The contact law of one node pair (thesis 3.2-3.3, eqs. 3.24-3.26) written as nonlinear
// equations for Newton's method with an active set (semi-smooth Newton on the Alart-Curnier
// form of the conditions). Local frame: components 0, 1 tangential (strike, dip), 2 normal.
//
//   lambda   total traction on side 1 [Pa], tension positive; sigma'_n = lambda_n + p_f the
//            effective normal traction (p_f the fluid pressure on the fault faces)
//   g        relative displacement u_side2 - u_side1 in the local frame [m]; g_n > 0 opens
//   g_c      g at the last converged (sub-)step: the slip increment is g_T - g_T,c
//
// States, decided from the augmented tractions (k the stiffness scale of the pair):
//   open   sigma'_n + k g_n > 0:        no contact traction: lambda_n = -p_f, lambda_T = 0
//   stick  |eta| <= tau_L:              g_n = 0 and g_T = g_T,c (continuity)
//   slip   |eta| >  tau_L:              g_n = 0 and lambda_T = tau_L eta / |eta|
// with eta = lambda_T + k (g_T - g_T,c) and the Mohr-Coulomb limit tau_L = c - sigma'_n tan(phi)
// (eq. 3.24). At a converged slip state the slip increment is parallel to lambda_T: the shear
// traction is aligned with the slip as maximum plastic dissipation requires (eqs. 3.25-3.26).
//
// Every equation is scaled to a force [N] (constraints by k A, tractions by A), so one norm
// measures the unbalanced forces of the whole system. Components that are not active (held slots of
// a pair on a prescribed boundary, fault_model.hpp constraint_frame) keep their initial traction;
// a pair with a held normal keeps friction on its active shear under that normal traction.
#pragma once
#include <array>
#include <cstdint>

namespace ugs::contact {

enum class PairState : std::uint8_t { Stick = 0, Slip = 1, Open = 2 };
const char* pair_state_name(PairState s);

struct PairLaw {
  double area = 0;       // A_q [m2]
  double k = 0;          // stiffness scale [Pa/m]
  double cohesion = 0;   // Pa
  double mu = 0;         // tan(phi)
  std::uint8_t active = 7;
  double regularization = 0;  // perturbed-Lagrangian weight of redundant pairs (0 otherwise)
};

struct PairEquations {
  PairState state = PairState::Stick;
  std::array<double, 3> F{};   // residual rows [N]
  std::array<double, 9> Jl{};  // dF / d lambda (row-major)
  std::array<double, 9> Jg{};  // dF / d g
};

// lambda0: the initial traction (kept on inactive components); lambda_c: the traction at the last
// converged (sub-)step (regularization of redundant pairs); previous: the state at the last
// evaluation — a pair changes state only when its criterion is passed by more than a relative
// 1e-9 (a pair exactly on a limit would otherwise alternate on round-off alone).
PairEquations pair_equations(const PairLaw& law, const std::array<double, 3>& lambda, const std::array<double, 3>& lambda0,
                             const std::array<double, 3>& lambda_c, const std::array<double, 3>& g,
                             const std::array<double, 3>& g_c, double p_f, PairState previous);

// Redundant pair: its constraints are implied by the others; a perturbed-Lagrangian term on its
// pure constraint rows keeps the multiplier determined (the constraint holds to weight * dlambda / k).
// pair_equations adds it for law.regularization > 0; a caller that chooses the weight after the
// pairs' states are known (they do not depend on it) adds it itself.
void add_regularization(PairEquations& e, double weight, double area, const std::array<double, 3>& lambda,
                        const std::array<double, 3>& lambda_c);

// Safety factor chi = |tau| / (c - sigma'_n tan(phi)) (eq. 4.2) of a sticking pair; 1 where the
// pair slips or is open, and where it carries shear it cannot carry (tau_L <= 0).
double safety_factor(double tau, double sigma_n_eff, double cohesion, double mu, PairState state);

}  // namespace ugs::contact
