// One ugs-seismicity run (docs/seismicity.md): read the case's [seismicity] parameters and the stress
// history (per-pair CSVs, the faults HDF5 or a `date,dcfs_MPa` table), check everything, compute the
// forecast and write its files. Every check comes before the first file is opened: bad input writes
// nothing (InputError, exit 2).
#pragma once
#include <string>
#include <vector>

#include "ugs/seismicity/forecast.hpp"

namespace ugs::seismicity {

struct RunSettings {
  std::vector<std::string> inputs;  // per-pair CSVs, or one faults HDF5, or one date,dcfs_MPa CSV
  std::string case_file;            // with a [seismicity] section
  std::string mesh;                 // names the faults of an HDF5 input ("" = "fault <tag>")
  std::string start;                // ISO date from which events are counted ("" = the first date)
  std::vector<std::string> windows; // START/END
  std::string patch_name = "patch"; // a date,dcfs_MPa input: its name and area
  double patch_area_km2 = 1.0;
  // Outputs: the per fault and date table ("-" = stdout); the others "" for the default beside it
  // (<stem>_windows.csv with windows, <stem>_pairs.csv, <stem>_pairs.h5 with an HDF5 input; none
  // when the table goes to stdout) or "none".
  std::string output = "-", windows_csv, pairs_csv, field_output;
  std::vector<std::string> comments;  // first comment lines of every table (the command line)
};

struct RunResult {
  Forecast forecast;
  std::string kind;                   // "pairs", "h5" or "dcfs"
  std::vector<std::string> written;   // the files written
};

// The stress history of `inputs` (kinds checked; a mix is refused).
StressHistory read_inputs(const RunSettings& s, std::string& kind);
// The forecast of a run without writing anything (for ugs-ensemble's metrics).
Forecast compute(const RunSettings& s, const CaseFile& c, const StressHistory& h);
RunResult run(const RunSettings& s);

}  // namespace ugs::seismicity
