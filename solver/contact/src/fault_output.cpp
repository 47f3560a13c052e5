#include "ugs/contact/fault_output.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/fields.hpp"

namespace ugs::contact {
namespace {

// Local (t1, t2, n) -> global.
std::array<double, 3> to_global(const std::array<double, 9>& R, double a, double b, double c) {
  return {R[0] * a + R[1] * b + R[2] * c, R[3] * a + R[4] * b + R[5] * c, R[6] * a + R[7] * b + R[8] * c};
}

}  // namespace

FaultFields derive_fault_fields(const FaultModel& fm, const PairResults& r) {
  const std::size_t n = fm.pairs.size();
  FaultFields f;
  for (auto* v : {&f.traction, &f.tau, &f.slip, &f.u_r}) v->resize(3 * n);
  for (auto* v : {&f.sigma_n, &f.sigma_n_eff, &f.tau_abs, &f.slip_abs, &f.opening, &f.state, &f.chi, &f.cfs_change, &f.p_fault})
    v->resize(n);
  for (std::size_t q = 0; q < n; ++q) {
    const NodePair& p = fm.pairs[q];
    const FaultProperties& fp = fm.faults[p.fault];
    const double* l = &r.lambda[3 * q];
    const double* g = &r.g[3 * q];
    const auto t = to_global(p.R, l[0], l[1], l[2]);
    const auto ts = to_global(p.R, l[0], l[1], 0.0);
    const auto s = to_global(p.R, g[0], g[1], 0.0);
    const auto ur = to_global(p.R, g[0], g[1], g[2]);
    for (int k = 0; k < 3; ++k) f.traction[3 * q + k] = t[k], f.tau[3 * q + k] = ts[k], f.slip[3 * q + k] = s[k], f.u_r[3 * q + k] = ur[k];
    const PairState st = static_cast<PairState>(r.state[q]);
    f.sigma_n[q] = l[2];
    f.p_fault[q] = r.p_f[q];
    f.sigma_n_eff[q] = l[2] + r.p_f[q];
    f.tau_abs[q] = std::hypot(l[0], l[1]);
    f.slip_abs[q] = std::hypot(g[0], g[1]);
    f.opening[q] = g[2];
    f.state[q] = static_cast<double>(r.state[q]);
    f.chi[q] = safety_factor(f.tau_abs[q], f.sigma_n_eff[q], fp.cohesion, fp.mu, st);
    const double tau0 = std::hypot(p.lambda0[0], p.lambda0[1]), sn0 = p.lambda0[2] + p.p0;
    f.cfs_change[q] = (f.tau_abs[q] - tau0) + fp.mu * (f.sigma_n_eff[q] - sn0);
  }
  return f;
}

std::vector<FaultDateStats> fault_date_stats(const FaultModel& fm, const FaultFields& f) {
  std::vector<FaultDateStats> s(fm.faults.size());
  for (std::size_t q = 0; q < fm.pairs.size(); ++q) {
    const NodePair& p = fm.pairs[q];
    if (!p.frictional()) continue;
    FaultDateStats& d = s[p.fault];
    ++d.pairs;
    if (f.chi[q] > d.max_chi || d.pairs == 1) d.max_chi = f.chi[q], d.at = p.x;
    d.max_slip = std::max(d.max_slip, f.slip_abs[q]);
    d.max_opening = std::max(d.max_opening, f.opening[q]);
    d.max_cfs_change = std::max(d.max_cfs_change, f.cfs_change[q]);
    if (f.state[q] == 1) ++d.slipping, d.slip_area += p.reported_area;
    if (f.state[q] == 2) ++d.open, d.open_area += p.reported_area;
  }
  for (auto& d : s)
    if (d.pairs == 0) d.max_cfs_change = 0;
  return s;
}

FaultPlaneCoordinates fault_plane_coordinates(const FaultModel& fm) {
  const FaultSurface& S = fm.surface;
  const std::size_t nf = fm.faults.size(), nn = S.mesh.num_nodes();
  FaultPlaneCoordinates c;
  c.along_strike.assign(nn, 0.0);
  c.down_dip.assign(nn, 0.0);
  c.strike.assign(nf, {1.0, 0.0, 0.0});
  c.dip_deg.assign(nf, 0.0);
  std::vector<std::array<double, 3>> normal(nf, {0.0, 0.0, 0.0});
  for (const NodePair& p : fm.pairs)
    for (int k = 0; k < 3; ++k) normal[p.fault][k] += p.area * p.R[3 * k + 2];
  std::vector<std::int32_t> node_fault(nn, -1);
  for (std::size_t t = 0; t < S.triangles.size(); ++t)
    for (auto v : S.triangles[t]) node_fault[v] = S.triangle_fault[t];
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& n = normal[f];
    const double nh = std::hypot(n[0], n[1]), nl = std::sqrt(nh * nh + n[2] * n[2]);
    const bool horizontal = !(nh > 1e-3 * nl);
    double sx = 1, sy = 0, sin_dip = 1;
    if (!horizontal) {
      sx = -n[1] / nh, sy = n[0] / nh;
      if (sx < 0 || (sx == 0 && sy < 0)) sx = -sx, sy = -sy;  // eastwards (northwards)
      sx += 0.0, sy += 0.0;                                    // no -0 in the comments
      sin_dip = nh / nl;
      c.dip_deg[f] = std::atan2(nh, std::abs(n[2])) * 180 / M_PI;
    }
    c.strike[f] = {sx, sy, 0.0};
    double s0 = INFINITY, top = -INFINITY;
    for (std::size_t i = 0; i < nn; ++i) {
      if (node_fault[i] != static_cast<std::int32_t>(f)) continue;
      const Point3& x = S.mesh.nodes[i];
      s0 = std::min(s0, x[0] * sx + x[1] * sy);
      top = std::max(top, horizontal ? x[1] : x[2]);
    }
    for (std::size_t i = 0; i < nn; ++i) {
      if (node_fault[i] != static_cast<std::int32_t>(f)) continue;
      const Point3& x = S.mesh.nodes[i];
      c.along_strike[i] = x[0] * sx + x[1] * sy - s0;
      c.down_dip[i] = horizontal ? top - x[1] : (top - x[2]) / sin_dip;
    }
  }
  return c;
}

std::string fault_file_name(const std::string& name) {
  std::string s = name;
  for (char& ch : s)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_' && ch != '.') ch = '_';
  return s;
}

struct FaultOutput::Impl {
  const FaultModel* fm = nullptr;
  std::unique_ptr<FieldSeriesWriter> h5;
  std::unique_ptr<CsvWriter> csv;
  // Surface nodes that show a node pair's values directly (pair index), or -1: those take the
  // mean of `neighbours` (tips, pairs on prescribed boundaries).
  std::vector<std::int64_t> direct;
  std::vector<std::vector<std::uint32_t>> neighbours;
  FaultPlaneCoordinates plane;
  // Per-pair CSVs: one per fault, and the surface nodes of its node pairs (surface order).
  std::vector<std::unique_ptr<CsvWriter>> pair_csv;
  std::vector<std::vector<std::uint32_t>> pair_nodes;

  // Node values (k per surface node) from per-pair values.
  // Filled in passes: first from the node pairs, then from nodes filled in the pass before (a
  // corner triangle of tip nodes takes the values of the next ring).
  std::vector<double> nodes(const std::vector<double>& v, int k, bool largest) const {
    const std::size_t n = direct.size();
    std::vector<double> out(k * n, 0.0);
    std::vector<char> filled(n, 0);
    for (std::size_t i = 0; i < n; ++i)
      if (direct[i] >= 0) {
        for (int c = 0; c < k; ++c) out[k * i + c] = v[k * direct[i] + c];
        filled[i] = 1;
      }
    for (bool more = true; more;) {
      more = false;
      std::vector<std::size_t> now;
      for (std::size_t i = 0; i < n; ++i) {
        if (filled[i]) continue;
        std::size_t m = 0;
        for (auto j : neighbours[i]) m += filled[j] != 0;
        if (!m) continue;
        for (int c = 0; c < k; ++c) {
          double acc = largest ? -1e300 : 0.0;
          for (auto j : neighbours[i])
            if (filled[j]) acc = largest ? std::max(acc, out[k * j + c]) : acc + out[k * j + c];
          out[k * i + c] = largest ? acc : acc / static_cast<double>(m);
        }
        now.push_back(i);
      }
      for (auto i : now) filled[i] = 1;
      more = !now.empty();
    }
    return out;
  }

  std::vector<double> cells(const std::vector<double>& nv, int k, bool largest) const {
    const auto& tri = fm->surface.triangles;
    std::vector<double> out(k * tri.size());
    for (std::size_t t = 0; t < tri.size(); ++t)
      for (int c = 0; c < k; ++c) {
        const double a = nv[k * tri[t][0] + c], b = nv[k * tri[t][1] + c], d = nv[k * tri[t][2] + c];
        out[k * t + c] = largest ? std::max({a, b, d}) : (a + b + d) / 3;
      }
    return out;
  }
};

FaultOutput::FaultOutput(const std::string& h5_path, const std::string& csv_path, const FaultModel& fm,
                         const std::vector<std::string>& comments, const std::string& pairs_prefix)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.fm = &fm;
  const FaultSurface& S = fm.surface;
  const std::size_t n = S.node_pair.size();
  s.direct.assign(n, -1);
  for (std::size_t i = 0; i < n; ++i)
    if (S.node_pair[i] >= 0 && fm.pairs[S.node_pair[i]].frictional()) s.direct[i] = S.node_pair[i];
  s.neighbours.resize(n);
  for (const auto& t : S.triangles)
    for (int a = 0; a < 3; ++a)
      if (s.direct[t[a]] < 0)
        for (int b = 0; b < 3; ++b)
          if (b != a) s.neighbours[t[a]].push_back(t[b]);
  for (auto& v : s.neighbours) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  if (!h5_path.empty()) {
    FieldSeriesOptions o;
    o.cell_types = {ElementType::Triangle};
    s.h5 = std::make_unique<FieldSeriesWriter>(h5_path, S.mesh, o);
  }
  if (!csv_path.empty())
    s.csv = std::make_unique<CsvWriter>(
        csv_path,
        std::vector<std::string>{"date", "fault", "max_chi", "x_m", "y_m", "z_m", "max_slip_mm", "slip_area_m2", "open_area_m2",
                                 "max_opening_mm", "max_cfs_change_MPa", "node_pairs", "slipping", "open"},
        comments);
  s.plane = fault_plane_coordinates(fm);
  if (!pairs_prefix.empty()) {
    s.pair_nodes.resize(fm.faults.size());
    for (std::size_t i = 0; i < n; ++i)
      if (S.node_pair[i] >= 0) s.pair_nodes[fm.pairs[S.node_pair[i]].fault].push_back(static_cast<std::uint32_t>(i));
    // Two fault names that become one file name ("a b", "a_b") would overwrite each other.
    std::map<std::string, std::string> file_of;
    for (const auto& fp : fm.faults)
      if (auto [it, fresh] = file_of.emplace(fault_file_name(fp.name), fp.name); !fresh)
        throw InputError(pairs_prefix + "<fault>.csv", fmt::format("faults '{}' and '{}' would both write {}{}.csv (rename one)",
                                                          it->second, fp.name, pairs_prefix, it->first));
    for (std::size_t f = 0; f < fm.faults.size(); ++f) {
      const auto& st = s.plane.strike[f];
      std::vector<std::string> c{
          fmt::format("ugs-solve fault {}: one row per node pair and output date; units m, MPa, mm; tension positive", fm.faults[f].name),
          fmt::format("along_strike_m: from the fault's {} end along the strike ({:.6f}, {:.6f}, 0); down_dip_m: from its top edge, "
                      "in its mean plane (dip {:.3f} deg)", st[0] > 1e-12 ? "west" : "south", st[0], st[1], s.plane.dip_deg[f]),
          "state: stick, slip or open; chi = |tau| / (c - sigma'_n tan(phi)), 1 in slip or open; interpolated = 1: the pair lies on a "
          "prescribed boundary and shows the mean of its neighbours (as the HDF5 node fields)"};
      if (!comments.empty()) c.push_back(comments.back());
      s.pair_csv.push_back(std::make_unique<CsvWriter>(
          pairs_prefix + fault_file_name(fm.faults[f].name) + ".csv",
          std::vector<std::string>{"date", "node", "x_m", "y_m", "z_m", "along_strike_m", "down_dip_m", "area_m2", "state", "tau_MPa",
                                   "sigma_n_eff_MPa", "chi", "slip_mm", "opening_mm", "cfs_change_MPa", "p_fault_MPa", "interpolated"},
          c));
    }
  }
}

FaultOutput::~FaultOutput() = default;

void FaultOutput::add(const std::string& date, double time, const FaultFields& f, bool write_fields, bool write_pairs) {
  Impl& s = *impl_;
  if (s.csv) {
    const auto stats = fault_date_stats(*s.fm, f);
    for (std::size_t k = 0; k < stats.size(); ++k) {
      const auto& d = stats[k];
      s.csv->text(date).text(s.fm->faults[k].name).number(d.max_chi, 6);
      s.csv->number(d.at[0], 2).number(d.at[1], 2).number(d.at[2], 2);
      s.csv->number(d.max_slip * 1e3, 6).number(d.slip_area, 1).number(d.open_area, 1).number(d.max_opening * 1e3, 6);
      s.csv->number(d.max_cfs_change * 1e-6, 6);
      s.csv->integer(static_cast<std::int64_t>(d.pairs)).integer(static_cast<std::int64_t>(d.slipping));
      s.csv->integer(static_cast<std::int64_t>(d.open)).end_row();
    }
  }
  const bool h5 = write_fields && s.h5, pairs = write_pairs && !s.pair_csv.empty();
  if (!h5 && !pairs) return;
  // Node values: the pairs' own, and the means of their neighbours at tips and prescribed pairs.
  std::vector<Field> nf, cf;
  auto add = [&](const char* name, const std::vector<double>& v, int k, bool largest = false) {
    auto nv = s.nodes(v, k, largest);
    cf.push_back({name, k, s.cells(nv, k, largest)});
    nf.push_back({name, k, std::move(nv)});
  };
  add("traction", f.traction, 3);
  add("sigma_n", f.sigma_n, 1);
  add("sigma_n_eff", f.sigma_n_eff, 1);
  add("tau", f.tau, 3);
  add("tau_abs", f.tau_abs, 1);
  add("slip", f.slip, 3);
  add("slip_abs", f.slip_abs, 1);
  add("opening", f.opening, 1);
  add("u_r", f.u_r, 3);
  add("state", f.state, 1, true);
  add("chi", f.chi, 1);
  add("cfs_change", f.cfs_change, 1);
  add("p_fault", f.p_fault, 1);
  // Where node values are the mean of their neighbours (tip nodes, pairs on prescribed boundaries).
  std::vector<double> interp(s.direct.size());
  for (std::size_t i = 0; i < interp.size(); ++i) interp[i] = s.direct[i] < 0 ? 1.0 : 0.0;
  nf.push_back({"interpolated", 1, std::move(interp)});
  nf.push_back({"along_strike", 1, s.plane.along_strike});
  nf.push_back({"down_dip", 1, s.plane.down_dip});
  if (pairs) {
    auto field = [&](const char* name) -> const std::vector<double>& {
      for (const auto& x : nf)
        if (x.name == name) return x.values;
      throw std::logic_error(std::string("fault output: no node field ") + name);
    };
    const auto &state = field("state"), &tau = field("tau_abs"), &sne = field("sigma_n_eff"), &chi = field("chi");
    const auto &slip = field("slip_abs"), &opening = field("opening"), &cfs = field("cfs_change"), &pf = field("p_fault");
    const auto& interp_v = field("interpolated");
    static const char* kState[3] = {"stick", "slip", "open"};
    const Mesh& M = s.fm->surface.mesh;
    for (std::size_t k = 0; k < s.pair_csv.size(); ++k) {
      CsvWriter& w = *s.pair_csv[k];
      for (auto i : s.pair_nodes[k]) {
        const Point3& x = M.nodes[i];
        const int st = std::clamp(static_cast<int>(std::lround(state[i])), 0, 2);
        w.text(date).integer(static_cast<std::int64_t>(M.node_tags[i]));
        w.number(x[0]).number(x[1]).number(x[2]).number(s.plane.along_strike[i]).number(s.plane.down_dip[i]);
        w.number(s.fm->pairs[s.fm->surface.node_pair[i]].reported_area);
        w.text(kState[st]).number(tau[i] * 1e-6).number(sne[i] * 1e-6).number(chi[i]).number(slip[i] * 1e3);
        w.number(opening[i] * 1e3).number(cfs[i] * 1e-6).number(pf[i] * 1e-6).integer(interp_v[i] != 0 ? 1 : 0).end_row();
      }
    }
  }
  if (h5) s.h5->add_step(date, time, nf, cf);
}

void FaultOutput::commit() {
  if (impl_->h5) impl_->h5->commit();
  if (impl_->csv) impl_->csv->commit();
  for (auto& w : impl_->pair_csv) w->commit();
}

}  // namespace ugs::contact
