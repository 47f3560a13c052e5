// The members of an ensemble: one row of parameter values (natural units) per member.
//   lhs     OpenTURNS' LHSExperiment (McKay, Beckman & Conover 1979) of the joint distribution
//           (independent marginals), random shift inside each stratum, `members` rows.
//   sobol   OpenTURNS' SobolIndicesExperiment over a Sobol' low-discrepancy sequence (Saltelli
//           2002): N = members / (d + 2) base points, rows in blocks A (N), B (N), then for each
//           parameter i the block A with column i taken from B; N (d + 2) rows.
//   morris  r = members / (d + 1) one-at-a-time trajectories (morris.hpp); r (d + 1) rows.
// Deterministic: the same spec (seed included) gives the same rows, bit for bit.
#pragma once
#include <cstddef>
#include <vector>

#include "ugs/ensemble/spec.hpp"

namespace ugs::ensemble {

struct Design {
  DesignMethod method = DesignMethod::lhs;
  std::size_t dimension = 0;
  std::size_t base = 0;                    // sobol: N; morris: trajectories r; lhs: rows
  std::vector<std::vector<double>> x;      // member -> values, in parameter order
  // Morris: each step's parameter and its signed step in probability space (morris.hpp).
  std::vector<std::size_t> morris_factor;  // per row (0 for a trajectory's first row)
  std::vector<double> morris_delta;
};

Design make_design(const EnsembleSpec& spec);

// The dimensions of OpenTURNS' Sobol' sequence (OT::SobolSequence::MaximumDimension, 1111 in 1.20),
// and the most parameters a sobol design takes: the blocks A and B take 2 per parameter.
// read_spec refuses more with the file's line; make_design checks it again.
std::size_t sobol_dimensions();
std::size_t max_sobol_parameters();

// The quantile of a parameter's distribution at probability q in (0, 1) (OpenTURNS).
double quantile(const Distribution& d, double q);

}  // namespace ugs::ensemble
