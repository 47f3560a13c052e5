#include "ugs/driver/output_set.hpp"

#include "ugs/mechanics/step_output.hpp"

namespace ugs::driver {

Mesh make_top_mesh(const Mesh& mesh, const mech::Model& model) {
  Mesh top;
  std::vector<std::uint32_t> local(mesh.num_nodes(), 0);
  for (auto v : model.top_nodes) local[v] = top.add_node(mesh.nodes[v], mesh.node_tags[v]);
  const int e = top.entity_for_physical(2, "bnd:top");
  auto& b = top.block(2, e, ElementType::Triangle);
  for (const auto& t : model.top_triangles) {
    const std::uint32_t n[3] = {local[t[0]], local[t[1]], local[t[2]]};
    top.add_element(b, n);
  }
  top.update_entity_bboxes();
  return top;
}

OutputSet::OutputSet(const RunSettings& o, const Mesh& mesh, const mech::Model& model, const CaseFile& cs,
                     const contact::FaultModel* fm)
    : mesh_(mesh), model_(model) {
  fields_.insert(cs.output_fields.begin(), cs.output_fields.end());
  if (fields_.empty()) fields_ = {"displacement", "strain", "stress", "stress_change", "cm", "state"};
  cell_fields_ = mech::volume_cell_fields(fields_);
  FieldSeriesOptions vol;
  if (fm) vol.cell_types = {ElementType::Tetrahedron};
  results_ = std::make_unique<FieldSeriesWriter>(o.output, mesh, vol);
  if (o.top && !model.top_nodes.empty()) {
    top_mesh_ = make_top_mesh(mesh, model);
    top_ = std::make_unique<FieldSeriesWriter>(*o.top, top_mesh_);
  }
  if (o.top_csv && !model.top_nodes.empty()) {
    const std::vector<std::string> comments{"ugs-solve top-surface displacement (bnd:top nodes), one row per node and date",
                                            o.command_line};
    top_csv_ = std::make_unique<CsvWriter>(*o.top_csv, std::vector<std::string>{"date", "node", "x_m", "y_m", "ux_mm", "uy_mm", "uz_mm"},
                                           comments);
  }
  if (fm) {
    const std::vector<std::string> comments{"ugs-solve fault statistics per fault and date (node pairs on free degrees of freedom)",
                                            o.command_line};
    const auto& f = o.faults;
    faults_ = std::make_unique<contact::FaultOutput>(f.fields.value_or(""), f.table.value_or(""), *fm, comments,
                                                     f.pairs_prefix.value_or(""));
  }
}

void OutputSet::write_step(const std::string& date, double time, const std::vector<double>& u, bool output,
                           mech::PressureHistory& history) {
  mech::write_top_surface(top_.get(), top_csv_.get(), mesh_, model_, date, time, u);
  if (output) mech::write_volume_step(*results_, fields_, history, date, time, u);
}

void OutputSet::add_cell_field(mech::CellField field, std::vector<double> values) {
  mech::write_cell_field(*results_, field, std::move(values));
}

void OutputSet::commit() {
  results_->commit();
  if (top_) top_->commit();
  if (top_csv_) top_csv_->commit();
  if (faults_) faults_->commit();
}

}  // namespace ugs::driver
