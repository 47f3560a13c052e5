// The panels of a fault (fault_cut.hpp): one planar polygon per trace segment and listric piece,
// bounded by its depth range, the vertical planes through the trace's vertices along the dip and,
// for a fault that ends against another, that fault's plane. And the cut's first stage: the panels
// of every fault to cut.
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "cut_stages.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/meshing/fault_cut.hpp"
#include "ugs/meshing/vec3.hpp"

namespace ugs {
namespace {

using namespace vec3;

constexpr double kPi = 3.14159265358979323846;

double cot_deg(double dip_deg) {
  if (dip_deg >= 90) return 0.0;
  const double d = dip_deg * kPi / 180;
  return std::cos(d) / std::sin(d);
}

using P2 = std::array<double, 2>;

// Panels of a trace without `ends_against` handling.
std::vector<CutPanel> plain_panels(const FaultTrace& tr) {
  const double az = tr.dip_dir_deg * kPi / 180;
  const double dx = std::sin(az), dy = std::cos(az);
  std::vector<CutPanel> out;
  const auto pcs = tr.piece_list();
  double above = tr.top;
  for (std::size_t j = 0; j < pcs.size(); ++j) {
    const double below = pcs[j].bottom, cot = cot_deg(pcs[j].dip_deg);
    const double off = tr.offset_at(above);  // offset of the piece's top line from the trace
    const Point3 w{dx * cot, dy * cot, -1.0};
    const Point3 wu = unit(w);
    const double dip = pcs[j].dip_deg * kPi / 180;
    const Point3 ref{-dx * std::sin(dip), -dy * std::sin(dip), -std::cos(dip)};
    std::size_t seg = 0;
    for (const auto& part : tr.parts) {
      const std::size_t nv = part.size();
      // Horizontal direction of the lateral bound at each vertex: the bisector of the segments.
      std::vector<Point3> h(nv);
      for (std::size_t v = 0; v < nv; ++v) {
        Point3 s{0, 0, 0};
        if (v > 0) {
          const Point3 e{part[v][0] - part[v - 1][0], part[v][1] - part[v - 1][1], 0};
          s = unit(e);
        }
        if (v + 1 < nv) {
          const Point3 e = unit(Point3{part[v + 1][0] - part[v][0], part[v + 1][1] - part[v][1], 0});
          s = {s[0] + e[0], s[1] + e[1], 0};
        }
        const Point3 m = sub(s, scaled(wu, dot(s, wu)));  // perpendicular to the down-dip direction
        h[v] = unit(m);
      }
      for (std::size_t i = 0; i + 1 < nv; ++i, ++seg) {
        const Point3 A{part[i][0] + off * dx, part[i][1] + off * dy, above};
        const Point3 B{part[i + 1][0] + off * dx, part[i + 1][1] + off * dy, above};
        CutPanel p;
        p.piece = j;
        p.segment = seg;
        Point3 n = unit(cross(sub(B, A), w));
        if (dot(n, ref) < 0 || (dot(n, ref) == 0 && n[1] + n[0] * 1e-9 > 0)) n = scaled(n, -1);
        p.n = n;
        p.c = dot(n, A);
        p.bounds.push_back({{0, 0, 1}, above});
        p.bounds.push_back({{0, 0, -1}, -below});
        p.bounds.push_back({scaled(h[i], -1), -dot(h[i], A)});
        p.bounds.push_back({h[i + 1], dot(h[i + 1], B)});
        out.push_back(std::move(p));
      }
    }
    above = below;
  }
  return out;
}

// Distance from x to panel p (its polygon, approximately: the plane distance plus how far the
// projection lies outside the bounds).
double panel_distance(const CutPanel& p, const Point3& x) {
  const double h = dot(p.n, x) - p.c;
  double out = 0;
  for (const auto& b : p.bounds) out = std::max(out, dot(b.m, x) - b.d);
  return std::hypot(h, out);
}

}  // namespace

bool panel_contains(const CutPanel& p, const Point3& x, double tol) {
  if (std::abs(dot(p.n, x) - p.c) > tol) return false;
  for (const auto& b : p.bounds)
    if (dot(b.m, x) > b.d + tol) return false;
  return true;
}

std::vector<CutPanel> fault_cut_panels(const FaultTrace& tr, const std::vector<FaultTrace>& all) {
  const std::string who = fmt::format("fault '{}'", tr.name);
  if (tr.surface) {
    if (!tr.ends_against.empty())
      throw InputError(tr.where, fmt::format("{}: a fault given as a surface ends where its surface ends (drop ends_against)", who));
    return fault_cut::surface_panels(tr);
  }
  if (tr.ends_against.empty()) return plain_panels(tr);
  const FaultTrace* other = nullptr;
  for (const auto& f : all)
    if (f.name == tr.ends_against) other = &f;
  if (!other) throw InputError(tr.where, fmt::format("{}: ends_against names fault '{}', which is not given", who, tr.ends_against));
  if (other->name == tr.name) throw InputError(tr.where, fmt::format("{}: a fault cannot end against itself", who));
  const auto target = other->surface ? fault_cut::surface_panels(*other) : plain_panels(*other);
  const double zmid = 0.5 * (tr.top + tr.bottom);
  // The trace end nearest the other fault (at mid-depth) and the panel of the other fault there.
  std::size_t best_part = 0;
  bool at_last = true;
  std::size_t best_panel = 0;
  double best = std::numeric_limits<double>::infinity();
  const double az = tr.dip_dir_deg * kPi / 180;
  const double dx = std::sin(az), dy = std::cos(az);
  const double off_mid = tr.offset_at(zmid);
  for (std::size_t q = 0; q < tr.parts.size(); ++q)
    for (bool last : {false, true}) {
      const P2& e = last ? tr.parts[q].back() : tr.parts[q].front();
      const Point3 x{e[0] + off_mid * dx, e[1] + off_mid * dy, zmid};
      for (std::size_t k = 0; k < target.size(); ++k)
        if (const double d = panel_distance(target[k], x); d < best) {
          best = d;
          best_part = q;
          at_last = last;
          best_panel = k;
        }
    }
  const CutPanel& A = target[best_panel];
  FaultTrace ext = tr;
  auto& part = ext.parts[best_part];
  const P2 end = at_last ? part.back() : part.front();
  const P2 prev = at_last ? part[part.size() - 2] : part[1];
  const P2 dir2{end[0] - prev[0], end[1] - prev[1]};
  const double len = std::hypot(dir2[0], dir2[1]);
  const Point3 u{dir2[0] / len, dir2[1] / len, 0};
  const double un = dot(A.n, u);
  if (std::abs(un) < 1e-3)
    throw InputError(tr.where, fmt::format("{}: runs parallel to fault '{}' and cannot end against it", who, other->name));
  // How far the end must move along u for the fault to reach the other one at every depth.
  double reach = 0;
  for (double z : {tr.top, tr.bottom, zmid}) {
    const double off = tr.offset_at(z);
    const Point3 x{end[0] + off * dx, end[1] + off * dy, z};
    reach = std::max(reach, (A.c - dot(A.n, x)) / un);
  }
  // A point of the trace away from that end says which side of the other fault it keeps.
  const P2 keep = at_last ? part.front() : part.back();
  const double off_top = tr.offset_at(zmid);
  const Point3 xk{keep[0] + off_top * dx, keep[1] + off_top * dy, zmid};
  double side = dot(A.n, xk) - A.c;
  if (side == 0) side = -reach;  // the other end lies on it: keep the side away from the extension
  if (reach > 0) {
    const double grow = 1.1 * reach + 0.01 * len + 1.0;
    const P2 moved{end[0] + grow * u[0], end[1] + grow * u[1]};
    (at_last ? part.back() : part.front()) = moved;
  }
  auto panels = plain_panels(ext);
  const double s = side > 0 ? 1.0 : -1.0;  // inside: s * (n . x - c) >= 0
  for (auto& p : panels) p.bounds.push_back({scaled(A.n, -s), -s * A.c});
  return panels;
}

namespace fault_cut {

std::vector<std::vector<CutPanel>> panels_of(const Mesh& mesh, const std::vector<FaultTrace>& traces) {
  std::vector<std::vector<CutPanel>> panels;
  for (const auto& tr : traces) {
    if (mesh.find_physical(2, "fault:" + tr.name))
      throw InputError(tr.where, fmt::format("fault '{}': the mesh already has a group fault:{}", tr.name, tr.name));
    panels.push_back(fault_cut_panels(tr, traces));
  }
  return panels;
}

}  // namespace fault_cut
}  // namespace ugs
