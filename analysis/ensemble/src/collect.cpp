#include "ugs/ensemble/collect.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "ugs/ensemble/fault_pairs.hpp"
#include "ugs/ensemble/morris.hpp"
#include "ugs/ensemble/statistics.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"

namespace ugs::ensemble {

namespace fs = std::filesystem;

CollectSummary collect(const EnsembleSpec& spec, const EnsembleMembers& members, const MetricOptions& options,
                       const std::string& out_dir, const std::vector<std::string>& comments) {
  CollectSummary sum;
  const std::size_t n = members.size(), d = spec.parameters.size();
  sum.members = n;
  const fs::path out(out_dir);
  // 1. Each member's metrics.
  std::vector<std::optional<Metrics>> metrics(n);
  std::vector<MemberOutputs> series(n);
  std::vector<std::string> errors(n);
  std::vector<std::string> names;
  std::map<std::string, std::size_t> column;
  PairHistoryCache histories;  // members sharing an entry read its per-pair CSVs once
  for (std::size_t k = 0; k < n; ++k) {
    const MemberStatus s = members.status(k);
    if (s.state != MemberState::done) {
      errors[k] = s.state == MemberState::failed ? s.error : "not run (no entry in the cache)";
      continue;
    }
    try {
      const std::optional<CaseFile> own = options.seismic_windows.empty() ? std::nullopt : members.forecast_case(k);
      series[k] = member_outputs(members.folder(k), options, own ? &*own : nullptr, &histories);
      metrics[k] = series[k].metrics;
    } catch (const InputError& e) {
      errors[k] = fmt::format("member {}: {}", k + 1, e.what());
      continue;
    }
  }
  // 2. Each member's chi at the fault node pairs. The members share the mesh: a member whose pairs
  // differ from the set most members share (ties: the earliest) is a failed member, never mixed in.
  std::vector<MemberPairs> pairs(n);
  std::vector<std::size_t> group(n, n), group_ref, group_size;  // group of member k; each group's first member, size
  std::map<std::string, std::size_t> read_for;  // folder -> the member whose pairs were read from it
  for (std::size_t k = 0; k < n; ++k) {
    if (!metrics[k]) continue;
    try {
      const auto [it, fresh] = read_for.emplace(members.folder(k), k);
      pairs[k] = fresh ? read_member_pairs(members.folder(k)) : pairs[it->second];
    } catch (const InputError& e) {
      errors[k] = fmt::format("member {}: {}", k + 1, e.what());
      metrics[k].reset();
      continue;
    }
    std::size_t g = 0;
    while (g < group_ref.size() && !pair_set_difference(pairs[k], pairs[group_ref[g]], group_ref[g] + 1).empty()) ++g;
    if (g == group_ref.size()) group_ref.push_back(k), group_size.push_back(0);
    group[k] = g;
    ++group_size[g];
  }
  std::vector<const MemberPairs*> same_pairs;
  if (!group_ref.empty()) {
    const std::size_t best = static_cast<std::size_t>(std::max_element(group_size.begin(), group_size.end()) - group_size.begin());
    const std::size_t ref = group_ref[best];
    for (std::size_t k = 0; k < n; ++k) {
      if (!metrics[k]) continue;
      if (group[k] == best) {
        same_pairs.push_back(&pairs[k]);
        continue;
      }
      errors[k] = fmt::format("member {}: its fault node pairs differ from member {}'s (the members share the mesh): {}", k + 1, ref + 1,
                              pair_set_difference(pairs[k], pairs[ref], ref + 1));
      metrics[k].reset();
    }
  }
  // The metric names in first-seen order (members in design order).
  for (std::size_t k = 0; k < n; ++k)
    if (metrics[k])
      for (const auto& [name, v] : *metrics[k])
        if (column.emplace(name, names.size()).second) names.push_back(name);
  for (std::size_t k = 0; k < n; ++k)
    if (metrics[k]) ++sum.done;
    else sum.failures.emplace_back(k + 1, errors[k]);
  // value[m][k], and whether member k has metric m
  std::vector<std::vector<double>> value(names.size(), std::vector<double>(n, 0.0));
  std::vector<std::vector<bool>> has(names.size(), std::vector<bool>(n, false));
  // The metric names in first-seen order (members in design order).
  for (std::size_t k = 0; k < n; ++k)
    if (metrics[k])
      for (const auto& [name, v] : *metrics[k]) {
        value[column[name]][k] = v;
        has[column[name]][k] = true;
      }

  {
    CsvWriter w((out / "parameters.csv").string(), {"parameter", "paths", "distribution"}, comments);
    for (const auto& p : spec.parameters) {
      std::string paths;
      for (const auto& q : p.paths) paths += (paths.empty() ? "" : ";") + q;
      w.text(p.name).text(paths).text(p.distribution.describe()).end_row();
    }
    w.commit();
  }
  {
    std::vector<std::string> cols{"member", "entry", "status"};
    for (const auto& p : spec.parameters) cols.push_back(p.name);
    cols.insert(cols.end(), names.begin(), names.end());
    CsvWriter w((out / "members.csv").string(), cols, comments);
    for (std::size_t k = 0; k < n; ++k) {
      w.integer(static_cast<std::int64_t>(k + 1)).text(members.entry(k)).text(metrics[k] ? "ok" : "failed");
      for (std::size_t i = 0; i < d; ++i) w.number(members.design().x[k][i]);
      for (std::size_t m = 0; m < names.size(); ++m) {
        if (has[m][k]) w.number(value[m][k]);
        else w.text("");
      }
      w.end_row();
    }
    w.commit();
  }
  {
    CsvWriter w((out / "failures.csv").string(), {"member", "entry", "error"}, comments);
    for (const auto& [k, e] : sum.failures) w.integer(static_cast<std::int64_t>(k)).text(members.entry(k - 1)).text(e).end_row();
    w.commit();
  }
  if (sum.done == 0) throw ComputeError(fmt::format("no member of {} succeeded (failures.csv lists them)", n));
  auto values_of = [&](std::size_t m) {
    std::vector<double> v;
    for (std::size_t k = 0; k < n; ++k)
      if (has[m][k]) v.push_back(value[m][k]);
    return v;
  };
  {
    CsvWriter w((out / "quantiles.csv").string(), {"metric", "n", "mean", "p10", "p50", "p90", "min", "max"}, comments);
    for (std::size_t m = 0; m < names.size(); ++m) {
      const Quantiles q = quantiles(values_of(m));
      w.text(names[m]).integer(static_cast<std::int64_t>(q.n)).number(q.mean).number(q.p10).number(q.p50).number(q.p90);
      w.number(q.min).number(q.max).end_row();
    }
    w.commit();
  }
  {
    CsvWriter w((out / "exceedance.csv").string(), {"fault", "n", "p_chi_ge_0.8", "p_chi_ge_1"}, comments);
    const std::string prefix = "chi_max.";
    for (std::size_t m = 0; m < names.size(); ++m) {
      const std::string& name = names[m];
      if (name.rfind(prefix, 0) != 0) continue;
      const std::string fault = name.substr(prefix.size());
      // chi_max.<fault>, not the per-date chi_max.<fault>.<date>
      const auto dot = fault.rfind('.');
      if (dot != std::string::npos && parse_iso_date(fault.substr(dot + 1))) continue;
      const auto v = values_of(m);
      w.text(fault).integer(static_cast<std::int64_t>(v.size())).number(exceedance(v, 0.8)).number(exceedance(v, 1.0)).end_row();
    }
    w.commit();
  }
  if (!same_pairs.empty() && !same_pairs.front()->empty())
    write_chi_exceedance(same_pairs, (out / "chi_exceedance_pairs.csv").string(), comments);
  // The fan charts' data: quantiles of the simulated series at each PS point and date, beside the
  // measured value (each relative to the first PS date the results reach).
  if (options.ps && options.ps->has_series()) {
    CsvWriter w((out / "ps_series.csv").string(), {"pid", "date", "n", "p10_mm", "p50_mm", "p90_mm", "measured_mm"}, comments);
    const MemberOutputs* ref = nullptr;
    for (std::size_t k = 0; k < n && !ref; ++k)
      if (metrics[k] && !series[k].ps_ids.empty()) ref = &series[k];
    if (ref) {
      const std::size_t nd = ref->ps_dates.size();
      for (std::size_t p = 0; p < ref->ps_ids.size(); ++p) {
        const auto mi = options.ps->find(ref->ps_ids[p]);
        for (std::size_t t = 0; t < nd; ++t) {
          std::vector<double> v;
          for (std::size_t k = 0; k < n; ++k)
            if (metrics[k] && series[k].ps_ids == ref->ps_ids && std::isfinite(series[k].ps_up_mm[p * nd + t]))
              v.push_back(series[k].ps_up_mm[p * nd + t]);
          if (v.empty()) continue;
          const Quantiles q = quantiles(v);
          w.text(ref->ps_ids[p]).date(ref->ps_dates[t]).integer(static_cast<std::int64_t>(q.n)).number(q.p10).number(q.p50).number(q.p90);
          const double meas = mi ? options.ps->value_mm(*mi, t) : NAN;
          if (std::isfinite(meas)) w.number(meas);
          else w.text("");
          w.end_row();
        }
      }
    }
    w.commit();
  }
  std::vector<bool> ok(n);
  auto ok_for = [&](std::size_t m) {
    for (std::size_t k = 0; k < n; ++k) ok[k] = has[m][k];
    return ok;
  };
  if (spec.method == DesignMethod::sobol) {
    std::vector<std::string> no_variance;
    std::vector<std::string> c = comments;
    CsvWriter w((out / "sobol.csv").string(),
                {"metric", "parameter", "s1", "s1_low", "s1_high", "st", "st_low", "st_high", "base_points"}, c);
    for (std::size_t m = 0; m < names.size(); ++m) {
      SobolIndices s;
      try {
        s = sobol_indices(members.design(), value[m], ok_for(m));
      } catch (const ComputeError& e) {
        sum.notes.push_back(fmt::format("no Sobol' indices for {}: {}", names[m], e.what()));
        continue;
      }
      for (std::size_t i = 0; i < d; ++i) {
        w.text(names[m]).text(spec.parameters[i].name).number(s.first[i]).number(s.first_low[i]).number(s.first_high[i]);
        w.number(s.total[i]).number(s.total_low[i]).number(s.total_high[i]).integer(static_cast<std::int64_t>(s.base)).end_row();
      }
    }
    w.commit();
  }
  if (spec.method == DesignMethod::morris) {
    CsvWriter w((out / "morris.csv").string(), {"metric", "parameter", "mu", "mu_star", "sigma", "trajectories"}, comments);
    for (std::size_t m = 0; m < names.size(); ++m) {
      const MorrisEffects e = morris_effects(d, members.design().morris_factor, members.design().morris_delta, value[m], ok_for(m));
      if (e.trajectories == 0) {
        sum.notes.push_back(fmt::format("no Morris effects for {}: no complete trajectory", names[m]));
        continue;
      }
      for (std::size_t i = 0; i < d; ++i)
        w.text(names[m]).text(spec.parameters[i].name).number(e.mu[i]).number(e.mu_star[i]).number(e.sigma[i])
            .integer(static_cast<std::int64_t>(e.trajectories)).end_row();
    }
    w.commit();
  }
  return sum;
}

}  // namespace ugs::ensemble
