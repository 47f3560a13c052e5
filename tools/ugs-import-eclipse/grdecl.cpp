#include "grdecl.hpp"

#include <cmath>

#include <fmt/format.h>

#include "ugs/formats/error.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/io.hpp"
#include "ugs/meshing/cell_locator.hpp"

namespace ugs::eclipse {
namespace {

// GRDECL values, 6 per line, runs of equal values as N*value.
void write_keyword(OutputFile& out, const std::string& name, const std::vector<double>& v) {
  std::string text = name + "\n";
  int on_line = 0;
  for (std::size_t i = 0; i < v.size();) {
    std::size_t j = i + 1;
    while (j < v.size() && v[j] == v[i]) ++j;
    const std::string value = v[i] == 0 ? std::string("0") : fmt::format("{:.7g}", v[i]);
    text += j - i > 1 ? fmt::format(" {}*{}", j - i, value) : " " + value;
    if (++on_line == 6) {
      text += "\n";
      on_line = 0;
    }
    i = j;
  }
  text += on_line ? "\n/\n\n" : "/\n\n";
  out.write(text);
}

}  // namespace

GrdeclReport export_grdecl(const Grid& grid, const std::string& results, std::vector<std::string> dates, const std::string& out_path,
                           const std::string& command_line) {
  FieldSeriesReader in(results);
  if (dates.empty())
    for (const auto& s : in.steps()) dates.push_back(s.date);
  if (dates.size() > 99) throw InputError("--dates", fmt::format("{} dates: at most 99 (keyword names UGSDSM1 .. UGSDSM99)", dates.size()));
  std::vector<std::size_t> steps;
  for (const auto& d : dates) steps.push_back(in.step(d));  // InputError naming the steps there are
  // The pressure unit of the grid's unit system (METRIC bar, FIELD psi, LAB atm).
  const bool feet = grid.length_unit == "FEET" || grid.length_unit == "FT", cm = grid.length_unit == "CM";
  const double unit = eclipse::pressure_unit_pa(feet ? 2 : cm ? 3 : 1, out_path);
  const std::string unit_name = feet ? "psi" : cm ? "atm" : "bar";

  // The tetrahedra of the results' mesh (the first rows of its cell fields when tetrahedra come
  // first, else after the cells of the types before them).
  const auto xyz = in.coordinates();
  const auto tets = in.cells(ElementType::Tetrahedron);
  std::size_t row0 = 0;
  for (const ElementType t : in.cell_types()) {
    if (t == ElementType::Tetrahedron) break;
    row0 += in.cells(t).size() / static_cast<std::size_t>(nodes_per_element(t));
  }
  const std::size_t ntet = tets.size() / 4;
  if (ntet == 0) throw InputError(results, "no tetrahedra");
  std::vector<Point3> centroid(ntet);
  std::vector<double> volume(ntet);
  for (std::size_t t = 0; t < ntet; ++t) {
    const auto& a = xyz.at(tets[4 * t]), &b = xyz.at(tets[4 * t + 1]), &c = xyz.at(tets[4 * t + 2]), &d = xyz.at(tets[4 * t + 3]);
    for (int k = 0; k < 3; ++k) centroid[t][k] = 0.25 * (a[k] + b[k] + c[k] + d[k]);
    volume[t] = std::abs(tet_signed_volume(a, b, c, d));
  }
  const HexLocator locator(grid.corners);
  const auto cell = locator.locate(centroid);
  GrdeclReport r;
  r.tetrahedra = ntet;
  std::vector<double> cell_volume(grid.num_active(), 0.0);
  for (std::size_t t = 0; t < ntet; ++t) {
    if (cell[t] < 0) {
      ++r.outside;
      continue;
    }
    cell_volume[static_cast<std::size_t>(cell[t])] += volume[t];
  }
  for (const double v : cell_volume) r.empty_cells += v == 0;
  if (r.outside == ntet)
    throw InputError(grid.path, fmt::format("the grid does not overlap the mesh of {}: same CRS? --offset for a local grid origin", results));

  OutputFile out(out_path);
  out.write(fmt::format("-- ugs mechanics per active cell of {} ({} x {} x {}), written by:\n-- {}\n", grid.path, grid.dims[0],
                        grid.dims[1], grid.dims[2], command_line));
  out.write("-- UGSEV<n>: volumetric strain change (-), extension positive; UGSDSM<n>: mean effective stress change (" + unit_name +
            "), tension positive; 0 in inactive cells and in the " + std::to_string(r.empty_cells) + " active cells no tetrahedron centroid lies in.\n\n");
  const std::size_t total = grid.active.size();
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const Field strain = in.cell_field(steps[k], "strain"), stress = in.cell_field(steps[k], "stress_change");
    for (const Field* f : {&strain, &stress})
      if (f->components != 6 || f->values.size() < 6 * (row0 + ntet))
        throw InputError(results, fmt::format("cell field '{}' at {}: {} components, {} values (expected 6 per cell)", f->name, dates[k],
                                              f->components, f->values.size()));
    std::vector<double> ev(grid.num_active(), 0.0), sm(grid.num_active(), 0.0);
    for (std::size_t t = 0; t < ntet; ++t) {
      if (cell[t] < 0) continue;
      const std::size_t a = static_cast<std::size_t>(cell[t]), row = 6 * (row0 + t);
      ev[a] += volume[t] * (strain.values[row] + strain.values[row + 1] + strain.values[row + 2]);
      sm[a] += volume[t] * (stress.values[row] + stress.values[row + 1] + stress.values[row + 2]) / 3.0;
    }
    std::vector<double> EV(total, 0.0), SM(total, 0.0);
    for (std::size_t a = 0; a < grid.num_active(); ++a) {
      if (cell_volume[a] == 0) continue;
      EV[grid.global[a]] = ev[a] / cell_volume[a];
      SM[grid.global[a]] = sm[a] / cell_volume[a] / unit;
      if (!std::isfinite(EV[grid.global[a]]) || !std::isfinite(SM[grid.global[a]]))
        throw InputError(results, fmt::format("strain or stress change at {} is not finite", dates[k]));
    }
    out.write(fmt::format("-- {} (step {} of {})\n", dates[k], steps[k], results));
    r.keywords.push_back(fmt::format("UGSEV{}", k + 1));
    write_keyword(out, r.keywords.back(), EV);
    r.keywords.push_back(fmt::format("UGSDSM{}", k + 1));
    write_keyword(out, r.keywords.back(), SM);
  }
  out.commit();
  return r;
}

}  // namespace ugs::eclipse
