// Inputs shared by ugs-sample, ugs-calibrate and ugs-report: the model CRS (from --crs or the case
// file's crs) and the top surface (the mesh group, or the results file's own cells).
#pragma once
#include <string>
#include <vector>

#include "ugs/insar/surface.hpp"

namespace ugs::insar {

// WKT of the model CRS: `crs` if given, else the case's `crs` key, else "".
std::string model_crs(const std::string& crs, const std::string& case_path);

// From `mesh_path` (group `group`, e.g. "bnd:top") when given, else from the results file.
TopSurface load_top_surface(const std::string& mesh_path, const std::string& group, const std::string& results_path);

// A numeric option: InputError(option, "inf (expected a finite number >= 0)") unless finite and
// within [lo, hi] (lo excluded when `lo_open`).
void check_option(const std::string& option, double value, double lo, double hi, bool lo_open = false);

// "A/B/..." with exactly `count` finite numbers (no trailing text): InputError(option, "'text' is
// not FORMAT (finite numbers)") otherwise.
std::vector<double> parse_number_list(const std::string& option, const std::string& text, std::size_t count,
                                      const std::string& format);

}  // namespace ugs::insar
