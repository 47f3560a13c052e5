#include "ugs/meshing/material_fields.hpp"

#include <map>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/meshing/field_sources.hpp"

namespace ugs {
namespace {

std::string material_of_block(const Mesh& mesh, const ElementBlock& b) {
  const Entity* e = mesh.find_entity(b.entity_dim, b.entity_tag);
  if (!e) return {};
  for (int p : e->physicals)
    if (const PhysicalGroup* g = mesh.find_physical_tag(b.entity_dim, p); g && g->name.rfind("mat:", 0) == 0) return g->name.substr(4);
  return {};
}

std::string site_text(const FieldSite& s) {
  return fmt::format("tetrahedron {} (centroid {:.2f}, {:.2f}, {:.2f})", s.tag, s.centroid[0], s.centroid[1], s.centroid[2]);
}

}  // namespace

MaterialFieldValues material_field_values(const Mesh& mesh, const CaseFile& cs) {
  MaterialFieldValues out;
  bool any = false;
  for (const auto& m : cs.materials) any = any || !m.fields.empty();
  if (!any) return out;

  // The tetrahedra of each material with fields: their index among the mesh's tetrahedra, sites.
  struct Group {
    const MaterialSpec* spec;
    std::vector<std::size_t> tets;
    std::vector<FieldSite> sites;
  };
  std::map<std::string, Group> groups;
  std::size_t ntet = 0;
  for (const auto& b : mesh.blocks) {
    if (b.type != ElementType::Tetrahedron) continue;
    const MaterialSpec* spec = cs.material(material_of_block(mesh, b));
    const bool varies = spec && !spec->fields.empty();
    for (std::size_t i = 0; i < b.size(); ++i, ++ntet) {
      if (!varies) continue;
      Group& g = groups[spec->name];
      g.spec = spec;
      FieldSite s;
      s.tag = b.tags[i];
      for (const std::uint32_t n : b.element(i))
        for (int d = 0; d < 3; ++d) s.centroid[d] += 0.25 * mesh.nodes[n][d];
      g.tets.push_back(ntet);
      g.sites.push_back(s);
    }
  }
  out.instance.assign(ntet, -1);
  if (groups.empty()) return out;

  FieldSources sources;
  for (const auto& m : cs.materials) {  // case order: the copies' order does not depend on std::map's
    const auto it = groups.find(m.name);
    if (it == groups.end()) continue;
    const Group& g = it->second;
    // values[f][s]: field f at site s, scaled to SI and checked.
    std::vector<std::vector<double>> values;
    for (const MaterialField& f : m.fields) {
      const Sampled v = sources.sample(f, g.sites, cs.initial_stress.surface_elevation);
      std::vector<double> si(g.sites.size());
      for (std::size_t s = 0; s < g.sites.size(); ++s) {
        if (!v.covered[s])
          throw InputError(f.where, fmt::format("material '{}' {}: {} of the material lies outside the field's source {}", m.name,
                                                f.key, site_text(g.sites[s]),
                                                f.source == MaterialField::Source::Table ? "table (rows cover " +
                                                    fmt::format("{} .. {} m {})", f.rows.front().depth, f.rows.back().depth,
                                                                f.by_depth ? "depth" : "elevation")
                                                : f.source == MaterialField::Source::Cells ? f.file + " (no cell with its tag)"
                                                : f.source == MaterialField::Source::Map ? f.file + " (outside the map or next to an undefined node)"
                                                                                          : f.file + " (in no active cell of the grid)"));
        si[s] = f.scale * f.si * v.value[s];
        if (const std::string why = material_value_problem(f.key, si[s]); !why.empty())
          throw InputError(f.where, fmt::format("material '{}': at {}: {}", m.name, site_text(g.sites[s]), why));
      }
      values.push_back(std::move(si));
    }
    // One copy per distinct set of values, in the order of first appearance.
    std::map<std::vector<double>, std::int32_t> copy_of;
    std::vector<double> key(m.fields.size());
    for (std::size_t s = 0; s < g.sites.size(); ++s) {
      for (std::size_t f = 0; f < m.fields.size(); ++f) key[f] = values[f][s];
      auto [c, fresh] = copy_of.emplace(key, static_cast<std::int32_t>(out.specs.size()));
      if (fresh) {
        MaterialSpec copy = m;
        copy.fields.clear();
        for (std::size_t f = 0; f < m.fields.size(); ++f) copy.set_value(m.fields[f].key, key[f]);
        out.specs.push_back(std::move(copy));
        out.first_tag.push_back(g.sites[s].tag);
        out.first_centroid.push_back(g.sites[s].centroid);
      }
      out.instance[g.tets[s]] = c->second;
    }
  }
  return out;
}

const MaterialSpec& material_of_tet(const MaterialFieldValues& v, std::size_t t, const MaterialSpec& own) {
  if (v.instance.empty() || v.instance[t] < 0) return own;
  return v.specs[static_cast<std::size_t>(v.instance[t])];
}

}  // namespace ugs
