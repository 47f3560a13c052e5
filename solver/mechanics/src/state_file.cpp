#include "ugs/mechanics/state_file.hpp"

#include <cmath>
#include <iterator>
#include <stdexcept>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/formats/fields.hpp"
#include "input_checks.hpp"

namespace ugs::mech {

namespace {

const char* state_field_name(StateField f) {
  switch (f) {
    case StateField::Dp: return "dp";
    case StateField::Eps: return "eps";
    case StateField::Dsig: return "dsig";
    case StateField::Hypo: return "hypo";
  }
  return "";
}

int state_field_components(StateField f) { return f == StateField::Dp ? 1 : f == StateField::Hypo ? 4 : 6; }

}  // namespace

StateFileWriter::StateFileWriter(const std::string& path, const Mesh& mesh, const std::string& date, double time,
                                 std::vector<double> u, const FieldSeriesOptions& options)
    : w_(path, mesh, options) {
  const Field nodes[] = {{"u", 3, std::move(u)}};
  w_.add_step(date, time, nodes);
}

StateFileWriter::StateFileWriter(const std::string& path, const FieldSeriesWriter& mesh_source, const std::string& date,
                                 double time, std::vector<double> u)
    : w_(path, mesh_source) {
  const Field nodes[] = {{"u", 3, std::move(u)}};
  w_.add_step(date, time, nodes);
}

void StateFileWriter::add(StateField field, std::vector<double> values) {
  if (next_ >= std::size(kStateFields) || kStateFields[next_] != field)
    throw std::logic_error("StateFileWriter: state fields added out of order");
  ++next_;
  w_.add_cell_field({state_field_name(field), state_field_components(field), std::move(values)});
}

void StateFileWriter::commit() {
  if (next_ != std::size(kStateFields)) throw std::logic_error("StateFileWriter: a state field is missing");
  w_.commit();
}

void write_state(const std::string& path, const Mesh& mesh, const std::string& date, double time, const SavedState& s,
                 const FieldSeriesOptions& options) {
  StateFileWriter w(path, mesh, date, time, s.u, options);
  w.add(StateField::Dp, s.dp);
  w.add(StateField::Eps, s.eps);
  w.add(StateField::Dsig, s.dsig);
  w.add(StateField::Hypo, s.hypo);
  w.commit();
}

SavedState read_state(const std::string& path, const Mesh& mesh, std::string& date, double& time) {
  FieldSeriesReader r(path);
  if (r.steps().size() != 1) throw InputError(path, "not a ugs-solve restart state (expected one step)");
  if (r.node_tags() != mesh.node_tags || r.num_cells() != mesh.count(ElementType::Tetrahedron))
    throw InputError(path, fmt::format("the restart state belongs to another mesh ({} nodes, {} cells; this mesh has {} "
                                       "nodes, {} tetrahedra)", r.num_nodes(), r.num_cells(), mesh.num_nodes(),
                                       mesh.count(ElementType::Tetrahedron)));
  {
    // The same cells in the same order (a state's cell values are matched by position).
    std::vector<std::uint64_t> tets;
    for (const auto& b : mesh.blocks)
      if (b.type == ElementType::Tetrahedron) tets.insert(tets.end(), b.tags.begin(), b.tags.end());
    const auto tags = r.cell_tags();
    for (std::size_t c = 0; c < tags.size() && c < tets.size(); ++c)
      if (tags[c] != tets[c])
        throw InputError(path, fmt::format("/mesh/cell_tags: cell {} has tag {}, the mesh's tetrahedron {} has tag {}: the "
                                           "restart state belongs to another mesh", c, tags[c], c, tets[c]));
  }
  date = r.steps()[0].date;
  time = r.steps()[0].time;
  if (!std::isfinite(time)) throw InputError(path, fmt::format("step {}: time {} is not a finite number of seconds", date, time));
  auto get_node = [&](const char* name, int comps) {
    Field f = r.node_field(0, name);
    if (f.components != comps) throw InputError(path, fmt::format("node field '{}' has {} components", name, f.components));
    check_finite(path, fmt::format("node field '{}'", name), f.values, comps, "a finite state");
    return std::move(f.values);
  };
  auto get_cell = [&](const char* name, int comps) {
    Field f = r.cell_field(0, name);
    if (f.components != comps) throw InputError(path, fmt::format("cell field '{}' has {} components", name, f.components));
    check_finite(path, fmt::format("cell field '{}'", name), f.values, comps, "a finite state");
    return std::move(f.values);
  };
  SavedState s;
  s.u = get_node("u", 3);
  s.dp = get_cell("dp", 1);
  s.eps = get_cell("eps", 6);
  s.dsig = get_cell("dsig", 6);
  s.hypo = get_cell("hypo", 4);
  // sigma_max and sigma_inv are stress magnitudes [MPa] (0 outside the hypo-plastic elements).
  for (std::size_t c = 0; 4 * c < s.hypo.size(); ++c)
    for (int k = 0; k < 2; ++k)
      if (s.hypo[4 * c + k] < 0)
        throw InputError(path, fmt::format("cell field 'hypo': {} {} MPa of cell {} is negative (expected a stress magnitude)",
                                           k == 0 ? "sigma_max" : "sigma_inv", s.hypo[4 * c + k], c));
  return s;
}

}  // namespace ugs::mech
