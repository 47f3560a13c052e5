// One step of ugs-solve's outputs, written on rank 0 the same way by the continuous and the faulted
// runs: the top-surface displacement (HDF5 and CSV, mm) every step, the volume fields at output dates.
#pragma once
#include <set>
#include <string>
#include <vector>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/mesh.hpp"
#include "ugs/mechanics/model.hpp"
#include "ugs/mechanics/pressure.hpp"
#include "ugs/mechanics/solver.hpp"

namespace ugs::mech {

// u: 3 per mesh node [m]. Either writer may be null (not asked for).
void write_top_surface(FieldSeriesWriter* top, CsvWriter* top_csv, const Mesh& mesh, const Model& model,
                       const std::string& date, double time, const std::vector<double>& u);

// The volume fields of an output date, written in two parts so that rank 0 holds one cell field at
// a time: write_volume_step adds the step with its node fields (displacement, pressure), then each
// of volume_cell_fields(fields), gathered in that order, goes in with write_cell_field.
// `fields` names any of displacement, pressure, strain, stress, stress_change, cm, state.
void write_volume_step(FieldSeriesWriter& results, const std::set<std::string>& fields, PressureHistory& history,
                       const std::string& date, double time, const std::vector<double>& u);
std::vector<CellField> volume_cell_fields(const std::set<std::string>& fields);
void write_cell_field(FieldSeriesWriter& results, CellField field, std::vector<double> values);

}  // namespace ugs::mech
