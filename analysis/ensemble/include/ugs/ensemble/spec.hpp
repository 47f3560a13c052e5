// An ensemble's description (a TOML file): the design and the uncertain parameters, each a
// case-file path (as ugs-calibrate names them: material.pool_c.c_R, initial_stress.k_Hmax,
// fault.backthrust_south.friction_deg, ...) or several set to the same value, with a distribution.
//
//   [design]
//   method = "sobol"          # "lhs" (Latin hypercube), "sobol" (Saltelli's design for Sobol'
//   members = 120             #  indices), "morris" (elementary effects); members requested
//   seed = 1                  # the random stream (OpenTURNS' Mersenne twister): same seed, same members
//   levels = 4                # Morris only: grid levels per parameter (even, >= 2)
//
//   [[parameter]]
//   path = "material.pool_c.c_R"             # or paths = ["material.pool_c.c_R", "material.aquifer_pool_c.c_R"]
//   distribution = "uniform"                 # uniform: lower, upper
//   lower = 2.0                              # normal: mean, std      lognormal: median, sigma_log
//   upper = 6.0                              # triangular: lower, mode, upper
//                                            # normal/lognormal with lower and/or upper: truncated
// Every error is an InputError naming the file and line of the offending key.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ugs::runner {
class CaseTemplate;
}

namespace ugs::ensemble {

enum class DistributionKind { uniform, normal, lognormal, triangular };

struct Distribution {
  DistributionKind kind = DistributionKind::uniform;
  double a = 0, b = 0, c = 0;              // uniform: lower, upper; normal: mean, std;
                                           // lognormal: median, sigma_log; triangular: lower, mode, upper
  std::optional<double> lower, upper;      // truncation of normal/lognormal
  std::string describe() const;            // "uniform(2, 6)", "normal(1.1, 0.1) on [0.9, inf)"
};

struct Parameter {
  std::string name;                        // `name`, or the first path (as in tables)
  std::vector<std::string> paths;          // case-file paths set to the same value
  Distribution distribution;
  std::string where;                       // "ensemble.toml:12" for messages
};

enum class DesignMethod { lhs, sobol, morris };
std::string to_string(DesignMethod m);

struct EnsembleSpec {
  std::string path;                        // the TOML file
  DesignMethod method = DesignMethod::lhs;
  std::size_t members = 0;                 // as requested
  std::uint64_t seed = 1;
  int levels = 4;                          // Morris
  std::vector<Parameter> parameters;
};

// Reads and checks the file: known keys only, a [design] table, at least one parameter, a path
// named once over all parameters, valid distribution parameters (lower < upper, std > 0,
// lower <= mode <= upper, truncation leaving some probability), `members` enough for the design
// (minimum_members).
EnsembleSpec read_spec(const std::string& path);

// The fewest members a design can have with d parameters: LHS 2, Sobol' 2 (d + 2) (two base
// points), Morris 2 (d + 1) (two trajectories).
std::size_t minimum_members(DesignMethod m, std::size_t d);

// Every path must be a number in the case, and the case must stay valid (ugs::read_case_file) at
// each parameter's low and high end (the 0.1 % and 99.9 % quantiles for unbounded
// distributions): the check ugs-calibrate makes for its bounds (runner::check_parameters).
void check_against_case(const EnsembleSpec& spec, const runner::CaseTemplate& tmpl);

}  // namespace ugs::ensemble
