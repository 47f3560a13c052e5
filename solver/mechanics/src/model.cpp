#include "ugs/mechanics/model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/meshing/material_fields.hpp"

namespace ugs::mech {
namespace {

std::string material_of_entity(const Mesh& mesh, int dim, int tag) {
  const Entity* e = mesh.find_entity(dim, tag);
  if (!e) return {};
  for (int p : e->physicals)
    if (const PhysicalGroup* g = mesh.find_physical_tag(dim, p); g && g->name.rfind("mat:", 0) == 0) return g->name.substr(4);
  return {};
}

// Nodes of the boundary triangles of group bnd:<side>; empty if the group does not exist.
std::vector<std::uint32_t> boundary_nodes(const Mesh& mesh, const std::string& side, bool& exists) {
  const PhysicalGroup* g = mesh.find_physical(2, "bnd:" + side);
  exists = g != nullptr;
  std::vector<std::uint32_t> nodes;
  if (!g) return nodes;
  for (const auto& b : mesh.blocks) {
    if (b.entity_dim != 2 || b.type != ElementType::Triangle) continue;
    const Entity* e = mesh.find_entity(2, b.entity_tag);
    if (!e || std::find(e->physicals.begin(), e->physicals.end(), g->tag) == e->physicals.end()) continue;
    nodes.insert(nodes.end(), b.nodes.begin(), b.nodes.end());
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

int roller_axis(const std::string& side) {
  if (side == "west" || side == "east") return 0;
  if (side == "south" || side == "north") return 1;
  return 2;  // bottom, top
}

std::string group_list(const Mesh& mesh) {
  std::string s;
  for (const auto& p : mesh.physicals)
    if (p.dim == 2 && p.name.rfind("bnd:", 0) == 0) s += (s.empty() ? "" : ", ") + p.name;
  return s.empty() ? "none" : s;
}

}  // namespace

bool Model::has_hypoplastic() const {
  for (const auto& m : materials)
    if (m.law == fem::Law::Hypoplastic) return true;
  return false;
}

fem::Material material_from_spec(const MaterialSpec& s, const CaseFile& cs) {
  fem::Material m;
  m.name = s.name;
  switch (s.law) {
    case MaterialLaw::Linear: m.law = fem::Law::Linear; break;
    case MaterialLaw::ElasticDepth: m.law = fem::Law::Elastic; break;
    case MaterialLaw::Hypoplastic: m.law = fem::Law::Hypoplastic; break;
  }
  m.ratios = {s.nu_z, s.Eh_over_Ez, s.nuh_over_nuz, s.Gh_over_Gz};
  m.biot = s.biot;
  if (s.law == MaterialLaw::Linear) {
    if (!s.E_Pa) throw InputError(s.where, fmt::format("material '{}': E_MPa is required for law = \"linear\"", s.name));
    m.E_z = *s.E_Pa;
  }
  m.hypo.a = s.cm_a;
  m.hypo.b = s.cm_b;
  m.hypo.sigma_min = s.sigma_z_min_MPa;
  if (s.law == MaterialLaw::Hypoplastic) {
    if (!s.c_R) throw InputError(s.where, fmt::format("material '{}': c_R is required for law = \"hypoplastic\"", s.name));
    m.hypo.c_R = *s.c_R;
  }
  try {
    m.hypo.rule = fem::parse_inversion_rule(cs.inversion_rule);
    m.finalize();
  } catch (const std::invalid_argument& e) {
    throw InputError(s.where, fmt::format("material '{}': {}", s.name, e.what()));
  }
  return m;
}

Model build_model(const Mesh& mesh, const CaseFile& cs) { return build_model(mesh, cs, false); }

Model build_model(const Mesh& mesh, const CaseFile& cs, bool allow_interface_elements) {
  Model model;
  if (const std::size_t np = mesh.count(ElementType::Prism); np > 0 && !allow_interface_elements)
    throw InputError(cs.path, fmt::format("the mesh holds {} interface elements (faults); the continuous solver takes the "
                                          "mesh before ugs-faultinsert", np));
  if (mesh.count(ElementType::Tetrahedron) == 0) throw InputError("mesh", "no tetrahedra in the mesh");
  if (mesh.num_nodes() >= (std::size_t(1) << 31) / 3)
    throw InputError("mesh", fmt::format("{} nodes exceed the 32-bit index range of this PETSc build", mesh.num_nodes()));

  // Materials in the mesh's order; only those the mesh uses are validated and kept. A material
  // with fields gets one entry per distinct set of its fields' values (index -1 here).
  const MaterialFieldValues fields = material_field_values(mesh, cs);
  std::map<std::string, int> index;
  std::map<std::string, std::size_t> unknown;
  for (const auto& b : mesh.blocks) {
    if (b.type != ElementType::Tetrahedron) continue;
    const std::string name = material_of_entity(mesh, b.entity_dim, b.entity_tag);
    if (name.empty())
      throw InputError("mesh", fmt::format("{} tetrahedra of volume {} belong to no mat:<name> group", b.size(), b.entity_tag));
    if (index.count(name)) continue;
    const MaterialSpec* spec = cs.material(name);
    if (!spec) {
      unknown[name] += b.size();
      continue;
    }
    if (!spec->fields.empty()) {
      index[name] = -1;
      continue;
    }
    index[name] = static_cast<int>(model.materials.size());
    model.materials.push_back(material_from_spec(*spec, cs));
  }
  if (!unknown.empty())
    throw InputError(cs.path, fmt::format("mesh material '{}' (mat:{}, {} tetrahedra) has no [[material]] entry",
                                          unknown.begin()->first, unknown.begin()->first, unknown.begin()->second));

  model.tets.reserve(mesh.count(ElementType::Tetrahedron));
  model.tet_material.reserve(mesh.count(ElementType::Tetrahedron));
  model.tet_tags.reserve(mesh.count(ElementType::Tetrahedron));
  std::vector<int> copy_material(fields.specs.size(), -1);  // model material of each field copy
  for (const auto& b : mesh.blocks) {
    if (b.type != ElementType::Tetrahedron) continue;
    const int mat = index.at(material_of_entity(mesh, b.entity_dim, b.entity_tag));
    for (std::size_t i = 0; i < b.size(); ++i) {
      const auto e = b.element(i);
      int m = mat;
      if (m < 0) {
        const auto c = static_cast<std::size_t>(fields.instance[model.tets.size()]);
        if (copy_material[c] < 0) {
          copy_material[c] = static_cast<int>(model.materials.size());
          try {
            model.materials.push_back(material_from_spec(fields.specs[c], cs));
          } catch (const InputError& err) {
            const Point3& x = fields.first_centroid[c];
            const std::string what = err.where().empty() ? err.what() : std::string(err.what()).substr(err.where().size() + 2);
            throw InputError(fields.specs[c].where, fmt::format("the fields' values at tetrahedron {} (centroid {:.2f}, {:.2f}, {:.2f}): {}",
                                                                fields.first_tag[c], x[0], x[1], x[2], what));
          }
        }
        m = copy_material[c];
      }
      model.tets.push_back({e[0], e[1], e[2], e[3]});
      model.tet_material.push_back(m);
      model.tet_tags.push_back(b.tags[i]);
    }
  }

  // Boundary conditions.
  const std::size_t n = mesh.num_nodes();
  model.x = mesh.nodes;
  model.fixed.assign(n, 0);
  model.prescribed.assign(n, {0, 0, 0});
  std::set<std::string> seen;
  auto check_unique = [&](const std::string& side, const char* list) {
    if (!seen.insert(side).second)
      throw InputError(cs.path, fmt::format("boundary '{}' is named twice in [boundary] ({})", side, list));
  };
  double extent = 0;
  {
    Point3 lo = mesh.nodes[0], hi = mesh.nodes[0];
    for (const auto& p : mesh.nodes)
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    for (int k = 0; k < 3; ++k) extent = std::max(extent, hi[k] - lo[k]);
  }
  for (const auto& side : cs.fixed_boundaries) {
    check_unique(side, "fixed");
    bool exists = false;
    const auto nodes = boundary_nodes(mesh, side, exists);
    if (!exists)
      throw InputError(cs.path, fmt::format("boundary '{}': the mesh has no bnd:{} group (it has: {})", side, side, group_list(mesh)));
    for (auto v : nodes) model.fixed[v] = 7;
  }
  for (const auto& side : cs.roller_boundaries) {
    check_unique(side, "rollers");
    bool exists = false;
    const auto nodes = boundary_nodes(mesh, side, exists);
    if (!exists)
      throw InputError(cs.path, fmt::format("boundary '{}': the mesh has no bnd:{} group (it has: {})", side, side, group_list(mesh)));
    const int ax = roller_axis(side);
    double lo = mesh.nodes[nodes.front()][ax], hi = lo;
    for (auto v : nodes) lo = std::min(lo, mesh.nodes[v][ax]), hi = std::max(hi, mesh.nodes[v][ax]);
    if (hi - lo > 1e-6 * extent)
      throw InputError(cs.path, fmt::format("rollers on '{}': bnd:{} is not a plane {} = const (spread {:.3g} m); rollers "
                                            "need a side normal to x, y or z", side, side, "xyz"[ax], hi - lo));
    for (auto v : nodes) model.fixed[v] |= static_cast<std::uint8_t>(1u << ax);
  }
  for (const auto& side : cs.free_boundaries) {
    check_unique(side, "free");
    bool exists = false;
    boundary_nodes(mesh, side, exists);
    if (!exists)
      throw InputError(cs.path, fmt::format("boundary '{}': the mesh has no bnd:{} group (it has: {})", side, side, group_list(mesh)));
  }

  // Top surface for the displacement table.
  if (const PhysicalGroup* g = mesh.find_physical(2, "bnd:top")) {
    for (const auto& b : mesh.blocks) {
      if (b.entity_dim != 2 || b.type != ElementType::Triangle) continue;
      const Entity* e = mesh.find_entity(2, b.entity_tag);
      if (!e || std::find(e->physicals.begin(), e->physicals.end(), g->tag) == e->physicals.end()) continue;
      for (std::size_t i = 0; i < b.size(); ++i) {
        const auto t = b.element(i);
        model.top_triangles.push_back({t[0], t[1], t[2]});
        model.top_nodes.insert(model.top_nodes.end(), t.begin(), t.end());
      }
    }
    std::sort(model.top_nodes.begin(), model.top_nodes.end());
    model.top_nodes.erase(std::unique(model.top_nodes.begin(), model.top_nodes.end()), model.top_nodes.end());
  }

  // The initial state, its regime checked over the model's depth.
  const auto& is = cs.initial_stress;
  double z_low = mesh.nodes[0][2];
  for (const auto& p : mesh.nodes) z_low = std::min(z_low, p[2]);
  model.initial = initial_state_of(cs, is.surface_elevation - z_low);
  for (const auto& m : model.materials) {
    const MaterialSpec& spec = *cs.material(m.name);
    model.material_k.push_back({spec.k_Hmax.value_or(is.kH()), spec.k_hmin.value_or(is.kh())});
    model.material_gas.push_back(gas_column_of(cs, m.name));
  }
  // A gas-water contact must cut its pool or lie below it (then the whole pool holds gas).
  for (const auto& pool : cs.pools) {
    if (!pool.gas_water_contact_m) continue;
    std::vector<char> in_pool(model.materials.size(), 0);
    for (std::size_t m = 0; m < model.materials.size(); ++m)
      in_pool[m] = std::find(pool.materials.begin(), pool.materials.end(), model.materials[m].name) != pool.materials.end();
    double top = -std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < model.tets.size(); ++t)
      if (in_pool[model.tet_material[t]])
        for (auto v : model.tets[t]) top = std::max(top, model.x[v][2]);
    if (std::isfinite(top)) check_gas_contact(pool, top, model.initial);
  }
  model.traction_force = boundary_traction_forces(mesh, cs, model);
  return model;
}

}  // namespace ugs::mech
