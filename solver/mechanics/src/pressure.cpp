#include "ugs/mechanics/pressure.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "input_checks.hpp"

namespace ugs::mech {

struct PressureHistory::File {
  std::unique_ptr<FieldSeriesReader> reader;
  // `dp` is a cell field (a reservoir simulator's, ugs-import-eclipse) rather than ugs-flow's node
  // field: one value per file cell, taken by its element as it is.
  bool cells = false;
  std::size_t count = 0;  // values per step
  // Nodal output of a cell field: each mesh node takes the mean of its elements' values (CSR).
  std::vector<std::uint32_t> avg_node, avg_start, avg_row;
  std::vector<std::uint32_t> mesh_index;  // mesh node of each file node
  // Mesh nodes that are corners of this file's cells without being file nodes themselves: the twins
  // ugs-faultinsert made on a fault, which take the pressure of the file node they were split from.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> twins;  // (mesh node, file node)
  std::vector<double> times;
  // The two steps last read (values per file node).
  long cached[2] = {-1, -1};
  std::vector<double> values[2];
  std::vector<char> checked;  // per step: read once, its values checked
  bool before_used = false, after_used = false;

  const std::vector<double>& step_values(long s) {
    for (int k = 0; k < 2; ++k)
      if (cached[k] == s) return values[k];
    const int slot = cached[0] == -1 || (cached[1] != -1 && cached[0] < cached[1]) ? 0 : 1;
    Field f = cells ? reader->cell_field(static_cast<std::size_t>(s), "dp") : reader->node_field(static_cast<std::size_t>(s), "dp");
    if (f.components != 1)
      throw InputError(reader->path(), fmt::format("field 'dp' has {} components, expected 1 (pressure change in Pa)", f.components));
    check_finite(reader->path(), fmt::format("field 'dp' at step {}", reader->steps()[s].date), f.values, 1, "a pressure change in Pa",
                 kMaxPressureChangePa);
    values[slot] = std::move(f.values);
    cached[slot] = s;
    checked[static_cast<std::size_t>(s)] = 1;
    return values[slot];
  }
};

PressureHistory::PressureHistory(const std::vector<std::string>& paths, const Mesh& mesh, const Model& model)
    : num_nodes_(mesh.num_nodes()) {
  const auto index = mesh.node_index_by_tag();
  std::unordered_map<std::uint64_t, std::uint32_t> tet_of_tag;
  tet_of_tag.reserve(model.tet_tags.size() * 2);
  for (std::uint32_t e = 0; e < model.tet_tags.size(); ++e) tet_of_tag.emplace(model.tet_tags[e], e);
  cell_file_.assign(model.tets.size(), -1);
  cell_nodes_.assign(model.tets.size(), {-1, -1, -1, -1});
  std::map<double, std::string> dates;
  for (const auto& p : paths) {
    auto f = std::make_unique<File>();
    f->reader = std::make_unique<FieldSeriesReader>(p);
    if (f->reader->steps().empty()) throw InputError(p, "no steps");
    const auto has_dp = [](const std::vector<std::string>& names) { return std::find(names.begin(), names.end(), "dp") != names.end(); };
    f->cells = !has_dp(f->reader->node_field_names(0)) && has_dp(f->reader->cell_field_names(0));
    const auto tags = f->reader->node_tags();
    f->count = f->cells ? f->reader->num_cells() : tags.size();
    f->mesh_index.resize(tags.size());
    std::vector<std::int32_t> file_node(mesh.num_nodes(), -1);
    std::size_t unknown = 0;
    std::uint64_t first_unknown = 0;
    for (std::size_t i = 0; i < tags.size(); ++i) {
      auto it = index.find(tags[i]);
      if (it == index.end()) {
        if (!unknown++) first_unknown = tags[i];
        continue;
      }
      if (file_node[it->second] >= 0)
        throw InputError(p, fmt::format("/mesh/node_tags: node tag {} appears twice (entries {} and {})", tags[i], file_node[it->second], i));
      f->mesh_index[i] = it->second;
      file_node[it->second] = static_cast<std::int32_t>(i);
    }
    if (unknown)
      throw InputError(p, fmt::format("node tag {} is not in the mesh ({} of {} node tags unknown): the pressure field was "
                                      "computed on another mesh", first_unknown, unknown, tags.size()));
    // The elements this pool's pressure acts on: its sub-mesh cells (tags kept by ugs-submesh), or
    // failing cells, every element whose four nodes the file covers.
    const int fi = static_cast<int>(files_.size());
    // Where a cell field and a node field cover the same element, the cell field wins (a simulator's
    // pressure in the reservoir, ugs-flow's in the aquifers around it), whatever the files' order.
    auto take = [&](std::uint32_t e, const std::array<std::int32_t, 4>& fn) {
      if (cell_file_[e] >= 0 && cell_file_[e] != fi) {
        const bool other_cells = files_[cell_file_[e]]->cells;
        if (other_cells == f->cells)
          throw InputError(p, fmt::format("element {} is also under the pressure of {}: two cell fields (or two node fields) "
                                          "must not overlap; a cell field takes precedence over a node field only",
                                          model.tet_tags[e], files_[cell_file_[e]]->reader->path()));
        if (other_cells) return;
      }
      cell_file_[e] = fi;
      cell_nodes_[e] = fn;
    };
    const auto cell_tags = f->reader->cell_tags();
    const auto file_tets = f->reader->cells(ElementType::Tetrahedron);
    if (!cell_tags.empty() && file_tets.size() == 4 * cell_tags.size()) {
      // The file's own cells give each element's corners, so a mesh whose fault nodes were split
      // after the flow sub-mesh was cut (ugs-faultinsert) gets the pressure of the parent nodes.
      const auto xyz = f->reader->coordinates();
      std::vector<char> is_twin(mesh.num_nodes(), 0);
      std::size_t missing = 0;
      std::uint64_t first_missing = 0;
      std::vector<std::int64_t> entry_of(model.tets.size(), -1);  // (a tag twice is damage, not a later value)
      for (std::size_t c = 0; c < cell_tags.size(); ++c) {
        auto it = tet_of_tag.find(cell_tags[c]);
        if (it == tet_of_tag.end()) {
          if (!missing++) first_missing = cell_tags[c];
          continue;
        }
        const std::uint32_t e = it->second;
        if (entry_of[e] >= 0)
          throw InputError(p, fmt::format("/mesh/cell_tags: cell tag {} appears twice (entries {} and {})", cell_tags[c],
                                          entry_of[e], c));
        entry_of[e] = static_cast<std::int64_t>(c);
        std::array<std::int32_t, 4> fn;
        for (int k = 0; k < 4; ++k) {
          const std::uint32_t m = model.tets[e][k];
          fn[k] = -1;
          for (int j = 0; j < 4 && fn[k] < 0; ++j)
            if (xyz[file_tets[4 * c + j]] == mesh.nodes[m]) fn[k] = static_cast<std::int32_t>(file_tets[4 * c + j]);
          if (fn[k] < 0)
            throw InputError(p, fmt::format("element {}: node {} is at no corner of the file's cell {}: the pressure field "
                                            "was computed on another mesh", model.tet_tags[e], mesh.node_tags[m], cell_tags[c]));
          if (file_node[m] < 0 && !is_twin[m]) {
            is_twin[m] = 1;
            f->twins.emplace_back(m, static_cast<std::uint32_t>(fn[k]));
          }
        }
        take(e, f->cells ? std::array<std::int32_t, 4>{static_cast<std::int32_t>(c), -1, -1, -1} : fn);
      }
      if (missing)
        throw InputError(p, fmt::format("element tag {} is not a tetrahedron of the mesh ({} of {} cell tags unknown)",
                                        first_missing, missing, cell_tags.size()));
    } else if (f->cells) {
      throw InputError(p, "cell field 'dp' without the file's tetrahedra and cell tags (only tetrahedra can carry it)");
    } else {
      for (std::uint32_t e = 0; e < model.tets.size(); ++e) {
        const auto& t = model.tets[e];
        if (file_node[t[0]] >= 0 && file_node[t[1]] >= 0 && file_node[t[2]] >= 0 && file_node[t[3]] >= 0)
          take(e, {file_node[t[0]], file_node[t[1]], file_node[t[2]], file_node[t[3]]});
      }
    }
    const auto& st = f->reader->steps();
    for (std::size_t s = 0; s < st.size(); ++s) {
      if (!std::isfinite(st[s].time))
        throw InputError(p, fmt::format("step {} ({}): time {} is not a finite number of seconds", s, st[s].date, st[s].time));
      if (s > 0 && !(st[s].time > st[s - 1].time))
        throw InputError(p, fmt::format("step {} ({}) is not later than step {} ({})", s, st[s].date, s - 1, st[s - 1].date));
      // Every step holds dp (a listing, no values read): a damaged later step is found before the
      // run starts, not after hours of it.
      const auto names = f->cells ? f->reader->cell_field_names(s) : f->reader->node_field_names(s);
      if (std::find(names.begin(), names.end(), "dp") == names.end())
        throw InputError(p, fmt::format("step {} ({}) has no {} field 'dp' (the first step has one)", s, st[s].date,
                                        f->cells ? "cell" : "node"));
      f->reader->check_field(s, "dp", f->cells);  // the dataset opens and has one value per node/cell
      f->times.push_back(st[s].time);
      dates.emplace(st[s].time, st[s].date);
    }
    // Check the field now rather than after hours of computing.
    f->checked.assign(f->times.size(), 0);
    f->step_values(0);
    files_.push_back(std::move(f));
  }
  for (const auto& [t, d] : dates) steps_.push_back({d, t});
  file_cells_.resize(files_.size());
  for (std::uint32_t e = 0; e < cell_file_.size(); ++e)
    if (cell_file_[e] >= 0) file_cells_[cell_file_[e]].push_back(e);
  for (std::size_t fi = 0; fi < files_.size(); ++fi) {
    File& f = *files_[fi];
    if (!f.cells) continue;
    std::vector<std::uint32_t> n_rows(num_nodes_ + 1, 0);
    for (const std::uint32_t e : file_cells_[fi])
      for (const std::uint32_t m : model.tets[e]) ++n_rows[m + 1];
    for (std::size_t m = 0; m < num_nodes_; ++m)
      if (n_rows[m + 1]) {
        f.avg_node.push_back(static_cast<std::uint32_t>(m));
        f.avg_start.push_back(0);
      }
    std::vector<std::int64_t> slot(num_nodes_, -1);
    for (std::size_t k = 0; k < f.avg_node.size(); ++k) slot[f.avg_node[k]] = static_cast<std::int64_t>(k);
    f.avg_start.assign(f.avg_node.size() + 1, 0);
    for (std::size_t k = 0; k < f.avg_node.size(); ++k) f.avg_start[k + 1] = f.avg_start[k] + n_rows[f.avg_node[k] + 1];
    f.avg_row.resize(f.avg_start.back());
    std::vector<std::uint32_t> fill(f.avg_start.begin(), f.avg_start.end() - 1);
    for (const std::uint32_t e : file_cells_[fi])
      for (const std::uint32_t m : model.tets[e]) f.avg_row[fill[static_cast<std::size_t>(slot[m])]++] = static_cast<std::uint32_t>(cell_nodes_[e][0]);
  }
}

PressureHistory::~PressureHistory() = default;

void PressureHistory::add_step(const std::string& date, const std::string& where) {
  const auto t = parse_iso_date(date);
  if (!t) throw InputError(where, fmt::format("'{}' is not an ISO 8601 date", date));
  const double time = static_cast<double>(*t);
  if (steps_.empty() || time < steps_.front().time || time > steps_.back().time)
    throw InputError(where, fmt::format("output date {} lies outside the pressure history ({} .. {})", date,
                                        steps_.empty() ? "" : steps_.front().date, steps_.empty() ? "" : steps_.back().date));
  for (const auto& s : steps_)
    if (s.time == time) return;
  steps_.push_back({date, time});
  std::sort(steps_.begin(), steps_.end(), [](const PressureStep& a, const PressureStep& b) { return a.time < b.time; });
}

std::vector<double> PressureHistory::file_values(File& f, double time) {
  const auto& T = f.times;
  if (time < T.front()) {
    f.before_used = true;
    return std::vector<double>(f.count, 0.0);
  }
  const long s1 = static_cast<long>(std::upper_bound(T.begin(), T.end(), time) - T.begin());  // first later step
  if (s1 == static_cast<long>(T.size())) {
    if (time > T.back()) f.after_used = true;
    return f.step_values(s1 - 1);
  }
  const long s0 = s1 - 1;
  const double w = (time - T[s0]) / (T[s1] - T[s0]);
  std::vector<double> v = f.step_values(s0);
  if (w == 0) return v;
  const auto& b = f.step_values(s1);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = (1 - w) * v[i] + w * b[i];
  return v;
}

void PressureHistory::check_steps(double until) {
  for (auto& f : files_)
    for (std::size_t s = 0; s < f->times.size(); ++s) {
      if (!f->checked[s]) f->step_values(static_cast<long>(s));
      if (f->times[s] >= until) break;
    }
}

std::vector<double> PressureHistory::cell_dp(double time) {
  const std::vector<double> forced = forced_cell_dp(time);
  std::vector<double> dp(cell_file_.size(), 0.0);
  std::size_t k = 0;
  for (const auto& cells : file_cells_)
    for (const std::uint32_t e : cells) dp[e] = forced[k++];
  return dp;
}

std::vector<double> PressureHistory::forced_cell_dp(double time) {
  std::vector<double> dp;
  dp.reserve(forced_cells());
  for (std::size_t fi = 0; fi < files_.size(); ++fi) {
    const auto v = file_values(*files_[fi], time);
    if (files_[fi]->cells) {
      for (const std::uint32_t e : file_cells_[fi]) dp.push_back(v[cell_nodes_[e][0]]);
      continue;
    }
    for (const std::uint32_t e : file_cells_[fi]) {
      const auto& n = cell_nodes_[e];
      dp.push_back(0.25 * (v[n[0]] + v[n[1]] + v[n[2]] + v[n[3]]));
    }
  }
  return dp;
}

std::vector<double> PressureHistory::node_dp(double time) {
  // Nodes of a cell field's elements take the mean of those elements (summed over cell fields);
  // the node fields are summed over the other nodes.
  std::vector<double> dp(num_nodes_, 0.0);
  std::vector<char> by_cells(num_nodes_, 0);
  for (auto& f : files_) {
    if (!f->cells) continue;
    const auto v = file_values(*f, time);
    for (std::size_t k = 0; k < f->avg_node.size(); ++k) {
      double sum = 0;
      for (std::uint32_t r = f->avg_start[k]; r < f->avg_start[k + 1]; ++r) sum += v[f->avg_row[r]];
      dp[f->avg_node[k]] += sum / static_cast<double>(f->avg_start[k + 1] - f->avg_start[k]);
      by_cells[f->avg_node[k]] = 1;
    }
  }
  for (auto& f : files_) {
    if (f->cells) continue;
    const auto v = file_values(*f, time);
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!by_cells[f->mesh_index[i]]) dp[f->mesh_index[i]] += v[i];
    for (const auto& [m, i] : f->twins)
      if (!by_cells[m]) dp[m] += v[i];
  }
  return dp;
}

std::size_t PressureHistory::forced_cells() const {
  std::size_t n = 0;
  for (const auto& cells : file_cells_) n += cells.size();
  return n;
}

std::vector<std::string> PressureHistory::notes() const {
  std::vector<std::string> n;
  for (const auto& f : files_) {
    const auto& st = f->reader->steps();
    if (f->before_used)
      n.push_back(fmt::format("{}: starts {}; zero pressure change assumed before", f->reader->path(), st.front().date));
    if (f->after_used)
      n.push_back(fmt::format("{}: ends {}; its last pressure change is held after", f->reader->path(), st.back().date));
  }
  return n;
}

}  // namespace ugs::mech
