// Selection of the tetrahedron faces lying on trace surfaces, and their coverage of the surface.
#include "ugs/meshing/fault_select.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/meshing/fault_insert.hpp"

namespace ugs {
namespace {

using P2 = std::array<double, 2>;
using Box = std::array<double, 6>;
constexpr double kInf = std::numeric_limits<double>::infinity();

bool boxes_overlap(const Box& a, const Box& b, double margin) {
  for (int k = 0; k < 3; ++k)
    if (a[k] > b[k + 3] + margin || b[k] > a[k + 3] + margin) return false;
  return true;
}

// Keeps the part of a polygon where c0 * s + c1 * t + c2 >= 0 (Sutherland-Hodgman).
std::vector<P2> clip(const std::vector<P2>& poly, double c0, double c1, double c2) {
  std::vector<P2> out;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const P2& p = poly[i];
    const P2& q = poly[(i + 1) % n];
    const double fp = c0 * p[0] + c1 * p[1] + c2, fq = c0 * q[0] + c1 * q[1] + c2;
    if (fp >= 0) out.push_back(p);
    if ((fp >= 0) != (fq >= 0)) {
      const double r = fp / (fp - fq);
      out.push_back({p[0] + r * (q[0] - p[0]), p[1] + r * (q[1] - p[1])});
    }
  }
  return out;
}

double polygon_area(const std::vector<P2>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const P2& u = p[i];
    const P2& v = p[(i + 1) % p.size()];
    a += u[0] * v[1] - u[1] * v[0];
  }
  return 0.5 * std::abs(a);
}

// Area (m2) of a polygon in panel coordinates (s, t) within the depth range, and within s in [0, 1]
// on the sides where the surface ends (all sides when `all_sides`).
double clipped_area(std::vector<P2> poly, const FaultSurface& S, const FaultSurface::Panel& p, bool all_sides) {
  poly = clip(poly, 0, 1, -p.t0);
  poly = clip(poly, 0, -1, p.t1);
  if (p.first || all_sides) poly = clip(poly, 1, 0, 0);
  if (p.last || all_sides) poly = clip(poly, -1, 0, 1);
  return poly.size() < 3 ? 0.0 : polygon_area(poly) * p.area_scale;
}

// A tetrahedron: its four node indices in the mesh, and their bounding box.
struct Tet {
  const std::uint32_t* n;
  Box box;
};

class Selector {
public:
  Selector(Mesh& m, const FaultSelectOptions& o) : m_(m), opt_(o) {}

  std::vector<FaultSelection> run(const std::vector<FaultTrace>& traces) {
    const auto have_tri = fault_triangle_groups(m_), have_ie = fault_interface_groups(m_);
    auto has = [](const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); };
    std::vector<FaultSelection> out(traces.size());
    std::vector<std::vector<std::array<std::uint32_t, 3>>> faces(traces.size());
    std::vector<std::size_t> todo;
    for (std::size_t f = 0; f < traces.size(); ++f) {
      const FaultTrace& tr = traces[f];
      out[f].name = tr.name;
      if (has(have_ie, tr.name))
        throw InputError(tr.where, fmt::format("fault '{}' already has interface elements in {}: it was inserted before",
                                               tr.name, opt_.source.empty() ? "the mesh" : opt_.source));
      if (has(have_tri, tr.name)) {
        out[f].from_mesh = true;
        deviation(tr, out[f]);
      } else {
        todo.push_back(f);
      }
    }
    // Up to 64 traces per pass over the mesh (one bit per trace and node).
    for (std::size_t c0 = 0; c0 < todo.size(); c0 += 64) {
      prepare();
      std::vector<std::size_t> chunk(todo.begin() + c0, todo.begin() + std::min(todo.size(), c0 + 64));
      std::vector<FaultSurface> surfaces;
      for (auto f : chunk) surfaces.emplace_back(traces[f]);
      scan(chunk, traces, surfaces);
      for (std::size_t k = 0; k < chunk.size(); ++k)
        faces[chunk[k]] = select(traces[chunk[k]], surfaces[k], k, out[chunk[k]]);
    }
    // All traces passed: add their groups.
    for (std::size_t f = 0; f < traces.size(); ++f) {
      if (out[f].from_mesh) continue;
      const int ent = m_.entity_for_physical(2, "fault:" + traces[f].name);
      for (const auto& t : faces[f]) m_.add_element(m_.block(2, ent, ElementType::Triangle), t);
    }
    m_.update_entity_bboxes();
    return out;
  }

private:
  // Tetrahedra with boxes, node edge lengths and the mesh's extent (once, for all traces).
  void prepare() {
    if (prepared_) return;
    prepared_ = true;
    const std::size_t nn = m_.num_nodes();
    hmin_.assign(nn, kInf);
    hmax_.assign(nn, 0.0);
    mesh_box_ = {kInf, kInf, kInf, -kInf, -kInf, -kInf};
    double scale = 1;
    for (const auto& b : m_.blocks) {
      if (b.type != ElementType::Tetrahedron) continue;
      for (std::size_t e = 0; e < b.size(); ++e) {
        const auto c = b.element(e);
        tets_.push_back(c.data());
        for (int i = 0; i < 4; ++i) {
          const Point3& x = m_.nodes[c[i]];
          for (int j = i + 1; j < 4; ++j) {
            const Point3& y = m_.nodes[c[j]];
            const double l = std::sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) + (x[2] - y[2]) * (x[2] - y[2]));
            hmin_[c[i]] = std::min(hmin_[c[i]], l);
            hmin_[c[j]] = std::min(hmin_[c[j]], l);
            hmax_[c[i]] = std::max(hmax_[c[i]], l);
            hmax_[c[j]] = std::max(hmax_[c[j]], l);
            max_edge_ = std::max(max_edge_, l);
          }
        }
      }
    }
    // Extent of the nodes in tetrahedra (hmax > 0).
    for (std::size_t v = 0; v < nn; ++v) {
      if (hmax_[v] == 0) continue;
      for (int k = 0; k < 3; ++k) {
        mesh_box_[k] = std::min(mesh_box_[k], m_.nodes[v][k]);
        mesh_box_[k + 3] = std::max(mesh_box_[k + 3], m_.nodes[v][k]);
        scale = std::max(scale, std::abs(m_.nodes[v][k]));
      }
    }
    hval_.assign(nn, 0.0);
    hstamp_.assign(nn, 0);
    if (tets_.empty()) throw InputError(opt_.source, "the mesh has no tetrahedra to select fault faces from");
    floor_tol_ = 1e-9 * scale;
  }

  Tet tet(const std::uint32_t* c) const {
    Tet t{c, {kInf, kInf, kInf, -kInf, -kInf, -kInf}};
    for (int i = 0; i < 4; ++i) {
      const Point3& x = m_.nodes[c[i]];
      for (int k = 0; k < 3; ++k) {
        t.box[k] = std::min(t.box[k], x[k]);
        t.box[k + 3] = std::max(t.box[k + 3], x[k]);
      }
    }
    return t;
  }

  double tol(std::uint32_t v) const {
    if (opt_.tolerance > 0) return opt_.tolerance;
    return std::max(0.01 * (std::isfinite(hmin_[v]) ? hmin_[v] : 0.0), floor_tol_);
  }

  // One pass over nodes and tetrahedra for a chunk of traces: for trace k, the candidate faces
  // (three nodes near its surface) and the tetrahedra that may meet it (a node within its longest
  // edge of the surface's box: every point of a tetrahedron lies that close to each of its nodes).
  void scan(const std::vector<std::size_t>& chunk, const std::vector<FaultTrace>& traces,
            const std::vector<FaultSurface>& surfaces) {
    const std::size_t nk = chunk.size();
    std::vector<Box> fbox(nk);
    for (std::size_t k = 0; k < nk; ++k) {
      const FaultTrace& tr = traces[chunk[k]];
      if (tr.top < mesh_box_[2] || tr.bottom > mesh_box_[5])
        throw InputError(tr.where, fmt::format("fault '{}': its depth range, top_m {:.1f} to bottom_m {:.1f}, lies outside "
                                               "the mesh (z from {:.1f} to {:.1f})",
                                               tr.name, tr.top, tr.bottom, mesh_box_[2], mesh_box_[5]));
      fbox[k] = surfaces[k].bbox();
    }
    box_mask_.assign(m_.num_nodes(), 0);
    near_mask_.assign(m_.num_nodes(), 0);
    for (std::uint32_t v = 0; v < m_.num_nodes(); ++v) {
      if (hmax_[v] == 0) continue;  // in no tetrahedron
      const Point3& x = m_.nodes[v];
      const double mg = hmax_[v];
      for (std::size_t k = 0; k < nk; ++k) {
        bool in = true;
        for (int d = 0; d < 3 && in; ++d) in = x[d] >= fbox[k][d] - mg && x[d] <= fbox[k][d + 3] + mg;
        if (!in) continue;
        box_mask_[v] |= std::uint64_t{1} << k;
        // Near: on a panel's plane, within the panel widened by the node's longest edge.
        const FaultSurface& S = surfaces[k];
        for (std::size_t i = 0; i < S.panels().size(); ++i) {
          const auto& p = S.panels()[i];
          const auto l = S.local(i, x);
          if (std::abs(l.h) <= tol(v) && l.s * p.length >= -mg && l.s * p.length <= p.length + mg &&
              l.t >= p.t0 - mg && l.t <= p.t1 + mg) {
            near_mask_[v] |= std::uint64_t{1} << k;
            break;
          }
        }
      }
    }
    cand_.assign(nk, {});
    near_tets_.assign(nk, {});
    for (std::uint32_t ti = 0; ti < tets_.size(); ++ti) {
      const std::uint32_t* n = tets_[ti];
      const std::uint64_t in = box_mask_[n[0]];
      if (in == 0) continue;
      const std::uint64_t nm[4] = {near_mask_[n[0]], near_mask_[n[1]], near_mask_[n[2]], near_mask_[n[3]]};
      for (std::uint64_t bits = in; bits; bits &= bits - 1) {
        const int k = std::countr_zero(bits);
        const std::uint64_t b = std::uint64_t{1} << k;
        near_tets_[k].push_back(ti);
        const int count = ((nm[0] & b) != 0) + ((nm[1] & b) != 0) + ((nm[2] & b) != 0) + ((nm[3] & b) != 0);
        if (count < 3) continue;
        for (int skip = 0; skip < 4; ++skip) {
          std::array<std::uint32_t, 3> f{};
          int q = 0;
          bool all = true;
          for (int j = 0; j < 4; ++j)
            if (j != skip) {
              f[q++] = n[j];
              all = all && (nm[j] & b);
            }
          if (!all) continue;
          std::sort(f.begin(), f.end());
          cand_[k].push_back(f);
        }
      }
    }
  }

  std::vector<std::array<std::uint32_t, 3>> select(const FaultTrace& tr, const FaultSurface& S, std::size_t k,
                                                   FaultSelection& out) {
    const auto& panels = S.panels();
    const std::string who = fmt::format("fault '{}'", tr.name);
    auto& cand = cand_[k];
    std::sort(cand.begin(), cand.end());
    cand.erase(std::unique(cand.begin(), cand.end()), cand.end());

    // 3. Faces on the surface: coverage, and selection by the centroid.
    std::vector<std::array<std::uint32_t, 3>> chosen;
    for (const auto& f : cand) {
      const Point3 &a = m_.nodes[f[0]], &b = m_.nodes[f[1]], &c = m_.nodes[f[2]];
      const Point3 g{(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3};
      const double tg = std::max({tol(f[0]), tol(f[1]), tol(f[2])});
      std::size_t best = panels.size();
      double best_h = kInf;
      FaultSurface::Local lg{};
      for (std::size_t i = 0; i < panels.size(); ++i) {
        const auto& p = panels[i];
        const auto l = S.local(i, g);
        if (std::abs(l.h) > tg || std::abs(l.h) >= best_h) continue;
        const double eps = 1e-9;
        if ((l.s < -eps && !p.first) || (l.s > 1 + eps && !p.last)) continue;
        bool on = true;
        for (int q = 0; q < 3 && on; ++q) on = std::abs(S.local(i, m_.nodes[f[q]]).h) <= tol(f[q]);
        if (!on) continue;
        best = i;
        best_h = std::abs(l.h);
        lg = l;
      }
      if (best == panels.size()) continue;
      const auto& p = panels[best];
      std::vector<P2> poly;
      for (int q = 0; q < 3; ++q) {
        const auto l = S.local(best, m_.nodes[f[q]]);
        poly.push_back({l.s, l.t});
      }
      const double area = clipped_area(poly, S, p, false);
      if (area <= 0) continue;
      out.covered += area;
      const bool inside = lg.t >= p.t0 && lg.t <= p.t1 && (!p.first || lg.s >= 0) && (!p.last || lg.s <= 1);
      if (!inside) continue;
      // Oriented along the reference normal (side 1 -> side 2).
      std::array<std::uint32_t, 3> t = f;
      const Point3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      const Point3 n{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
      const Point3& r = S.reference_normal();
      if (n[0] * r[0] + n[1] * r[1] + n[2] * r[2] < 0) std::swap(t[1], t[2]);
      chosen.push_back(t);
    }
    out.triangles = chosen.size();

    // 4. Area of the surface inside the model: the section of every tetrahedron by each panel.
    // Signed distances are computed once per node and panel (stamped), most tetrahedra are
    // rejected by their signs.
    const auto& near_tets = near_tets_[k];
    for (std::size_t i = 0; i < panels.size(); ++i) {
      const auto& p = panels[i];
      ++stamp_;
      for (auto ti : near_tets) {
        const std::uint32_t* n = tets_[ti];
        double h[4];
        int nf = 0;
        for (int k = 0; k < 4; ++k) {
          const std::uint32_t v = n[k];
          if (hstamp_[v] != stamp_) {
            const Point3& x = m_.nodes[v];
            hval_[v] = (x[0] - p.a[0]) * p.n[0] + (x[1] - p.a[1]) * p.n[1] + (x[2] - p.a[2]) * p.n[2];
            hstamp_[v] = stamp_;
          }
          h[k] = hval_[v];
          nf += h[k] >= 0;
        }
        if (nf == 0 || nf == 4) continue;
        const Tet t = tet(n);
        if (!boxes_overlap(t.box, p.bbox, 0)) continue;
        out.area_inside += section_area(S, i, n, h);
      }
    }
    if (!(out.area_inside > 0))
      throw InputError(tr.where, fmt::format("{}: its surface does not cross the mesh (is the trace inside the model, "
                                             "and in the mesh's coordinates?)",
                                             who));
    out.coverage = std::min(1.0, out.covered / out.area_inside);
    if (out.coverage < opt_.min_coverage)
      throw InputError(tr.where,
                       fmt::format("{}: mesh faces cover {:.1f} % of its {:.4g} km2 inside the model ({:.0f} % needed): the "
                                   "mesh does not follow the fault; embed the trace in the plan (ugs-mesh2d constraint "
                                   "lines) so the mesh is built along it, or check dip_deg and dip_dir_deg",
                                   who, 100 * out.coverage, out.area_inside * 1e-6, 100 * opt_.min_coverage));
    return chosen;
  }

  // Area of the section of tetrahedron t by panel i's plane, within the panel. Nodes on the plane
  // count as in front, so a face lying on the plane is counted once (by the tetrahedron behind it).
  double section_area(const FaultSurface& S, std::size_t i, const std::uint32_t* tn, const double* h) const {
    const auto& p = S.panels()[i];
    int front[4], nf = 0;
    for (int k = 0; k < 4; ++k) {
      front[k] = h[k] >= 0;
      nf += front[k];
    }
    if (nf == 0 || nf == 4) return 0;
    auto cut = [&](int a, int b) {
      const Point3 &x = m_.nodes[tn[a]], &y = m_.nodes[tn[b]];
      const double r = h[a] / (h[a] - h[b]);
      const Point3 q{x[0] + r * (y[0] - x[0]), x[1] + r * (y[1] - x[1]), x[2] + r * (y[2] - x[2])};
      const auto l = S.local(i, q);
      return P2{l.s, l.t};
    };
    std::vector<P2> poly;
    if (nf == 1 || nf == 3) {
      int lone = 0;
      for (int k = 0; k < 4; ++k)
        if ((front[k] == 1) == (nf == 1)) lone = k;
      for (int k = 0; k < 4; ++k)
        if (k != lone) poly.push_back(cut(lone, k));
    } else {
      int f[2], b[2], a = 0, c = 0;
      for (int k = 0; k < 4; ++k) (front[k] ? f[a++] : b[c++]) = k;
      poly = {cut(f[0], b[0]), cut(f[0], b[1]), cut(f[1], b[1]), cut(f[1], b[0])};
    }
    return clipped_area(poly, S, p, true);
  }

  void deviation(const FaultTrace& tr, FaultSelection& s) const {
    const FaultSurface S(tr);
    const PhysicalGroup* g = m_.find_physical(2, "fault:" + tr.name);
    std::vector<char> seen(m_.num_nodes(), 0);
    s.zmin = kInf;
    s.zmax = -kInf;
    for (const auto& b : m_.blocks) {
      if (b.type != ElementType::Triangle) continue;
      const Entity* e = m_.find_entity(b.entity_dim, b.entity_tag);
      if (!e || std::find(e->physicals.begin(), e->physicals.end(), g->tag) == e->physicals.end()) continue;
      s.triangles += b.size();
      for (std::size_t e = 0; e < b.size(); ++e) {
        double lo = kInf, hi = -kInf;
        for (auto v : b.element(e)) {
          lo = std::min(lo, m_.nodes[v][2]);
          hi = std::max(hi, m_.nodes[v][2]);
          if (seen[v]) continue;
          seen[v] = 1;
          s.max_deviation = std::max(s.max_deviation, S.distance(m_.nodes[v], false));
        }
        s.zmin = std::min(s.zmin, lo);
        s.zmax = std::max(s.zmax, hi);
        s.beyond_depth += lo > tr.top || hi < tr.bottom;
      }
    }
  }

  Mesh& m_;
  const FaultSelectOptions& opt_;
  bool prepared_ = false;
  std::vector<const std::uint32_t*> tets_;  // node indices of each tetrahedron, in the mesh's blocks
  std::vector<double> hval_;                 // signed distance of a node from the current panel
  std::vector<std::uint32_t> hstamp_;
  std::uint32_t stamp_ = 0;
  std::vector<double> hmin_, hmax_;
  std::vector<std::uint64_t> box_mask_, near_mask_;  // per node, one bit per trace of the chunk
  std::vector<std::vector<std::array<std::uint32_t, 3>>> cand_;
  std::vector<std::vector<std::uint32_t>> near_tets_;
  Box mesh_box_{};
  double max_edge_ = 0, floor_tol_ = 0;
};

}  // namespace

std::vector<FaultSelection> select_fault_faces(Mesh& mesh, const std::vector<FaultTrace>& traces,
                                               const FaultSelectOptions& options) {
  return Selector(mesh, options).run(traces);
}

}  // namespace ugs
