// The gmsh side of ugs-mesh2d: OpenCASCADE geometry (domain, regions, constraint lines made
// conformal by one boolean fragment), size fields (Distance + Threshold around refinements,
// Restrict inside refined regions, Min of all), 2D meshing, and conversion to ugs::Mesh.
#include "ugs/meshing/plan_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <unordered_map>

#include <gmsh.h>
#include <fmt/format.h>

#include "ugs/formats/error.hpp"

namespace ugs {

namespace {

using DimTags = gmsh::vectorpair;

class GmshSession {
public:
  explicit GmshSession(bool messages) {
    gmsh::initialize(0, nullptr, false);  // no user configuration files: same input, same mesh
    gmsh::option::setNumber("General.Terminal", messages ? 1 : 0);
    gmsh::option::setNumber("General.Verbosity", messages ? 4 : 0);
    gmsh::option::setNumber("General.NumThreads", 1);
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

std::vector<XY> clean_ring(const std::vector<XY>& r) {
  std::vector<XY> out;
  for (const auto& p : r)
    if (out.empty() || p != out.back()) out.push_back(p);
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  return out;
}

double signed_area(const std::vector<XY>& r) {
  double a = 0;
  for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) a += r[j][0] * r[i][1] - r[i][0] * r[j][1];
  return 0.5 * a;
}

struct Segment {
  XY a, b;
};

class PlanMesher {
public:
  explicit PlanMesher(const PlanSpec& s) : s_(s) {
    double xmin = std::numeric_limits<double>::infinity(), ymin = xmin;
    for (const auto& p : s.domain)
      for (const auto& q : p.outer) xmin = std::min(xmin, q[0]), ymin = std::min(ymin, q[1]);
    // A round local origin keeps OpenCASCADE's tolerances meaningful and the shift exact.
    x0_ = std::floor(xmin / 1000.0) * 1000.0;
    y0_ = std::floor(ymin / 1000.0) * 1000.0;
  }

  Mesh run(PlanMeshStats* stats) {
    build_geometry();
    fragment();
    set_sizes();
    gmsh::model::mesh::generate(2);
    check_region_areas();
    gmsh::model::mesh::renumberNodes();
    gmsh::model::mesh::renumberElements();
    Mesh m = extract();
    if (stats) {
      stats->nodes = m.num_nodes();
      stats->triangles = m.count(ElementType::Triangle);
      stats->line_elements = m.count(ElementType::Line);
      stats->min_size = min_size_;
    }
    return m;
  }

private:
  int point(const XY& p) { return gmsh::model::occ::addPoint(p[0] - x0_, p[1] - y0_, 0); }

  int surface(const geo::Polygon& poly) {
    std::vector<int> loops;
    bool outer_ccw = true;
    for (std::size_t k = 0; k <= poly.holes.size(); ++k) {
      auto ring = clean_ring(k == 0 ? poly.outer : poly.holes[k - 1]);
      if (ring.size() < 3) {
        if (k == 0) return -1;
        continue;
      }
      // Holes wound like their outer ring (gmsh turns hole loops itself): a hole wound against it (as
      // GEOS returns a clipped polygon) became an area added, not removed, and the boolean fragment
      // then made overlapping surfaces and lost the region.
      if (k == 0) outer_ccw = signed_area(ring) > 0;
      else if ((signed_area(ring) > 0) != outer_ccw) std::reverse(ring.begin(), ring.end());
      std::vector<int> pts, curves;
      for (const auto& p : ring) pts.push_back(point(p));
      for (std::size_t i = 0; i < pts.size(); ++i) curves.push_back(gmsh::model::occ::addLine(pts[i], pts[(i + 1) % pts.size()]));
      loops.push_back(gmsh::model::occ::addCurveLoop(curves));
    }
    return gmsh::model::occ::addPlaneSurface(loops);
  }

  void build_geometry() {
    for (const auto& p : s_.domain)
      if (int t = surface(p); t > 0) domain_in_.push_back({2, t});
    if (domain_in_.empty()) throw InputError("", "the domain has no polygon with three or more distinct corners");
    region_in_.resize(s_.regions.size());
    for (std::size_t r = 0; r < s_.regions.size(); ++r)
      for (const auto& p : s_.regions[r].polygons)
        if (int t = surface(p); t > 0) region_in_[r].push_back({2, t});
    line_in_.resize(s_.lines.size());
    for (std::size_t l = 0; l < s_.lines.size(); ++l)
      for (const auto& raw : s_.lines[l].lines) {
        std::vector<XY> pl;
        for (const auto& p : raw)
          if (pl.empty() || p != pl.back()) pl.push_back(p);
        if (pl.size() < 2) continue;
        std::vector<int> pts;
        for (const auto& p : pl) pts.push_back(point(p));
        for (std::size_t i = 0; i + 1 < pts.size(); ++i)
          line_in_[l].push_back({1, gmsh::model::occ::addLine(pts[i], pts[i + 1])});
      }
  }

  // One boolean fragment makes regions and lines conformal with the domain; the map tells which
  // pieces each input became.
  void fragment() {
    DimTags tools;
    for (const auto& r : region_in_) tools.insert(tools.end(), r.begin(), r.end());
    for (const auto& l : line_in_) tools.insert(tools.end(), l.begin(), l.end());
    std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> became;
    if (!tools.empty() || domain_in_.size() > 1) {
      DimTags out;
      std::vector<DimTags> map;
      gmsh::model::occ::fragment(domain_in_, tools, out, map);
      DimTags inputs = domain_in_;
      inputs.insert(inputs.end(), tools.begin(), tools.end());
      for (std::size_t i = 0; i < inputs.size() && i < map.size(); ++i) became[inputs[i]] = map[i];
    } else {
      for (const auto& d : domain_in_) became[d] = {d};
    }
    gmsh::model::occ::synchronize();
    auto pieces = [&](const DimTags& in) {
      std::set<int> s;
      for (const auto& d : in)
        for (const auto& p : became[d]) s.insert(p.second);
      return s;
    };
    // Surfaces are classified by geometry, not by the fragment's map: OpenCASCADE's history can come
    // back empty for a polygon with a hole that another polygon overlaps, which dropped its region
    // (group, refinement) without a word. Each piece lies wholly inside or outside every input
    // polygon, so one interior point of the piece decides.
    const geo::PolygonSet domain_set(s_.domain);
    std::vector<geo::PolygonSet> region_sets;
    for (const auto& r : s_.regions) region_sets.emplace_back(r.polygons);
    DimTags all;
    gmsh::model::getEntities(all, 2);
    DimTags outside;
    std::map<int, XY> inner;
    for (const auto& [d, t] : all) {
      const XY p = interior_point(t);
      inner[t] = p;
      if (domain_set.contains(p)) domain_.insert(t);
      else outside.push_back({2, t});
    }
    // Pieces of regions outside the domain (clipping leftovers) are dropped.
    if (!outside.empty()) {
      gmsh::model::occ::remove(outside, true);
      gmsh::model::occ::synchronize();
    }
    for (std::size_t r = 0; r < region_in_.size(); ++r) {
      std::set<int> s;
      for (int t : domain_)
        if (region_sets[r].contains(inner[t])) s.insert(t);
      regions_.push_back(s);
    }
    // Curves on a domain surface's boundary or embedded in it; other line pieces lie outside.
    std::set<int> inside_curves;
    for (int t : domain_) {
      DimTags b, e;
      gmsh::model::getBoundary({{2, t}}, b, false, false, false);
      for (const auto& [d, c] : b) inside_curves.insert(std::abs(c));
      gmsh::model::mesh::getEmbedded(2, t, e);
      for (const auto& [d, c] : e)
        if (d == 1) inside_curves.insert(c);
    }
    DimTags stray;
    for (const auto& l : line_in_) {
      std::set<int> s;
      for (int c : pieces(l)) {
        if (inside_curves.count(c)) s.insert(c);
        else stray.push_back({1, c});
      }
      lines_.push_back(s);
    }
    if (!stray.empty()) {
      std::sort(stray.begin(), stray.end());
      stray.erase(std::unique(stray.begin(), stray.end()), stray.end());
      gmsh::model::occ::remove(stray, true);
      gmsh::model::occ::synchronize();
    }
  }

  // A point strictly inside surface `t` (global coordinates): beside the middle of its longest
  // boundary segment, on the side that the even-odd rule over its boundary says is inside.
  XY interior_point(int t) {
    DimTags b;
    gmsh::model::getBoundary({{2, t}}, b, false, false, false);
    std::vector<Segment> segs;
    for (const auto& [d, c] : b) {
      DimTags ends;
      gmsh::model::getBoundary({{1, std::abs(c)}}, ends, false, false, false);
      if (ends.size() != 2) continue;  // closed curves do not occur: every input is a polyline
      std::vector<double> a, e;
      gmsh::model::getValue(0, ends[0].second, {}, a);
      gmsh::model::getValue(0, ends[1].second, {}, e);
      segs.push_back({XY{a[0], a[1]}, XY{e[0], e[1]}});
    }
    auto inside = [&](const XY& p) {
      bool in = false;
      for (const auto& sg : segs)
        if ((sg.a[1] > p[1]) != (sg.b[1] > p[1]) &&
            p[0] < (sg.b[0] - sg.a[0]) * (p[1] - sg.a[1]) / (sg.b[1] - sg.a[1]) + sg.a[0])
          in = !in;
      return in;
    };
    std::vector<std::size_t> order(segs.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    auto len = [&](std::size_t i) { return std::hypot(segs[i].b[0] - segs[i].a[0], segs[i].b[1] - segs[i].a[1]); };
    std::stable_sort(order.begin(), order.end(), [&](auto i, auto j) { return len(i) > len(j); });
    for (std::size_t i : order) {
      const auto& sg = segs[i];
      const double L = len(i);
      if (!(L > 0)) continue;
      const XY m{0.5 * (sg.a[0] + sg.b[0]), 0.5 * (sg.a[1] + sg.b[1])};
      const XY n{-(sg.b[1] - sg.a[1]) / L, (sg.b[0] - sg.a[0]) / L};
      for (double delta : {1e-3 * L, 1e-5 * L})
        for (double side : {1.0, -1.0}) {
          const XY p{m[0] + side * delta * n[0], m[1] + side * delta * n[1]};
          if (inside(p)) return {p[0] + x0_, p[1] + y0_};
        }
    }
    throw ComputeError(fmt::format("gmsh: no interior point found for plan surface {}", t));
  }

  // Never silently: the triangles of each region must cover its polygons (clipped to the domain).
  void check_region_areas() {
    std::map<int, double> area;  // per surface
    {
      double want = 0, got = 0;
      for (const auto& poly : s_.domain) want += polygon_area(poly);
      for (int t : domain_) got += area[t] = surface_mesh_area(t);
      if (std::abs(got - want) > 1e-6 * want)
        throw InputError("", fmt::format("the domain covers {:.9g} m2, but its triangles {:.9g} m2: the plan geometry made "
                                         "overlapping or missing pieces (self-touching rings or holes?); simplify the "
                                         "polygons",
                                         want, got));
    }
    for (std::size_t r = 0; r < s_.regions.size(); ++r) {
      double want = 0, got = 0;
      for (const auto& poly : s_.regions[r].polygons) want += polygon_area(poly);
      if (!(want > 0)) continue;
      for (int t : regions_[r]) {
        if (!area.count(t)) area[t] = surface_mesh_area(t);
        got += area[t];
      }
      if (std::abs(got - want) > 1e-6 * want)
        throw InputError("", fmt::format("region '{}': its polygons cover {:.9g} m2 of the domain, but its triangles {:.9g} m2: "
                                       "the plan geometry lost part of it (self-touching rings or holes?); simplify the "
                                       "polygon",
                                       s_.regions[r].name, want, got));
    }
  }

  double surface_mesh_area(int t) {
    if (node_at_.empty()) {  // every node (a surface's own list lacks the nodes of curves embedded in it)
      std::vector<std::size_t> tags;
      std::vector<double> param;
      gmsh::model::mesh::getNodes(tags, node_xyz_, param, -1, -1, false, false);
      for (std::size_t i = 0; i < tags.size(); ++i) node_at_[tags[i]] = i;
    }
    const auto& at = node_at_;
    const auto& xyz = node_xyz_;
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> etags, enodes;
    gmsh::model::mesh::getElements(types, etags, enodes, 2, t);
    double a = 0;
    for (std::size_t k = 0; k < types.size(); ++k) {
      if (types[k] != 2) continue;
      for (std::size_t e = 0; e + 2 < enodes[k].size(); e += 3) {
        const double* A = &xyz[3 * at.at(enodes[k][e])];
        const double* B = &xyz[3 * at.at(enodes[k][e + 1])];
        const double* C = &xyz[3 * at.at(enodes[k][e + 2])];
        a += 0.5 * std::abs((B[0] - A[0]) * (C[1] - A[1]) - (B[1] - A[1]) * (C[0] - A[0]));
      }
    }
    return a;
  }

  static double ring_area(const std::vector<XY>& r) { return std::abs(signed_area(r)); }
  static double polygon_area(const geo::Polygon& p) {
    const auto outer = clean_ring(p.outer);
    if (outer.size() < 3) return 0;
    double a = ring_area(outer);
    for (const auto& h : p.holes)
      if (const auto r = clean_ring(h); r.size() >= 3) a -= ring_area(r);
    return a;
  }

  std::vector<double> as_doubles(const std::set<int>& s) { return std::vector<double>(s.begin(), s.end()); }

  double longest_curve(const std::set<int>& curves) {
    double L = 0;
    for (int c : curves) {
      double x0, y0, z0, x1, y1, z1;
      gmsh::model::getBoundingBox(1, c, x0, y0, z0, x1, y1, z1);
      L = std::max(L, std::hypot(x1 - x0, y1 - y0));
    }
    return L;
  }

  // Size s at distance 0 from `curves`, growing by `grading` per metre up to hmax.
  int graded_field(const std::set<int>& curves, double size) {
    const int d = gmsh::model::mesh::field::add("Distance");
    gmsh::model::mesh::field::setNumbers(d, "CurvesList", as_doubles(curves));
    const double n = std::clamp(std::ceil(longest_curve(curves) / (0.5 * size)) + 1, 10.0, 4000.0);
    gmsh::model::mesh::field::setNumber(d, "NumPointsPerCurve", n);
    const int t = gmsh::model::mesh::field::add("Threshold");
    gmsh::model::mesh::field::setNumber(t, "InField", d);
    gmsh::model::mesh::field::setNumber(t, "SizeMin", size);
    gmsh::model::mesh::field::setNumber(t, "SizeMax", s_.hmax);
    gmsh::model::mesh::field::setNumber(t, "DistMin", 0);
    gmsh::model::mesh::field::setNumber(t, "DistMax", std::max((s_.hmax - size) / s_.grading, 1e-6));
    return t;
  }

  void set_sizes() {
    std::vector<double> fields;
    min_size_ = s_.hmax;
    for (std::size_t r = 0; r < s_.regions.size(); ++r) {
      const double size = s_.regions[r].size;
      if (!(size > 0) || regions_[r].empty() || size >= s_.hmax) continue;
      min_size_ = std::min(min_size_, size);
      DimTags surf, bnd;
      for (int t : regions_[r]) surf.push_back({2, t});
      gmsh::model::getBoundary(surf, bnd, true, false, false);
      std::set<int> outline;
      for (const auto& [d, c] : bnd) outline.insert(std::abs(c));
      fields.push_back(graded_field(outline, size));
      // Inside: the constant size, on the region's surfaces and on the curves and points in them.
      std::set<int> curves, points;
      for (int t : regions_[r]) {
        DimTags b, e, pts;
        gmsh::model::getBoundary({{2, t}}, b, false, false, false);
        gmsh::model::mesh::getEmbedded(2, t, e);
        for (const auto& [d, c] : b) curves.insert(std::abs(c));
        for (const auto& [d, c] : e) (d == 1 ? curves : points).insert(c);
        gmsh::model::getBoundary({{2, t}}, pts, false, false, true);
        for (const auto& [d, p] : pts)
          if (d == 0) points.insert(std::abs(p));
      }
      for (int c : curves) {
        DimTags pts;
        gmsh::model::getBoundary({{1, c}}, pts, false, false, false);
        for (const auto& [d, p] : pts) points.insert(std::abs(p));
      }
      const int f = gmsh::model::mesh::field::add("MathEval");
      gmsh::model::mesh::field::setString(f, "F", fmt::format("{:.17g}", size));
      const int rf = gmsh::model::mesh::field::add("Restrict");
      gmsh::model::mesh::field::setNumber(rf, "InField", f);
      gmsh::model::mesh::field::setNumbers(rf, "SurfacesList", as_doubles(regions_[r]));
      gmsh::model::mesh::field::setNumbers(rf, "CurvesList", as_doubles(curves));
      gmsh::model::mesh::field::setNumbers(rf, "PointsList", as_doubles(points));
      fields.push_back(rf);
    }
    for (std::size_t l = 0; l < s_.lines.size(); ++l) {
      const double size = s_.lines[l].size;
      if (!(size > 0) || lines_[l].empty() || size >= s_.hmax) continue;
      min_size_ = std::min(min_size_, size);
      fields.push_back(graded_field(lines_[l], size));
    }
    int background;
    if (fields.empty()) {
      background = gmsh::model::mesh::field::add("MathEval");
      gmsh::model::mesh::field::setString(background, "F", fmt::format("{:.17g}", s_.hmax));
    } else {
      background = gmsh::model::mesh::field::add("Min");
      gmsh::model::mesh::field::setNumbers(background, "FieldsList", fields);
    }
    gmsh::model::mesh::field::setAsBackgroundMesh(background);
    gmsh::option::setNumber("Mesh.MeshSizeMax", s_.hmax);
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
    gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.Algorithm", s_.algorithm);
  }

  Mesh extract() {
    // Groups: the domain, each region, each line group (and region outlines as line groups).
    struct Group {
      int dim;
      std::string name;
      std::set<int> entities;
      std::vector<Segment> direction;   // input segments giving line elements their direction
    };
    std::vector<Group> groups;
    auto add_group = [&](int dim, const std::string& name, const std::set<int>& ents, std::vector<Segment> dir = {}) {
      if (ents.empty()) return;
      for (auto& g : groups)
        if (g.dim == dim && g.name == name) {
          g.entities.insert(ents.begin(), ents.end());
          g.direction.insert(g.direction.end(), dir.begin(), dir.end());
          return;
        }
      groups.push_back({dim, name, ents, std::move(dir)});
    };
    add_group(2, "region:" + s_.domain_name, domain_);
    for (std::size_t r = 0; r < s_.regions.size(); ++r) {
      add_group(2, "region:" + s_.regions[r].name, regions_[r]);
      if (s_.regions[r].outline_group.empty() || regions_[r].empty()) continue;
      DimTags surf, bnd;
      for (int t : regions_[r]) surf.push_back({2, t});
      gmsh::model::getBoundary(surf, bnd, true, false, false);
      std::set<int> outline;
      for (const auto& [d, c] : bnd) outline.insert(std::abs(c));
      std::vector<Segment> dir;
      for (const auto& p : s_.regions[r].polygons) {
        const auto ring = clean_ring(p.outer);
        for (std::size_t i = 0; i < ring.size(); ++i) dir.push_back({ring[i], ring[(i + 1) % ring.size()]});
      }
      add_group(1, s_.regions[r].outline_group, outline, std::move(dir));
    }
    for (std::size_t l = 0; l < s_.lines.size(); ++l) {
      std::vector<Segment> dir;
      for (const auto& pl : s_.lines[l].lines)
        for (std::size_t i = 0; i + 1 < pl.size(); ++i)
          if (pl[i] != pl[i + 1]) dir.push_back({pl[i], pl[i + 1]});
      add_group(1, s_.lines[l].group, lines_[l], std::move(dir));
    }

    Mesh m;
    std::vector<std::size_t> node_tags;
    std::vector<double> coords, param;
    gmsh::model::mesh::getNodes(node_tags, coords, param, -1, -1, false, false);
    std::unordered_map<std::size_t, std::uint32_t> index;
    index.reserve(node_tags.size());
    {
      std::vector<std::size_t> order(node_tags.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::sort(order.begin(), order.end(), [&](auto a, auto b) { return node_tags[a] < node_tags[b]; });
      for (auto i : order) {
        index[node_tags[i]] = static_cast<std::uint32_t>(m.nodes.size());
        m.node_tags.push_back(node_tags[i]);
        m.nodes.push_back({coords[3 * i] + x0_, coords[3 * i + 1] + y0_, 0.0});
      }
    }
    for (std::size_t g = 0; g < groups.size(); ++g) m.physicals.push_back({groups[g].dim, static_cast<int>(g + 1), groups[g].name});
    // Entities: every gmsh surface of the domain and every grouped curve, with all its groups.
    std::map<std::pair<int, int>, std::vector<int>> entity_groups;
    for (std::size_t g = 0; g < groups.size(); ++g)
      for (int t : groups[g].entities) entity_groups[{groups[g].dim, t}].push_back(static_cast<int>(g + 1));
    for (const auto& [dt, phys] : entity_groups) {
      const auto [dim, tag] = dt;
      m.entities.push_back({dim, tag, phys, {}});
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> etags, enodes;
      gmsh::model::mesh::getElements(types, etags, enodes, dim, tag);
      const ElementType want = dim == 2 ? ElementType::Triangle : ElementType::Line;
      for (std::size_t k = 0; k < types.size(); ++k) {
        if (types[k] != static_cast<int>(want)) {
          throw ComputeError(fmt::format("gmsh produced elements of type {} on {} {}; expected {}", types[k],
                                         dim == 2 ? "surface" : "curve", tag, element_name(want)));
        }
        ElementBlock& b = m.block(dim, tag, want);
        const int npe = b.npe();
        for (std::size_t e = 0; e < etags[k].size(); ++e) {
          std::array<std::uint32_t, 3> n{};
          for (int j = 0; j < npe; ++j) n[j] = index.at(enodes[k][e * npe + j]);
          if (dim == 2) {
            const auto &A = m.nodes[n[0]], &B = m.nodes[n[1]], &C = m.nodes[n[2]];
            if ((B[0] - A[0]) * (C[1] - A[1]) - (B[1] - A[1]) * (C[0] - A[0]) < 0) std::swap(n[1], n[2]);
          } else {
            orient_line(n, m, groups, phys);
          }
          b.tags.push_back(etags[k][e]);
          b.nodes.insert(b.nodes.end(), n.begin(), n.begin() + npe);
        }
      }
    }
    // Blocks in a stable order: triangles first, then lines, each by entity tag.
    std::stable_sort(m.blocks.begin(), m.blocks.end(), [](const ElementBlock& a, const ElementBlock& b) {
      if (a.entity_dim != b.entity_dim) return a.entity_dim > b.entity_dim;
      return a.entity_tag < b.entity_tag;
    });
    std::stable_sort(m.entities.begin(), m.entities.end(), [](const Entity& a, const Entity& b) {
      return std::pair(a.dim, a.tag) < std::pair(b.dim, b.tag);
    });
    // Keep only the nodes the elements use (points of removed pieces may leave some).
    std::vector<char> used(m.num_nodes(), 0);
    for (const auto& b : m.blocks)
      for (auto n : b.nodes) used[n] = 1;
    if (std::find(used.begin(), used.end(), 0) != used.end()) {
      std::vector<std::uint32_t> remap(m.num_nodes(), UINT32_MAX);
      Mesh k;
      for (std::uint32_t i = 0; i < m.num_nodes(); ++i)
        if (used[i]) {
          remap[i] = static_cast<std::uint32_t>(k.nodes.size());
          k.nodes.push_back(m.nodes[i]);
          k.node_tags.push_back(m.node_tags[i]);
        }
      for (auto& b : m.blocks)
        for (auto& n : b.nodes) n = remap[n];
      m.nodes = std::move(k.nodes);
      m.node_tags = std::move(k.node_tags);
    }
    m.update_entity_bboxes();
    return m;
  }

  // Gives a line element the direction of the input segment nearest to its midpoint.
  template <class G>
  static void orient_line(std::array<std::uint32_t, 3>& n, const Mesh& m, const std::vector<G>& groups,
                          const std::vector<int>& phys) {
    const auto &A = m.nodes[n[0]], &B = m.nodes[n[1]];
    const XY mid{0.5 * (A[0] + B[0]), 0.5 * (A[1] + B[1])};
    double best = std::numeric_limits<double>::infinity();
    const Segment* seg = nullptr;
    for (int p : phys)
      for (const auto& s : groups[p - 1].direction) {
        const double dx = s.b[0] - s.a[0], dy = s.b[1] - s.a[1], L2 = dx * dx + dy * dy;
        double t = L2 > 0 ? ((mid[0] - s.a[0]) * dx + (mid[1] - s.a[1]) * dy) / L2 : 0.0;
        t = std::clamp(t, 0.0, 1.0);
        const double ex = s.a[0] + t * dx - mid[0], ey = s.a[1] + t * dy - mid[1], d2 = ex * ex + ey * ey;
        if (d2 < best) best = d2, seg = &s;
      }
    if (seg && (B[0] - A[0]) * (seg->b[0] - seg->a[0]) + (B[1] - A[1]) * (seg->b[1] - seg->a[1]) < 0) std::swap(n[0], n[1]);
  }

  const PlanSpec& s_;
  double x0_ = 0, y0_ = 0, min_size_ = 0;
  std::unordered_map<std::size_t, std::size_t> node_at_;
  std::vector<double> node_xyz_;
  DimTags domain_in_;
  std::vector<DimTags> region_in_, line_in_;
  std::set<int> domain_;
  std::vector<std::set<int>> regions_, lines_;
};

}  // namespace

namespace {
double polygon_area_of(const geo::Polygon& p) {
  const auto outer = clean_ring(p.outer);
  if (outer.size() < 3) return 0;
  double a = std::abs(signed_area(outer));
  for (const auto& h : p.holes)
    if (const auto r = clean_ring(h); r.size() >= 3) a -= std::abs(signed_area(r));
  return std::max(a, 0.0);
}
double ring_length(const std::vector<XY>& r, bool closed) {
  double L = 0;
  for (std::size_t i = 0; i + 1 < r.size(); ++i) L += std::hypot(r[i + 1][0] - r[i][0], r[i + 1][1] - r[i][1]);
  if (closed && r.size() > 2) L += std::hypot(r.front()[0] - r.back()[0], r.front()[1] - r.back()[1]);
  return L;
}
}  // namespace

PlanEstimate estimate_plan_triangles(const PlanSpec& s) {
  PlanEstimate e;
  e.smallest_size = s.hmax;
  e.smallest_where = "the far field (hmax)";
  double integral = 0;  // of 1 / h^2 over the plan
  for (const auto& p : s.domain) integral += polygon_area_of(p) / (s.hmax * s.hmax);
  auto band = [&](double length, double size) { return length / s.grading * (1.0 / size - 1.0 / s.hmax); };
  for (const auto& r : s.regions) {
    if (!(r.size > 0) || r.size >= s.hmax) continue;
    for (const auto& p : r.polygons) {
      double perimeter = ring_length(p.outer, true);
      for (const auto& h : p.holes) perimeter += ring_length(h, true);
      integral += polygon_area_of(p) / (r.size * r.size) + band(perimeter, r.size);
    }
    if (r.size < e.smallest_size) e.smallest_size = r.size, e.smallest_where = "region '" + r.name + "'";
  }
  for (const auto& l : s.lines) {
    if (!(l.size > 0) || l.size >= s.hmax) continue;
    for (const auto& pl : l.lines) integral += band(2 * ring_length(pl, false), l.size);
    if (l.size < e.smallest_size) e.smallest_size = l.size, e.smallest_where = "line " + l.group;
  }
  e.triangles = kTrianglesPerSquare * integral;
  return e;
}

Mesh make_plan_mesh(const PlanSpec& spec, PlanMeshStats* stats) {
  if (!(spec.hmax > 0) || !std::isfinite(spec.hmax)) throw InputError("", "hmax must be a size in metres, > 0");
  if (!(spec.grading > 0) || !std::isfinite(spec.grading)) throw InputError("", "grading must be > 0");
  if (spec.domain.empty()) throw InputError("", "the domain is empty");
  {
    double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
    for (const auto& p : spec.domain)
      for (const auto& q : p.outer) x0 = std::min(x0, q[0]), x1 = std::max(x1, q[0]), y0 = std::min(y0, q[1]), y1 = std::max(y1, q[1]);
    if (x1 - x0 > kMaxPlanExtentM || y1 - y0 > kMaxPlanExtentM)
      throw InputError("", fmt::format("the domain spans {:.0f} km x {:.0f} km (x {:.1f} .. {:.1f}, y {:.1f} .. {:.1f}), more than "
                                       "{:.0f} km across: a coordinate out of place? (expected a field-scale plan in a projected "
                                       "CRS, in metres)",
                                       (x1 - x0) / 1e3, (y1 - y0) / 1e3, x0, x1, y0, y1, kMaxPlanExtentM / 1e3));
  }
  // Refuse before meshing what would not fit in memory (a size of 1e-9 m grew gmsh's memory without
  // bound until std::bad_alloc).
  if (const PlanEstimate est = estimate_plan_triangles(spec); !(est.triangles <= spec.max_triangles))
    throw InputError("element limit",
                     fmt::format("the sizes ask for about {:.3g} triangles (estimate: {:.4g} x the integral of 1/size^2 "
                                 "over the plan), more than the limit of {:.0f}: the smallest size is {:g} m ({}); use "
                                 "larger sizes or raise the element limit",
                                 est.triangles, kTrianglesPerSquare, spec.max_triangles, est.smallest_size,
                                 est.smallest_where));
  GmshSession session(spec.gmsh_messages);
  try {
    return PlanMesher(spec).run(stats);
  } catch (const std::string& e) {  // how the gmsh 4.8 API reports errors
    throw ComputeError("gmsh failed to mesh the plan: " + (e.empty() ? std::string("no message") : e));
  }
}

}  // namespace ugs
