// Saddle system of the contact solver: the blocks that the faults add to the displacement block K,
//
//   [ K   C ] [du]     [ f_ext - f_int(u) - C (lambda - lambda_0) ]
//   [ B   D ] [dl] = - [ F(u, lambda)                              ]
//
// C the node-to-node coupling (constant: C_q = A_q R_q on the side-2 rows, -A_q R_q on the side-1
// rows, free components only), B and D the derivatives of each owned pair's equations (pair_law.hpp)
// with respect to the twins' displacements and to its multiplier, refilled at every Newton
// iteration in the pattern fixed here.
#pragma once
#include <array>
#include <vector>

#include <petscmat.h>

#include "pair_distribution.hpp"
#include "ugs/contact/pair_law.hpp"

namespace ugs::contact::detail {

class SaddleSystem {
public:
  SaddleSystem() = default;
  ~SaddleSystem();
  SaddleSystem(const SaddleSystem&) = delete;
  SaddleSystem& operator=(const SaddleSystem&) = delete;

  // Collective: C (and C^T), the patterns of B and D, the work vectors.
  void create(const mech::CouplingContext& ctx, const PairDistribution& pd);
  // Collective: r -= C (lambda - lambda_0).
  void subtract_coupling_force(const PairDistribution& pd, const std::vector<std::array<double, 3>>& lam, Vec r);
  // Collective: B and D from the pairs' equations in their current state.
  void fill(const PairDistribution& pd, const std::vector<PairEquations>& eq);

  Mat Ct = nullptr, C = nullptr, B = nullptr, D = nullptr;
  Vec dl = nullptr;  // a multiplier vector (work)
  Vec fc = nullptr;  // a displacement vector (work)
};

}  // namespace ugs::contact::detail
