// The pore-pressure change that drives the mechanics: one or more field series written by
// ugs-flow, one per pool (node field `dp` [Pa] on the pool's flow sub-mesh; node and cell tags are
// the parent mesh's). The solver's steps are the union of the files' dates; each file is
// interpolated linearly in time onto them (zero before its first date — a flow run starts from
// the undisturbed state — and held at its last value after its last date).
//
// Biot forcing is per element: an element of a pool's sub-mesh takes the mean of that file's
// nodal values at its four nodes; elements outside every sub-mesh (impermeable rock) have no
// pressure change. So two pools whose sub-meshes share an interface are not added twice there,
// and the forcing of a layer has exactly the layer's thickness. For the nodal output `dp` the
// files are summed per parent node.
//
// A file may instead hold `dp` as a cell field (a reservoir simulator's pressure, written by
// ugs-import-eclipse on the tetrahedra inside its grid): each of its elements takes its value as it
// is, and its nodes the mean of their elements' values in the nodal output. Where a cell field and
// a node field cover the same element the cell field wins, whatever the order of the files (the
// simulator inside the reservoir, ugs-flow's aquifer field around it); two cell fields, or two node
// fields, on one element are refused.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ugs/formats/fields.hpp"
#include "ugs/formats/mesh.hpp"
#include "ugs/mechanics/model.hpp"

namespace ugs::mech {

struct PressureStep {
  std::string date;  // ISO 8601
  double time = 0;   // seconds since 1970
};

class PressureHistory {
public:
  // Opens every file; InputError if one is not a field series, lacks `dp`, has node or cell tags
  // that are not in the mesh, claims elements another file of its kind claims, or has dates out
  // of order.
  PressureHistory(const std::vector<std::string>& paths, const Mesh& mesh, const Model& model);
  ~PressureHistory();

  const std::vector<PressureStep>& steps() const { return steps_; }
  // Adds a date (e.g. an output date of the case) inside the history; InputError outside it.
  void add_step(const std::string& date, const std::string& where);
  // Pressure change [Pa] per element (model tetrahedra order) and summed per mesh node at time t.
  std::vector<double> cell_dp(double time);
  std::vector<double> node_dp(double time);
  // The pressure change [Pa] of the elements under a pressure field only (a sixth of the thesis
  // model), file by file, in the same order at every time: the others stay at 0.
  std::vector<double> forced_cell_dp(double time);
  // Number of elements under a pressure field.
  std::size_t forced_cells() const;
  // Reads every step of every file that the times up to `until` interpolate from (the first step
  // at or after `until` included), with the checks of a step's values (components, finite, in
  // range), so that a damaged step is refused before the run starts rather than hours into it,
  // after its notes were printed. Steps read before are not read again.
  void check_steps(double until);
  // Notes about clamping (a file that starts late or ends early), for the log.
  std::vector<std::string> notes() const;

private:
  struct File;
  std::vector<double> file_values(File& f, double time);
  std::vector<std::unique_ptr<File>> files_;
  std::vector<PressureStep> steps_;
  std::vector<std::int32_t> cell_file_;                 // file of each tetrahedron, -1 none
  std::vector<std::vector<std::uint32_t>> file_cells_;  // the tetrahedra of each file
  std::vector<std::array<std::int32_t, 4>> cell_nodes_; // the tetrahedron's nodes in its file
  std::size_t num_nodes_ = 0;
};

}  // namespace ugs::mech
