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

// The fields named in `fields` (displacement, pressure, strain, stress, stress_change, cm, state);
// the cell results are moved out.
void write_volume_fields(FieldSeriesWriter& results, const std::set<std::string>& fields, PressureHistory& history,
                         const std::string& date, double time, const std::vector<double>& u, CellResults& cells);

}  // namespace ugs::mech
