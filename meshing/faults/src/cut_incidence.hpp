// Node -> element lists of the fault cut (cutter.hpp), and the lookups over them.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ugs::fault_cut {

// Node -> element incidences (unordered lists), kept up to date by apply, so that the work of a
// panel visits the elements around the nodes it concerns instead of the whole mesh. The input's
// lists in one array (each node's at its start size, filled by a counting pass: half a million
// vectors were allocated and grown one element at a time before), with a vector per node for
// what no longer fits and for the nodes the cut adds.
class Incidence {
public:
  template <std::size_t K>
  void build(std::size_t nodes, const std::vector<std::array<std::uint32_t, K>>& elements) {
    count_.assign(nodes, 0);
    for (const auto& e : elements)
      for (auto v : e) ++count_[v];
    start_.assign(nodes + 1, 0);
    for (std::size_t v = 0; v < nodes; ++v) start_[v + 1] = start_[v] + count_[v];
    data_.resize(start_[nodes]);
    std::fill(count_.begin(), count_.end(), 0);
    for (std::size_t i = 0; i < elements.size(); ++i)
      for (auto v : elements[i]) data_[start_[v] + count_[v]++] = static_cast<std::uint32_t>(i);
  }
  void add(std::uint32_t v, std::uint32_t i) {
    if (v < count_.size() && start_[v] + count_[v] < start_[v + 1]) {
      data_[start_[v] + count_[v]++] = i;
      return;
    }
    if (v >= more_.size()) more_.resize(std::size_t{v} + 1);
    more_[v].push_back(i);
  }
  void remove(std::uint32_t v, std::uint32_t i) {
    if (v < count_.size()) {
      std::uint32_t* b = data_.data() + start_[v];
      std::uint32_t* e = b + count_[v];
      if (std::uint32_t* it = std::find(b, e, i); it != e) {
        *it = e[-1];
        --count_[v];
        return;
      }
    }
    auto& l = more_[v];
    auto it = std::find(l.begin(), l.end(), i);
    *it = l.back();
    l.pop_back();
  }
  // Appends v's elements to out.
  void append(std::uint32_t v, std::vector<std::uint32_t>& out) const {
    if (v < count_.size()) out.insert(out.end(), data_.begin() + start_[v], data_.begin() + start_[v] + count_[v]);
    if (v < more_.size()) out.insert(out.end(), more_[v].begin(), more_[v].end());
  }

private:
  std::vector<std::size_t> start_;     // per input node: its first slot in data_
  std::vector<std::uint32_t> count_;   // per input node: its slots in use
  std::vector<std::uint32_t> data_;
  std::vector<std::vector<std::uint32_t>> more_;
};

template <std::size_t K>
void link(Incidence& at, const std::array<std::uint32_t, K>& e, std::uint32_t i) {
  for (auto v : e) at.add(v, i);
}
// Element i changed from `before` to `after`.
template <std::size_t K>
void relink(Incidence& at, const std::array<std::uint32_t, K>& before, const std::array<std::uint32_t, K>& after, std::uint32_t i) {
  for (auto v : before)
    if (std::find(after.begin(), after.end(), v) == after.end()) at.remove(v, i);
  for (auto v : after)
    if (std::find(before.begin(), before.end(), v) == before.end()) at.add(v, i);
}

// v's elements, sorted.
std::vector<std::uint32_t> sorted_at(const Incidence& at, std::uint32_t v);
// The elements holding a node flagged in `want`, in increasing order.
std::vector<std::uint32_t> elements_at(const Incidence& at, const std::vector<char>& want);
// The elements holding one of `nodes`, in increasing order.
std::vector<std::uint32_t> elements_at(const Incidence& at, const std::vector<std::uint32_t>& nodes);
// The elements listed, sorted, each once.
std::vector<std::uint32_t> sorted_unique(std::vector<std::uint32_t> out);

}  // namespace ugs::fault_cut
