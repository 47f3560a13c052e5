// Small models for the InSAR tests: a box mesh with a gently undulating top surface, analytical
// displacement fields written as results files, and PS files in the EGMS layout.
#pragma once
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/mesh.hpp"
#include "ugs/meshing/box_mesh.hpp"

namespace ugs::test {

// Box [x0, x0+lx] x [y0, y0+ly] x [-depth, 0] with the top raised by up to `bump` metres
// (the perturbation fades with depth, so tetrahedra stay positive).
inline Mesh undulating_box(double x0, double y0, double lx, double ly, double depth, int nx, int ny, int nz, double bump) {
  BoxMeshSpec spec;
  spec.x = linspace(x0, x0 + lx, nx);
  spec.y = linspace(y0, y0 + ly, ny);
  spec.z = linspace(-depth, 0, nz);
  Mesh m = make_box_mesh(spec);
  for (auto& p : m.nodes) {
    const double f = (p[2] + depth) / depth;
    p[2] += f * bump * std::sin((p[0] - x0) / lx * 3.1) * std::cos((p[1] - y0) / ly * 2.3);
  }
  return m;
}

// A linear field u = a + B x (m).
struct LinearField {
  double a[3];
  double B[3][3];
  std::array<double, 3> at(const Point3& x) const {
    std::array<double, 3> u{};
    for (int i = 0; i < 3; ++i) u[i] = a[i] + B[i][0] * x[0] + B[i][1] * x[1] + B[i][2] * x[2];
    return u;
  }
  Field field(const Mesh& m, const std::string& name = "u") const {
    Field f{name, 3, {}};
    for (const auto& p : m.nodes)
      for (double v : at(p)) f.values.push_back(v);
    return f;
  }
};

}  // namespace ugs::test
