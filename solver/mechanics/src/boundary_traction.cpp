// Traction boundary conditions ([[boundary_traction]], docs/case-file.md): consistent nodal forces of
// the change of the boundary traction from the initial state, a constant load of every step.
//
// ugs-solve solves for the change from the geostatic state, which is taken to be in equilibrium with
// t_0 = sigma_0 n on every boundary that is not held: a side in no [boundary] list keeps its in-situ
// traction (the stress-consistent lateral load), and a [[boundary_traction]] with the total traction t
// loads its face with t - sigma_0 n.
#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/formats/face_key.hpp"
#include "ugs/mechanics/model.hpp"

namespace ugs::mech {
namespace {

using Triangle = std::array<std::uint32_t, 3>;  // node indices of a boundary triangle

std::string boundary_groups(const Mesh& mesh) {
  std::string s;
  for (const auto& p : mesh.physicals)
    if (p.dim == 2 && p.name.rfind("bnd:", 0) == 0) s += (s.empty() ? "" : ", ") + p.name.substr(4);
  return s.empty() ? "none" : s;
}

// The triangles of bnd:<group> (mesh node indices).
std::vector<Triangle> group_triangles(const Mesh& mesh, const PhysicalGroup& g) {
  std::vector<Triangle> tris;
  for (const auto& b : mesh.blocks) {
    if (b.entity_dim != 2 || b.type != ElementType::Triangle) continue;
    const Entity* e = mesh.find_entity(2, b.entity_tag);
    if (!e || std::find(e->physicals.begin(), e->physicals.end(), g.tag) == e->physicals.end()) continue;
    for (std::size_t i = 0; i < b.size(); ++i) {
      const auto t = b.element(i);
      tris.push_back({t[0], t[1], t[2]});
    }
  }
  return tris;
}

}  // namespace

std::vector<std::array<double, 3>> boundary_traction_forces(const Mesh& mesh, const CaseFile& cs, const Model& model) {
  std::vector<std::array<double, 3>> f(mesh.num_nodes(), {0, 0, 0});
  // Every group must exist (also the in-situ ones, which add nothing).
  std::vector<std::pair<const TractionSpec*, std::vector<Triangle>>> loaded;
  for (const auto& t : cs.tractions) {
    const PhysicalGroup* g = mesh.find_physical(2, "bnd:" + t.group);
    if (!g)
      throw InputError(t.where, fmt::format("boundary_traction: the mesh has no group bnd:{} (expected one of its boundary "
                                            "groups: {})", t.group, boundary_groups(mesh)));
    auto tris = group_triangles(mesh, *g);
    if (tris.empty())
      throw InputError(t.where, fmt::format("boundary_traction: bnd:{} holds no triangles (expected a surface group)", t.group));
    if (!t.in_situ) loaded.emplace_back(&t, std::move(tris));
  }
  if (loaded.empty()) return f;

  // The tetrahedron each loaded triangle bounds.
  std::unordered_map<FaceKey, std::int64_t, FaceKeyHash> tet_of;
  for (const auto& [spec, tris] : loaded)
    for (const auto& tri : tris) tet_of.emplace(face_key(tri), -1);
  static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  for (std::size_t t = 0; t < model.tets.size(); ++t)
    for (const auto& fi : kFaces) {
      const auto it = tet_of.find(face_key({model.tets[t][fi[0]], model.tets[t][fi[1]], model.tets[t][fi[2]]}));
      if (it != tet_of.end()) it->second = static_cast<std::int64_t>(t);
    }

  const InitialState& init = model.initial;
  for (const auto& [spec, tris] : loaded) {
    for (const auto& tri : tris) {
      const std::int64_t t = tet_of.at(face_key(tri));
      if (t < 0)
        throw InputError(spec->where, fmt::format("boundary_traction: a triangle of bnd:{} (nodes {}, {}, {}) is no face of a "
                                                  "tetrahedron (expected the model's outer surface)", spec->group,
                                                  mesh.node_tags[tri[0]], mesh.node_tags[tri[1]], mesh.node_tags[tri[2]]));
      const auto& x0 = model.x[tri[0]];
      const auto& x1 = model.x[tri[1]];
      const auto& x2 = model.x[tri[2]];
      const std::array<double, 3> e1{x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]}, e2{x2[0] - x0[0], x2[1] - x0[1], x2[2] - x0[2]};
      std::array<double, 3> n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!(len > 0)) continue;  // a degenerate triangle carries no load
      // Outward: away from the tetrahedron's fourth node.
      std::uint32_t opp = 0;
      for (auto v : model.tets[t])
        if (v != tri[0] && v != tri[1] && v != tri[2]) opp = v;
      const double side = n[0] * (model.x[opp][0] - x0[0]) + n[1] * (model.x[opp][1] - x0[1]) + n[2] * (model.x[opp][2] - x0[2]);
      const double sgn = side > 0 ? -1.0 : 1.0;
      for (auto& v : n) v *= sgn / len;
      const double area = 0.5 * len;
      const int mat = model.tet_material[t];
      const double alpha = model.materials[mat].biot;
      // Traction change at the three nodes: t - (sigma'_0 - alpha p0 I) n.
      std::array<std::array<double, 3>, 3> dt;
      for (int j = 0; j < 3; ++j) {
        const double z = model.x[tri[j]][2];
        const GasColumn gas = model.material_gas.size() > static_cast<std::size_t>(mat) ? model.material_gas[mat] : GasColumn{};
        fem::Vec6 s = init.effective_stress(z, alpha, model.material_k[mat], gas);
        const double p0 = init.pore_pressure(z, gas);
        for (int k = 0; k < 3; ++k) s[k] -= alpha * p0;
        // Thesis Voigt order xx yy zz yz xz xy.
        const std::array<double, 3> t0{s[0] * n[0] + s[5] * n[1] + s[4] * n[2], s[5] * n[0] + s[1] * n[1] + s[3] * n[2],
                                       s[4] * n[0] + s[3] * n[1] + s[2] * n[2]};
        for (int k = 0; k < 3; ++k) dt[j][k] = spec->traction_Pa[k] - t0[k];
      }
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k)
          f[tri[i]][k] += area / 12.0 * (2 * dt[i][k] + dt[(i + 1) % 3][k] + dt[(i + 2) % 3][k]);
    }
  }
  return f;
}

}  // namespace ugs::mech
