// Case-file pieces that library-level tests build in code, as read_case_file would from a
// [[material]] or [[fault]] table: every field not named keeps the reader's default.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ugs/formats/case_file.hpp"
#include "ugs/formats/mesh.hpp"

namespace ugs::test {

// An isotropic linear-elastic [[material]] (E in Pa).
inline MaterialSpec linear_material(const std::string& name, const std::string& where, double E_Pa, double nu) {
  MaterialSpec m;
  m.name = name;
  m.where = where;
  m.law = MaterialLaw::Linear;
  m.E_Pa = E_Pa;
  m.nu_z = nu;
  return m;
}

// A hypo-plastic [[material]] with the thesis' anisotropy (Table 4.3: nu_z 0.3, E_h/E_z 3,
// nu_h/nu_z 0.2) and c_R 3.
inline MaterialSpec hypoplastic_material(const std::string& name, const std::string& where) {
  MaterialSpec m;
  m.name = name;
  m.where = where;
  m.law = MaterialLaw::Hypoplastic;
  m.nu_z = 0.3;
  m.Eh_over_Ez = 3.0;
  m.nuh_over_nuz = 0.2;
  m.c_R = 3.0;
  return m;
}

// A [[fault]] with its Mohr-Coulomb strength.
inline FaultSpec fault_spec(const std::string& name, const std::string& where, double cohesion_Pa, double friction_deg) {
  FaultSpec f;
  f.name = name;
  f.where = where;
  f.cohesion_Pa = cohesion_Pa;
  f.friction_deg = friction_deg;
  return f;
}

// For each node of `faulted`, the index of the node of `plain` at the same position: a fault's
// twin nodes map to the node they were copied from.
inline std::vector<std::uint32_t> original_nodes(const Mesh& faulted, const Mesh& plain) {
  std::map<Point3, std::uint32_t> at;
  for (std::uint32_t i = 0; i < plain.num_nodes(); ++i) at[plain.nodes[i]] = i;
  std::vector<std::uint32_t> o(faulted.num_nodes());
  for (std::uint32_t i = 0; i < faulted.num_nodes(); ++i) o[i] = at.at(faulted.nodes[i]);
  return o;
}

}  // namespace ugs::test
