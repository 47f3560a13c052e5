#include "ugs/meshing/box_mesh.hpp"

#include <cmath>
#include <map>
#include <stdexcept>

namespace ugs {

std::vector<double> linspace(double lo, double hi, int n) {
  if (n < 1) throw std::invalid_argument("linspace: need at least one interval");
  std::vector<double> v(n + 1);
  for (int i = 0; i <= n; ++i) v[i] = lo + (hi - lo) * i / n;
  v[n] = hi;
  return v;
}

std::vector<double> graded(double lo, double hi, double first, double ratio) {
  if (!(first > 0) || !(ratio >= 1) || !(hi > lo)) throw std::invalid_argument("graded: bad spacing");
  std::vector<double> v{lo};
  double h = first;
  while (v.back() + h < hi - 0.5 * h) {
    v.push_back(v.back() + h);
    h *= ratio;
  }
  v.push_back(hi);
  return v;
}

Mesh make_box_mesh(const BoxMeshSpec& s) {
  const int nx = static_cast<int>(s.x.size()) - 1, ny = static_cast<int>(s.y.size()) - 1,
            nz = static_cast<int>(s.z.size()) - 1;
  if (nx < 1 || ny < 1 || nz < 1) throw std::invalid_argument("box mesh: each axis needs two coordinates");
  Mesh m;
  m.nodes.reserve(static_cast<std::size_t>(nx + 1) * (ny + 1) * (nz + 1));
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) m.add_node({s.x[i], s.y[j], s.z[k]});
  auto id = [&](int i, int j, int k) { return static_cast<std::uint32_t>(i + (nx + 1) * (j + (ny + 1) * k)); };

  auto block_of = [&](const std::string& name) -> ElementBlock& {
    // Blocks are re-looked-up: Mesh::block may reallocate the vector of blocks.
    const int e = m.entity_for_physical(3, "mat:" + name);
    return m.block(3, e, ElementType::Tetrahedron);
  };
  // Kuhn split: the six paths from corner (0,0,0) to (1,1,1) of a cell along the axes.
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const Point3 c{0.5 * (s.x[i] + s.x[i + 1]), 0.5 * (s.y[j] + s.y[j + 1]), 0.5 * (s.z[k] + s.z[k + 1])};
        const std::string name = s.material ? s.material(c) : std::string("rock");
        ElementBlock& b = block_of(name);
        for (const auto& p : perms) {
          int o[3] = {0, 0, 0};
          std::uint32_t n[4];
          n[0] = id(i, j, k);
          for (int st = 0; st < 3; ++st) {
            o[p[st]] = 1;
            n[st + 1] = id(i + o[0], j + o[1], k + o[2]);
          }
          if (tet_signed_volume(m.nodes[n[0]], m.nodes[n[1]], m.nodes[n[2]], m.nodes[n[3]]) < 0) std::swap(n[2], n[3]);
          m.add_element(b, n);
        }
      }

  // Boundary triangles: each boundary quad split along the diagonal the Kuhn tetrahedra use
  // (from the corner with the smaller index sum to the larger), outward normals.
  auto quad = [&](const std::string& side, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    // a-b-c-d counter-clockwise seen from outside; the diagonal a-c joins the (0,0)-(1,1) corners.
    const int e = m.entity_for_physical(2, "bnd:" + side);
    ElementBlock& t = m.block(2, e, ElementType::Triangle);
    const std::uint32_t t1[3] = {a, b, c}, t2[3] = {a, c, d};
    m.add_element(t, t1);
    m.add_element(t, t2);
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j) {
      quad("west", id(0, j, k), id(0, j, k + 1), id(0, j + 1, k + 1), id(0, j + 1, k));
      quad("east", id(nx, j, k), id(nx, j + 1, k), id(nx, j + 1, k + 1), id(nx, j, k + 1));
    }
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      quad("south", id(i, 0, k), id(i + 1, 0, k), id(i + 1, 0, k + 1), id(i, 0, k + 1));
      quad("north", id(i, ny, k), id(i, ny, k + 1), id(i + 1, ny, k + 1), id(i + 1, ny, k));
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      quad("bottom", id(i, j, 0), id(i, j + 1, 0), id(i + 1, j + 1, 0), id(i + 1, j, 0));
      quad("top", id(i, j, nz), id(i + 1, j, nz), id(i + 1, j + 1, nz), id(i, j + 1, nz));
    }
  m.update_entity_bboxes();
  return m;
}

}  // namespace ugs
