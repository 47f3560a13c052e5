// The output set of a run, on rank 0: the volume fields at the output dates, the top surface at
// every step (HDF5 and optional CSV), the fault outputs of a faulted model, and the restart state.
// Everything is written to temporaries and renamed into place by commit(): a failed run leaves
// no results behind (the restart state, written whole at each checkpoint, is the exception).
#pragma once
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "ugs/contact/fault_output.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/mesh.hpp"
#include "ugs/mechanics/model.hpp"
#include "ugs/mechanics/pressure.hpp"
#include "ugs/mechanics/solver.hpp"
#include "ugs/driver/settings.hpp"

namespace ugs::driver {

// The bnd:top triangles of `model` as a mesh of their own.
Mesh make_top_mesh(const Mesh& mesh, const mech::Model& model);

class OutputSet {
public:
  // `fm` non-null for a faulted model: its volume results hold the tetrahedra only, and the fault
  // outputs are opened too.
  OutputSet(const RunSettings& o, const Mesh& mesh, const mech::Model& model, const CaseFile& cs,
            const contact::FaultModel* fm);

  // One step: the top surface always, the volume step with its node fields when `output`; its cell
  // fields follow one at a time, in the order of cell_fields(), through add_cell_field.
  void write_step(const std::string& date, double time, const std::vector<double>& u, bool output,
                  mech::PressureHistory& history);
  const std::vector<mech::CellField>& cell_fields() const { return cell_fields_; }
  void add_cell_field(mech::CellField field, std::vector<double> values);
  contact::FaultOutput* faults() { return faults_.get(); }
  // The volume results' writer (its mesh is the restart state's).
  const FieldSeriesWriter& results() const { return *results_; }
  void commit();

private:
  const Mesh& mesh_;
  const mech::Model& model_;
  std::set<std::string> fields_;
  std::vector<mech::CellField> cell_fields_;
  Mesh top_mesh_;
  std::unique_ptr<FieldSeriesWriter> results_, top_;
  std::unique_ptr<CsvWriter> top_csv_;
  std::unique_ptr<contact::FaultOutput> faults_;
};

}  // namespace ugs::driver
