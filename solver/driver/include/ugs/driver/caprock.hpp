// Caprock integrity (docs/caprock.md): every element of a [[seal]] material is checked at every
// step against hydraulic fracturing (its tensile margin, fracture pressure S3 + T0 against the pore
// pressure) and against shear failure of the intact rock (Mohr-Coulomb with the seal's cohesion and
// friction), from the solver's stress and the pressure history. Rank 0 only.
//
// The pore pressure of a seal element is the highest of its nodes' (p0 + dp): where a seal sits on
// a pool, the pool's pressure pushes on the seal's base, and a tight seal's own pore pressure lags
// behind it for years. Taking the highest is conservative for both checks.
#pragma once
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "ugs/fem/rock_integrity.hpp"
#include "ugs/formats/case_file.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/mesh.hpp"
#include "ugs/mechanics/model.hpp"

namespace ugs::driver {

// The worst seal element of a step for each criterion.
struct CaprockWorst {
  double margin_Pa = std::numeric_limits<double>::infinity();
  std::string material;
  Point3 at{};
  double pore_pressure_Pa = 0;  // there
};

struct CaprockStep {
  // Per seal element, in the order of CaprockCheck::seal_mesh()'s cells (Pa).
  std::vector<double> pore_pressure, fracture_pressure, tensile_margin, shear_margin;
  CaprockWorst tensile, shear;                                 // over every seal
  std::vector<CaprockWorst> tensile_by_seal, shear_by_seal;    // per [[seal]], in case order
  bool tensile_failure() const { return tensile.margin_Pa <= 0; }
  bool shear_failure() const { return shear.margin_Pa <= 0; }
};

class CaprockCheck {
public:
  // From the global model (rank 0, before its arrays are released) and the case's [[seal]] entries;
  // empty when the case has none. InputError (at the [[seal]] line) for a seal material without
  // elements in the mesh.
  CaprockCheck(const mech::Model& model, const Mesh& mesh, const CaseFile& cs);
  bool empty() const { return cells_.empty(); }
  std::size_t size() const { return cells_.size(); }

  // `effective_stress`: the solver's stress field of every cell (6 per cell, output order and
  // Voigt order, Pa); `cell_dp`, `node_dp`: the step's pressure change per cell and per node.
  CaprockStep evaluate(const std::vector<double>& effective_stress, const std::vector<double>& cell_dp,
                       const std::vector<double>& node_dp) const;

  // The seal elements as a mesh of their own (mat:<name> groups), for the fields file.
  const Mesh& seal_mesh() const { return mesh_; }
  const std::vector<SealSpec>& seals() const { return seals_; }

private:
  struct Cell {
    std::uint32_t index;                  // output index of the tetrahedron
    std::array<std::uint32_t, 4> nodes;   // global node indices
    std::array<double, 4> node_p0;        // initial pore pressure at the nodes
    double p0;                            // and at the centroid (the solver's effective stress uses it)
    double biot;
    int seal;                             // index into seals_
    Point3 centroid;
  };
  std::vector<Cell> cells_;
  std::vector<SealSpec> seals_;
  Mesh mesh_;
};

// The outputs of the check: per step a CSV row per seal material (the worst element of each
// criterion), and at the output dates the fields over the seal elements (HDF5 + XDMF).
class CaprockOutput {
public:
  // `fields` or `table` empty: that output is off.
  CaprockOutput(const std::string& fields, const std::string& table, const CaprockCheck& check,
                const std::vector<std::string>& comments);
  void add(const std::string& date, double time, const CaprockStep& step, bool write_fields);
  void commit();

private:
  std::unique_ptr<FieldSeriesWriter> fields_;
  std::unique_ptr<CsvWriter> table_;
};

}  // namespace ugs::driver
