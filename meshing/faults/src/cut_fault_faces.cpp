// The fault groups of the fault cut (cutter.hpp): the faces lying in each panel with their centroid
// inside it, oriented toward the hanging wall; those of a fault's panels make its group fault:<name>.
#include "cut_stages.hpp"

#include <algorithm>
#include <map>
#include <set>

#include <fmt/format.h>

#include "cutter.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/meshing/vec3.hpp"

namespace ugs::fault_cut {

using namespace vec3;

// Faces lying in panel p with their centroid inside it, sorted node triples -> oriented face.
void Cutter::collect(const CutPanel& p, std::map<std::array<std::uint32_t, 3>, std::array<std::uint32_t, 3>>& faces,
             std::map<std::array<std::uint32_t, 3>, int>& uses) const {
  auto on = [&](std::uint32_t i) { return std::abs(dot(p.n, X_[i]) - p.c) <= tol_; };
  static constexpr int face_of[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (auto i : elements_at(tets_at_, nodes_on_plane(p.n, p.c))) {
    const auto& t = T_[i];
    if (on(t[0]) + on(t[1]) + on(t[2]) + on(t[3]) < 3) continue;
    for (const auto& f : face_of) {
      std::array<std::uint32_t, 3> tri{t[f[0]], t[f[1]], t[f[2]]};
      if (!on(tri[0]) || !on(tri[1]) || !on(tri[2])) continue;
      Point3 cen{0, 0, 0};
      for (auto v : tri)
        for (int k = 0; k < 3; ++k) cen[k] += X_[v][k] / 3;
      bool inside = true;
      for (const auto& b : p.bounds)
        if (dot(b.m, cen) > b.d) inside = false;
      if (!inside) continue;
      auto key = tri;
      std::sort(key.begin(), key.end());
      ++uses[key];
      const Point3 nrm = cross(sub(X_[tri[1]], X_[tri[0]]), sub(X_[tri[2]], X_[tri[0]]));
      if (dot(nrm, p.n) < 0) std::swap(tri[1], tri[2]);
      faces.emplace(key, tri);
    }
  }
}

// Adds the faces of fault f (oriented) as elements of a virtual block after the mesh's blocks,
// so that later bisections split them too.
void Cutter::add_fault_faces(std::size_t f, const std::vector<std::array<std::uint32_t, 3>>& faces) {
  for (const auto& t : faces) {
    link(tris_at_, t, static_cast<std::uint32_t>(F_.size()));
    F_.push_back(t);
    Fb_.push_back(static_cast<std::uint32_t>(mesh_.blocks.size() + f));
  }
}

// The fault faces after every bisection, for the report.
std::vector<std::array<std::uint32_t, 3>> Cutter::fault_faces(std::size_t f) const {
  std::vector<std::array<std::uint32_t, 3>> out;
  const std::size_t id = mesh_.blocks.size() + f;
  for (std::size_t i = 0; i < F_.size(); ++i)
    if (Fb_[i] == id) out.push_back(F_[i]);
  return out;
}

std::vector<std::string> add_fault_groups(Cutter& cut, const std::vector<FaultTrace>& traces,
                                          const std::vector<std::vector<CutPanel>>& panels, std::vector<FaultCutReport>& reports) {
  std::vector<std::string> names;
  for (std::size_t f = 0; f < traces.size(); ++f) {
    std::vector<std::array<std::uint32_t, 3>> tris;
    std::set<std::array<std::uint32_t, 3>> taken;
    std::size_t on_boundary = 0;
    for (const auto& p : panels[f]) {
      std::map<std::array<std::uint32_t, 3>, std::array<std::uint32_t, 3>> faces;
      std::map<std::array<std::uint32_t, 3>, int> uses;
      cut.collect(p, faces, uses);
      for (const auto& [key, tri] : faces) {
        if (uses[key] < 2) {
          ++on_boundary;
          continue;
        }
        if (taken.insert(key).second) tris.push_back(tri);
      }
    }
    if (tris.empty())
      throw InputError(traces[f].where,
                       fmt::format("fault '{}': its surface does not cross the mesh (check the trace, top_m, bottom_m, "
                                   "dip_deg and dip_dir_deg)",
                                   traces[f].name));
    cut.add_fault_faces(f, tris);
    names.push_back(traces[f].name);
    FaultCutReport r;
    r.name = traces[f].name;
    r.panels = panels[f].size();
    r.boundary_faces = on_boundary;
    reports.push_back(r);
  }
  return names;
}

}  // namespace ugs::fault_cut
