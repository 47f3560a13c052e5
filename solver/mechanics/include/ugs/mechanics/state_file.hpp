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

void write_state(const std::string& path, const Mesh& mesh, const std::string& date, double time, const SavedState& s,
                 const FieldSeriesOptions& options = {});
// InputError if the file is not a state of this mesh.
SavedState read_state(const std::string& path, const Mesh& mesh, std::string& date, double& time);

}  // namespace ugs::mech
