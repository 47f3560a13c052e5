// The panels of a fault given as a surface (fault_cut.hpp; docs/faults.md, "Faults as surfaces"):
// its triangles, neighbours in one plane merged while their union stays convex (a planar surface
// is then cut as the trace's panels are, not along every diagonal of its triangulation), each
// panel bounded by planes through its border edges. Two panels sharing an edge are bounded by one
// plane through it (the bisector of their planes, as listric pieces share their horizontal lines),
// the one's bound the other's reversed, so that the cut puts mesh edges along the shared edge once;
// an edge on the surface's border (a tip line, or beyond the model) is bounded by the plane through
// it perpendicular to its triangle.
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include <fmt/format.h>

#include "cut_stages.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/meshing/fault_surface_input.hpp"
#include "ugs/meshing/surface_checks.hpp"
#include "ugs/meshing/vec3.hpp"

namespace ugs::fault_cut {

using namespace vec3;

namespace {

using Edge = std::pair<std::uint32_t, std::uint32_t>;
using Users = std::vector<std::pair<std::size_t, int>>;  // (triangle, edge k: corner k to k + 1)

struct Surface {
  const TriangulatedSurface& s;
  std::vector<Point3> n;                  // unit normals, oriented (surface_orientation)
  std::map<Edge, Users> edges;
  const Point3& X(std::uint32_t v) const { return s.vertices[v]; }
  Edge edge(std::size_t t, int k) const {
    const std::uint32_t a = s.triangles[t][k], b = s.triangles[t][(k + 1) % 3];
    return {std::min(a, b), std::max(a, b)};
  }
  // The outward direction in triangle t's plane across its edge k.
  Point3 outward(std::size_t t, int k) const {
    const auto& tri = s.triangles[t];
    const Point3 &a = X(tri[k]), &b = X(tri[(k + 1) % 3]), &c = X(tri[(k + 2) % 3]);
    Point3 o = unit(cross(sub(b, a), n[t]));
    if (dot(o, sub(c, a)) > 0) o = scaled(o, -1);
    return o;
  }
  double longest_edge(std::size_t t) const {
    double l = 0;
    for (int k = 0; k < 3; ++k) l = std::max(l, norm(sub(X(s.triangles[t][(k + 1) % 3]), X(s.triangles[t][k]))));
    return l;
  }
};

// The border edges of a set of triangles (sorted): edges whose other triangle is not in the set.
std::vector<std::pair<std::size_t, int>> border(const Surface& S, const std::vector<std::size_t>& members) {
  const std::set<std::size_t> in(members.begin(), members.end());
  std::vector<std::pair<std::size_t, int>> out;
  for (auto t : members)
    for (int k = 0; k < 3; ++k) {
      bool inner = false;
      for (const auto& [u, j] : S.edges.at(S.edge(t, k)))
        if (u != t && in.count(u)) inner = true;
      if (!inner) out.push_back({t, k});
    }
  return out;
}

// Is the union of coplanar triangles convex: every corner inside every border edge's half-plane?
bool convex(const Surface& S, const std::vector<std::size_t>& members) {
  double scale = 0;
  for (auto t : members) scale = std::max(scale, S.longest_edge(t));
  for (const auto& [t, k] : border(S, members)) {
    const Point3 o = S.outward(t, k);
    const Point3& a = S.X(S.s.triangles[t][k]);
    for (auto u : members)
      for (auto v : S.s.triangles[u])
        if (dot(o, sub(S.X(v), a)) > 1e-9 * scale) return false;
  }
  return true;
}

}  // namespace

std::vector<CutPanel> surface_panels(const FaultTrace& tr) {
  const TriangulatedSurface& s = tr.surface->mesh;
  Surface S{s, {}, {}};
  const double sign = surface_orientation(s);
  const std::size_t nt = s.triangles.size();
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = s.triangles[t];
    S.n.push_back(scaled(unit(cross(sub(S.X(tri[1]), S.X(tri[0])), sub(S.X(tri[2]), S.X(tri[0])))), sign));
    for (int k = 0; k < 3; ++k) S.edges[S.edge(t, k)].push_back({t, k});
  }
  // Coplanar neighbours merged (in edge order) while the union stays convex.
  std::vector<std::size_t> root(nt);
  std::iota(root.begin(), root.end(), std::size_t{0});
  std::vector<std::vector<std::size_t>> members(nt);
  for (std::size_t t = 0; t < nt; ++t) members[t] = {t};
  auto find = [&](std::size_t t) {
    while (root[t] != t) t = root[t] = root[root[t]];
    return t;
  };
  auto coplanar = [&](std::size_t t, std::size_t u) {
    if (dot(S.n[t], S.n[u]) < 1 - 1e-12) return false;
    const double tol = 1e-9 * std::max(S.longest_edge(t), S.longest_edge(u));
    for (auto v : s.triangles[u])
      if (std::abs(dot(S.n[t], sub(S.X(v), S.X(s.triangles[t][0])))) > tol) return false;
    return true;
  };
  for (const auto& [e, users] : S.edges) {
    if (users.size() != 2 || !coplanar(users[0].first, users[1].first)) continue;
    const std::size_t a = find(users[0].first), b = find(users[1].first);
    if (a == b) continue;
    std::vector<std::size_t> both = members[a];
    both.insert(both.end(), members[b].begin(), members[b].end());
    std::sort(both.begin(), both.end());
    if (!convex(S, both)) continue;
    const std::size_t keep = std::min(a, b), drop = std::max(a, b);
    root[drop] = keep;
    members[keep] = std::move(both);
    members[drop].clear();
  }
  // One panel per group, in the order of its first triangle; its plane is that triangle's.
  std::vector<CutPanel> out;
  std::vector<std::size_t> panel_of(nt);
  for (std::size_t t = 0; t < nt; ++t)
    if (find(t) == t) {
      CutPanel p;
      p.n = S.n[t];
      p.c = dot(p.n, S.X(s.triangles[t][0]));
      p.segment = out.size();
      for (auto u : members[t]) panel_of[u] = out.size();
      out.push_back(std::move(p));
    }
  // The bounds: one plane per border edge, shared (reversed) by the panel across it.
  for (std::size_t g = 0; g < nt; ++g) {
    if (find(g) != g) continue;
    for (const auto& [t, k] : border(S, members[g])) {
      const Edge e = S.edge(t, k);
      const auto& users = S.edges.at(e);
      const Point3& a = S.X(e.first);  // one point of the edge for both sides: the same plane bit for bit
      if (users.size() == 1) {
        const Point3 m = S.outward(t, k);
        out[panel_of[t]].bounds.push_back({m, dot(m, a)});
        continue;
      }
      // check_surface_topology leaves two users at most; the first one (in file order) makes the plane.
      const auto& [t0, k0] = users[0];
      const auto& [t1, k1] = users[1];
      const Point3 d = sub(S.outward(t0, k0), S.outward(t1, k1));
      if (!(norm(d) > 1e-6))
        throw at_triangle(s, t1,
                          fmt::format("fault '{}': the surface folds back onto itself across the edge from the {} to the {}",
                                      tr.name, vertex_at(s, e.first), vertex_at(s, e.second)));
      const Point3 m = unit(d);
      const double c = dot(m, a);
      if (t == t0) out[panel_of[t]].bounds.push_back({m, c});
      else out[panel_of[t]].bounds.push_back({scaled(m, -1), -c});
    }
  }
  return out;
}

}  // namespace ugs::fault_cut
