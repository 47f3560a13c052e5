// Stress pictures (thesis 4.3.2): the change of the normal stresses over each phase, normalized by
// the initial pressure of the pool, along the sections A-A and B-B with vertical exaggeration
// (figures 4.27-4.32) and in the cells just above the top of the pool's layer (4.33-4.35); and the
// height above that top where the change of sigma_z falls below 1 % of its peak in the layer.
#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "report.hpp"
#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/insar/inputs.hpp"
#include "ugs/insar/npy.hpp"
#include "ugs/insar/sections.hpp"

namespace ugs::report {

namespace {

const PoolSpec* stress_pool(const Context& c) {
  if (!c.cs || c.cs->pools.empty()) return nullptr;
  const std::string want = wanted_stress_pool(c);
  for (const auto& p : c.cs->pools)
    if (p.name == want) return &p;
  if (!c.opt.stress_pool.empty()) {
    std::string names;
    for (const auto& p : c.cs->pools) names += (names.empty() ? "" : ", ") + p.name;
    throw InputError("--stress-pool", fmt::format("no pool '{}' in {} (pools: {})", want, c.cs->path, names));
  }
  return &c.cs->pools.back();
}

// p0 [Pa]: the option, else the pool's reference pressure, else its schedule's first value.
double reference_pressure(const Context& c, const PoolSpec* pool) {
  if (c.opt.reference_pressure_MPa > 0) return c.opt.reference_pressure_MPa * 1e6;
  if (!pool) return 0;
  if (pool->reference_pressure_Pa) return *pool->reference_pressure_Pa;
  const CsvTable t = CsvTable::read(pool->schedule);
  if (t.rows() && pool->column == "p_MPa") return t.number(0, t.column("p_MPa")) * 1e6;
  return 0;
}

}  // namespace

void build_stress(Context& c) {
  const auto& r = *c.results;
  const auto names = r.cell_field_names(0);
  std::string field = c.opt.stress_field;
  if (field.empty())
    for (const char* n : {"stress_change", "dstress", "stress"})
      if (std::find(names.begin(), names.end(), n) != names.end()) {
        field = n;
        break;
      }
  if (field.empty() || std::find(names.begin(), names.end(), field) == names.end()) {
    if (!c.opt.stress_field.empty()) throw InputError(c.opt.results, fmt::format("no cell field '{}'", field));
    c.notes.push_back("the results hold no stress field (stress_change, dstress or stress): stress pictures skipped");
    return;
  }
  // Tetrahedra and where their rows start among the written cells.
  const auto x = r.coordinates();
  const auto tags = r.node_tags();
  const auto flat = r.cells(ElementType::Tetrahedron);
  std::vector<insar::Tet> tets(flat.size() / 4);
  for (std::size_t i = 0; i < tets.size(); ++i) tets[i] = {flat[4 * i], flat[4 * i + 1], flat[4 * i + 2], flat[4 * i + 3]};
  if (tets.empty()) {
    c.notes.push_back("the results hold no tetrahedra: stress pictures skipped");
    return;
  }
  std::size_t row0 = 0;
  for (ElementType t : r.cell_types()) {
    if (t == ElementType::Tetrahedron) break;
    row0 += r.cells(t).size() / static_cast<std::size_t>(nodes_per_element(t));
  }
  const PoolSpec* pool = stress_pool(c);
  const double p0 = reference_pressure(c, pool);
  const double norm = p0 > 0 ? p0 : 1e6;
  const std::string unit = p0 > 0 ? fmt::format("p0 = {:.4g} MPa", p0 / 1e6) : "MPa";
  if (p0 <= 0) c.notes.push_back("no reference pressure (case pool or --reference-pressure-MPa): stress changes shown in MPa");

  // The pool's layer (the pool's materials and its aquifers), by the cells' physical names.
  // The other pools' materials and aquifers have a pressure change of their own: the confinement
  // height leaves them out (insar::confinement_height).
  std::vector<char> in_layer, own_load;
  std::string layer_name;
  if (pool && c.mesh) {
    std::set<std::string> mats(pool->materials.begin(), pool->materials.end()), others;
    mats.insert(pool->aquifer_materials.begin(), pool->aquifer_materials.end());
    for (const auto& q : c.cs->pools) {
      others.insert(q.materials.begin(), q.materials.end());
      others.insert(q.aquifer_materials.begin(), q.aquifer_materials.end());
    }
    const auto m = r.materials();
    in_layer.assign(tets.size(), 0);
    own_load.assign(tets.size(), 0);
    std::size_t n = 0;
    for (std::size_t e = 0; e < tets.size(); ++e) {
      const PhysicalGroup* g = row0 + e < m.size() ? c.mesh->find_physical_tag(3, m[row0 + e]) : nullptr;
      if (!g || g->name.rfind("mat:", 0) != 0) continue;
      const std::string name = g->name.substr(4);
      if (mats.count(name)) in_layer[e] = 1, ++n;
      else if (others.count(name)) own_load[e] = 1;
    }
    if (n == 0) {
      c.notes.push_back(fmt::format("no cell of {}'s materials in the results: pool-top pictures skipped", pool->name));
      in_layer.clear();
    }
    layer_name = pool->name;
  } else {
    c.notes.push_back(pool ? "no mesh (--mesh) to name the cells' materials: pool-top pictures and the confinement height skipped"
                           : "no case with pools: pool-top pictures and the confinement height skipped");
  }

  // Section geometry (the same for every phase).
  double zmin = -1e300, zmax = 1e300;
  if (!c.opt.section_zrange.empty()) {
    const auto z = insar::parse_number_list("--section-zrange", c.opt.section_zrange, 2, "ZMIN/ZMAX");
    zmin = z[0];
    zmax = z[1];
    if (!(zmin < zmax)) throw InputError("--section-zrange", fmt::format("'{}': ZMIN is not below ZMAX", c.opt.section_zrange));
  } else if (!in_layer.empty()) {
    double lo = 1e300, hi = -1e300;
    for (std::size_t e = 0; e < tets.size(); ++e)
      if (in_layer[e])
        for (auto n : tets[e]) lo = std::min(lo, x[n][2]), hi = std::max(hi, x[n][2]);
    zmin = lo - 150;
    zmax = hi + 150;
  } else if (!c.phases.empty() && c.phases.front().start >= c.result_times.front() &&
             c.phases.front().end <= c.result_times.back()) {
    // No layer known: where the first phase changes sigma_z by more than 1 % of its largest change.
    int nc = 0;
    auto a = cell_field_at(r, c.result_times, field, c.phases.front().start, nc);
    const auto b = cell_field_at(r, c.result_times, field, c.phases.front().end, nc);
    double peak = 0;
    for (std::size_t e = 0; e < tets.size() && nc >= 3; ++e) peak = std::max(peak, std::abs(b[(row0 + e) * nc + 2] - a[(row0 + e) * nc + 2]));
    double lo = 1e300, hi = -1e300;
    for (std::size_t e = 0; e < tets.size() && nc >= 3 && peak > 0; ++e)
      if (std::abs(b[(row0 + e) * nc + 2] - a[(row0 + e) * nc + 2]) >= 0.01 * peak)
        for (auto n : tets[e]) lo = std::min(lo, x[n][2]), hi = std::max(hi, x[n][2]);
    if (lo < hi) {
      zmin = lo - 150;
      zmax = hi + 150;
    }
  }
  struct Section {
    insar::SectionSlice slice;
    std::string from, to;
  };
  std::vector<Section> sections;
  if (!c.opt.sections.empty()) {
    for (const SectionLine& line : section_lines(c)) {
      const std::string& name = line.name;
      Section s{insar::slice_tets(x, tets, name, line.polyline, zmin, zmax), line.from, line.to};
      if (s.slice.cell.empty()) {
        c.notes.push_back(zmin > -1e299 ? fmt::format("section {} does not cross the model in z {:.0f} .. {:.0f}", name, zmin, zmax)
                                        : fmt::format("section {} does not cross the model", name));
        continue;
      }
      const std::string stem = "sec_" + slug(name);
      std::vector<double> sz = s.slice.sz;
      insar::write_npy(c.work_file(stem + "_sz.npy"), sz, {sz.size() / 2, 2});
      insar::write_npy(c.work_file(stem + "_off.npy"), s.slice.offsets, {s.slice.offsets.size()});
      sections.push_back(std::move(s));
    }
  } else {
    c.notes.push_back("no section lines (--sections): section pictures skipped");
  }
  std::optional<insar::LayerTop> ltop;
  std::unique_ptr<insar::SurfaceLocator> top_locator;
  if (!in_layer.empty()) {
    ltop = insar::layer_top(x, tags, tets, in_layer);
    top_locator = std::make_unique<insar::SurfaceLocator>(ltop->surface);
    std::vector<double> xy;
    for (const auto& p : ltop->surface.points) xy.insert(xy.end(), {p[0], p[1]});
    std::vector<std::int32_t> tri;
    for (const auto& t : ltop->surface.triangles)
      for (auto n : t) tri.push_back(static_cast<std::int32_t>(n));
    insar::write_npy(c.work_file("pooltop_xy.npy"), xy, {ltop->surface.points.size(), 2});
    insar::write_npy(c.work_file("pooltop_tri.npy"), tri, {ltop->surface.triangles.size(), 3});
  }

  static const char* kComp[3] = {"x", "y", "z"};
  auto is_step = [&](std::int64_t t) { return std::find(c.result_times.begin(), c.result_times.end(), t) != c.result_times.end(); };
  for (const auto& ph : c.phases) {
    if (ph.start < c.result_times.front() || ph.end > c.result_times.back()) {
      c.notes.push_back(fmt::format("{}: beyond the output dates of {} ({} .. {}): no stress pictures", ph.label(),
                                    c.opt.results, format_iso_date(c.result_times.front()), format_iso_date(c.result_times.back())));
      continue;
    }
    if (!is_step(ph.start) || !is_step(ph.end))
      c.notes.push_back(fmt::format("{}: not both dates are output dates of {}: stresses interpolated linearly in time",
                                    ph.label(), c.opt.results));
    int nc = 0;
    auto a = cell_field_at(r, c.result_times, field, ph.start, nc);
    const auto b = cell_field_at(r, c.result_times, field, ph.end, nc);
    if (nc < 3) throw InputError(c.opt.results, fmt::format("cell field '{}' has {} components, expected 6", field, nc));
    for (const std::vector<double>* v : {static_cast<const std::vector<double>*>(&a), &b})
      for (std::size_t e = 0; e < tets.size(); ++e)
        for (int k = 0; k < 3; ++k)
          if (!std::isfinite((*v)[(row0 + e) * nc + k]))
            throw InputError(c.opt.results, fmt::format("cell field '{}' at {}: tetrahedron {} has component {} = {} (expected "
                                                        "finite values)", field,
                                                        format_iso_date(v == &b ? ph.end : ph.start), e, k,
                                                        (*v)[(row0 + e) * nc + k]));
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = b[i] - a[i];
    auto change = [&](std::size_t e, int k) { return a[(row0 + e) * nc + k] / norm; };
    for (int k = 0; k < 3; ++k) {
      const std::string label = fmt::format("Δσ_{} / {}", kComp[k], p0 > 0 ? "p0" : "1 MPa");
      for (const auto& s : sections) {
        std::vector<double> v(s.slice.cell.size());
        for (std::size_t i = 0; i < v.size(); ++i) v[i] = change(s.slice.cell[i], k);
        const std::string sstem = "sec_" + slug(s.slice.name);
        const std::string stem = fmt::format("{}_{}_s{}", sstem, slug(ph.name), kComp[k]);
        insar::write_npy(c.work_file(stem + ".npy"), v, {v.size()});
        Figure f;
        f.kind = "section";
        f.png = stem + ".png";
        f.title = fmt::format("{} along {}, {}", label, s.slice.name, ph.label());
        f.caption = fmt::format("Normalized change of σ_{} ({}) along section {} over the {} phase, {} to {}. The "
                                "vertical scale is exaggerated {:g} times.", kComp[k], unit, s.slice.name, ph.name,
                                format_iso_date(ph.start), format_iso_date(ph.end), c.opt.exaggeration);
        f.json = fmt::format("\"sz\": {}, \"offsets\": {}, \"values\": {}, \"label\": {}, \"exaggeration\": {}, "
                             "\"length\": {}, \"from\": {}, \"to\": {}",
                             jwork(sstem + "_sz.npy"), jwork(sstem + "_off.npy"), jwork(stem + ".npy"), jstr(label),
                             c.opt.exaggeration, s.slice.length, jstr(s.from), jstr(s.to));
        c.add(f);
      }
      if (ltop) {
        std::vector<double> v(ltop->above.size(), NAN);
        for (std::size_t i = 0; i < v.size(); ++i)
          if (ltop->above[i] >= 0) v[i] = change(static_cast<std::size_t>(ltop->above[i]), k);
        const std::string stem = fmt::format("pooltop_{}_s{}", slug(ph.name), kComp[k]);
        insar::write_npy(c.work_file(stem + ".npy"), v, {v.size()});
        Figure f;
        f.kind = "pooltop";
        f.png = stem + ".png";
        f.title = fmt::format("{} above the top of {}, {}", label, layer_name, ph.label());
        f.caption = fmt::format("Normalized change of σ_{} ({}) in the cells just above the top of {} over the {} phase, "
                                "{} to {}.", kComp[k], unit, layer_name, ph.name, format_iso_date(ph.start),
                                format_iso_date(ph.end));
        f.json = fmt::format("\"nodes\": {}, \"triangles\": {}, \"values\": {}, \"label\": {}, \"trace\": {}, "
                             "\"symmetric\": true, \"cell_values\": true",
                             jwork("pooltop_xy.npy"), jwork("pooltop_tri.npy"), jwork(stem + ".npy"), jstr(label),
                             c.trace_lines.empty() ? "null" : jwork("trace.csv"));
        c.add(f);
      }
    }
    if (ltop) {
      std::vector<double> vz(tets.size());
      for (std::size_t e = 0; e < tets.size(); ++e) vz[e] = change(e, 2);
      const auto h = insar::confinement_height(x, tets, vz, in_layer, *top_locator, 0.01, own_load);
      c.headlines.push_back({ph.label(),
                             fmt::format("height above the top of {} where |Δσ_z| falls below 1 % of its peak (outside every pool and "
                                         "aquifer)", layer_name),
                             fmt::format("{:.1f} m (peak |Δσ_z| = {:.3g} MPa = {:.3f} p0; {} of {} cells above beyond 1 %)",
                                         h.height, h.peak * norm / 1e6, p0 > 0 ? h.peak : NAN, h.cells_over, h.cells_above),
                             "about 20 m above Pool C"});
    }
  }
}

}  // namespace ugs::report
