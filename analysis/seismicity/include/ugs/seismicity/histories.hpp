// The Coulomb stress histories a forecast starts from, read from what ugs-solve writes on a faulted
// run (docs/fault-mechanics.md "Outputs") or from a plain table of one patch:
//   - per-pair CSVs `<stem>_fault_<fault>.csv`: one row per node pair and output date, with the
//     pair's area share `area_m2`, `cfs_change_MPa`, position and in-plane coordinates;
//   - the faults HDF5 `<stem>_faults.h5`: the node field `cfs_change` (Pa) on the fault surfaces;
//     each node carries a third of each of its triangles (tip nodes too, with their neighbours'
//     mean), fault names from the mesh's fault:<name> groups when the mesh is given;
//   - a CSV `date,dcfs_MPa`: one patch of a given area (a user of another simulator).
// Every count, index, date and value is checked: bad input is an InputError naming file and line.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ugs/formats/mesh.hpp"

namespace ugs::seismicity {

struct PairHistory {
  std::uint64_t node = 0;         // node tag (side 1)
  Point3 x{};                     // m
  double along_strike = 0, down_dip = 0;  // m, in the fault's plane
  double area = 0;                // m2, the pair's share of the fault (>= 0)
  bool interpolated = false;      // values are the mean of its neighbours (docs/fault-mechanics.md)
  std::uint32_t surface_node = 0; // node index in StressHistory::surface (HDF5 input)
  std::vector<double> dcfs;       // Coulomb stress change from the initial state, Pa, one per date
};

struct FaultHistory {
  std::string name;
  std::string source;             // the file it came from, for messages
  std::vector<PairHistory> pairs;
};

struct StressHistory {
  std::vector<std::int64_t> dates;  // seconds since 1970, strictly increasing, two or more
  std::vector<FaultHistory> faults; // in input order
  // With the faults HDF5: its surface (nodes in the file's order, one triangle block per fault),
  // for writing the forecast as node fields ParaView shows on the fault planes.
  std::optional<Mesh> surface;
};

// The fault name of a per-pair CSV: from its first comment line ("# ugs-solve fault NAME: one row
// ..."), else the file name after its last "_fault_", else the file's stem.
std::string pair_csv_fault_name(const std::string& path);
// One or more per-pair CSVs (one fault each); the files must share their dates exactly.
StressHistory read_pair_csvs(const std::vector<std::string>& paths);
// The faults HDF5 of a faulted ugs-solve run; `mesh_path` ("" = none) names the faults.
StressHistory read_faults_h5(const std::string& path, const std::string& mesh_path);
// A CSV `date,dcfs_MPa` for one patch named `name` of area `area_m2` (> 0).
StressHistory read_dcfs_csv(const std::string& path, const std::string& name, double area_m2);
// What kind of input a file is: "h5", "pairs" (a cfs_change_MPa column) or "dcfs" (dcfs_MPa).
std::string input_kind(const std::string& path);

}  // namespace ugs::seismicity
