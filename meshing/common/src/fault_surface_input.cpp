// Fault surfaces from files (fault_surface_input.hpp): TSurf or sticks, checked.
#include "ugs/meshing/fault_surface_input.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/formats/io.hpp"
#include "ugs/meshing/surface_checks.hpp"
#include "ugs/meshing/vec3.hpp"

namespace ugs {

using namespace vec3;

namespace {

// The first word of the file (past blank lines and '#' comments).
std::string first_word(const std::string& path) {
  auto in = InputStream::open(path, "a fault surface (GOCAD TSurf or fault sticks)");
  std::string line;
  while (in->getline(line)) {
    const auto b = line.find_first_not_of(" \t\r");
    if (b == std::string::npos || line[b] == '#') continue;
    const auto e = line.find_first_of(" \t\r", b);
    return line.substr(b, e == std::string::npos ? std::string::npos : e - b);
  }
  return "";
}

Point3 area_normal(const TriangulatedSurface& s, std::size_t t) {
  const auto& tri = s.triangles[t];
  return cross(sub(s.vertices[tri[1]], s.vertices[tri[0]]), sub(s.vertices[tri[2]], s.vertices[tri[0]]));
}

}  // namespace

void check_fault_surface(const TriangulatedSurface& s) {
  check_surface_topology(s);
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const auto& tri = s.triangles[t];
    double l2 = 0;
    for (int k = 0; k < 3; ++k) {
      const Point3 e = sub(s.vertices[tri[(k + 1) % 3]], s.vertices[tri[k]]);
      l2 = std::max(l2, dot(e, e));
    }
    if (!(norm(area_normal(s, t)) > 1e-12 * l2))
      throw at_triangle(s, t, "the triangle has no area (its corners are on one line): the fault's normal is undefined there");
  }
  check_surface_self_intersections(s);
}

double surface_orientation(const TriangulatedSurface& s) {
  Point3 sum{0, 0, 0};
  for (std::size_t t = 0; t < s.triangles.size(); ++t) sum = add(sum, area_normal(s, t));
  const double n = norm(sum);
  if (std::abs(sum[2]) > 1e-9 * n) return sum[2] < 0 ? 1.0 : -1.0;
  if (std::abs(sum[1]) > 1e-9 * n) return sum[1] < 0 ? 1.0 : -1.0;
  return sum[0] <= 0 ? 1.0 : -1.0;
}

Point3 surface_reference_normal(const TriangulatedSurface& s) {
  Point3 sum{0, 0, 0};
  for (std::size_t t = 0; t < s.triangles.size(); ++t) sum = add(sum, area_normal(s, t));
  return scaled(unit(sum), surface_orientation(s));
}

FaultSurfaceInput sticks_surface(const FaultSticks& in) {
  FaultSurfaceInput out;
  out.format = "fault sticks";
  auto& s = out.mesh;
  s.path = in.path;
  s.objects = 1;
  s.faces = 1;
  std::map<Point3, std::uint32_t> at;  // merged points
  std::size_t merged = 0;
  // Each stick's vertices, oriented like the one before (the first one downward).
  std::vector<std::vector<std::uint32_t>> ids;
  std::vector<std::vector<double>> frac;  // fraction of the stick's length at each point
  Point3 before{0, 0, -1};
  for (const auto& st : in.sticks) {
    std::vector<std::size_t> order(st.points.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    const Point3 dir = sub(st.points.back(), st.points.front());
    if (dot(dir, before) < 0) std::reverse(order.begin(), order.end());
    before = dot(dir, before) < 0 ? scaled(dir, -1) : dir;
    std::vector<std::uint32_t> v;
    std::vector<double> f{0};
    for (std::size_t k = 0; k < order.size(); ++k) {
      const auto& p = st.points[order[k]];
      auto [it, fresh] = at.emplace(p, static_cast<std::uint32_t>(s.vertices.size()));
      if (fresh) {
        s.vertices.push_back(p);
        s.vertex_line.push_back(st.lines[order[k]]);
      } else {
        ++merged;
      }
      v.push_back(it->second);
      if (k > 0) f.push_back(f.back() + norm(sub(p, st.points[order[k - 1]])));
    }
    for (auto& x : f) x /= f.back();
    ids.push_back(std::move(v));
    frac.push_back(std::move(f));
  }
  if (merged)
    out.cleaned.push_back(fmt::format("{}: {} stick point(s) at the same x, y, z as a point of an earlier stick merged into it",
                                      in.path, merged));
  // Strips between consecutive sticks A (i) and B (j): triangles (A_i, A_i+1, B_j) or (A_i, B_j+1, B_j).
  Point3 strip_before{0, 0, 0};
  for (std::size_t k = 0; k + 1 < ids.size(); ++k) {
    const auto &A = ids[k], &B = ids[k + 1];
    const auto &fa = frac[k], &fb = frac[k + 1];
    const std::size_t first = s.triangles.size();
    std::size_t i = 0, j = 0;
    while (i + 1 < A.size() || j + 1 < B.size()) {
      const bool along_a = j + 1 >= B.size() || (i + 1 < A.size() && fa[i + 1] <= fb[j + 1]);
      std::array<std::uint32_t, 3> tri = along_a ? std::array{A[i], A[i + 1], B[j]} : std::array{A[i], B[j + 1], B[j]};
      if (along_a) ++i;
      else ++j;
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;  // at a point the sticks share
      s.triangles.push_back(tri);
      s.triangle_line.push_back(in.sticks[k + 1].lines.front());
    }
    // The strip's triangles face one way, and the same way as the strip before.
    Point3 sum{0, 0, 0};
    for (std::size_t t = first; t < s.triangles.size(); ++t) sum = add(sum, area_normal(s, t));
    auto cross_error = [&](const std::string& how) {
      return InputError(fmt::format("{}:{}", in.path, in.sticks[k + 1].lines.front()),
                        fmt::format("the stick beginning here crosses the stick of line {} ({}): sticks must follow "
                                    "each other along the fault without crossing",
                                    in.sticks[k].lines.front(), how));
    };
    for (std::size_t t = first; t < s.triangles.size(); ++t)
      if (dot(area_normal(s, t), sum) <= 0) throw cross_error("the surface between them folds back");
    if (k > 0 && dot(sum, strip_before) <= 0)
      throw cross_error("the surface doubles back against the one before");
    strip_before = sum;
  }
  if (s.triangles.empty()) throw InputError(in.path, "the sticks make no triangle");
  return out;
}

FaultSurfaceInput read_fault_surface(const std::string& path) {
  FaultSurfaceInput out;
  if (first_word(path) == "GOCAD") {
    out.mesh = read_gocad_tsurf(path);
    out.format = "GOCAD TSurf";
    if (out.mesh.merged_vertices)
      out.cleaned.push_back(fmt::format("{}: {} vertices at the same x, y, z as an earlier one merged into it", path,
                                        out.mesh.merged_vertices));
  } else {
    out = sticks_surface(read_fault_sticks(path));
  }
  check_fault_surface(out.mesh);
  return out;
}

}  // namespace ugs
