#include "ugs/flow/flow_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/meshing/material_fields.hpp"
#include "ugs/solver/compressibility.hpp"
#include <fmt/ranges.h>

namespace ugs::flow {
namespace {

constexpr double kMPa = 1e6;

std::string join(const std::vector<std::string>& v) { return fmt::format("{}", fmt::join(v, ", ")); }

// Material name (without "mat:") of a tetrahedron block's entity, or "" if it has none.
std::string material_of(const Mesh& mesh, const ElementBlock& b) {
  const Entity* e = mesh.find_entity(b.entity_dim, b.entity_tag);
  if (!e) return {};
  for (int p : e->physicals)
    if (const PhysicalGroup* g = mesh.find_physical_tag(b.entity_dim, p); g && g->name.rfind("mat:", 0) == 0)
      return g->name.substr(4);
  return {};
}

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  // The smaller index stays the root, so numbering does not depend on the order of the ties.
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// Vertical uniaxial compressibility c_M [1/Pa] of a material at elevation z.
double cm_per_pa(const CaseFile& c, const InitialState& init, const MaterialSpec& m, double z) {
  if (m.law == MaterialLaw::Linear) {
    // Eq. 3.23 (eq. 3.21 when isotropic) with the given vertical Young's modulus.
    const double Ez = *m.E_Pa, nu_z = m.nu_z, nu_h = m.nu_z * m.nuh_over_nuz;
    return (1.0 - 2.0 * nu_z * nu_z / (1.0 - nu_h) * m.Eh_over_Ez) / Ez;
  }
  // Floored as in the mechanics: the law is singular at zero stress (near or above the surface).
  const double sigma = std::max(initial_effective_vertical_stress(c, init, m, z), m.sigma_z_min_MPa * kMPa);
  return CompressibilityLaw{m.cm_a, m.cm_b}.cm(sigma / kMPa) / kMPa;
}

}  // namespace

double initial_effective_vertical_stress(const CaseFile& c, const InitialState& init, const MaterialSpec& m, double z) {
  return init.effective_vertical_stress(z, m.biot, gas_column_of(c, m.name));
}

double storage_coefficient(const CaseFile& c, const InitialState& init, const MaterialSpec& m, double z) {
  if (!m.porosity) throw InputError(m.where, fmt::format("material '{}' has no porosity", m.name));
  return *m.porosity * c.water_compressibility + cm_per_pa(c, init, m, z);
}

std::vector<double> FlowModel::conductance_values() const {
  std::vector<double> a(pattern.col.size(), 0.0);
  for (std::size_t m = 0; m < conductance_by_material.size(); ++m) {
    const auto& v = conductance_by_material[m];
    if (v.empty()) continue;
    const double f = k_multiplier[m];
    for (std::size_t k = 0; k < a.size(); ++k) a[k] += f * v[k];
  }
  return a;
}

double FlowModel::stored_water(const std::vector<double>& dp) const {
  double s = 0;
  for (std::size_t i = 0; i < num_dofs; ++i) s += storage[i] * dp[i];
  return s;
}

FlowModel build_flow_model(const Mesh& mesh, const CaseFile& c, const FlowModelOptions& opt) {
  if (const std::size_t np = mesh.count(ElementType::Prism); np > 0)
    throw InputError(opt.mesh_name, fmt::format("has {} interface elements: a flow mesh has none (extract it with "
                                                "ugs-submesh, which drops them and ties non-barrier faults)",
                                                np));
  FlowModel fm;
  fm.num_nodes = mesh.num_nodes();

  // 1. Materials of the mesh, in block order of first appearance.
  std::vector<int> block_material(mesh.blocks.size(), -1);
  std::map<std::string, int> material_index;
  for (std::size_t bi = 0; bi < mesh.blocks.size(); ++bi) {
    const ElementBlock& b = mesh.blocks[bi];
    if (b.type != ElementType::Tetrahedron || b.size() == 0) continue;
    const std::string name = material_of(mesh, b);
    if (name.empty())
      throw InputError(opt.mesh_name, fmt::format("tetrahedra of volume entity {} belong to no mat:<name> group", b.entity_tag));
    auto [it, fresh] = material_index.emplace(name, static_cast<int>(fm.materials.size()));
    if (fresh) fm.materials.push_back({name});
    block_material[bi] = it->second;
    fm.materials[it->second].tets += b.size();
  }
  if (fm.materials.empty()) throw InputError(opt.mesh_name, "has no tetrahedra");
  std::vector<std::string> mesh_materials;
  for (const auto& m : fm.materials) mesh_materials.push_back(m.name);
  std::vector<const MaterialSpec*> spec(fm.materials.size());
  for (std::size_t m = 0; m < fm.materials.size(); ++m) {
    spec[m] = c.material(fm.materials[m].name);
    if (!spec[m])
      throw InputError(c.path, fmt::format("material '{}' of {} is not defined in the case file", fm.materials[m].name,
                                           opt.mesh_name));
  }

  // 2. Pools: chosen by name, or every pool with a material in the mesh; all their materials must be there.
  for (const auto& name : opt.pools)
    if (std::none_of(c.pools.begin(), c.pools.end(), [&](const PoolSpec& p) { return p.name == name; })) {
      std::vector<std::string> names;
      for (const auto& p : c.pools) names.push_back("'" + p.name + "'");
      throw InputError(c.path, fmt::format("no pool '{}' (pools: {})", name, names.empty() ? "none" : join(names)));
    }
  for (const PoolSpec& p : c.pools) {
    const bool chosen = opt.pools.empty() || std::find(opt.pools.begin(), opt.pools.end(), p.name) != opt.pools.end();
    if (!chosen) continue;
    std::size_t present = 0;
    for (const auto& m : p.materials) present += material_index.count(m);
    if (present == 0 && opt.pools.empty()) continue;  // another pool's sub-mesh
    for (const auto& m : p.materials)
      if (!material_index.count(m))
        throw InputError(p.where, fmt::format("pool '{}': material '{}' is not in {} (materials: {})", p.name, m,
                                              opt.mesh_name, join(mesh_materials)));
    const int pi = static_cast<int>(fm.pools.size());
    fm.pools.push_back({p.name, p.where, {}});
    for (const auto& m : p.materials) {
      FlowMaterial& fmat = fm.materials[material_index.at(m)];
      if (fmat.pool >= 0)
        throw InputError(p.where, fmt::format("material '{}' belongs to pools '{}' and '{}'", m, fm.pools[fmat.pool].name, p.name));
      fmat.pool = pi;
    }
  }
  if (fm.pools.empty())
    throw InputError(c.path, fmt::format("no pool has a material in {} (materials: {})", opt.mesh_name, join(mesh_materials)));

  // 3. Aquifer materials need a conductivity and a porosity.
  for (std::size_t m = 0; m < fm.materials.size(); ++m) {
    if (fm.materials[m].pool >= 0) continue;
    if (!spec[m]->K)
      throw InputError(spec[m]->where, fmt::format("material '{}' has no conductivity K_m_per_s, needed for flow", spec[m]->name));
    if (!spec[m]->porosity)
      throw InputError(spec[m]->where, fmt::format("material '{}' has no porosity, needed for flow", spec[m]->name));
    fm.materials[m].K = *spec[m]->K;
    fm.materials[m].porosity = *spec[m]->porosity;
  }

  // 4. Unknowns: one per node of a tetrahedron, nodes tied across faults sharing one.
  UnionFind uf(mesh.num_nodes());
  for (const ElementBlock& b : mesh.blocks) {
    if (b.type != ElementType::Line) continue;
    const Entity* e = mesh.find_entity(b.entity_dim, b.entity_tag);
    bool tie = false;
    if (e)
      for (int p : e->physicals)
        if (const PhysicalGroup* g = mesh.find_physical_tag(b.entity_dim, p); g && g->name.rfind("tie:", 0) == 0) tie = true;
    if (!tie) continue;
    for (std::size_t i = 0; i < b.size(); ++i) uf.unite(b.element(i)[0], b.element(i)[1]);
  }
  std::vector<char> used(mesh.num_nodes(), 0);
  for (const ElementBlock& b : mesh.blocks)
    if (b.type == ElementType::Tetrahedron)
      for (auto n : b.nodes) used[uf.find(n)] = 1;
  fm.dof_of_node.assign(mesh.num_nodes(), kNoDof);
  std::vector<std::uint32_t> dof_of_root(mesh.num_nodes(), kNoDof);
  for (std::uint32_t n = 0; n < mesh.num_nodes(); ++n) {
    const std::uint32_t r = uf.find(n);
    if (!used[r]) continue;
    if (dof_of_root[r] == kNoDof) dof_of_root[r] = static_cast<std::uint32_t>(fm.num_dofs++);
    fm.dof_of_node[n] = dof_of_root[r];
  }

  // 5. Pool unknowns.
  fm.pool_of_dof.assign(fm.num_dofs, -1);
  for (std::size_t bi = 0; bi < mesh.blocks.size(); ++bi) {
    if (block_material[bi] < 0) continue;
    const int pi = fm.materials[block_material[bi]].pool;
    if (pi < 0) continue;
    for (auto n : mesh.blocks[bi].nodes) {
      const std::uint32_t d = fm.dof_of_node[n];
      if (fm.pool_of_dof[d] >= 0 && fm.pool_of_dof[d] != pi)
        throw InputError(fm.pools[pi].where, fmt::format("pools '{}' and '{}' share node {} of {}: give each pool its own sub-mesh or "
                                                         "choose one with the pool selection",
                                                         fm.pools[fm.pool_of_dof[d]].name, fm.pools[pi].name, mesh.node_tags[n],
                                                         opt.mesh_name));
      fm.pool_of_dof[d] = pi;
    }
  }
  for (std::uint32_t d = 0; d < fm.num_dofs; ++d)
    if (fm.pool_of_dof[d] >= 0) fm.pools[fm.pool_of_dof[d]].dofs.push_back(d);

  // 6. Aquifer tetrahedra as unknowns; the sparsity pattern from their edges plus every diagonal.
  struct Tet {
    std::array<std::uint32_t, 4> node, dof;
    int material;
    std::size_t in_mesh;  // index among the mesh's tetrahedra (MaterialFieldValues::instance)
  };
  std::vector<Tet> tets;
  std::size_t in_mesh = 0;
  for (std::size_t bi = 0; bi < mesh.blocks.size(); ++bi) {
    const int m = block_material[bi];
    if (mesh.blocks[bi].type != ElementType::Tetrahedron) continue;
    const ElementBlock& b = mesh.blocks[bi];
    if (m < 0 || fm.materials[m].pool >= 0) {
      in_mesh += b.size();
      continue;
    }
    for (std::size_t i = 0; i < b.size(); ++i) {
      Tet t;
      for (int k = 0; k < 4; ++k) t.node[k] = b.element(i)[k], t.dof[k] = fm.dof_of_node[t.node[k]];
      t.material = m;
      t.in_mesh = in_mesh++;
      tets.push_back(t);
    }
  }
  // Constants that vary in space: each tetrahedron's own copy of its material (none without fields).
  const MaterialFieldValues fields = material_field_values(mesh, c);
  const std::size_t n = fm.num_dofs;
  std::vector<std::size_t> tet_start(n + 1, 0);
  for (const Tet& t : tets)
    for (auto d : t.dof) ++tet_start[d + 1];
  std::partial_sum(tet_start.begin(), tet_start.end(), tet_start.begin());
  std::vector<std::uint32_t> tets_of_dof(tet_start[n]);
  {
    std::vector<std::size_t> fill(tet_start.begin(), tet_start.end() - 1);
    for (std::uint32_t ti = 0; ti < tets.size(); ++ti)
      for (auto d : tets[ti].dof) tets_of_dof[fill[d]++] = ti;
  }
  CsrMatrix& P = fm.pattern;
  P.n = n;
  P.row_start.assign(n + 1, 0);
  std::vector<std::uint32_t> row;
  for (std::uint32_t d = 0; d < n; ++d) {
    row.clear();
    row.push_back(d);
    for (std::size_t k = tet_start[d]; k < tet_start[d + 1]; ++k)
      for (auto e : tets[tets_of_dof[k]].dof) row.push_back(e);
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    P.col.insert(P.col.end(), row.begin(), row.end());
    P.row_start[d + 1] = P.col.size();
  }
  auto position = [&](std::uint32_t i, std::uint32_t j) {
    auto b = P.col.begin() + P.row_start[i], e = P.col.begin() + P.row_start[i + 1];
    return static_cast<std::size_t>(std::lower_bound(b, e, j) - P.col.begin());
  };

  // The initial state (c_M at its effective vertical stress), checked over the sub-mesh's depth, and
  // each pool's gas-water contact against the top of its rock here.
  double z_low = mesh.nodes.empty() ? 0.0 : mesh.nodes[0][2];
  for (const auto& x : mesh.nodes) z_low = std::min(z_low, x[2]);
  const InitialState init = initial_state_of(c, c.initial_stress.surface_elevation - z_low);
  {
    std::vector<double> top(fm.pools.size(), -std::numeric_limits<double>::infinity());
    for (std::size_t bi = 0; bi < mesh.blocks.size(); ++bi)
      if (block_material[bi] >= 0 && fm.materials[block_material[bi]].pool >= 0)
        for (auto v : mesh.blocks[bi].nodes) {
          double& t = top[fm.materials[block_material[bi]].pool];
          t = std::max(t, mesh.nodes[v][2]);
        }
    for (std::size_t pi = 0; pi < fm.pools.size(); ++pi)
      for (const auto& spec_pool : c.pools)
        if (spec_pool.name == fm.pools[pi].name && std::isfinite(top[pi])) check_gas_contact(spec_pool, top[pi], init);
  }

  // 7. Element conductance V grad N^T (K/gamma_w) grad N and lumped storage V s / 4.
  fm.conductance_by_material.assign(fm.materials.size(), {});
  for (std::size_t m = 0; m < fm.materials.size(); ++m)
    if (fm.materials[m].pool < 0) fm.conductance_by_material[m].assign(P.col.size(), 0.0);
  fm.k_multiplier.assign(fm.materials.size(), 1.0);
  fm.storage.assign(n, 0.0);
  std::vector<char> cm_seen(fm.materials.size(), 0);
  // Materials with fields: K and porosity reported as their volume-weighted means.
  std::vector<std::array<double, 5>> field_sums(fm.materials.size(), {0, 0, 0, 0, 0});  // V K, V n, V
  for (const Tet& t : tets) {
    const Point3 &x0 = mesh.nodes[t.node[0]], &x1 = mesh.nodes[t.node[1]], &x2 = mesh.nodes[t.node[2]],
                 &x3 = mesh.nodes[t.node[3]];
    const double J[3][3] = {{x1[0] - x0[0], x2[0] - x0[0], x3[0] - x0[0]},
                            {x1[1] - x0[1], x2[1] - x0[1], x3[1] - x0[1]},
                            {x1[2] - x0[2], x2[2] - x0[2], x3[2] - x0[2]}};
    const double det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                       J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
    const double vol = std::abs(det) / 6.0;
    const double scale = std::abs(J[0][0]) + std::abs(J[1][1]) + std::abs(J[2][2]) + std::abs(J[0][1]) + std::abs(J[1][2]) +
                         std::abs(J[2][0]);
    if (!(vol > 1e-14 * scale * scale * scale))
      throw InputError(opt.mesh_name, fmt::format("degenerate tetrahedron with nodes {} {} {} {}", mesh.node_tags[t.node[0]],
                                                  mesh.node_tags[t.node[1]], mesh.node_tags[t.node[2]], mesh.node_tags[t.node[3]]));
    // Rows of J^-1 are the gradients of the barycentric coordinates of nodes 1..3.
    double g[4][3];
    const double inv = 1.0 / det;
    g[1][0] = (J[1][1] * J[2][2] - J[1][2] * J[2][1]) * inv;
    g[1][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) * inv;
    g[1][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) * inv;
    g[2][0] = (J[1][2] * J[2][0] - J[1][0] * J[2][2]) * inv;
    g[2][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) * inv;
    g[2][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) * inv;
    g[3][0] = (J[1][0] * J[2][1] - J[1][1] * J[2][0]) * inv;
    g[3][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) * inv;
    g[3][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) * inv;
    for (int k = 0; k < 3; ++k) g[0][k] = -(g[1][k] + g[2][k] + g[3][k]);
    FlowMaterial& mat = fm.materials[t.material];
    const MaterialSpec& ms = material_of_tet(fields, t.in_mesh, *spec[t.material]);
    const std::array<double, 3>& K = &ms == spec[t.material] ? mat.K : *ms.K;
    const double porosity = &ms == spec[t.material] ? mat.porosity : *ms.porosity;
    if (&ms != spec[t.material]) {
      auto& sum = field_sums[t.material];
      for (int d = 0; d < 3; ++d) sum[d] += vol * K[d];
      sum[3] += vol * porosity, sum[4] += vol;
    }
    const double kx = K[0] / c.water_unit_weight, ky = K[1] / c.water_unit_weight, kz = K[2] / c.water_unit_weight;
    auto& a = fm.conductance_by_material[t.material];
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        a[position(t.dof[i], t.dof[j])] += vol * (g[i][0] * kx * g[j][0] + g[i][1] * ky * g[j][1] + g[i][2] * kz * g[j][2]);
    const double zc = 0.25 * (x0[2] + x1[2] + x2[2] + x3[2]);
    const double s = storage_coefficient(c, init, ms, zc);
    if (!(s > 0) || !std::isfinite(s))
      throw InputError(spec[t.material]->where,
                       fmt::format("material '{}': specific storage gamma_w (n beta + c_M) = {:g} 1/m at z = {:g} m is not a "
                                   "positive finite number (porosity {:g}, water compressibility {:g} 1/Pa, c_M {:g} 1/Pa)",
                                   mat.name, s * c.water_unit_weight, zc, porosity, c.water_compressibility,
                                   s - porosity * c.water_compressibility));
    const double cm = s - porosity * c.water_compressibility;
    if (!cm_seen[t.material]) mat.cm_min = mat.cm_max = cm, cm_seen[t.material] = 1;
    mat.cm_min = std::min(mat.cm_min, cm), mat.cm_max = std::max(mat.cm_max, cm);
    for (int i = 0; i < 4; ++i) fm.storage[t.dof[i]] += 0.25 * vol * s;
  }
  for (std::size_t m = 0; m < fm.materials.size(); ++m)
    if (const auto& sum = field_sums[m]; sum[4] > 0) {
      for (int d = 0; d < 3; ++d) fm.materials[m].K[d] = sum[d] / sum[4];
      fm.materials[m].porosity = sum[3] / sum[4];
    }
  return fm;
}

}  // namespace ugs::flow
