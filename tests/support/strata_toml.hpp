// ugs-meshgen strata files (the layered meshes' input) for tests, composed like case files
// (case_toml.hpp): a head (crs, min_thickness, faults lines as written), then [[surface]], [[unit]]
// and [[material]] sections in the order added. Surface elevations are written as TOML floats.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "case_toml.hpp"

namespace ugs::testcase {

// A surface from a constant elevation [m], a raster or picks (one of them), maybe an unconformity.
struct Surface {
  std::string name{};
  std::optional<double> constant{};
  std::string raster{}, picks{};
  bool unconformity = false;
};

struct Unit {
  std::string name{};
  int layers = 1;
  std::optional<double> bias{};
};

// A material of some units, inside a polygon file's features (an attribute filter) or everywhere.
struct UnitMaterial {
  std::string name{};
  std::vector<std::string> units{};
  std::string polygon{}, where{};
};

class StrataToml : public TomlSections {
 public:
  explicit StrataToml(std::string head, Layout layout = Layout::Spaced) : TomlSections(std::move(head), Numbers::Decimal, layout) {}
  StrataToml& surface(const Surface& s);
  StrataToml& unit(const Unit& u);
  StrataToml& material(const UnitMaterial& m);
};

}  // namespace ugs::testcase
