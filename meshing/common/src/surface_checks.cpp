// Checks of triangulated surfaces (surface_checks.hpp): topology by an edge map, self-intersections
// by CGAL Polygon Mesh Processing.
#include "ugs/meshing/surface_checks.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <numeric>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <fmt/format.h>

namespace ugs {

namespace {

struct Dsu {
  std::vector<std::uint32_t> p;
  explicit Dsu(std::size_t n) : p(n) { std::iota(p.begin(), p.end(), 0u); }
  std::uint32_t find(std::uint32_t a) {
    while (p[a] != a) a = p[a] = p[p[a]];
    return a;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) p[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace

std::string vertex_at(const TriangulatedSurface& s, std::uint32_t v) {
  const auto& p = s.vertices[v];
  return fmt::format("vertex of line {} ({:.2f}, {:.2f}, {:.2f})", s.vertex_line[v], p[0], p[1], p[2]);
}

InputError at_triangle(const TriangulatedSurface& s, std::size_t t, const std::string& what) {
  return InputError(fmt::format("{}:{}", s.path, s.triangle_line[t]), what);
}

void check_surface_topology(const TriangulatedSurface& s) {
  const std::size_t nt = s.triangles.size(), nv = s.vertices.size();
  // Edges: each undirected edge and the triangles using it, with the direction they run it.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::pair<std::uint32_t, bool>>> edges;
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = s.triangles[t][k], b = s.triangles[t][(k + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}].push_back({static_cast<std::uint32_t>(t), a < b});
    }
  Dsu corners(3 * nt);
  auto corner = [&](std::uint32_t t, std::uint32_t v) {
    for (std::uint32_t k = 0; k < 3; ++k)
      if (s.triangles[t][k] == v) return 3 * t + k;
    return 3 * t;
  };
  for (const auto& [e, users] : edges) {
    if (users.size() > 2)
      throw at_triangle(s, users[2].first,
                        fmt::format("non-manifold edge: the edge from the {} to the {} is shared by {} triangles (lines "
                                    "{}, {}, {}{}); a surface's edge borders at most two",
                                    vertex_at(s, e.first), vertex_at(s, e.second), users.size(),
                                    s.triangle_line[users[0].first], s.triangle_line[users[1].first],
                                    s.triangle_line[users[2].first], users.size() > 3 ? ", ..." : ""));
    if (users.size() == 2) {
      if (users[0].second == users[1].second)
        throw at_triangle(s, users[1].first,
                          fmt::format("inconsistent orientation: this triangle and its neighbour of line {} run their "
                                      "shared edge ({} to {}) the same way (expected opposite ways: renumber one "
                                      "triangle's corners, or re-orient the surface in the exporting package)",
                                      s.triangle_line[users[0].first], vertex_at(s, e.first), vertex_at(s, e.second)));
      for (auto v : {e.first, e.second}) corners.unite(corner(users[0].first, v), corner(users[1].first, v));
    }
  }
  // A vertex where two fans of triangles meet only at the vertex.
  std::vector<std::uint32_t> root(nv, std::numeric_limits<std::uint32_t>::max());
  for (std::uint32_t t = 0; t < nt; ++t)
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t v = s.triangles[t][k], r = corners.find(3 * t + k);
      if (root[v] == std::numeric_limits<std::uint32_t>::max()) root[v] = r;
      else if (root[v] != r)
        throw at_triangle(s, t,
                          fmt::format("non-manifold vertex: the {} joins triangles that share no edge around it (two "
                                      "sheets touching at one point)",
                                      vertex_at(s, v)));
    }
}

void check_surface_self_intersections(const TriangulatedSurface& s) {
  const std::size_t nt = s.triangles.size(), nv = s.vertices.size();
  // Self-intersections (CGAL PMP on the mesh the checks above make possible).
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<K::Point_3>;
  Mesh m;
  std::vector<Mesh::Vertex_index> vi(nv);
  for (std::size_t v = 0; v < nv; ++v)
    vi[v] = m.add_vertex(K::Point_3(s.vertices[v][0], s.vertices[v][1], s.vertices[v][2]));
  std::vector<std::size_t> face_triangle;
  for (std::size_t t = 0; t < nt; ++t) {
    const auto f = m.add_face(vi[s.triangles[t][0]], vi[s.triangles[t][1]], vi[s.triangles[t][2]]);
    if (f == Mesh::null_face())
      throw at_triangle(s, t, "the triangle cannot join the surface made by the ones before it (non-manifold)");
    face_triangle.push_back(t);
  }
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> hits;
  CGAL::Polygon_mesh_processing::self_intersections(m, std::back_inserter(hits));
  if (!hits.empty()) {
    std::size_t a = face_triangle[hits[0].first], b = face_triangle[hits[0].second];
    for (const auto& [f, g] : hits) {  // the first pair in file order, whatever CGAL's order
      std::size_t p = face_triangle[f], q = face_triangle[g];
      if (p > q) std::swap(p, q);
      if (std::min(a, b) > p || (std::min(a, b) == p && std::max(a, b) > q)) a = p, b = q;
    }
    if (a > b) std::swap(a, b);
    throw at_triangle(s, b,
                      fmt::format("self-intersection: the triangle crosses the one of line {} ({} pair(s) of triangles "
                                  "intersect)",
                                  s.triangle_line[a], hits.size()));
  }
}

}  // namespace ugs
