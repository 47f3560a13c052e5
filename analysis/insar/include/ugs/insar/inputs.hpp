// Inputs shared by ugs-sample, ugs-calibrate, ugs-ensemble and ugs-report: the model CRS (given,
// or the case file's crs), the top surface (the mesh group, or the results file's own
// cells), PS points in the model CRS and the polygons that choose them (a reservoir trace).
#pragma once
#include <string>
#include <vector>

#include "ugs/insar/ps_data.hpp"
#include "ugs/insar/surface.hpp"
#include "ugs/meshing/geodata.hpp"

namespace ugs::insar {

// WKT of the model CRS: `crs` if given (InputError at "model CRS" if unknown), else the case's `crs`
// key, else "". Messages name the settings in words (model CRS, points CRS, polygon filter, mesh of
// the top surface); each tool maps them to its flags (cli::Tool::name_setting).
std::string model_crs(const std::string& crs, const std::string& case_path);

// From `mesh_path` (group `group`, e.g. "bnd:top") when given, else from the results file.
TopSurface load_top_surface(const std::string& mesh_path, const std::string& group, const std::string& results_path);

// The polygons of any OGR file (in the model CRS, `where` an attribute filter); InputError "has no
// polygon: ... none kept by the polygon filter" when there is none.
geo::PolygonSet read_polygons(const std::string& path, const std::string& model_crs, const std::string& where);

// read_ps, refusing points that declare a CRS when the model CRS (options.model_crs) is unknown.
PsData read_ps_in_model(const std::string& path, const PsReadOptions& options);

// "A/B/..." with exactly `count` finite numbers (no trailing text): InputError(option, "'text' is
// not FORMAT (finite numbers)") otherwise.
std::vector<double> parse_number_list(const std::string& option, const std::string& text, std::size_t count,
                                      const std::string& format);

}  // namespace ugs::insar
