#include "state_file.hpp"

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/formats/fields.hpp"

namespace ugs::mech {

void write_state(const std::string& path, const Mesh& mesh, const std::string& date, double time, const SavedState& s) {
  FieldSeriesWriter w(path, mesh);
  const Field nodes[] = {{"u", 3, s.u}};
  const Field cells[] = {{"dp", 1, s.dp}, {"eps", 6, s.eps}, {"dsig", 6, s.dsig}, {"hypo", 4, s.hypo}};
  w.add_step(date, time, nodes, cells);
  w.commit();
}

SavedState read_state(const std::string& path, const Mesh& mesh, std::string& date, double& time) {
  FieldSeriesReader r(path);
  if (r.steps().size() != 1) throw InputError(path, "not a ugs-solve restart state (expected one step)");
  if (r.node_tags() != mesh.node_tags || r.num_cells() != mesh.count(ElementType::Tetrahedron))
    throw InputError(path, fmt::format("the restart state belongs to another mesh ({} nodes, {} cells; this mesh has {} "
                                       "nodes, {} tetrahedra)", r.num_nodes(), r.num_cells(), mesh.num_nodes(),
                                       mesh.count(ElementType::Tetrahedron)));
  date = r.steps()[0].date;
  time = r.steps()[0].time;
  auto get_node = [&](const char* name, int comps) {
    Field f = r.node_field(0, name);
    if (f.components != comps) throw InputError(path, fmt::format("node field '{}' has {} components", name, f.components));
    return std::move(f.values);
  };
  auto get_cell = [&](const char* name, int comps) {
    Field f = r.cell_field(0, name);
    if (f.components != comps) throw InputError(path, fmt::format("cell field '{}' has {} components", name, f.components));
    return std::move(f.values);
  };
  SavedState s;
  s.u = get_node("u", 3);
  s.dp = get_cell("dp", 1);
  s.eps = get_cell("eps", 6);
  s.dsig = get_cell("dsig", 6);
  s.hypo = get_cell("hypo", 4);
  return s;
}

}  // namespace ugs::mech
