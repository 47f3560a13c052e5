// The order rule and pinch-outs of a stack of surfaces sampled at the plan columns.
//
// 1. Unconformities: a surface marked `unconformity` truncates every surface below it: wherever one
//    of them rises above it, it is lowered onto it (erosional truncation).
// 2. Order: going down, a surface may rise above the one above it by at most `tolerance` metres
//    (interpolation noise between maps); there it is lowered onto it. Crossing by more is an
//    error naming both surfaces, the number of columns and the first one with its coordinates.
// 3. Pinch-out: going down, a unit thinner than `min_thickness` at a column collapses there: its
//    base is raised onto its top, so the unit has exactly zero thickness and its nodes merge.
#pragma once
#include <string>
#include <vector>

#include "ugs/meshing/plan.hpp"

namespace ugs {

struct StackSurface {
  std::string name;
  std::string where;        // "file:line" of its definition, for errors
  bool unconformity = false;
};

struct StackRules {
  double tolerance = 1.0;      // m
  double min_thickness = 0.5;  // m
};

struct StackReport {
  std::vector<std::size_t> truncated;   // per surface: columns lowered by an unconformity
  std::vector<std::size_t> clamped;     // per surface: columns lowered by the order rule (within tolerance)
  std::vector<double> max_clamp;        // per surface: largest such lowering (m)
  std::vector<std::size_t> collapsed;   // per unit: columns where it has zero thickness after the rule
};

// Applies the rules in place to z[surface][column]. Throws InputError at the lower surface's
// `where` when the order is broken beyond the tolerance.
StackReport apply_stack_rules(std::vector<std::vector<double>>& z, const std::vector<StackSurface>& surfaces,
                              const Plan& plan, const StackRules& rules);

// "1,532"
std::string thousands(std::size_t n);

}  // namespace ugs
