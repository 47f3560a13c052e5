// Fault traces: checks (no self-intersection) and the planar panels of the swept surface.
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/meshing/fault_traces.hpp"

namespace ugs {
namespace {

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

Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

void check_fault_trace(FaultTrace& tr) {
  const std::string who = fmt::format("fault '{}'", tr.name);
  auto fail = [&](const std::string& msg) { return InputError(tr.where, who + ": " + msg); };
  if (tr.name.empty()) throw InputError(tr.where, "a fault trace has no name");
  for (double v : {tr.top, tr.bottom, tr.dip_deg, tr.dip_dir_deg, tr.trace_z})
    if (!std::isfinite(v)) throw fail("top_m, bottom_m, dip_deg, dip_dir_deg and trace_z_m must be finite numbers");
  if (!(tr.top > tr.bottom))
    throw fail(fmt::format("top_m ({:.1f}) must lie above bottom_m ({:.1f})", tr.top, tr.bottom));
  if (!(tr.dip_deg > 0 && tr.dip_deg <= 90))
    throw fail(fmt::format("dip_deg {} is outside (0, 90] (a horizontal fault has no trace)", tr.dip_deg));
  tr.dip_dir_deg = std::fmod(std::fmod(tr.dip_dir_deg, 360.0) + 360.0, 360.0);
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

FaultSurface::FaultSurface(const FaultTrace& tr) {
  const double dip = tr.dip_deg * kPi / 180, az = tr.dip_dir_deg * kPi / 180;
  const double dx = std::sin(az), dy = std::cos(az);  // horizontal dip direction (azimuth from north)
  const double cot = tr.dip_deg >= 90 ? 0.0 : std::cos(dip) / std::sin(dip);
  t0_ = tr.trace_z - tr.top;
  t1_ = tr.trace_z - tr.bottom;
  normal_ = {-dx * std::sin(dip), -dy * std::sin(dip), -std::cos(dip)};
  const Point3 w{dx * cot, dy * cot, -1.0};
  for (const auto& part : tr.parts)
    for (std::size_t i = 0; i + 1 < part.size(); ++i) {
      Panel p;
      p.a = {part[i][0], part[i][1], tr.trace_z};
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
      constexpr double inf = std::numeric_limits<double>::infinity();
      p.bbox = {inf, inf, inf, -inf, -inf, -inf};
      for (double s : {0.0, 1.0})
        for (double t : {t0_, t1_})
          for (int k = 0; k < 3; ++k) {
            const double x = p.a[k] + s * p.e[k] + t * p.w[k];
            p.bbox[k] = std::min(p.bbox[k], x);
            p.bbox[k + 3] = std::max(p.bbox[k + 3], x);
          }
      panels_.push_back(p);
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
    const double s = std::clamp(l.s, 0.0, 1.0), t = within_depth ? std::clamp(l.t, t0_, t1_) : l.t;
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
