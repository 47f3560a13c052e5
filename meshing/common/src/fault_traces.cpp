// Fault traces: checks (no self-intersection) and the planar panels of the swept surface.
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/meshing/fault_traces.hpp"
#include "ugs/meshing/vec3.hpp"

namespace ugs {
namespace {

using namespace vec3;

using P2 = std::array<double, 2>;
constexpr double kPi = 3.14159265358979323846;

double orient2(const P2& a, const P2& b, const P2& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

// Does segment (a, b) meet segment (c, d), touching included? `eps` is an area tolerance.
bool segments_meet(const P2& a, const P2& b, const P2& c, const P2& d, double eps) {
  const double o1 = orient2(a, b, c), o2 = orient2(a, b, d), o3 = orient2(c, d, a), o4 = orient2(c, d, b);
  auto sgn = [eps](double v) { return v > eps ? 1 : (v < -eps ? -1 : 0); };
  const int s1 = sgn(o1), s2 = sgn(o2), s3 = sgn(o3), s4 = sgn(o4);
  if (s1 * s2 < 0 && s3 * s4 < 0) return true;
  auto on = [](const P2& p, const P2& q, const P2& r) {  // r within the box of p-q (collinear case)
    return std::min(p[0], q[0]) <= r[0] + 1e-12 && r[0] <= std::max(p[0], q[0]) + 1e-12 &&
           std::min(p[1], q[1]) <= r[1] + 1e-12 && r[1] <= std::max(p[1], q[1]) + 1e-12;
  };
  if (s1 == 0 && on(a, b, c)) return true;
  if (s2 == 0 && on(a, b, d)) return true;
  if (s3 == 0 && on(c, d, a)) return true;
  if (s4 == 0 && on(c, d, b)) return true;
  return false;
}

// Where two meeting segments meet: the crossing point, or an end lying on the other segment.
P2 meeting_point(const P2& a, const P2& b, const P2& c, const P2& d) {
  const P2 u{b[0] - a[0], b[1] - a[1]}, v{d[0] - c[0], d[1] - c[1]};
  const double den = u[0] * v[1] - u[1] * v[0];
  if (den != 0) {
    const double r = ((c[0] - a[0]) * v[1] - (c[1] - a[1]) * v[0]) / den;
    if (r >= 0 && r <= 1) return {a[0] + r * u[0], a[1] + r * u[1]};
  }
  auto dist = [](const P2& p, const P2& q, const P2& x) {  // from x to segment p-q
    const P2 w{q[0] - p[0], q[1] - p[1]};
    const double l = w[0] * w[0] + w[1] * w[1];
    const double r = l > 0 ? std::clamp(((x[0] - p[0]) * w[0] + (x[1] - p[1]) * w[1]) / l, 0.0, 1.0) : 0.0;
    return std::hypot(p[0] + r * w[0] - x[0], p[1] + r * w[1] - x[1]);
  };
  P2 best = a;
  double bd = dist(c, d, a);
  auto consider = [&](const P2& p, const P2& q, const P2& x) {
    if (const double e = dist(p, q, x); e < bd) {
      bd = e;
      best = x;
    }
  };
  consider(c, d, b);
  consider(a, b, c);
  consider(a, b, d);
  return best;
}

}  // namespace

void check_fault_trace(FaultTrace& tr) {
  const std::string who = fmt::format("fault '{}'", tr.name);
  auto fail = [&](const std::string& msg) { return InputError(tr.where, who + ": " + msg); };
  if (tr.name.empty()) throw InputError(tr.where, "a fault trace has no name");
  for (double v : {tr.top, tr.bottom, tr.dip_deg, tr.dip_dir_deg, tr.trace_z})
    if (!std::isfinite(v)) throw fail("top_m, bottom_m, dip_deg, dip_dir_deg and trace_z_m must be finite numbers");
  if (tr.surface && !(tr.top > tr.bottom))
    throw fail(fmt::format("its surface is flat (every vertex at elevation {:.1f} m): a fault surface must span a depth range",
                           tr.top));
  if (!(tr.top > tr.bottom))
    throw fail(fmt::format("top_m ({:.1f}) must lie above bottom_m ({:.1f})", tr.top, tr.bottom));
  if (!(tr.dip_deg > 0 && tr.dip_deg <= 90))
    throw fail(fmt::format("dip_deg {} is outside (0, 90] (a horizontal fault has no trace)", tr.dip_deg));
  tr.dip_dir_deg = std::fmod(std::fmod(tr.dip_dir_deg, 360.0) + 360.0, 360.0);
  if (!tr.pieces.empty()) {
    double above = tr.top;
    for (std::size_t i = 0; i < tr.pieces.size(); ++i) {
      const auto& pc = tr.pieces[i];
      if (!std::isfinite(pc.bottom) || !std::isfinite(pc.dip_deg))
        throw fail(fmt::format("listric piece {}: bottom_m and dip_deg must be finite numbers", i + 1));
      if (!(pc.dip_deg > 0 && pc.dip_deg <= 90))
        throw fail(fmt::format("listric piece {}: dip_deg {} is outside (0, 90]", i + 1, pc.dip_deg));
      if (!(pc.bottom < above))
        throw fail(fmt::format("listric piece {}: bottom_m ({:.1f}) must lie below the piece above ({:.1f})", i + 1,
                               pc.bottom, above));
      above = pc.bottom;
    }
    if (std::abs(tr.pieces.back().bottom - tr.bottom) > 1e-9 * (1 + std::abs(tr.bottom)))
      throw fail(fmt::format("the last listric piece ends at {:.1f}, not at bottom_m ({:.1f})", tr.pieces.back().bottom,
                             tr.bottom));
    tr.pieces.back().bottom = tr.bottom;
    tr.dip_deg = tr.pieces.front().dip_deg;
  }
  if (tr.parts.empty()) throw fail("the trace has no line");
  // Drop repeated consecutive points.
  double scale = 0;
  for (auto& part : tr.parts) {
    std::vector<P2> clean;
    for (const auto& p : part) {
      if (!std::isfinite(p[0]) || !std::isfinite(p[1])) throw fail("the trace has a point that is not a number");
      if (clean.empty() || std::hypot(p[0] - clean.back()[0], p[1] - clean.back()[1]) > 1e-9 * (1 + std::abs(p[0]) + std::abs(p[1])))
        clean.push_back(p);
      scale = std::max({scale, std::abs(p[0]), std::abs(p[1])});
    }
    if (clean.size() < 2) throw fail("a part of the trace has fewer than two distinct points");
    part = std::move(clean);
  }
  // Self-intersection: every pair of segments except neighbours sharing their common point.
  struct Seg {
    P2 a, b;
    std::size_t part, index, count;
  };
  std::vector<Seg> segs;
  for (std::size_t p = 0; p < tr.parts.size(); ++p)
    for (std::size_t i = 0; i + 1 < tr.parts[p].size(); ++i)
      segs.push_back({tr.parts[p][i], tr.parts[p][i + 1], p, i, tr.parts[p].size() - 1});
  std::sort(segs.begin(), segs.end(), [](const Seg& x, const Seg& y) {
    return std::min(x.a[0], x.b[0]) < std::min(y.a[0], y.b[0]);
  });
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const Seg& s = segs[i];
    const double xmax = std::max(s.a[0], s.b[0]);
    for (std::size_t j = i + 1; j < segs.size(); ++j) {
      const Seg& r = segs[j];
      if (std::min(r.a[0], r.b[0]) > xmax) break;
      const double len = std::max(std::hypot(s.b[0] - s.a[0], s.b[1] - s.a[1]), std::hypot(r.b[0] - r.a[0], r.b[1] - r.a[1]));
      const double eps = 1e-12 * len * (len + scale);
      const bool same = s.part == r.part;
      const std::size_t lo = std::min(s.index, r.index), hi = std::max(s.index, r.index);
      const bool closed = same && tr.parts[s.part].front() == tr.parts[s.part].back();
      const bool neighbours = same && (hi == lo + 1 || (closed && lo == 0 && hi == s.count - 1));
      bool bad;
      P2 where{};
      if (neighbours) {
        // They share one point; they must not run back over each other.
        const Seg& first = s.index == lo ? s : r;
        const Seg& second = s.index == lo ? r : s;
        const bool wrap = hi != lo + 1;  // last and first segments of a closed part: they share first.a
        where = wrap ? first.a : first.b;
        const P2 u = wrap ? P2{first.b[0] - first.a[0], first.b[1] - first.a[1]} : P2{first.a[0] - first.b[0], first.a[1] - first.b[1]};
        const P2 v = wrap ? P2{second.a[0] - second.b[0], second.a[1] - second.b[1]} : P2{second.b[0] - second.a[0], second.b[1] - second.a[1]};
        const double c = u[0] * v[1] - u[1] * v[0], d = u[0] * v[0] + u[1] * v[1];
        bad = std::abs(c) <= 1e-12 * std::hypot(u[0], u[1]) * std::hypot(v[0], v[1]) && d > 0;
      } else {
        bad = segments_meet(s.a, s.b, r.a, r.b, eps);
        where = meeting_point(s.a, s.b, r.a, r.b);
      }
      if (bad)
        throw fail(fmt::format("the trace {} near ({:.2f}, {:.2f}): the fault surface would intersect itself",
                               same ? "crosses itself" : "touches another of its parts", where[0], where[1]));
    }
  }
}

bool FaultTrace::vertical() const {
  for (const auto& p : piece_list())
    if (p.dip_deg < 90) return false;
  return true;
}

std::vector<FaultTrace::Piece> FaultTrace::piece_list() const {
  if (!pieces.empty()) return pieces;
  return {Piece{bottom, dip_deg}};
}

namespace {
double cot_deg(double dip_deg) {
  if (dip_deg >= 90) return 0.0;
  const double d = dip_deg * kPi / 180;
  return std::cos(d) / std::sin(d);
}
}  // namespace

double FaultTrace::offset_at(double z) const {
  // Piece tops, top to bottom; the offset is the integral of cot(dip) from trace_z down to z.
  const auto pcs = piece_list();
  auto integral_from_top = [&](double zz) {  // offset at zz relative to the surface at `top`
    double off = 0, above = top;
    for (std::size_t i = 0; i < pcs.size(); ++i) {
      const bool last = i + 1 == pcs.size();
      const double below = last ? -std::numeric_limits<double>::infinity() : pcs[i].bottom;
      const double c = cot_deg(pcs[i].dip_deg);
      if (i == 0 && zz > above) return -(zz - above) * c;  // above the top: first piece extended
      if (zz >= below) return off + (above - zz) * c;
      off += (above - below) * c;
      above = below;
    }
    return off;
  };
  return integral_from_top(z) - integral_from_top(trace_z);
}

FaultSurface::FaultSurface(const FaultTrace& tr) {
  const double az = tr.dip_dir_deg * kPi / 180;
  const double dx = std::sin(az), dy = std::cos(az);  // horizontal dip direction (azimuth from north)
  t0_ = tr.trace_z - tr.top;
  t1_ = tr.trace_z - tr.bottom;
  open_ends_ = !tr.ends_against.empty();
  const auto pcs = tr.piece_list();
  {
    const double dip = pcs.front().dip_deg * kPi / 180;
    normal_ = {-dx * std::sin(dip), -dy * std::sin(dip), -std::cos(dip)};
  }
  double above = tr.top;
  for (std::size_t j = 0; j < pcs.size(); ++j) {
    const double cot = cot_deg(pcs[j].dip_deg);
    const double below = pcs[j].bottom;
    // The piece's plane at elevation trace_z: the offset at its top minus its own run up to trace_z.
    const double off = tr.offset_at(above) - (tr.trace_z - above) * cot;
    const Point3 w{dx * cot, dy * cot, -1.0};
    for (const auto& part : tr.parts)
      for (std::size_t i = 0; i + 1 < part.size(); ++i) {
        Panel p;
        p.a = {part[i][0] + off * dx, part[i][1] + off * dy, tr.trace_z};
        p.e = {part[i + 1][0] - part[i][0], part[i + 1][1] - part[i][1], 0.0};
        p.w = w;
        const Point3 c = cross(p.e, p.w);
        p.area_scale = std::sqrt(dot(c, c));
        p.n = {c[0] / p.area_scale, c[1] / p.area_scale, c[2] / p.area_scale};
        p.ee = dot(p.e, p.e);
        p.ew = dot(p.e, p.w);
        p.ww = dot(p.w, p.w);
        p.det = p.ee * p.ww - p.ew * p.ew;
        p.length = std::sqrt(p.ee);
        p.first = i == 0;
        p.last = i + 2 == part.size();
        p.t0 = tr.trace_z - above;
        p.t1 = tr.trace_z - below;
        p.piece = j;
        constexpr double inf = std::numeric_limits<double>::infinity();
        p.bbox = {inf, inf, inf, -inf, -inf, -inf};
        for (double s : {0.0, 1.0})
          for (double t : {p.t0, p.t1})
            for (int k = 0; k < 3; ++k) {
              const double x = p.a[k] + s * p.e[k] + t * p.w[k];
              p.bbox[k] = std::min(p.bbox[k], x);
              p.bbox[k + 3] = std::max(p.bbox[k + 3], x);
            }
        panels_.push_back(p);
      }
    above = below;
  }
}

FaultSurface::Local FaultSurface::local(std::size_t i, const Point3& x) const {
  const Panel& p = panels_[i];
  const Point3 r{x[0] - p.a[0], x[1] - p.a[1], x[2] - p.a[2]};
  const double re = dot(r, p.e), rw = dot(r, p.w);
  Local l;
  l.h = dot(r, p.n);
  l.s = (re * p.ww - rw * p.ew) / p.det;
  l.t = (rw * p.ee - re * p.ew) / p.det;
  return l;
}

double FaultSurface::distance(const Point3& x, bool within_depth) const {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < panels_.size(); ++i) {
    const Local l = local(i, x);
    const Panel& p = panels_[i];
    // A listric panel extends up and down only at the top and bottom of the fault.
    const double lo = within_depth || p.piece > 0 ? p.t0 : -std::numeric_limits<double>::infinity();
    const double hi = within_depth || p.t1 < t1_ ? p.t1 : std::numeric_limits<double>::infinity();
    constexpr double inf = std::numeric_limits<double>::infinity();
    const double s = std::clamp(l.s, p.first && open_ends_ ? -inf : 0.0, p.last && open_ends_ ? inf : 1.0);
    const double t = std::clamp(l.t, lo, hi);
    Point3 q;
    for (int k = 0; k < 3; ++k) q[k] = p.a[k] + s * p.e[k] + t * p.w[k] - x[k];
    best = std::min(best, std::sqrt(dot(q, q)));
  }
  return best;
}

std::array<double, 6> FaultSurface::bbox() const {
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::array<double, 6> b{inf, inf, inf, -inf, -inf, -inf};
  for (const auto& p : panels_)
    for (int k = 0; k < 3; ++k) {
      b[k] = std::min(b[k], p.bbox[k]);
      b[k + 3] = std::max(b[k + 3], p.bbox[k + 3]);
    }
  return b;
}

}  // namespace ugs
