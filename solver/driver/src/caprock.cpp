#include "ugs/driver/caprock.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs::driver {

namespace {

// The gas column of a material (water when the model has none recorded).
const GasColumn& gas_of(const mech::Model& model, int material) {
  static const GasColumn water{};
  return static_cast<std::size_t>(material) < model.material_gas.size() ? model.material_gas[material] : water;
}

}  // namespace

CaprockCheck::CaprockCheck(const mech::Model& model, const Mesh& mesh, const CaseFile& cs) : seals_(cs.seals) {
  if (seals_.empty()) return;
  // A seal node's initial pore pressure: the highest of the elements around it, so that a gas cap
  // under the seal (its pool's gas column) pushes on the seal's base with the gas pressure.
  std::vector<char> seal_material(model.materials.size(), 0);
  for (const SealSpec& s : seals_)
    for (std::size_t m = 0; m < model.materials.size(); ++m)
      if (model.materials[m].name == s.material) seal_material[m] = 1;
  std::vector<char> on_seal(model.num_nodes(), 0);
  for (std::size_t c = 0; c < model.tets.size(); ++c)
    if (seal_material[model.tet_material[c]])
      for (auto v : model.tets[c]) on_seal[v] = 1;
  std::vector<double> node_p0(model.num_nodes(), -INFINITY);
  for (std::size_t c = 0; c < model.tets.size(); ++c)
    for (auto v : model.tets[c])
      if (on_seal[v])
        node_p0[v] = std::max(node_p0[v], model.initial.pore_pressure(model.x[v][2], gas_of(model, model.tet_material[c])));
  std::vector<std::uint32_t> local(model.num_nodes(), UINT32_MAX);
  for (std::size_t k = 0; k < seals_.size(); ++k) {
    const SealSpec& s = seals_[k];
    int mat = -1;
    for (std::size_t m = 0; m < model.materials.size(); ++m)
      if (model.materials[m].name == s.material) mat = static_cast<int>(m);
    const int entity = mesh_.entity_for_physical(3, "mat:" + s.material);
    ElementBlock& block = mesh_.block(3, entity, ElementType::Tetrahedron);
    std::size_t count = 0;
    for (std::size_t c = 0; c < model.tets.size(); ++c) {
      if (model.tet_material[c] != mat) continue;
      Cell cell;
      cell.index = static_cast<std::uint32_t>(c);
      cell.nodes = model.tets[c];
      cell.seal = static_cast<int>(k);
      cell.biot = model.materials[mat].biot;
      cell.centroid = {0, 0, 0};
      std::uint32_t n[4];
      for (int j = 0; j < 4; ++j) {
        const std::uint32_t v = cell.nodes[j];
        const Point3& x = model.x[v];
        cell.node_p0[j] = node_p0[v];
        for (int d = 0; d < 3; ++d) cell.centroid[d] += 0.25 * x[d];
        if (local[v] == UINT32_MAX) local[v] = mesh_.add_node(x, mesh.node_tags[v]);
        n[j] = local[v];
      }
      cell.p0 = model.initial.pore_pressure(cell.centroid[2], gas_of(model, mat));
      mesh_.add_element(block, n, model.tet_tags[c]);
      cells_.push_back(cell);
      ++count;
    }
    if (count == 0)
      throw InputError(s.where, fmt::format("[[seal]] material '{}' has no element in the mesh (expected tetrahedra of mat:{})",
                                            s.material, s.material));
  }
  mesh_.update_entity_bboxes();
}

CaprockStep CaprockCheck::evaluate(const std::vector<double>& stress, const std::vector<double>& cell_dp,
                                   const std::vector<double>& node_dp) const {
  CaprockStep st;
  const std::size_t n = cells_.size();
  st.pore_pressure.resize(n), st.fracture_pressure.resize(n), st.tensile_margin.resize(n), st.shear_margin.resize(n);
  st.tensile_by_seal.resize(seals_.size()), st.shear_by_seal.resize(seals_.size());
  for (std::size_t k = 0; k < seals_.size(); ++k) st.tensile_by_seal[k].material = st.shear_by_seal[k].material = seals_[k].material;
  for (std::size_t i = 0; i < n; ++i) {
    const Cell& c = cells_[i];
    const SealSpec& s = seals_[c.seal];
    // Total stress from the solver's effective one: sigma = sigma' - alpha p, p the element's own.
    const double p_own = c.p0 + cell_dp[c.index];
    std::array<double, 6> total;
    for (int j = 0; j < 6; ++j) total[j] = stress[6 * static_cast<std::size_t>(c.index) + j];
    for (int j = 0; j < 3; ++j) total[j] -= c.biot * p_own;
    double p = -std::numeric_limits<double>::infinity();
    for (int j = 0; j < 4; ++j) p = std::max(p, c.node_p0[j] + node_dp[c.nodes[j]]);
    const fem::RockMargins m = fem::rock_margins(total, p, {s.cohesion_Pa, s.friction_deg, s.tensile_strength_Pa});
    st.pore_pressure[i] = p;
    st.fracture_pressure[i] = m.fracture_pressure_Pa;
    st.tensile_margin[i] = m.tensile_margin_Pa;
    st.shear_margin[i] = m.shear_margin_Pa;
  }
  // The worst element of each seal: margins within kTie of the smallest count as equal and the first
  // in output order is named, so that rounding (another process count) does not move it among equals.
  constexpr double kTie = 1.0;  // Pa
  std::vector<double> low_t(seals_.size(), INFINITY), low_s(seals_.size(), INFINITY);
  for (std::size_t i = 0; i < n; ++i) {
    const int k = cells_[i].seal;
    low_t[k] = std::min(low_t[k], st.tensile_margin[i]);
    low_s[k] = std::min(low_s[k], st.shear_margin[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Cell& c = cells_[i];
    CaprockWorst& t = st.tensile_by_seal[c.seal];
    CaprockWorst& h = st.shear_by_seal[c.seal];
    if (t.margin_Pa == INFINITY && st.tensile_margin[i] <= low_t[c.seal] + kTie)
      t.margin_Pa = low_t[c.seal], t.at = c.centroid, t.pore_pressure_Pa = st.pore_pressure[i];
    if (h.margin_Pa == INFINITY && st.shear_margin[i] <= low_s[c.seal] + kTie)
      h.margin_Pa = low_s[c.seal], h.at = c.centroid, h.pore_pressure_Pa = st.pore_pressure[i];
  }
  for (std::size_t k = 0; k < seals_.size(); ++k) {
    if (st.tensile_by_seal[k].margin_Pa < st.tensile.margin_Pa) st.tensile = st.tensile_by_seal[k];
    if (st.shear_by_seal[k].margin_Pa < st.shear.margin_Pa) st.shear = st.shear_by_seal[k];
  }
  return st;
}

CaprockOutput::CaprockOutput(const std::string& fields, const std::string& table, const CaprockCheck& check,
                             const std::vector<std::string>& comments) {
  if (!fields.empty()) fields_ = std::make_unique<FieldSeriesWriter>(fields, check.seal_mesh());
  if (!table.empty())
    table_ = std::make_unique<CsvWriter>(
        table,
        std::vector<std::string>{"date", "seal", "min_tensile_margin_MPa", "tensile_x_m", "tensile_y_m", "tensile_z_m",
                                 "pore_pressure_MPa", "min_shear_margin_MPa", "shear_x_m", "shear_y_m", "shear_z_m"},
        comments);
}

void CaprockOutput::add(const std::string& date, double time, const CaprockStep& step, bool write_fields) {
  if (table_)
    for (std::size_t k = 0; k < step.tensile_by_seal.size(); ++k) {
      const CaprockWorst& t = step.tensile_by_seal[k];
      const CaprockWorst& s = step.shear_by_seal[k];
      table_->text(date).text(t.material).number(t.margin_Pa * 1e-6, 4);
      table_->number(t.at[0], 2).number(t.at[1], 2).number(t.at[2], 2).number(t.pore_pressure_Pa * 1e-6, 4);
      table_->number(s.margin_Pa * 1e-6, 4).number(s.at[0], 2).number(s.at[1], 2).number(s.at[2], 2).end_row();
    }
  if (fields_ && write_fields) {
    const std::vector<Field> cell{{"pore_pressure", 1, step.pore_pressure},
                                  {"fracture_pressure", 1, step.fracture_pressure},
                                  {"tensile_margin", 1, step.tensile_margin},
                                  {"shear_margin", 1, step.shear_margin}};
    fields_->add_step(date, time, {}, cell);
  }
}

void CaprockOutput::commit() {
  if (fields_) fields_->commit();
  if (table_) table_->commit();
}

}  // namespace ugs::driver
