// Inputs shared by ugs-sample, ugs-calibrate and ugs-report: the model CRS (from --crs or the case
// file's crs) and the top surface (the mesh group, or the results file's own cells).
#pragma once
#include <string>

#include "ugs/insar/surface.hpp"

namespace ugs::insar {

// WKT of the model CRS: `crs` if given, else the case's `crs` key, else "".
std::string model_crs(const std::string& crs, const std::string& case_path);

// From `mesh_path` (group `group`, e.g. "bnd:top") when given, else from the results file.
TopSurface load_top_surface(const std::string& mesh_path, const std::string& group, const std::string& results_path);

}  // namespace ugs::insar
