#include "ugs/insar/inputs.hpp"

#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"
#include "ugs/formats/toml_reader.hpp"
#include "ugs/insar/crs.hpp"

namespace ugs::insar {

std::string model_crs(const std::string& crs, const std::string& case_path) {
  if (!crs.empty()) return any_crs_wkt(crs, "--crs");
  if (case_path.empty()) return "";
  const TomlTable t = TomlTable::parse_file(case_path);
  if (auto c = t.string_opt("crs")) return any_crs_wkt(*c, t.where("crs"));
  return "";
}

TopSurface load_top_surface(const std::string& mesh_path, const std::string& group, const std::string& results_path) {
  if (!mesh_path.empty()) {
    const Mesh mesh = read_msh(mesh_path);
    return surface_from_mesh(mesh, group, mesh_path);
  }
  const FieldSeriesReader r(results_path);
  return surface_from_results(r);
}

}  // namespace ugs::insar
