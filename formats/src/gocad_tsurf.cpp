// GOCAD TSurf reader. Ids are per object (VRTX 1 in two objects are two vertices); ATOM and PATOM
// name an earlier vertex of the same object. Header blocks ({ ... }) and coordinate-system blocks
// are read for ZPOSITIVE and AXIS_UNIT only.
#include "ugs/formats/gocad_tsurf.hpp"

#include <map>
#include <unordered_map>

#include <fmt/format.h>

#include "text_lines.hpp"

namespace ugs {

namespace {

constexpr long long max_id = 4'000'000'000LL;

struct ArrayHash {
  std::size_t operator()(const std::array<double, 3>& a) const {
    std::size_t h = 0;
    for (double v : a) h = h * 1000003u ^ std::hash<double>()(v == 0 ? 0.0 : v);
    return h;
  }
};

}  // namespace

TriangulatedSurface read_gocad_tsurf(const std::string& path) {
  text::Lines in(path, "a GOCAD TSurf file");
  TriangulatedSurface s;
  s.path = in.name();

  bool in_object = false, in_face = false, in_crs = false;
  int brace_depth = 0;
  double zsign = 1;
  std::map<long long, std::uint32_t> ids;  // this object's vertex ids
  std::unordered_map<std::array<double, 3>, std::uint32_t, ArrayHash> at;
  std::size_t object_line = 0;
  auto vertex_of = [&](std::string_view t, const char* what) {
    const long long id = text::integer(in, t, what, 0, max_id);
    const auto it = ids.find(id);
    if (it == ids.end()) throw in.error(fmt::format("{} {} names no vertex of this TSurf (no VRTX {} before)", what, id, id));
    return it->second;
  };
  while (in.next()) {
    const auto& t = in.tokens();
    if (t.empty() || t[0].starts_with("#")) continue;
    const std::string_view key = t[0];
    if (brace_depth > 0) {  // inside a HEADER { ... } or another brace block: only its closing brace counts
      for (char c : in.text()) brace_depth += c == '{' ? 1 : c == '}' ? -1 : 0;
      brace_depth = std::max(brace_depth, 0);
      continue;
    }
    if (!in_object) {
      if (key != "GOCAD")
        throw in.error(fmt::format("'{}' outside a TSurf object (expected GOCAD TSurf 1)", text::shown(key)));
      if (t.size() < 2 || t[1] != "TSurf")
        throw in.error(fmt::format("a GOCAD {} object, not a TSurf (expected GOCAD TSurf 1)",
                                   t.size() < 2 ? std::string("") : text::shown(t[1])));
      in_object = true;
      in_face = false;
      zsign = 1;
      ids.clear();
      object_line = in.line();
      ++s.objects;
      continue;
    }
    if (in_crs) {
      if (key == "END_ORIGINAL_COORDINATE_SYSTEM") {
        in_crs = false;
      } else if (key == "ZPOSITIVE") {
        if (t.size() != 2 || (t[1] != "Elevation" && t[1] != "Depth"))
          throw in.error("ZPOSITIVE must be Elevation or Depth");
        zsign = t[1] == "Depth" ? -1 : 1;
      } else if (key == "AXIS_UNIT") {
        for (std::size_t k = 1; k < t.size(); ++k)
          if (t[k] != "\"m\"" && t[k] != "m")
            throw in.error(fmt::format("AXIS_UNIT {}: ugs reads coordinates in metres (export the surface in metres)",
                                       text::shown(t[k])));
      }
      continue;
    }
    if (key == "END") {
      in_object = false;
      continue;
    }
    if (key == "GOCAD_ORIGINAL_COORDINATE_SYSTEM") {
      in_crs = true;
      continue;
    }
    if (key == "TFACE") {
      in_face = true;
      ++s.faces;
      continue;
    }
    const bool vrtx = key == "VRTX" || key == "PVRTX", atom = key == "ATOM" || key == "PATOM";
    if (vrtx || atom || key == "TRGL") {
      if (!in_face) throw in.error(fmt::format("{} before the first TFACE", key));
      if (vrtx) {
        if (t.size() < 5) throw in.error(fmt::format("{} needs an id and x y z", key));
        const long long id = text::integer(in, t[1], fmt::format("{} id", key), 0, max_id);
        const std::array<double, 3> p{text::number(in, t[2], "x"), text::number(in, t[3], "y"),
                                      zsign * text::number(in, t[4], "z")};
        if (ids.count(id)) throw in.error(fmt::format("vertex id {} is given twice in this TSurf", id));
        auto [it, fresh] = at.emplace(p, static_cast<std::uint32_t>(s.vertices.size()));
        if (fresh) {
          if (s.vertices.size() >= 0xffffffffu) throw in.error("more than 4 billion vertices");
          s.vertices.push_back(p);
          s.vertex_line.push_back(in.line());
        } else {
          ++s.merged_vertices;
        }
        ids[id] = it->second;
      } else if (atom) {
        if (t.size() < 3) throw in.error(fmt::format("{} needs an id and the id of the vertex it repeats", key));
        const long long id = text::integer(in, t[1], fmt::format("{} id", key), 0, max_id);
        if (ids.count(id)) throw in.error(fmt::format("vertex id {} is given twice in this TSurf", id));
        ids[id] = vertex_of(t[2], key == "ATOM" ? "ATOM" : "PATOM");
      } else {
        if (t.size() != 4) throw in.error(fmt::format("TRGL needs 3 vertex ids, the line has {}", t.size() - 1));
        const std::array<std::uint32_t, 3> tri{vertex_of(t[1], "TRGL"), vertex_of(t[2], "TRGL"),
                                               vertex_of(t[3], "TRGL")};
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
          throw in.error(fmt::format("TRGL {} {} {} has two corners at one vertex or at one point (a degenerate triangle)",
                                     t[1], t[2], t[3]));
        s.triangles.push_back(tri);
        s.triangle_line.push_back(in.line());
      }
      continue;
    }
    if (key == "BSTONE" || key == "BORDER") continue;  // boundary markers: the triangles say it all
    if (in_face)
      throw in.error(fmt::format("unknown keyword '{}' inside a TFACE (expected VRTX, PVRTX, ATOM, PATOM, TRGL, BSTONE, "
                                 "BORDER, TFACE or END)",
                                 text::shown(key)));
    // The object's header: names, properties, display settings; brace blocks skipped whole.
    for (char c : in.text()) brace_depth += c == '{' ? 1 : c == '}' ? -1 : 0;
    brace_depth = std::max(brace_depth, 0);
  }
  const std::string end = fmt::format("{}:{}", in.name(), in.line());
  if (in_object)
    throw InputError(end, fmt::format("the TSurf object begun at line {} has no END (truncated file?)", object_line));
  if (s.objects == 0) throw InputError(end, "no GOCAD TSurf object (expected a line GOCAD TSurf 1)");
  if (s.triangles.empty()) throw InputError(end, "the TSurf has no triangle (no TRGL line)");
  s.depth_positive = zsign < 0;
  return s;
}

}  // namespace ugs
