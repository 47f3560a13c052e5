#include "ugs/ensemble/friction_variants.hpp"

#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <unordered_map>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/io.hpp"

namespace ugs::ensemble {

namespace fs = std::filesystem;

bool friction_only(const std::string& path) {
  return path.size() > std::string_view("fault..friction_deg").size() && path.starts_with("fault.") && path.ends_with(".friction_deg");
}

namespace {

// Thrown inside the derivation when it does not hold; caught at the top into `reason`.
struct NotDerived {
  std::string why;
};

FaultSpec fault_of(const CaseFile& c, const std::string& name) {
  for (const auto& f : c.faults)
    if (f.name == name) return f;
  FaultSpec d;  // not in the case: ugs-solve's defaults
  d.name = name;
  return d;
}

double tan_deg(double deg) { return std::tan(deg * M_PI / 180.0); }

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> cells;
  std::size_t start = 0;
  for (;;) {
    const auto comma = line.find(',', start);
    cells.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) return cells;
    start = comma + 1;
  }
}

// A CSV of ugs-solve read line by line: the comment lines, the header, then one row at a time.
class CsvLines {
public:
  explicit CsvLines(const std::string& path) : in_(InputStream::open(path, "a CSV table of ugs-solve")) {
    std::string line;
    while (in_->getline(line)) {
      if (!line.empty() && line[0] == '#') {
        comments_.push_back(line.size() > 1 && line[1] == ' ' ? line.substr(2) : line.substr(1));
        continue;
      }
      for (auto c : split(line)) header_.emplace_back(c);
      return;
    }
    throw in_->error("no header line");
  }
  const std::vector<std::string>& comments() const { return comments_; }
  const std::vector<std::string>& header() const { return header_; }
  std::size_t column(const std::string& name) const {
    for (std::size_t i = 0; i < header_.size(); ++i)
      if (header_[i] == name) return i;
    throw InputError(in_->name(), fmt::format("no column '{}' (expected a table of ugs-solve)", name));
  }
  // The next row's cells (views into this reader's buffer, valid until the next call); false at the end.
  bool next(std::vector<std::string_view>& cells) {
    while (in_->getline(line_)) {
      if (line_.empty()) continue;
      cells = split(line_);
      if (cells.size() != header_.size())
        throw InputError(where(), fmt::format("{} fields for {} columns", cells.size(), header_.size()));
      return true;
    }
    return false;
  }
  double number(std::string_view cell) const {
    const auto v = parse_finite_number(cell);
    if (!v) throw InputError(where(), fmt::format("'{}' is not a finite number", cell));
    return *v;
  }
  std::string where() const { return fmt::format("{}:{}", in_->name(), in_->line()); }

private:
  std::unique_ptr<InputStream> in_;
  std::vector<std::string> comments_, header_;
  std::string line_;
};

// Per fault and date: the fault table's statistics over the frictional pairs (interpolated = 0).
struct DateStats {
  std::size_t pairs = 0;
  double max_chi = 0, max_cfs = 0;
  double x = 0, y = 0, z = 0;
};

struct FaultChange {
  std::string name;
  double mu_run = 0, mu = 0, cohesion_MPa = 0;
};

// Rewrites one fault's per-pair CSV for the member's friction; returns its statistics by date and
// the largest chi.
std::map<std::string, DateStats> rewrite_pairs(const std::string& in, const std::string& out, const FaultChange& f,
                                               double& max_chi, std::string& max_at) {
  CsvLines r(in);
  const std::size_t c_date = r.column("date"), c_node = r.column("node"), c_x = r.column("x_m"), c_y = r.column("y_m"),
                    c_z = r.column("z_m"), c_state = r.column("state"), c_tau = r.column("tau_MPa"),
                    c_sn = r.column("sigma_n_eff_MPa"), c_chi = r.column("chi"), c_cfs = r.column("cfs_change_MPa"), c_interp = r.column("interpolated");
  CsvWriter w(out, r.header(), r.comments());
  std::map<std::string, DateStats> stats;
  std::unordered_map<std::string, double> sn0;  // node -> sigma'_n at the initial state [MPa]
  std::string first_date;
  std::vector<std::string_view> cells;
  while (r.next(cells)) {
    const std::string date(cells[c_date]), node(cells[c_node]);
    if (first_date.empty()) first_date = date;
    // A stuck pair's slip and opening are round-off (1e-16 mm): its state is what the solver decided.
    if (cells[c_state] != "stick")
      throw NotDerived{fmt::format("fault {} is {} at node {} on {} in that run", f.name, cells[c_state], cells[c_node], date)};
    const double tau = r.number(cells[c_tau]), sn = r.number(cells[c_sn]), chi = r.number(cells[c_chi]);
    double cfs = r.number(cells[c_cfs]);
    const bool interpolated = cells[c_interp] != "0";
    if (date == first_date) {
      if (cfs != 0)
        throw NotDerived{fmt::format("the per-pair CSV of fault {} starts on {}, not at the initial state (Coulomb change {} MPa)", f.name,
                                     date, cfs)};
      sn0[node] = sn;
    }
    const auto s0 = sn0.find(node);
    if (s0 == sn0.end()) throw InputError(r.where(), fmt::format("node {} is not among the pairs of the first date", cells[c_node]));
    if (!(chi < 1)) throw NotDerived{fmt::format("fault {} has chi {} at node {} on {} in that run", f.name, chi, cells[c_node], date)};
    double chi_m;
    if (f.cohesion_MPa == 0) {
      chi_m = chi * (f.mu_run / f.mu);  // chi = |tau| / (-sigma'_n tan phi): the same factor for every pair and their means
    } else {
      if (interpolated)
        throw NotDerived{fmt::format("fault {} has cohesion and interpolated pairs (node {}), whose chi is a mean of their neighbours'",
                                     f.name, cells[c_node])};
      const double tau_L = f.cohesion_MPa - sn * f.mu;  // as contact::safety_factor (solver/contact/src/pair_law.cpp)
      chi_m = tau_L > 0 ? tau / tau_L : (tau > 0 ? 1.0 : 0.0);
    }
    cfs += (f.mu - f.mu_run) * (sn - s0->second);
    if (!(chi_m < 1))
      throw NotDerived{fmt::format("with friction {:.4g} deg fault {} reaches chi {:.4f} at node {} on {}", std::atan(f.mu) * 180 / M_PI,
                                   f.name, chi_m, cells[c_node], date)};
    if (chi_m > max_chi) max_chi = chi_m, max_at = fmt::format("fault {}, node {}, {}", f.name, cells[c_node], date);
    if (!interpolated) {
      DateStats& d = stats[date];
      ++d.pairs;
      if (chi_m > d.max_chi || d.pairs == 1)
        d.max_chi = chi_m, d.x = r.number(cells[c_x]), d.y = r.number(cells[c_y]), d.z = r.number(cells[c_z]);
      d.max_cfs = d.pairs == 1 ? cfs : std::max(d.max_cfs, cfs);
    }
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (i == c_chi) w.number(chi_m);
      else if (i == c_cfs) w.number(cfs);
      else w.text(cells[i]);
    }
    w.end_row();
  }
  w.commit();
  return stats;
}

// The fault named in a per-pair CSV's first comment ("ugs-solve fault NAME: one row per ...").
std::string fault_named_in(const std::string& path) {
  CsvLines r(path);
  static const std::string head = "ugs-solve fault ";
  if (!r.comments().empty() && r.comments().front().rfind(head, 0) == 0) {
    const std::string& c = r.comments().front();
    const auto colon = c.find(": one row per node pair", head.size());
    if (colon != std::string::npos) return c.substr(head.size(), colon - head.size());
  }
  throw InputError(path, "does not name its fault in its first line (expected ugs-solve's per-pair CSV)");
}

void link_or_copy(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::create_hard_link(from, to, ec);
  if (ec) fs::copy_file(from, to, fs::copy_options::overwrite_existing);
}

FrictionVariant derive(const std::string& run_folder, const CaseFile& run, const CaseFile& member, const std::string& out_folder) {
  std::string table;  // the fault table *_faults.csv
  std::vector<std::string> pair_csvs, others;
  static const std::set<std::string> record{"case.toml", "command.sh", "inputs.txt", "solver.log", "entry.json", "timing.txt", "key.txt"};
  for (const auto& e : fs::directory_iterator(run_folder)) {
    if (!e.is_regular_file()) continue;
    const std::string n = e.path().filename().string();
    if (record.count(n)) continue;
    if (n.ends_with("_scenario.csv")) throw NotDerived{"a safe-scale search ran (its answer depends on the friction)"};
    if (n.ends_with("_faults.csv")) {
      if (!table.empty()) throw InputError(run_folder, "has two fault tables (*_faults.csv): expected one");
      table = e.path().string();
    } else if (n.find("_fault_") != std::string::npos && n.ends_with(".csv")) {
      pair_csvs.push_back(e.path().string());
    } else {
      others.push_back(e.path().string());
    }
  }
  if (table.empty()) throw NotDerived{"the run wrote no fault table (*_faults.csv)"};
  std::sort(pair_csvs.begin(), pair_csvs.end());

  // 1. Every pair of every fault sticks at every step (the fault table has a row per step and fault).
  std::map<std::string, FaultChange> changed;  // fault -> its friction in the run and for the member (each fault once)
  {
    CsvLines r(table);
    const std::size_t c_fault = r.column("fault"), c_date = r.column("date"), c_slip = r.column("slipping"), c_open = r.column("open");
    std::vector<std::string_view> cells;
    while (r.next(cells)) {
      if (r.number(cells[c_slip]) != 0 || r.number(cells[c_open]) != 0)
        throw NotDerived{fmt::format("fault {} has pairs slipping or open on {} in that run", cells[c_fault], cells[c_date])};
      const std::string name(cells[c_fault]);
      if (changed.count(name)) continue;
      const FaultSpec a = fault_of(run, name), b = fault_of(member, name);
      if (a.cohesion_Pa != b.cohesion_Pa) throw NotDerived{fmt::format("fault {} has another cohesion", name)};
      changed[name] = {name, tan_deg(a.friction_deg), tan_deg(b.friction_deg), a.cohesion_Pa * 1e-6};
    }
    std::erase_if(changed, [](const auto& f) { return f.second.mu == f.second.mu_run; });  // the faults whose friction changes
  }

  // 2. The per-pair CSVs of the faults whose friction changes, rewritten; the others linked.
  std::map<std::string, std::map<std::string, DateStats>> stats;  // fault -> date -> statistics
  double max_chi = 0;
  std::string max_at = "no pair";
  for (const auto& p : pair_csvs) {
    const fs::path to = fs::path(out_folder) / fs::path(p).filename();
    const std::string name = fault_named_in(p);
    const auto c = changed.find(name);
    if (c == changed.end()) link_or_copy(p, to);
    else stats[name] = rewrite_pairs(p, to.string(), c->second, max_chi, max_at);
  }
  for (const auto& [name, f] : changed)
    if (!stats.count(name)) throw NotDerived{fmt::format("the run wrote no per-pair CSV of fault {}", name)};

  // 3. The fault table: chi, where it peaks and the Coulomb change of the changed faults, per step.
  {
    CsvLines r(table);
    const std::size_t c_fault = r.column("fault"), c_date = r.column("date"), c_chi = r.column("max_chi"), c_x = r.column("x_m"),
                      c_y = r.column("y_m"), c_z = r.column("z_m"), c_cfs = r.column("max_cfs_change_MPa"), c_pairs = r.column("node_pairs");
    CsvWriter w((fs::path(out_folder) / fs::path(table).filename()).string(), r.header(), r.comments());
    std::map<std::string, std::size_t> rows;  // per changed fault
    std::vector<std::string_view> cells;
    while (r.next(cells)) {
      const std::string name(cells[c_fault]);
      const auto s = stats.find(name);
      const DateStats* d = nullptr;
      if (s != stats.end()) {
        const auto it = s->second.find(std::string(cells[c_date]));
        if (it == s->second.end() || static_cast<double>(it->second.pairs) != r.number(cells[c_pairs]))
          throw NotDerived{fmt::format("the per-pair CSV of fault {} does not list its pairs on {} (the run must write them at every "
                                       "step: --fault-pairs-every-step)", name, cells[c_date])};
        d = &it->second;
        ++rows[name];
      }
      for (std::size_t i = 0; i < cells.size(); ++i) {
        if (d && i == c_chi) w.number(d->max_chi, 6);
        else if (d && i == c_x) w.number(d->x, 2);
        else if (d && i == c_y) w.number(d->y, 2);
        else if (d && i == c_z) w.number(d->z, 2);
        else if (d && i == c_cfs) w.number(d->max_cfs, 6);
        else w.text(cells[i]);
      }
      w.end_row();
    }
    for (const auto& [name, by_date] : stats)
      if (rows[name] != by_date.size())
        throw NotDerived{fmt::format("the per-pair CSV of fault {} has dates the fault table lacks", name)};
    w.commit();
  }
  for (const auto& o : others) link_or_copy(o, fs::path(out_folder) / fs::path(o).filename());
  FrictionVariant v;
  v.derived = true;
  v.reason = changed.empty() ? "the same friction" : fmt::format("every fault sticks at every step; chi with this friction at most {:.4f} ({})", max_chi, max_at);
  return v;
}

}  // namespace

FrictionVariant derive_friction_variant(const std::string& run_folder, const CaseFile& run, const CaseFile& member,
                                        const std::string& out_folder) {
  try {
    return derive(run_folder, run, member, out_folder);
  } catch (const NotDerived& e) {
    return {false, e.why};
  }
}

}  // namespace ugs::ensemble
