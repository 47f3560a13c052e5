#include "ugs/seismicity/run.hpp"

#include <cmath>
#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/seismicity/tables.hpp"

namespace ugs::seismicity {
namespace fs = std::filesystem;

StressHistory read_inputs(const RunSettings& s, std::string& kind) {
  if (s.inputs.empty())
    throw InputError("input", "no fault results given (expected ugs-solve's per-pair CSVs, its faults HDF5, or a date,dcfs_MPa CSV)");
  kind.clear();
  for (const auto& in : s.inputs) {
    std::error_code ec;
    if (!fs::is_regular_file(in, ec)) throw InputError(in, "no such file (expected fault results)");
    const std::string k = input_kind(in);
    if (k.empty())
      throw InputError(in, "is neither a faults HDF5 (.h5) nor a CSV with a cfs_change_MPa column (ugs-solve's per-pair CSV) or "
                           "a dcfs_MPa column (one patch)");
    if (!kind.empty() && k != kind)
      throw InputError(in, fmt::format("is a {} input after a {} one (expected one kind: per-pair CSVs, one faults HDF5 or one "
                                       "date,dcfs_MPa CSV)", k, kind));
    kind = k;
  }
  if (kind != "pairs" && s.inputs.size() > 1)
    throw InputError(s.inputs[1], fmt::format("a second {} input (expected one)", kind == "h5" ? "faults HDF5" : "date,dcfs_MPa"));
  if (kind == "pairs") return read_pair_csvs(s.inputs);
  if (kind == "h5") return read_faults_h5(s.inputs[0], s.mesh);
  return read_dcfs_csv(s.inputs[0], s.patch_name, s.patch_area_km2 * 1e6);
}

Forecast compute(const RunSettings& s, const CaseFile& c, const StressHistory& h) {
  if (!c.seismicity)
    throw InputError(c.path, "has no [seismicity] section (expected A_sigma_MPa, stressing_rate_MPa_per_yr, "
                             "background_rate_per_yr_km2, M_c: docs/seismicity.md)");
  // A date,dcfs_MPa patch is not a fault of the model: only overrides must name it.
  check_case_faults(c, h, s.inputs.empty() || input_kind(s.inputs.front()) != "dcfs");
  std::vector<Parameters> params;
  for (const auto& f : h.faults) params.push_back(parameters_for(*c.seismicity, f.name, c.path));
  std::int64_t start = h.dates.front();
  if (!s.start.empty()) {
    const auto d = parse_iso_date(s.start);
    if (!d) throw InputError("start date", fmt::format("'{}' is not an ISO 8601 date", s.start));
    start = *d;
  }
  std::vector<Window> windows;
  for (const auto& w : s.windows) windows.push_back(parse_window(w, "window " + w));
  return forecast(h, params, start, windows);
}

RunResult run(const RunSettings& s) {
  const CaseFile c = read_case_file(s.case_file);
  RunResult r;
  const StressHistory h = read_inputs(s, r.kind);
  r.forecast = compute(s, c, h);
  // Output paths: all decided and distinct before anything is opened.
  const bool to_stdout = s.output == "-" || s.output.empty();
  std::string stem = s.output;
  if (fs::path(stem).extension() == ".csv") stem.resize(stem.size() - 4);
  auto path = [&](const std::string& given, const std::string& suffix, bool wanted) -> std::string {
    if (given == "none") return "";
    if (!given.empty()) return given;
    return to_stdout || !wanted ? "" : stem + suffix;
  };
  const std::string windows_csv = path(s.windows_csv, "_windows.csv", !s.windows.empty());
  const std::string pairs_csv = path(s.pairs_csv, "_pairs.csv", true);
  const std::string fields = path(s.field_output, "_pairs.h5", r.kind == "h5");
  if (!fields.empty() && r.kind != "h5")
    throw InputError("field output", fmt::format("{}: node fields need the faults HDF5 as input (per-pair CSVs and a dcfs table "
                                                 "have no fault triangles)", fields));
  if (!fields.empty() && fs::path(fields).extension() != ".h5")
    throw InputError("field output", fmt::format("{}: expected a .h5 file name (the XDMF goes beside it)", fields));
  std::set<std::string> seen;
  for (const auto& p : {to_stdout ? std::string() : s.output, windows_csv, pairs_csv, fields})
    if (!p.empty() && !seen.insert(fs::weakly_canonical(fs::absolute(p)).string()).second)
      throw InputError(p, "is named for two outputs (expected distinct files)");
  for (const auto& in : s.inputs)
    if (seen.count(fs::weakly_canonical(fs::absolute(in)).string())) throw InputError(in, "is an input and an output");
  if (windows_csv.empty() && !s.windows.empty() && s.windows_csv != "none")
    throw InputError("event counts table", "no file named for the expected events per forecast period (the table of dates goes to "
                                           "stdout): name one");

  std::vector<std::string> comments = s.comments;
  comments.push_back(fmt::format("ugs-seismicity: Dieterich (1994) rate-and-state seismicity, Heimisson & Segall (2018) closed form, "
                                 "dCFS linear between dates; events >= M_c counted from {}; year = 365.25 days; km2 of fault area",
                                 format_iso_date(r.forecast.start)));
  for (const auto& f : r.forecast.faults)
    comments.push_back(fmt::format("fault {}: A_sigma_MPa = {}, stressing_rate_MPa_per_yr = {}, background_rate_per_yr_km2 = {}, "
                                   "M_c = {}, b_value = {}, area_km2 = {}", f.name, f.params.A_sigma / 1e6,
                                   f.params.stressing_rate * kSecondsPerYear / 1e6,
                                   f.params.background_rate * kSecondsPerYear * 1e6, f.params.M_c, f.params.b_value, f.area / 1e6));
  auto fault_csv = fault_table(to_stdout ? "-" : s.output, r.forecast, comments);
  std::unique_ptr<CsvWriter> win, pairs;
  std::unique_ptr<FieldSeriesWriter> h5;
  if (!windows_csv.empty()) win = window_table(windows_csv, r.forecast, c.seismicity->magnitudes, comments);
  if (!pairs_csv.empty()) pairs = pair_table(pairs_csv, h, r.forecast, comments);
  if (!fields.empty()) h5 = pair_fields(fields, h, r.forecast);
  if (h5) h5->commit(), r.written.push_back(fields);
  if (pairs) pairs->commit(), r.written.push_back(pairs_csv);
  if (win) win->commit(), r.written.push_back(windows_csv);
  fault_csv->commit();
  r.written.push_back(to_stdout ? "-" : s.output);
  return r;
}

}  // namespace ugs::seismicity
