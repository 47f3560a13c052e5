#include "fault_part.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "ugs/contact/pair_law.hpp"

namespace ugs::driver {

contact::FaultModel build_faults(const Mesh& mesh, const CaseFile& cs, const mech::Model& model, const Log& note) {
  contact::FaultModel fm = contact::build_fault_model(mesh, cs, model, contact::geostatic_fault_state(model.initial));
  for (const auto& f : fm.faults) {
    // The initial state against the Mohr-Coulomb limit (the thesis' figures 4.41-4.42).
    double chi0 = 0;
    std::size_t over = 0;
    for (const auto& p : fm.pairs) {
      if (&fm.faults[p.fault] != &f || !p.frictional()) continue;
      const double c = contact::safety_factor(std::hypot(p.lambda0[0], p.lambda0[1]), p.lambda0[2] + p.p0, f.cohesion, f.mu,
                                              p.lambda0[2] + p.p0 > 0 ? contact::PairState::Open : contact::PairState::Stick);
      chi0 = std::max(chi0, c);
      over += c > 1;
    }
    note(0, fmt::format("fault {}: {} interface elements, {:.4g} km2, {} node pairs, {} tip nodes; cohesion {:g} MPa, friction "
                        "{:g} deg; initial chi up to {:.3f}", f.name, f.elements, f.area * 1e-6, f.pairs, f.tip_nodes,
                        f.cohesion * 1e-6, f.friction_deg, chi0));
    if (over)
      note(-1, fmt::format("fault {}: the geostatic stress exceeds the Mohr-Coulomb strength at {} node pairs (chi up to "
                           "{:.3f}): they slip in the first step", f.name, over, chi0));
  }
  if (fm.redundant_pairs) note(1, fmt::format("{} node pairs close cycles at fault junctions (regularised)", fm.redundant_pairs));
  if (fm.boundary_pairs)
    note(1, fmt::format("{} node pairs lie on prescribed boundaries (constrained in their free directions only); {} of them "
                        "lack a free normal or shear and are left out of the statistics",
                        fm.boundary_pairs, fm.inactive_pairs));
  return fm;
}

std::vector<double> pair_dp(const contact::FaultModel& fm, const std::vector<double>& node) {
  std::vector<double> pair(fm.pairs.size());
  for (std::size_t q = 0; q < pair.size(); ++q) pair[q] = 0.5 * (node[fm.pairs[q].side1] + node[fm.pairs[q].side2]);
  return pair;
}

std::string fault_step_note(const contact::FaultModel& fm, const contact::FaultFields& ff) {
  const auto stats = contact::fault_date_stats(fm, ff);
  double mc = 0;
  std::size_t ns = 0, no = 0;
  std::string worst;
  for (std::size_t k = 0; k < stats.size(); ++k) {
    if (stats[k].max_chi >= mc) mc = stats[k].max_chi, worst = fm.faults[k].name;
    ns += stats[k].slipping;
    no += stats[k].open;
  }
  return fmt::format("max chi {:.3f} ({}), {} node pairs slipping, {} open", mc, worst, ns, no);
}

}  // namespace ugs::driver
