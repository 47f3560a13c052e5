// Calibration parameters as paths into the case file (TOML) and modified copies of the case.
//
// A path names tables and keys with dots; an array of tables ([[material]], [[pool]]) is indexed
// by the `name` of its element (or by a number), an array of numbers by [i]:
//   material.pool_c.c_R            initial_stress.k0            material.aquifer_pool_c.K_m_per_s[0]
//   pool."Pool C".reference_pressure_MPa   (quotes for names with dots)
// A constant given as a field (c_R = { grdecl = "x.GRDECL", keyword = "CR", scale = 1.0 }) is
// varied through its scale factor: material.pool_c.c_R (or material.pool_c.c_R.scale) sets scale.
// A parameter is one or more paths set to the same value, with bounds, optionally searched in log10:
//   material.pool_c.c_R=2:6
//   material.pool_c.c_R,material.aquifer_pool_c.c_R=2:6      (Pool C and its connected aquifer)
//   material.aquifer_pool_c.K_m_per_s[0],material.aquifer_pool_c.K_m_per_s[1]=1e-8:1e-6:log
// A modified copy keeps the case's text (comments, order, formatting): only the values change, and
// file names relative to the case (schedules, ...) become absolute so the copy works anywhere.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "ugs/formats/case_file.hpp"

namespace ugs::runner {

struct ParameterSpec {
  std::string name;                 // the paths as written, for tables and messages
  std::vector<std::string> paths;   // case-file paths set to the same value
  double lower = 0, upper = 0;
  bool log_scale = false;
};

// InputError at "parameter to calibrate TEXT" when malformed: no '=', bad numbers, lower >= upper (bounds reversed), log scale
// with a non-positive bound.
ParameterSpec parse_parameter(const std::string& text);

class CaseTemplate {
public:
  explicit CaseTemplate(const std::string& case_path);  // InputError if it does not parse as TOML
  const std::string& path() const { return path_; }
  const std::string& text() const { return text_; }

  // The number at `path`; InputError("case.toml", "no parameter ...") when the path does not exist
  // in this case or is not a number.
  double value(const std::string& path) const;
  // The case text with each path set to its value (shortest round-trip decimal) and relative file
  // names made absolute.
  std::string render(const std::vector<std::pair<std::string, double>>& values) const;
  // The files the case names (strings that are existing files, relative to the case's folder or
  // absolute): absolute, sorted, unique. Their content decides a run as much as the case text.
  std::vector<std::string> referenced_files() const;

private:
  std::string path_, text_;
};

// The checks every tool that varies case parameters makes before running anything (ugs-calibrate,
// ugs-ensemble): each path is a number in the case, no path is named twice, and the case stays
// valid (ugs::read_case_file) at each parameter's lower and upper value, rendered to a temporary
// file that is always removed. Errors are InputErrors at `source` ("" = "parameter to calibrate <name>"), the
// case's own message quoted. Returns warnings for the caller to print: a case value outside
// [lower, upper].
std::vector<std::string> check_parameters(const CaseTemplate& tmpl, const std::vector<ParameterSpec>& params, const std::string& source = "");

// The case with each path set to its value, read as ugs::read_case_file reads a case (through a
// copy in the system's temporary folder, always removed). InputError naming the case, not the
// copy, when the values make it invalid.
CaseFile read_rendered_case(const CaseTemplate& tmpl, const std::vector<std::pair<std::string, double>>& values);

// Shortest decimal that reads back to `v`, always a TOML float ("3.0", "2.5e-07").
std::string toml_float(double v);

}  // namespace ugs::runner
