// Restart state files: a field series with one step (the date of the state) holding node u and the
// cell pressure change dp and history variables eps, dsig (thesis Voigt order) and hypo (sigma_max, sigma_inv
// [MPa], direction, sign of the last pressure change). ParaView opens them like any result.
// A faulted mesh writes its tetrahedra only (`options`), as its volume results do.
#pragma once
#include <string>

#include "ugs/formats/fields.hpp"
#include "ugs/formats/mesh.hpp"
#include "ugs/mechanics/solver.hpp"

namespace ugs::mech {

// The cell fields of a state file, in the file's order.
inline constexpr StateField kStateFields[] = {StateField::Dp, StateField::Eps, StateField::Dsig, StateField::Hypo};

// A state file written one field at a time (each gathered only when written: rank 0 holds one cell
// field, not all of SavedState). Give add() every field of kStateFields in that order, then commit();
// given the mesh, the bytes are write_state()'s. Without commit() nothing is left behind.
class StateFileWriter {
public:
  StateFileWriter(const std::string& path, const Mesh& mesh, const std::string& date, double time,
                  std::vector<double> u, const FieldSeriesOptions& options = {});
  // The mesh copied from an open writer of the same mesh and cell types (the run's results): the
  // same arrays, not deflated again.
  StateFileWriter(const std::string& path, const FieldSeriesWriter& mesh_source, const std::string& date, double time,
                  std::vector<double> u);
  void add(StateField field, std::vector<double> values);
  void commit();

private:
  FieldSeriesWriter w_;
  std::size_t next_ = 0;
};

void write_state(const std::string& path, const Mesh& mesh, const std::string& date, double time, const SavedState& s,
                 const FieldSeriesOptions& options = {});
// InputError if the file is not a state of this mesh.
SavedState read_state(const std::string& path, const Mesh& mesh, std::string& date, double& time);

}  // namespace ugs::mech
