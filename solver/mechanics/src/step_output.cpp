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

void write_volume_fields(FieldSeriesWriter& results, const std::set<std::string>& fields, PressureHistory& history,
                         const std::string& date, double time, const std::vector<double>& u, CellResults& cells) {
  std::vector<Field> nf, cf;
  if (fields.count("displacement")) nf.push_back({"u", 3, u});
  if (fields.count("pressure")) nf.push_back({"dp", 1, history.node_dp(time)});
  if (fields.count("strain")) cf.push_back({"strain", 6, std::move(cells.strain)});
  if (fields.count("stress")) cf.push_back({"stress", 6, std::move(cells.stress)});
  if (fields.count("stress_change")) cf.push_back({"stress_change", 6, std::move(cells.stress_change)});
  if (fields.count("cm")) cf.push_back({"cM", 1, std::move(cells.cm)});
  if (fields.count("state")) {
    cf.push_back({"state", 1, std::move(cells.state)});
    cf.push_back({"sigma_z_max", 1, std::move(cells.sigma_max)});
  }
  results.add_step(date, time, nf, cf);
}

}  // namespace ugs::mech
