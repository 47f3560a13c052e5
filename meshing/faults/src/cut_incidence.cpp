// Lookups over the fault cut's node -> element lists (cut_incidence.hpp).
#include "cut_incidence.hpp"

#include <bit>

namespace ugs::fault_cut {

std::vector<std::uint32_t> sorted_at(const Incidence& at, std::uint32_t v) {
  std::vector<std::uint32_t> l;
  at.append(v, l);
  std::sort(l.begin(), l.end());
  return l;
}

std::vector<std::uint32_t> elements_at(const Incidence& at, const std::vector<char>& want) {
  std::vector<std::uint32_t> out;
  for (std::size_t v = 0; v < want.size(); ++v)
    if (want[v]) at.append(static_cast<std::uint32_t>(v), out);
  return sorted_unique(std::move(out));
}

// The elements holding one of `nodes`, in increasing order.
std::vector<std::uint32_t> elements_at(const Incidence& at, const std::vector<std::uint32_t>& nodes) {
  std::vector<std::uint32_t> out;
  for (auto v : nodes) at.append(v, out);
  return sorted_unique(std::move(out));
}

std::vector<std::uint32_t> sorted_unique(std::vector<std::uint32_t> out) {
  if (out.size() < (std::size_t{1} << 12)) {
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  // Many: a bit per element and one sweep of 64-bit words instead of the sort (the sort of a
  // panel's few ten thousand was ~5 % of the thesis bench).
  const std::uint32_t top = *std::max_element(out.begin(), out.end());
  std::vector<std::uint64_t> hit(top / 64 + 1, 0);
  for (auto i : out) hit[i / 64] |= std::uint64_t{1} << (i % 64);
  out.clear();
  for (std::size_t w = 0; w < hit.size(); ++w)
    for (std::uint64_t bits = hit[w]; bits != 0; bits &= bits - 1)
      out.push_back(static_cast<std::uint32_t>(w * 64 + static_cast<std::size_t>(std::countr_zero(bits))));
  return out;
}

}  // namespace ugs::fault_cut
