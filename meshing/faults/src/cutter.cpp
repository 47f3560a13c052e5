// The fault cut's arrays (cutter.hpp): read from the mesh's blocks (with the incidences, each node's
// reach and the node grid), and written back into them with the fault groups when the cut is done.
#include "cutter.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "ugs/formats/run_beside.hpp"
#include "ugs/meshing/vec3.hpp"

namespace ugs::fault_cut {

using namespace vec3;

Cutter::Cutter(Mesh& mesh, double tol) : mesh_(mesh), X_(mesh.nodes), tol_(tol) {
  std::size_t ntets = 0;
  for (const auto& blk : mesh.blocks)
    if (blk.type == ElementType::Tetrahedron) ntets += blk.size();
  ntets += ntets / 8;  // room for the cut's new tetrahedra (2.4 % at the thesis scale)
  T_.reserve(ntets);
  Tb_.reserve(ntets);
  Tp_.reserve(ntets);
  for (std::size_t b = 0; b < mesh.blocks.size(); ++b) {
    const auto& blk = mesh.blocks[b];
    if (blk.type == ElementType::Tetrahedron) {  // from the node array (element(i) looked up the type per element)
      const std::uint32_t* e = blk.nodes.data();
      for (std::size_t i = 0; i < blk.size(); ++i, e += 4) {
        T_.push_back({e[0], e[1], e[2], e[3]});
        Tp_.push_back(static_cast<std::uint32_t>(Tp_.size()));
      }
      Tb_.insert(Tb_.end(), blk.size(), static_cast<std::uint32_t>(b));
    } else if (blk.type == ElementType::Triangle)
      for (std::size_t i = 0; i < blk.size(); ++i) {
        const auto e = blk.element(i);
        F_.push_back({e[0], e[1], e[2]});
        Fb_.push_back(static_cast<std::uint32_t>(b));
      }
  }
  {  // the input tetrahedra, read from the blocks (unchanged until finish)
    std::vector<std::span<const std::uint32_t>> input;
    for (const auto& blk : mesh.blocks)
      if (blk.type == ElementType::Tetrahedron) input.emplace_back(blk.nodes);
    parent_.emplace(X_, std::move(input));
  }
  // Two threads (two cores): the second builds the incidences and the reaches of the last
  // tetrahedra into an array of its own, this one the reaches of the first; then the larger of
  // the two per node (a maximum: the same whatever the split or the timing) and the node grid.
  reach_.assign(X_.size(), 0.0);
  std::vector<double> reach_last(X_.size(), 0.0);
  const std::size_t split = T_.size() * 5 / 8;
  run_beside(
      [&] {
        tets_at_.build(X_.size(), T_);
        tris_at_.build(X_.size(), F_);
        for (std::size_t i = split; i < T_.size(); ++i) raise_reach(T_[i], reach_last);
      },
      [&] {
        for (std::size_t i = 0; i < split; ++i) raise_reach(T_[i], reach_);
      });
  for (std::size_t v = 0; v < X_.size(); ++v) reach_[v] = std::max(reach_[v], reach_last[v]);
  grid_.build(X_, reach_);
}

// Writes the elements back into the mesh's blocks, plus the fault groups (the virtual blocks);
// renumbers element tags.
void Cutter::finish(const std::vector<std::string>& names, std::size_t nodes_before) {
  std::uint64_t next_tag = mesh_.max_node_tag();
  for (std::size_t i = nodes_before; i < X_.size(); ++i) mesh_.node_tags.push_back(++next_tag);
  const std::size_t nb = mesh_.blocks.size();
  for (auto& b : mesh_.blocks) {
    if (b.type == ElementType::Tetrahedron || b.type == ElementType::Triangle) {
      b.nodes.clear();
      b.tags.clear();
    }
  }
  int ptag = 0, etag2 = 0;
  for (const auto& p : mesh_.physicals) ptag = std::max(ptag, p.tag);
  for (const auto& e : mesh_.entities)
    if (e.dim == 2) etag2 = std::max(etag2, e.tag);
  for (const auto& name : names) {
    mesh_.physicals.push_back({2, ++ptag, "fault:" + name});
    mesh_.entities.push_back({2, ++etag2, {ptag}, {}});
    ElementBlock b;
    b.entity_dim = 2;
    b.entity_tag = etag2;
    b.type = ElementType::Triangle;
    mesh_.blocks.push_back(std::move(b));
  }
  // Each block's size first, then plain appends (an insert per element was a third of this).
  std::vector<std::size_t> size(mesh_.blocks.size(), 0);
  for (auto b : Tb_) size[b] += 4;
  for (auto b : Fb_) size[b] += 3;
  for (std::size_t b = 0; b < size.size(); ++b) mesh_.blocks[b].nodes.reserve(size[b]);
  for (std::size_t i = 0; i < T_.size(); ++i) {
    auto& nodes = mesh_.blocks[Tb_[i]].nodes;
    for (auto v : T_[i]) nodes.push_back(v);
  }
  for (std::size_t i = 0; i < F_.size(); ++i) {
    auto& nodes = mesh_.blocks[Fb_[i]].nodes;
    for (auto v : F_[i]) nodes.push_back(v);
  }
  (void)nb;
  std::uint64_t tag = 0;
  for (auto& b : mesh_.blocks) {
    b.tags.resize(b.nodes.size() / b.npe());
    for (auto& t : b.tags) t = ++tag;
  }
  mesh_.blocks.erase(std::remove_if(mesh_.blocks.begin(), mesh_.blocks.end(), [](const ElementBlock& b) { return b.tags.empty(); }),
                     mesh_.blocks.end());
  mesh_.update_entity_bboxes();
}

}  // namespace ugs::fault_cut
