#include "ugs/driver/fault_state_file.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include <fmt/format.h>

#include "ugs/driver/settings.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/fields.hpp"

namespace ugs::driver {
namespace {

// Surface node of each pair (the fault output surface has one node per pair, and tip nodes).
std::vector<std::size_t> pair_nodes(const contact::FaultModel& fm) {
  std::vector<std::size_t> at(fm.pairs.size(), SIZE_MAX);
  const auto& np = fm.surface.node_pair;
  for (std::size_t k = 0; k < np.size(); ++k)
    if (np[k] >= 0 && static_cast<std::size_t>(np[k]) < at.size()) at[np[k]] = k;
  for (std::size_t q = 0; q < at.size(); ++q)
    if (at[q] == SIZE_MAX) throw std::logic_error(fmt::format("fault state: node pair {} is not on the fault surface", q));
  return at;
}

}  // namespace

std::string fault_state_path(const std::string& state_h5) { return output_stem(state_h5) + "_faults.h5"; }

void write_fault_state(const std::string& path, const contact::FaultModel& fm, const std::string& date, double time,
                       const contact::FaultContact::Snapshot& s) {
  const auto at = pair_nodes(fm);
  const std::size_t n = fm.surface.mesh.num_nodes();
  std::vector<double> lambda(3 * n, 0.0), g(3 * n, 0.0), dp(n, 0.0), state(n, 0.0);
  for (std::size_t q = 0; q < at.size(); ++q) {
    for (int j = 0; j < 3; ++j) lambda[3 * at[q] + j] = s.lambda[3 * q + j], g[3 * at[q] + j] = s.g[3 * q + j];
    dp[at[q]] = s.dp[q];
    state[at[q]] = s.state[q];
  }
  FieldSeriesWriter w(path, fm.surface.mesh);
  const Field nodes[] = {{"lambda", 3, lambda}, {"g", 3, g}, {"dp", 1, dp}, {"state", 1, state}};
  w.add_step(date, time, nodes);
  w.commit();
}

contact::FaultContact::Snapshot read_fault_state(const std::string& path, const contact::FaultModel& fm,
                                                 const std::string& date) {
  FieldSeriesReader r(path);
  if (r.steps().size() != 1) throw InputError(path, "not a ugs-solve fault state (expected one step)");
  if (r.node_tags() != fm.surface.mesh.node_tags)
    throw InputError(path, fmt::format("the fault state belongs to other faults ({} surface nodes; the faults of this mesh have {})",
                                       r.num_nodes(), fm.surface.mesh.num_nodes()));
  if (r.steps()[0].date != date)
    throw InputError(path, fmt::format("the fault state is of {}, the volume state of {}", r.steps()[0].date, date));
  auto get = [&](const char* name, int comps) {
    Field f = r.node_field(0, name);
    if (f.components != comps) throw InputError(path, fmt::format("node field '{}' has {} components", name, f.components));
    for (std::size_t i = 0; i < f.values.size(); ++i)
      if (!std::isfinite(f.values[i]))
        throw InputError(path, fmt::format("node field '{}': value {} at entry {} is not a finite number", name, f.values[i], i));
    return std::move(f.values);
  };
  const auto at = pair_nodes(fm);
  const auto lambda = get("lambda", 3), g = get("g", 3), dp = get("dp", 1), state = get("state", 1);
  contact::FaultContact::Snapshot s;
  for (std::size_t q = 0; q < at.size(); ++q) {
    const double v = state[at[q]];
    if (v != 0 && v != 1 && v != 2)
      throw InputError(path, fmt::format("node field 'state': {} is not a contact state (0 stick, 1 slip, 2 open)", v));
    for (int j = 0; j < 3; ++j) s.lambda.push_back(lambda[3 * at[q] + j]);
    for (int j = 0; j < 3; ++j) s.g.push_back(g[3 * at[q] + j]);
    s.dp.push_back(dp[at[q]]);
    s.state.push_back(static_cast<std::uint8_t>(v));
  }
  return s;
}

}  // namespace ugs::driver
