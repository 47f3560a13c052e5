// ugs-seismicity — the expected rate of induced earthquakes from the Coulomb stress history of the
// faults: Dieterich's (1994) rate-and-state seismicity in the closed form of Heimisson & Segall
// (2018), dCFS linear between dates and integrated exactly (VERIFICATION.md V11, docs/seismicity.md).
// Per fault and date R/r, its largest value over the node pairs, the rate and the expected events
// from a start date; per window the expected events and P(at least one) above M_c and other
// magnitudes (Gutenberg-Richter); per node pair R/r for maps (CSV, and HDF5 + XDMF node fields).
//
//   ugs-seismicity faulted_fault_*.csv --case case.toml --start 2025-01-01 --window 2025-01-01/2033-01-01 -o forecast.csv
//   ugs-seismicity faulted_faults.h5 --mesh faulted.msh --case case.toml -o forecast.csv
//   ugs-seismicity patch_dcfs.csv --case case.toml --patch-area-km2 4 --window 2025-01-01/2030-01-01 -o patch.csv
#include <algorithm>

#include "ugs/cli/number_option.hpp"
#include "ugs/cli/tool.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/seismicity/run.hpp"

int main(int argc, char** argv) {
  using namespace ugs;
  cli::Tool tool({"ugs-seismicity",
                  "Forecast induced seismicity from the faults' Coulomb stress history: rate-and-state R/r, expected events and "
                  "P(M >= m) per fault and window.",
                  "ugs-seismicity faulted_fault_F1.csv faulted_fault_F2.csv --case case.toml --start 2025-01-01 "
                  "--window 2025-01-01/2033-01-01 -o forecast.csv   (writes forecast.csv, forecast_windows.csv, forecast_pairs.csv)"});
  seismicity::RunSettings s;
  auto& app = tool.app();
  app.add_option("inputs", s.inputs,
                 "ugs-solve's per-pair fault CSVs (<stem>_fault_<name>.csv), or its faults HDF5 (<stem>_faults.h5), or one CSV "
                 "date,dcfs_MPa for a single patch")
      ->required();
  app.add_option("--case", s.case_file, "Case file with the [seismicity] section (and [[fault]] entries)")->required();
  app.add_option("--mesh", s.mesh, "Mesh of the faulted run (MSH): names the faults of an HDF5 input");
  app.add_option("--start", s.start, "Count events from this date (ISO 8601; default the first date of the history)");
  app.add_option("--window", s.windows, "Forecast window START/END (ISO 8601), repeatable: expected events and P(M >= m)");
  app.add_option("--patch-name", s.patch_name, "Name of the patch of a date,dcfs_MPa input")->capture_default_str();
  app.add_option("--patch-area-km2", s.patch_area_km2, "Area of the patch of a date,dcfs_MPa input, km2")
      ->check(cli::number_in(0, 1e6, cli::Ends::OpenLow))
      ->capture_default_str();
  app.add_option("--windows-csv", s.windows_csv, "Per window, fault and magnitude (default <stem>_windows.csv with --window; none)");
  app.add_option("--pairs-csv", s.pairs_csv, "Per date, fault and node pair, for maps (default <stem>_pairs.csv; none)");
  app.add_option("--field-output", s.field_output,
                 "R/r, rate and event density as HDF5 + XDMF node fields on the fault surfaces (HDF5 input; default "
                 "<stem>_pairs.h5; none)");
  std::string& output = tool.add_output("-", "Per fault and date (CSV): R/r, its maximum over pairs, rate, expected events");
  tool.name_setting("start date", "--start");
  tool.name_setting("window", "--window");
  tool.name_setting("patch area", "--patch-area-km2");
  tool.name_setting("field output", "--field-output");
  tool.name_setting("event counts table", "--windows-csv");
  tool.name_setting("input", "inputs");
  tool.name_setting("mesh of the run", "--mesh");
  return tool.run(argc, argv, [&] {
    s.output = output;
    s.comments = {tool.command_line()};
    const auto r = seismicity::run(s);
    for (const auto& f : r.forecast.faults) {
      double peak = 0;
      for (double v : f.rate_ratio_max) peak = std::max(peak, v);
      cli::detail("fault {}: {:.3f} km2, largest R/r over pairs {:.4g}, {:.4g} events >= M {} from {}", f.name, f.area / 1e6, peak,
                  f.events.back(), f.params.M_c, format_iso_date(r.forecast.start));
    }
    for (const auto& w : r.written) cli::detail("wrote {}", w);
  });
}
