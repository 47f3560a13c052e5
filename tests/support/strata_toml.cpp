#include "strata_toml.hpp"

namespace ugs::testcase {

StrataToml& StrataToml::surface(const Surface& s) {
  section("[[surface]]");
  add("name = \"" + s.name + "\"\n");
  if (s.constant) add("constant = " + number(*s.constant) + "\n");
  if (!s.raster.empty()) add("raster = \"" + s.raster + "\"\n");
  if (!s.picks.empty()) add("picks = \"" + s.picks + "\"\n");
  if (s.unconformity) add("unconformity = true\n");
  return *this;
}

StrataToml& StrataToml::unit(const Unit& u) {
  section("[[unit]]");
  add("name = \"" + u.name + "\"\nlayers = " + std::to_string(u.layers) + "\n");
  if (u.bias) add("bias = " + number(*u.bias) + "\n");
  return *this;
}

StrataToml& StrataToml::material(const UnitMaterial& m) {
  section("[[material]]");
  add("name = \"" + m.name + "\"\nunits = " + string_list(m.units) + "\n");
  if (!m.polygon.empty()) add("polygon = \"" + m.polygon + "\"\n");
  if (!m.where.empty()) add("where = \"" + m.where + "\"\n");
  return *this;
}

}  // namespace ugs::testcase
