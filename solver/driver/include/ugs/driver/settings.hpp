// The settings of one ugs-solve run, typed once at the tool's edge (tools/ugs-solve/main.cpp):
// paths resolved (an output that is off is std::nullopt, never a "none" string), dates as
// seconds, solver choices as enums; what is not set falls back to the case file. Library code
// names case-file keys in its messages, never command-line flags.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ugs/contact/contact.hpp"
#include "ugs/mechanics/partition.hpp"
#include "ugs/mechanics/solver.hpp"

namespace ugs::driver {

struct FaultSettings {
  std::optional<std::string> fields;      // fault fields at the output dates (HDF5 + XDMF)
  std::optional<std::string> table;       // per fault and date: max chi, slip, areas (CSV)
  std::optional<std::string> pairs_prefix;  // per fault, every node pair at the output dates: PREFIX<fault>.csv
  bool pairs_every_step = false;          // the per-pair CSVs at every step instead (a stress history)
  std::string scenario_table;             // the scales tried by the safe-scale search (CSV)
  std::optional<contact::SaddleSolver> solver;  // overrides [solver] fault_solver
  std::optional<double> scale;            // overrides [scenario] pressure_scale (>= 0)
  bool find_safe_scale = false;
};

struct RunSettings {
  std::string mesh = "-";
  std::string case_file;
  std::vector<std::string> pressure;
  std::string output;                     // volume results (HDF5 + XDMF)
  std::optional<std::string> top;         // top surface at every step (HDF5 + XDMF)
  std::optional<std::string> top_csv;     // the same as a CSV table (mm)
  std::optional<std::string> state;       // restart state, written at output dates and checkpoints
  std::optional<std::string> restart;     // a state to resume from
  std::optional<double> until;            // stop after this time [s since the epoch]
  std::optional<mech::LinearSolver> linear;  // overrides [solver] linear_solver
  mech::PartitionMethod partition = mech::PartitionMethod::PtScotch;
  std::optional<int> checkpoint_every;    // overrides [output] checkpoint_every
  std::optional<std::string> steps;       // overrides [solver] steps: every-date | turning-points
  std::optional<double> tolerance;        // overrides [solver] tolerance
  std::optional<std::string> tolerance_of;  // overrides [solver] tolerance_of: step | total-load
  // Windows [from, to] (s since the epoch) where every date of the pressure fields is stepped on
  // whatever `steps` says: the per-step outputs (top surface, fault table) hold every one of them
  // (a monthly InSAR window, the storage years of a seismicity forecast).
  std::vector<std::pair<double, double>> every_date_in;
  FaultSettings faults;
  // Caprock integrity of the [[seal]] materials (docs/caprock.md): fields over the seal elements at
  // the output dates (HDF5 + XDMF) and the worst element of each seal at every step (CSV).
  std::optional<std::string> caprock_fields;
  std::optional<std::string> caprock_table;
  std::string command_line;               // recorded in the CSV headers
  // Messages (level 0 info, 1 detail, -1 warning) and progress; called on rank 0 only.
  std::function<void(int, const std::string&)> log;
  std::function<void(std::size_t done, std::size_t total)> progress;
};

// "<stem>" of a results path: "out/solve.h5" -> "out/solve".
std::string output_stem(const std::string& h5_path);

}  // namespace ugs::driver
