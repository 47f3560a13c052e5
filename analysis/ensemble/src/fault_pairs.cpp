#include "ugs/ensemble/fault_pairs.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "ugs/ensemble/statistics.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"

namespace ugs::ensemble {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kTag = "_fault_";

FaultPairs read_fault_pairs(const std::string& path, const std::string& fault) {
  const CsvTable t = CsvTable::read(path);
  const auto cd = t.column("date"), cn = t.column("node"), cx = t.column("x_m"), cy = t.column("y_m"), cz = t.column("z_m");
  const auto cs = t.column("along_strike_m"), cw = t.column("down_dip_m"), cc = t.column("chi");
  if (t.rows() == 0) throw InputError(path, "has no node pair");
  // Rows by date; every date must list the pairs of the first date's rows, in the same order.
  std::map<std::int64_t, std::vector<std::size_t>> rows;
  for (std::size_t r = 0; r < t.rows(); ++r) rows[t.date(r, cd)].push_back(r);
  FaultPairs f;
  f.fault = fault;
  const auto& first = rows.begin()->second;
  for (std::size_t r : first) {
    f.nodes.push_back(t.integer(r, cn));
    f.x.push_back(t.number(r, cx));
    f.y.push_back(t.number(r, cy));
    f.z.push_back(t.number(r, cz));
    f.along_strike.push_back(t.number(r, cs));
    f.down_dip.push_back(t.number(r, cw));
  }
  for (const auto& [date, rs] : rows) {
    if (rs.size() != first.size())
      throw InputError(t.where(rs.front()), fmt::format("{} pairs on {}, {} on {} (expected the same pairs at every date)", rs.size(),
                                                        format_iso_date(date), first.size(), format_iso_date(rows.begin()->first)));
    for (std::size_t i = 0; i < rs.size(); ++i) {
      if (t.integer(rs[i], cn) != f.nodes[i])
        throw InputError(t.where(rs[i]), fmt::format("node {} where the first date has node {} (expected the same pairs in the same "
                                                     "order at every date)", t.integer(rs[i], cn), f.nodes[i]));
      f.chi.push_back(t.number(rs[i], cc));
    }
    f.dates.push_back(date);
  }
  return f;
}

}  // namespace

MemberPairs read_member_pairs(const std::string& folder) {
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(folder)) {
    const std::string n = e.path().filename().string();
    if (n.find(kTag) != std::string::npos && n.size() > 4 && n.compare(n.size() - 4, 4, ".csv") == 0) files.push_back(n);
  }
  std::sort(files.begin(), files.end());  // the directory's order is not the same everywhere
  MemberPairs out;
  for (const auto& n : files) {
    const auto at = n.find(kTag) + kTag.size();
    out.push_back(read_fault_pairs((fs::path(folder) / n).string(), n.substr(at, n.size() - 4 - at)));
  }
  return out;
}

std::string pair_set_difference(const MemberPairs& a, const MemberPairs& ref, std::size_t ref_member) {
  auto names = [](const MemberPairs& m) {
    std::string s;
    for (const auto& f : m) s += (s.empty() ? "" : ", ") + f.fault;
    return s.empty() ? std::string("none") : s;
  };
  if (a.size() != ref.size() || !std::equal(a.begin(), a.end(), ref.begin(), [](const auto& p, const auto& q) { return p.fault == q.fault; }))
    return fmt::format("faults with per-pair CSVs {}, member {} has {}", names(a), ref_member, names(ref));
  for (std::size_t k = 0; k < a.size(); ++k) {
    const FaultPairs &f = a[k], &g = ref[k];
    if (f.pairs() != g.pairs()) return fmt::format("fault {}: {} pairs, member {} has {}", f.fault, f.pairs(), ref_member, g.pairs());
    if (f.dates != g.dates)
      return fmt::format("fault {}: {} dates ({} .. {}), member {} has {} ({} .. {})", f.fault, f.dates.size(), format_iso_date(f.dates.front()),
                         format_iso_date(f.dates.back()), ref_member, g.dates.size(), format_iso_date(g.dates.front()),
                         format_iso_date(g.dates.back()));
    for (std::size_t i = 0; i < f.pairs(); ++i)
      if (f.nodes[i] != g.nodes[i] || f.x[i] != g.x[i] || f.y[i] != g.y[i] || f.z[i] != g.z[i] || f.along_strike[i] != g.along_strike[i] ||
          f.down_dip[i] != g.down_dip[i])
        return fmt::format("fault {}: pair {} is node {} at ({}, {}, {}) m, member {} has node {} at ({}, {}, {}) m", f.fault, i + 1, f.nodes[i],
                           f.x[i], f.y[i], f.z[i], ref_member, g.nodes[i], g.x[i], g.y[i], g.z[i]);
  }
  return "";
}

void write_chi_exceedance(std::span<const MemberPairs* const> members, const std::string& path,
                          const std::vector<std::string>& comments) {
  std::vector<std::string> c = comments;
  c.insert(c.begin(), "P(chi >= t) over the members at each fault node pair and output date; date 'max': of each member's largest chi "
                      "over the dates");
  CsvWriter w(path, {"fault", "date", "node", "x_m", "y_m", "z_m", "along_strike_m", "down_dip_m", "p_chi_ge_0.8", "p_chi_ge_1", "n_members"},
              c);
  const MemberPairs& ref = *members.front();
  const auto n = static_cast<std::int64_t>(members.size());
  std::vector<double> v(members.size());
  for (std::size_t k = 0; k < ref.size(); ++k) {
    const FaultPairs& f = ref[k];
    const std::size_t np = f.pairs(), nd = f.dates.size();
    auto row = [&](std::size_t i, const std::string& date) {
      w.text(f.fault).text(date).integer(f.nodes[i]).number(f.x[i]).number(f.y[i]).number(f.z[i]).number(f.along_strike[i]);
      w.number(f.down_dip[i]).number(exceedance(v, 0.8)).number(exceedance(v, 1.0)).integer(n).end_row();
    };
    for (std::size_t d = 0; d < nd; ++d)
      for (std::size_t i = 0; i < np; ++i) {
        for (std::size_t m = 0; m < members.size(); ++m) v[m] = (*members[m])[k].chi[d * np + i];
        row(i, format_iso_date(f.dates[d]));
      }
    for (std::size_t i = 0; i < np; ++i) {
      for (std::size_t m = 0; m < members.size(); ++m) {
        const auto& chi = (*members[m])[k].chi;
        v[m] = -INFINITY;
        for (std::size_t d = 0; d < nd; ++d) v[m] = std::max(v[m], chi[d * np + i]);
      }
      row(i, "max");
    }
  }
  w.commit();
}

}  // namespace ugs::ensemble
