#include "ugs/ensemble/design.hpp"

#include <fmt/format.h>
#include <openturns/OT.hxx>

#include "ugs/ensemble/morris.hpp"
#include "ugs/formats/error.hpp"

namespace ugs::ensemble {

namespace {

OT::Distribution to_ot(const Distribution& d) {
  OT::Distribution base;
  switch (d.kind) {
    case DistributionKind::uniform: return OT::Uniform(d.a, d.b);
    case DistributionKind::triangular: return OT::Triangular(d.a, d.c, d.b);
    case DistributionKind::normal: base = OT::Normal(d.a, d.b); break;
    case DistributionKind::lognormal: base = OT::LogNormal(std::log(d.a), d.b); break;
  }
  if (d.lower && d.upper) return OT::TruncatedDistribution(base, *d.lower, *d.upper);
  if (d.lower) return OT::TruncatedDistribution(base, *d.lower, OT::TruncatedDistribution::LOWER);
  if (d.upper) return OT::TruncatedDistribution(base, *d.upper, OT::TruncatedDistribution::UPPER);
  return base;
}

OT::Distribution joint(const EnsembleSpec& spec) {
  OT::Collection<OT::Distribution> m;
  for (const auto& p : spec.parameters) m.add(to_ot(p.distribution));
  return OT::ComposedDistribution(m);
}

std::vector<std::vector<double>> rows(const OT::Sample& s) {
  std::vector<std::vector<double>> x(s.getSize(), std::vector<double>(s.getDimension()));
  for (OT::UnsignedInteger i = 0; i < s.getSize(); ++i)
    for (OT::UnsignedInteger j = 0; j < s.getDimension(); ++j) x[i][j] = s(i, j);
  return x;
}

}  // namespace

double quantile(const Distribution& d, double q) { return to_ot(d).computeQuantile(q)[0]; }

std::size_t sobol_dimensions() { return static_cast<std::size_t>(OT::SobolSequence::MaximumDimension); }
std::size_t max_sobol_parameters() { return sobol_dimensions() / 2; }

Design make_design(const EnsembleSpec& spec) {
  const std::size_t d = spec.parameters.size();
  if (spec.members < minimum_members(spec.method, d))
    throw InputError(spec.path, "fewer members than the design needs");  // read_spec checked it already
  Design design;
  design.method = spec.method;
  design.dimension = d;
  OT::RandomGenerator::SetSeed(spec.seed);
  switch (spec.method) {
    case DesignMethod::lhs: {
      OT::LHSExperiment lhs(joint(spec), spec.members, false, true);
      design.base = spec.members;
      design.x = rows(lhs.generate());
      break;
    }
    case DesignMethod::sobol: {
      if (d > max_sobol_parameters())  // read_spec refused it already
        throw InputError(spec.path, fmt::format("the sobol design takes at most {} parameters (OpenTURNS' Sobol' sequence), here {}",
                                                max_sobol_parameters(), d));
      design.base = spec.members / (d + 2);
      // A Sobol' sequence (not randomised: no seed needed) through the joint distribution's
      // quantiles; SobolIndicesExperiment lays out the A, B and pick-freeze blocks.
      OT::LowDiscrepancyExperiment lde(OT::SobolSequence(), joint(spec), design.base, true);
      OT::SobolIndicesExperiment sie(lde, false);
      design.x = rows(sie.generate());
      break;
    }
    case DesignMethod::morris: {
      design.base = spec.members / (d + 1);
      const MorrisDesign m = morris_trajectories(d, design.base, spec.levels);
      design.morris_factor = m.factor;
      // Steps in probability: a unit-cube step Delta moves the quantile's probability by
      // Delta (p - 1) / p (morris_probability), so effects are per unit of probability.
      for (double st : m.step) design.morris_delta.push_back(st * (spec.levels - 1) / spec.levels);
      design.x.resize(m.unit.size(), std::vector<double>(d));
      for (std::size_t j = 0; j < d; ++j) {
        const OT::Distribution dist = to_ot(spec.parameters[j].distribution);
        for (std::size_t i = 0; i < m.unit.size(); ++i)
          design.x[i][j] = dist.computeQuantile(morris_probability(m.unit[i][j], spec.levels))[0];
      }
      break;
    }
  }
  return design;
}

}  // namespace ugs::ensemble
