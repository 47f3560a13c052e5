#include "ugs/insar/inputs.hpp"

#include <charconv>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/formats/toml_reader.hpp"
#include "ugs/insar/crs.hpp"

namespace ugs::insar {

std::string model_crs(const std::string& crs, const std::string& case_path) {
  if (!crs.empty()) return any_crs_wkt(crs, "model CRS");
  if (case_path.empty()) return "";
  const TomlTable t = TomlTable::parse_file(case_path);
  if (auto c = t.string_opt("crs")) return any_crs_wkt(*c, t.where("crs"));
  return "";
}

std::vector<double> parse_number_list(const std::string& option, const std::string& text, std::size_t count,
                                      const std::string& format) {
  std::vector<double> out;
  std::string_view rest = text;
  bool ok = true;
  while (ok) {
    const auto slash = rest.find('/');
    std::string_view part = rest.substr(0, slash);
    const auto v = parse_finite_number(part);
    ok = v.has_value();
    out.push_back(v.value_or(0));
    if (slash == std::string_view::npos) break;
    rest.remove_prefix(slash + 1);
  }
  if (!ok || out.size() != count)
    throw InputError(option, fmt::format("'{}' is not {} (finite numbers)", text, format));
  return out;
}

TopSurface load_top_surface(const std::string& mesh_path, const std::string& group, const std::string& results_path) {
  if (!mesh_path.empty()) {
    const Mesh mesh = read_msh(mesh_path);
    return surface_from_mesh(mesh, group, mesh_path);
  }
  const FieldSeriesReader r(results_path);
  return surface_from_results(r);
}

geo::PolygonSet read_polygons(const std::string& path, const std::string& model_crs, const std::string& where) {
  const auto vec = geo::read_vector(path, model_crs, where);
  std::vector<geo::Polygon> polys;
  for (const auto& f : vec.features) polys.insert(polys.end(), f.polygons.begin(), f.polygons.end());
  if (polys.empty()) throw InputError(path, "has no polygon: none in the file, or none kept by the polygon filter");
  return geo::PolygonSet(polys);
}

PsData read_ps_in_model(const std::string& path, const PsReadOptions& options) {
  PsData d = read_ps(path, options);
  if (options.model_crs.empty() && !d.source_crs.empty())
    throw InputError(path, fmt::format("points are in {}, but the model CRS is unknown: give it, or a case with crs",
                                       crs_name(d.source_crs)));
  return d;
}

}  // namespace ugs::insar
