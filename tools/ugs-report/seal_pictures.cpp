// The seals' margins as pictures (docs/caprock.md): from ugs-solve's fields over the seal elements
// (<stem>_caprock.h5 beside the --caprock table), at the output date where the tensile margin is
// smallest, a map of each margin on the base of the seal (the faces the pool's pressure pushes on:
// boundary faces of the seal elements facing down, each with its element's value) and each margin
// along the section lines (exact slices of the seal elements). Negative is failure.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "report.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/insar/npy.hpp"
#include "ugs/insar/sections.hpp"

namespace ugs::report {

namespace fs = std::filesystem;

namespace {

// Boundary faces of the tetrahedra whose outward normal points down (n_z below -0.3 |n|), with the
// tetrahedron each belongs to.
void base_faces(const std::vector<Point3>& x, const std::vector<insar::Tet>& tets, std::vector<std::array<std::uint32_t, 3>>& tri,
                std::vector<std::uint32_t>& cell) {
  std::map<std::array<std::uint32_t, 3>, int> count;
  static const int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  for (const auto& t : tets)
    for (const auto& f : kFace) {
      std::array<std::uint32_t, 3> k{t[f[0]], t[f[1]], t[f[2]]};
      std::sort(k.begin(), k.end());
      ++count[k];
    }
  for (std::size_t e = 0; e < tets.size(); ++e)
    for (int j = 0; j < 4; ++j) {
      const auto& f = kFace[j];
      std::array<std::uint32_t, 3> k{tets[e][f[0]], tets[e][f[1]], tets[e][f[2]]};
      std::array<std::uint32_t, 3> sorted = k;
      std::sort(sorted.begin(), sorted.end());
      if (count[sorted] != 1) continue;
      const Point3 &a = x[k[0]], &b = x[k[1]], &c = x[k[2]], &o = x[tets[e][j]];  // o: the node off the face
      const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
      if (n[0] * (o[0] - a[0]) + n[1] * (o[1] - a[1]) + n[2] * (o[2] - a[2]) > 0)
        for (double& q : n) q = -q;  // outward: away from the fourth node
      if (n[2] < -0.3 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2])) {
        tri.push_back(k);
        cell.push_back(static_cast<std::uint32_t>(e));
      }
    }
}

}  // namespace

void build_seal_pictures(Context& c) {
  if (c.opt.caprock.empty()) return;
  std::string h5 = c.opt.caprock;
  if (h5.size() > 4 && h5.compare(h5.size() - 4, 4, ".csv") == 0) h5 = h5.substr(0, h5.size() - 4) + ".h5";
  if (h5 == c.opt.caprock || !fs::exists(h5)) {
    c.notes.push_back(fmt::format("no seal fields beside {} ({}): seal maps and sections skipped", c.opt.caprock, h5));
    return;
  }
  const FieldSeriesReader r(h5);
  if (r.steps().empty()) {
    c.notes.push_back(fmt::format("{} has no output date: seal maps and sections skipped", h5));
    return;
  }
  const auto x = r.coordinates();
  const auto flat = r.cells(ElementType::Tetrahedron);
  std::vector<insar::Tet> tets(flat.size() / 4);
  for (std::size_t i = 0; i < tets.size(); ++i) tets[i] = {flat[4 * i], flat[4 * i + 1], flat[4 * i + 2], flat[4 * i + 3]};
  if (tets.empty()) throw InputError(h5, "has no tetrahedra (expected ugs-solve's seal elements)");
  // The output date of the smallest tensile margin.
  std::size_t step = 0;
  double worst = INFINITY;
  for (std::size_t s = 0; s < r.steps().size(); ++s) {
    const auto v = r.cell_field(s, "tensile_margin").values;
    if (v.size() != tets.size()) throw InputError(h5, fmt::format("tensile_margin has {} values for {} cells", v.size(), tets.size()));
    for (double m : v)
      if (m < worst) worst = m, step = s;
  }
  const std::string date = r.steps()[step].date;
  struct Margin {
    const char* field;
    const char* name;
    const char* label;
  };
  const Margin margins[] = {{"tensile_margin", "tensile", "tensile margin (fracture pressure - pore pressure), MPa"},
                            {"shear_margin", "shear", "Mohr-Coulomb shear margin, MPa"}};
  std::vector<std::array<std::uint32_t, 3>> tri;
  std::vector<std::uint32_t> under;
  base_faces(x, tets, tri, under);
  std::vector<double> xy;
  for (const auto& p : x) xy.insert(xy.end(), {p[0], p[1]});
  std::vector<std::int32_t> tflat;
  for (const auto& t : tri)
    for (auto n : t) tflat.push_back(static_cast<std::int32_t>(n));
  insar::write_npy(c.work_file("seal_xy.npy"), xy, {x.size(), 2});
  insar::write_npy(c.work_file("seal_tri.npy"), tflat, {tri.size(), 3});
  // Sections through the seal: its elevation range and a little more.
  double zlo = INFINITY, zhi = -INFINITY;
  for (const auto& p : x) zlo = std::min(zlo, p[2]), zhi = std::max(zhi, p[2]);
  struct Slice {
    insar::SectionSlice slice;
    std::string from, to;
  };
  std::vector<Slice> slices;
  for (const SectionLine& line : section_lines(c)) {
    Slice s{insar::slice_tets(x, tets, line.name, line.polyline, zlo - 20, zhi + 20), line.from, line.to};
    if (s.slice.cell.empty()) continue;  // the section misses the seal
    const std::string stem = "seal_sec_" + slug(line.name);
    insar::write_npy(c.work_file(stem + "_sz.npy"), s.slice.sz, {s.slice.sz.size() / 2, 2});
    insar::write_npy(c.work_file(stem + "_off.npy"), s.slice.offsets, {s.slice.offsets.size()});
    slices.push_back(std::move(s));
  }
  for (const Margin& m : margins) {
    std::vector<double> v = r.cell_field(step, m.field).values;
    for (double& q : v) q *= 1e-6;
    std::vector<double> base(under.size());
    for (std::size_t i = 0; i < under.size(); ++i) base[i] = v[under[i]];
    const std::string stem = fmt::format("seal_base_{}", m.name);
    insar::write_npy(c.work_file(stem + ".npy"), base, {base.size()});
    Figure f;
    f.kind = "pooltop";
    f.png = stem + ".png";
    f.title = fmt::format("Seal {}, its base, {}", m.label, date);
    f.caption = fmt::format("The {} of the seal elements on the base of the seal (their faces facing down), on {}, the "
                            "output date of the smallest tensile margin. Negative is failure (docs/caprock.md).",
                            m.label, date);
    f.json = fmt::format("\"nodes\": {}, \"triangles\": {}, \"values\": {}, \"label\": {}, \"trace\": {}, \"cell_values\": true",
                         jwork("seal_xy.npy"), jwork("seal_tri.npy"), jwork(stem + ".npy"), jstr(m.label),
                         c.trace_lines.empty() ? "null" : jwork("trace.csv"));
    c.add(f);
    for (const Slice& s : slices) {
      std::vector<double> sv(s.slice.cell.size());
      for (std::size_t i = 0; i < sv.size(); ++i) sv[i] = v[s.slice.cell[i]];
      const std::string sstem = "seal_sec_" + slug(s.slice.name);
      const std::string vstem = fmt::format("{}_{}", sstem, m.name);
      insar::write_npy(c.work_file(vstem + ".npy"), sv, {sv.size()});
      Figure g;
      g.kind = "section";
      g.png = vstem + ".png";
      g.title = fmt::format("Seal {} along {}, {}", m.label, s.slice.name, date);
      g.caption = fmt::format("The {} of the seal elements cut by section {} on {}. The vertical scale is exaggerated {:g} "
                              "times.", m.label, s.slice.name, date, c.opt.exaggeration);
      g.json = fmt::format("\"sz\": {}, \"offsets\": {}, \"values\": {}, \"label\": {}, \"exaggeration\": {}, \"length\": {}, "
                           "\"from\": {}, \"to\": {}",
                           jwork(sstem + "_sz.npy"), jwork(sstem + "_off.npy"), jwork(vstem + ".npy"), jstr(m.label),
                           c.opt.exaggeration, s.slice.length, jstr(s.from), jstr(s.to));
      c.add(g);
    }
  }
}

}  // namespace ugs::report
