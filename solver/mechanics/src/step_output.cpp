#include "ugs/mechanics/step_output.hpp"

#include <cstdint>
#include <utility>

namespace ugs::mech {

void write_top_surface(FieldSeriesWriter* top, CsvWriter* top_csv, const Mesh& mesh, const Model& model,
                       const std::string& date, double time, const std::vector<double>& u) {
  if (top) {
    std::vector<double> v;
    v.reserve(3 * model.top_nodes.size());
    for (auto n : model.top_nodes)
      for (int c = 0; c < 3; ++c) v.push_back(u[3 * n + c] * 1e3);
    const Field f[] = {{"u_mm", 3, std::move(v)}};
    top->add_step(date, time, f);
  }
  if (top_csv)
    for (auto n : model.top_nodes) {
      top_csv->text(date).integer(static_cast<std::int64_t>(mesh.node_tags[n]));
      top_csv->number(mesh.nodes[n][0], 3).number(mesh.nodes[n][1], 3);
      top_csv->number(u[3 * n] * 1e3, 4).number(u[3 * n + 1] * 1e3, 4).number(u[3 * n + 2] * 1e3, 4).end_row();
    }
}

void write_volume_step(FieldSeriesWriter& results, const std::set<std::string>& fields, PressureHistory& history,
                       const std::string& date, double time, const std::vector<double>& u) {
  std::vector<Field> nf;
  if (fields.count("displacement")) nf.push_back({"u", 3, u});
  if (fields.count("pressure")) nf.push_back({"dp", 1, history.node_dp(time)});
  results.add_step(date, time, nf);
}

std::vector<CellField> volume_cell_fields(const std::set<std::string>& fields) {
  std::vector<CellField> out;
  if (fields.count("strain")) out.push_back(CellField::Strain);
  if (fields.count("stress")) out.push_back(CellField::Stress);
  if (fields.count("stress_change")) out.push_back(CellField::StressChange);
  if (fields.count("cm")) out.push_back(CellField::Cm);
  if (fields.count("state")) {
    out.push_back(CellField::State);
    out.push_back(CellField::SigmaMax);
  }
  return out;
}

void write_cell_field(FieldSeriesWriter& results, CellField field, std::vector<double> values) {
  switch (field) {
    case CellField::Strain: results.add_cell_field({"strain", 6, std::move(values)}); break;
    case CellField::Stress: results.add_cell_field({"stress", 6, std::move(values)}); break;
    case CellField::StressChange: results.add_cell_field({"stress_change", 6, std::move(values)}); break;
    case CellField::Cm: results.add_cell_field({"cM", 1, std::move(values)}); break;
    case CellField::State: results.add_cell_field({"state", 1, std::move(values)}); break;
    case CellField::SigmaMax: results.add_cell_field({"sigma_z_max", 1, std::move(values)}); break;
  }
}

}  // namespace ugs::mech
