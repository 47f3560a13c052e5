#include "ugs/insar/fault_results.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs::insar {

std::string fault_group_name(const Mesh* mesh, std::int32_t tag) {
  std::string name;
  if (mesh) {
    for (int dim : {3, 2})
      if (const PhysicalGroup* g = mesh->find_physical_tag(dim, tag); g && name.empty() && g->name.rfind("fault:", 0) == 0)
        name = g->name;
    for (int dim : {2, 3})
      if (const PhysicalGroup* g = mesh->find_physical_tag(dim, tag); g && name.empty()) name = g->name;
  }
  if (name.rfind("fault:", 0) == 0) name = name.substr(6);
  return name.empty() ? fmt::format("fault {}", tag) : name;
}

std::vector<FaultChi> read_fault_chi(const FieldSeriesReader& r, std::size_t step, const Mesh* mesh,
                                     const std::string& field) {
  const auto x = r.coordinates();
  const auto types = r.cell_types();
  const auto mats = r.materials();
  // Cells in output order: the fault cells are the triangles and the prisms.
  std::vector<std::array<std::uint32_t, 3>> tri;
  std::vector<std::size_t> row;   // output-order index of each fault cell
  std::size_t offset = 0;
  for (ElementType t : types) {
    const auto c = r.cells(t);
    const int npe = nodes_per_element(t);
    const std::size_t n = c.size() / npe;
    if (t == ElementType::Triangle || t == ElementType::Prism)
      for (std::size_t i = 0; i < n; ++i) {
        tri.push_back({c[i * npe], c[i * npe + 1], c[i * npe + 2]});
        row.push_back(offset + i);
      }
    offset += n;
  }
  if (tri.empty()) throw InputError(r.path(), "has no fault cells (triangles or interface prisms)");
  std::vector<double> chi(tri.size());
  const auto cell_names = r.cell_field_names(step);
  if (std::find(cell_names.begin(), cell_names.end(), field) != cell_names.end()) {
    const Field f = r.cell_field(step, field);
    for (std::size_t i = 0; i < tri.size(); ++i) chi[i] = f.values[row[i] * f.components];
  } else {
    const Field f = r.node_field(step, field);  // InputError naming the field when absent
    for (std::size_t i = 0; i < tri.size(); ++i) {
      double s = 0;
      for (auto n : tri[i]) s += f.values[std::size_t(n) * f.components];
      chi[i] = s / 3;
    }
  }
  std::map<std::int32_t, FaultChi> by_tag;
  for (std::size_t i = 0; i < tri.size(); ++i) {
    const std::int32_t tag = row[i] < mats.size() ? mats[row[i]] : 0;
    auto& f = by_tag[tag];
    if (f.name.empty()) f.name = fault_group_name(mesh, tag);
    f.triangles.push_back({x[tri[i][0]], x[tri[i][1]], x[tri[i][2]]});
    f.chi.push_back(chi[i]);
    if (std::isfinite(chi[i])) f.max_chi = std::max(f.max_chi, chi[i]);
  }
  std::vector<FaultChi> out;
  for (auto& [tag, f] : by_tag) {
    // Strike: the principal direction of the corners in plan.
    double mx = 0, my = 0, n = 0;
    for (const auto& t : f.triangles)
      for (const auto& p : t) mx += p[0], my += p[1], n += 1;
    mx /= n, my /= n;
    double sxx = 0, sxy = 0, syy = 0;
    for (const auto& t : f.triangles)
      for (const auto& p : t) {
        sxx += (p[0] - mx) * (p[0] - mx);
        sxy += (p[0] - mx) * (p[1] - my);
        syy += (p[1] - my) * (p[1] - my);
      }
    // Strike: horizontal and normal to the mean fault normal (area-weighted, triangles oriented
    // alike); the plan's principal direction only for a (nearly) horizontal fault, whose strike is
    // undefined — the corners' spread in plan would pick the dip direction of a short, wide fault.
    double nx = 0, ny = 0, nz = 0;
    for (const auto& t : f.triangles) {
      const double ax = t[1][0] - t[0][0], ay = t[1][1] - t[0][1], az = t[1][2] - t[0][2];
      const double bx = t[2][0] - t[0][0], by = t[2][1] - t[0][1], bz = t[2][2] - t[0][2];
      double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
      if (cx * nx + cy * ny + cz * nz < 0) cx = -cx, cy = -cy, cz = -cz;
      nx += cx, ny += cy, nz += cz;
    }
    const double nh = std::hypot(nx, ny), nn = std::sqrt(nx * nx + ny * ny + nz * nz);
    const double ang = nh > 1e-3 * nn ? std::atan2(nx, -ny) : 0.5 * std::atan2(2 * sxy, sxx - syy);
    double ux = std::cos(ang), uy = std::sin(ang);
    if (ux < 0 || (ux == 0 && uy < 0)) ux = -ux, uy = -uy;  // s grows eastwards
    double smin = 1e300;
    for (const auto& t : f.triangles)
      for (const auto& p : t) smin = std::min(smin, (p[0] - mx) * ux + (p[1] - my) * uy);
    for (const auto& t : f.triangles) {
      std::array<double, 6> q{};
      for (int k = 0; k < 3; ++k) {
        q[2 * k] = (t[k][0] - mx) * ux + (t[k][1] - my) * uy - smin;
        q[2 * k + 1] = t[k][2];
      }
      f.sz.push_back(q);
    }
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace ugs::insar
