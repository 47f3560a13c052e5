// Chi at every fault node pair across the ensemble: each member's per-pair CSVs of ugs-solve
// (`<stem>_fault_<fault>.csv`, docs/fault-mechanics.md "Outputs"), checked to describe the same
// pairs (the members share the mesh), and the probability that chi reaches 0.8 and 1 at each pair
// and date, and over the dates (chi_exceedance_pairs.csv, docs/ensemble.md).
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace ugs::ensemble {

// One fault of one member: its pairs (in the file's order) and chi at each date.
struct FaultPairs {
  std::string fault;                        // from the file name: <stem>_fault_<fault>.csv
  std::vector<std::int64_t> dates;          // ascending, seconds since 1970
  std::vector<std::int64_t> nodes;          // per pair
  std::vector<double> x, y, z, along_strike, down_dip;  // per pair [m]
  std::vector<double> chi;                  // dates x pairs
  std::size_t pairs() const { return nodes.size(); }
};
using MemberPairs = std::vector<FaultPairs>;  // by file name; empty: a run without faults

// The per-pair CSVs of a member's folder (every file whose name holds "_fault_" and ends in
// ".csv"). InputError when one is unreadable, or when its dates do not all list the same pairs.
MemberPairs read_member_pairs(const std::string& folder);

// "" when `a` describes the same faults, dates and pairs (node, coordinates: exactly) as `ref`,
// else what differs first, e.g. "fault F1: 12 pairs, member 2 has 13".
std::string pair_set_difference(const MemberPairs& a, const MemberPairs& ref, std::size_t ref_member);

// Writes chi_exceedance_pairs.csv from members with the same pair set (pair_set_difference "").
void write_chi_exceedance(std::span<const MemberPairs* const> members, const std::string& path,
                          const std::vector<std::string>& comments);

}  // namespace ugs::ensemble
