#include "ugs/ensemble/spec.hpp"

#include <cmath>
#include <limits>
#include <set>

#include <fmt/format.h>

#include "ugs/ensemble/design.hpp"
#include "ugs/formats/toml_reader.hpp"
#include "ugs/runner/case_params.hpp"

namespace ugs::ensemble {

std::string to_string(DesignMethod m) {
  switch (m) {
    case DesignMethod::lhs: return "lhs";
    case DesignMethod::sobol: return "sobol";
    case DesignMethod::morris: return "morris";
  }
  return "";
}

std::string Distribution::describe() const {
  std::string s;
  switch (kind) {
    case DistributionKind::uniform: s = fmt::format("uniform({:g}, {:g})", a, b); break;
    case DistributionKind::normal: s = fmt::format("normal({:g}, {:g})", a, b); break;
    case DistributionKind::lognormal: s = fmt::format("lognormal(median {:g}, sigma_log {:g})", a, b); break;
    case DistributionKind::triangular: s = fmt::format("triangular({:g}, {:g}, {:g})", a, c, b); break;
  }
  if (lower || upper)
    s += fmt::format(" on [{}, {}]", lower ? fmt::format("{:g}", *lower) : "-inf", upper ? fmt::format("{:g}", *upper) : "inf");
  return s;
}

std::size_t minimum_members(DesignMethod m, std::size_t d) {
  switch (m) {
    case DesignMethod::lhs: return 2;
    case DesignMethod::sobol: return 2 * (d + 2);
    case DesignMethod::morris: return 2 * (d + 1);
  }
  return 2;
}

namespace {

// The probability of [lo, hi] under an untruncated normal or lognormal law (closed form: the
// normal CDF through erfc, each tail from its own side so that far tails do not cancel to 0).
double probability_between(const Distribution& d, double lo, double hi) {
  auto z = [&](double x) {
    if (d.kind == DistributionKind::lognormal) return x <= 0 ? -std::numeric_limits<double>::infinity() : (std::log(x) - std::log(d.a)) / d.b;
    return (x - d.a) / d.b;
  };
  const double zl = z(lo), zh = z(hi);
  const double r = 1 / std::sqrt(2.0);
  if (zl >= 0) return 0.5 * (std::erfc(zl * r) - std::erfc(zh * r));   // upper tail
  if (zh <= 0) return 0.5 * (std::erfc(-zh * r) - std::erfc(-zl * r));  // lower tail
  return 1 - 0.5 * (std::erfc(-zl * r) + std::erfc(zh * r));
}

Distribution read_distribution(const TomlTable& t) {
  Distribution d;
  const std::string kind = t.string("distribution");
  // Every number of a law is 0 or a normal double: OpenTURNS writes a law's numbers into its own
  // formulas and cannot read back a subnormal one (uniform(0, 5e-324): "Invalid numeric token").
  auto number = [&](const std::string& key) {
    const double v = t.number(key);
    if (v != 0 && !std::isnormal(v))
      throw t.error(key, fmt::format("{:g} is too close to 0 (expected 0 or a magnitude above {:g})", v,
                                     std::numeric_limits<double>::min()));
    return v;
  };
  auto positive = [&](const std::string& key) {
    const double v = number(key);
    if (!(v > 0)) throw t.error(key, fmt::format("must be > 0 (got {:g})", v));
    return v;
  };
  // The width of a bounded law must be a finite number: uniform(-1e308, 1e308) has none, and its
  // members would be inf or NaN. The triangular quantile takes the square root of a product of two
  // widths (upper - lower)(upper - mode), so its width must be at most 1e150 (triangular(0, 0, 1e308)
  // drew -inf).
  auto finite_width = [&](const char* law, double most) {
    const double w = d.b - d.a;
    if (!std::isnormal(w) || w > most)
      throw t.error("upper", fmt::format("{} range [{:g}, {:g}]: upper - lower = {:g} (expected a width from {:g} to {:g})", law,
                                         d.a, d.b, w, std::numeric_limits<double>::min(), most));
  };
  if (kind == "uniform") {
    d.kind = DistributionKind::uniform;
    d.a = number("lower");
    d.b = number("upper");
    if (!(d.a < d.b)) throw t.error("upper", fmt::format("uniform bounds reversed or equal: lower {:g} >= upper {:g}", d.a, d.b));
    finite_width("uniform", std::numeric_limits<double>::max());
    t.reject_unknown({"name", "path", "paths", "distribution", "lower", "upper"});
    return d;
  }
  if (kind == "triangular") {
    d.kind = DistributionKind::triangular;
    d.a = number("lower");
    d.c = number("mode");
    d.b = number("upper");
    if (!(d.a < d.b)) throw t.error("upper", fmt::format("triangular bounds reversed or equal: lower {:g} >= upper {:g}", d.a, d.b));
    if (d.c < d.a || d.c > d.b) throw t.error("mode", fmt::format("mode {:g} outside [lower, upper] = [{:g}, {:g}]", d.c, d.a, d.b));
    finite_width("triangular", 1e150);
    t.reject_unknown({"name", "path", "paths", "distribution", "lower", "mode", "upper"});
    return d;
  }
  // Unbounded laws: their values within 9 standard deviations (probability 1 - 2e-19, beyond any
  // quantile taken) must be finite doubles; OpenTURNS refuses a lognormal law whose range leaves
  // them ("too much wide range").
  if (kind == "normal") {
    d.kind = DistributionKind::normal;
    d.a = number("mean");
    d.b = positive("std");
    if (!(std::abs(d.a) + 9 * d.b <= std::numeric_limits<double>::max()))
      throw t.error("std", fmt::format("normal({:g}, {:g}) reaches beyond the largest double within 9 std (expected |mean| + 9 std "
                                       "<= {:g})", d.a, d.b, std::numeric_limits<double>::max()));
    t.reject_unknown({"name", "path", "paths", "distribution", "mean", "std", "lower", "upper"});
  } else if (kind == "lognormal") {
    d.kind = DistributionKind::lognormal;
    d.a = positive("median");
    d.b = positive("sigma_log");
    if (!(std::abs(std::log(d.a)) + 9 * d.b < 700))
      throw t.error("sigma_log", fmt::format("lognormal(median {:g}, sigma_log {:g}) spans more than doubles hold within 9 sigma_log "
                                             "(expected |ln median| + 9 sigma_log < 700)", d.a, d.b));
    t.reject_unknown({"name", "path", "paths", "distribution", "median", "sigma_log", "lower", "upper"});
  } else {
    throw t.error("distribution", fmt::format("unknown distribution '{}' (expected uniform, normal, lognormal or triangular; "
                                              "normal and lognormal take lower/upper to truncate)", kind));
  }
  if (t.has("lower")) d.lower = number("lower");
  if (t.has("upper")) d.upper = number("upper");
  if (d.lower && d.upper && !(*d.lower < *d.upper))
    throw t.error("upper", fmt::format("truncation bounds reversed or equal: lower {:g} >= upper {:g}", *d.lower, *d.upper));
  // The truncation must leave some probability: at least 1e-6 of the untruncated law (OpenTURNS
  // refuses an interval whose probability rounds to 0, and the law of a thinner slice is noise).
  if (d.lower || d.upper) {
    Distribution base = d;
    base.lower.reset();
    base.upper.reset();
    const double lo = d.lower ? *d.lower : -std::numeric_limits<double>::infinity();
    const double hi = d.upper ? *d.upper : std::numeric_limits<double>::infinity();
    if (base.kind == DistributionKind::lognormal && hi <= 0)
      throw t.error("upper", fmt::format("a lognormal law has no probability below {:g}", hi));
    const double p = probability_between(base, lo, hi);
    if (!(p >= 1e-6))
      throw t.error(d.lower ? "lower" : "upper",
                    fmt::format("the truncation [{}, {}] leaves no probability of {} ({:.3g} of it; expected at least 1e-06)",
                                lo, hi, base.describe(), p));
  }
  return d;
}

}  // namespace

EnsembleSpec read_spec(const std::string& path) {
  const TomlTable root = TomlTable::parse_file(path);
  root.reject_unknown({"design", "parameter"});
  EnsembleSpec s;
  s.path = path;
  const TomlTable design = root.table("design");
  design.reject_unknown({"method", "members", "seed", "levels"});
  const std::string method = design.string("method");
  if (method == "lhs") s.method = DesignMethod::lhs;
  else if (method == "sobol") s.method = DesignMethod::sobol;
  else if (method == "morris") s.method = DesignMethod::morris;
  else throw design.error("method", fmt::format("unknown design '{}' (expected lhs, sobol or morris)", method));
  const long long members = design.integer("members");
  if (members < 1 || members > 10'000'000) throw design.error("members", fmt::format("{} members (expected 1 to 10000000)", members));
  s.members = static_cast<std::size_t>(members);
  const long long seed = design.integer_opt("seed").value_or(1);
  if (seed < 0) throw design.error("seed", "must be >= 0");
  s.seed = static_cast<std::uint64_t>(seed);
  const long long levels = design.integer_opt("levels").value_or(4);
  if (levels < 2 || levels % 2 != 0 || levels > 1000)
    throw design.error("levels", fmt::format("{} Morris levels (expected an even number from 2 to 1000)", levels));
  if (design.has("levels") && s.method != DesignMethod::morris) throw design.error("levels", "only the morris design has levels");
  s.levels = static_cast<int>(levels);

  const auto params = root.tables("parameter");
  if (params.empty()) throw InputError(path, "no [[parameter]] (expected at least one uncertain parameter)");
  std::set<std::string> seen;
  for (const auto& t : params) {
    Parameter p;
    p.where = t.where();
    if (t.has("path") == t.has("paths")) throw t.error("path", "give either path = \"...\" or paths = [...]");
    p.paths = t.has("path") ? std::vector<std::string>{t.string("path")} : t.strings("paths");
    if (p.paths.empty()) throw t.error("paths", "is empty");
    for (const auto& q : p.paths)
      if (!seen.insert(q).second) throw t.error(t.has("path") ? "path" : "paths", fmt::format("'{}' is named twice", q));
    // The name in every table and chart: `name`, or the first path (one value set on several paths,
    // e.g. the friction of every fault, reads better under a name of its own).
    p.name = t.has("name") ? t.string("name") : p.paths.front();
    if (p.name.empty() || p.name.find_first_of(",\"\n\r") != std::string::npos)
      throw t.error("name", "must be non-empty text without commas, quotes or line breaks (it heads a CSV column)");
    for (const auto& other : s.parameters)
      if (other.name == p.name) throw t.error(t.has("name") ? "name" : "path", fmt::format("'{}' names two parameters", p.name));
    p.distribution = read_distribution(t);
    s.parameters.push_back(std::move(p));
  }
  // Beyond max_sobol_parameters() OpenTURNS throws its own exception.
  if (s.method == DesignMethod::sobol && s.parameters.size() > max_sobol_parameters())
    throw design.error("method", fmt::format("the sobol design takes at most {} parameters (OpenTURNS' Sobol' sequence has {} "
                                             "dimensions, 2 per parameter), here {}",
                                             max_sobol_parameters(), sobol_dimensions(), s.parameters.size()));
  const std::size_t need = minimum_members(s.method, s.parameters.size());
  if (s.members < need)
    throw design.error("members", fmt::format("{} members are fewer than the {} design needs with {} parameters (at least {})",
                                              s.members, method, s.parameters.size(), need));
  return s;
}

void check_against_case(const EnsembleSpec& spec, const runner::CaseTemplate& tmpl) {
  std::vector<runner::ParameterSpec> ps;
  for (const auto& p : spec.parameters) {
    runner::ParameterSpec q;
    q.name = p.name;
    q.paths = p.paths;
    const Distribution& d = p.distribution;
    q.lower = d.kind == DistributionKind::uniform || d.kind == DistributionKind::triangular ? d.a : quantile(d, 1e-3);
    q.upper = d.kind == DistributionKind::uniform || d.kind == DistributionKind::triangular ? d.b : quantile(d, 1 - 1e-3);
    ps.push_back(std::move(q));
  }
  runner::check_parameters(tmpl, ps, spec.path);
}

}  // namespace ugs::ensemble
