#include "ugs/seismicity/histories.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/msh.hpp"

namespace ugs::seismicity {
namespace fs = std::filesystem;

namespace {

constexpr double kMPa = 1e6;
// Largest |dCFS| and pair area taken as data: beyond them a value is a corrupt number, not a stress
// (1e6 MPa) or a share of a fault (1e6 km2), and sums of them would leave doubles.
constexpr double kMaxCfsMPa = 1e6, kMaxAreaM2 = 1e12;

double checked_cfs_MPa(const CsvTable& t, std::size_t r, std::size_t c) {
  const double v = t.number(r, c);
  if (!(std::abs(v) <= kMaxCfsMPa))
    throw InputError(t.where(r), fmt::format("column '{}': {} MPa (expected a Coulomb stress change within +-1e6 MPa)", t.columns()[c], v));
  return v;
}

std::string date_text(std::int64_t t) { return format_iso_date(t); }

// The dates of a table whose rows come in date blocks: each block's rows share one date, blocks
// strictly increasing. Returns the first row of each block.
std::vector<std::size_t> date_blocks(const CsvTable& t, std::size_t date_col, std::vector<std::int64_t>& dates) {
  std::vector<std::size_t> first;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const std::int64_t d = t.date(r, date_col);
    if (!dates.empty() && d == dates.back()) continue;
    if (!dates.empty() && d < dates.back())
      throw InputError(t.where(r), fmt::format("date {} after {} (expected dates increasing, the rows of a date together)",
                                               date_text(d), date_text(dates.back())));
    dates.push_back(d);
    first.push_back(r);
  }
  return first;
}

void require_two_dates(const std::vector<std::int64_t>& dates, const std::string& where) {
  if (dates.size() < 2)
    throw InputError(where, fmt::format("{} date{} (expected a stress history of two dates or more)", dates.size(),
                                        dates.size() == 1 ? "" : "s"));
}

}  // namespace

std::string input_kind(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  if (ext == ".h5" || ext == ".hdf5") return "h5";
  std::ifstream f(path);
  std::string line;
  while (std::getline(f, line))
    if (!line.empty() && line[0] != '#') break;
  if (line.find("cfs_change_MPa") != std::string::npos) return "pairs";
  if (line.find("dcfs_MPa") != std::string::npos) return "dcfs";
  return "";
}

std::string pair_csv_fault_name(const std::string& path) {
  std::ifstream f(path);
  std::string line;
  const std::string head = "# ugs-solve fault ", tail = ": one row";
  if (std::getline(f, line) && line.rfind(head, 0) == 0) {
    const auto end = line.find(tail, head.size());
    if (end != std::string::npos && end > head.size()) return line.substr(head.size(), end - head.size());
  }
  const std::string stem = fs::path(path).stem().string();
  const auto at = stem.rfind("_fault_");
  return at == std::string::npos || at + 7 == stem.size() ? stem : stem.substr(at + 7);
}

StressHistory read_pair_csvs(const std::vector<std::string>& paths) {
  StressHistory h;
  std::set<std::string> names;
  for (const auto& path : paths) {
    const CsvTable t = CsvTable::read(path);
    const std::size_t c_date = t.column("date"), c_node = t.column("node"), c_x = t.column("x_m"), c_y = t.column("y_m"),
                      c_z = t.column("z_m"), c_s = t.column("along_strike_m"), c_d = t.column("down_dip_m"),
                      c_area = t.column("area_m2"), c_cfs = t.column("cfs_change_MPa");
    const auto c_interp = t.find_column("interpolated");
    if (t.rows() == 0) throw InputError(path, "has no rows (expected one row per node pair and date)");
    std::vector<std::int64_t> dates;
    const auto first = date_blocks(t, c_date, dates);
    require_two_dates(dates, path);
    const std::size_t npairs = (first.size() > 1 ? first[1] : t.rows()) - first[0];
    FaultHistory fh;
    fh.name = pair_csv_fault_name(path);
    fh.source = path;
    if (!names.insert(fh.name).second)
      throw InputError(path, fmt::format("fault '{}' is given twice (expected one per-pair CSV per fault)", fh.name));
    fh.pairs.resize(npairs);
    for (std::size_t q = 0; q < npairs; ++q) {
      PairHistory& p = fh.pairs[q];
      const std::size_t r = first[0] + q;
      const std::int64_t node = t.integer(r, c_node);
      if (node <= 0) throw InputError(t.where(r), fmt::format("node {} (expected a positive node tag)", node));
      p.node = static_cast<std::uint64_t>(node);
      p.x = {t.number(r, c_x), t.number(r, c_y), t.number(r, c_z)};
      p.along_strike = t.number(r, c_s);
      p.down_dip = t.number(r, c_d);
      p.area = t.number(r, c_area);
      if (!(p.area >= 0 && p.area <= kMaxAreaM2))
        throw InputError(t.where(r), fmt::format("area_m2 = {} (expected a share of the fault in [0, 1e12] m2)", p.area));
      if (c_interp) {
        const std::int64_t i = t.integer(r, *c_interp);
        if (i != 0 && i != 1) throw InputError(t.where(r), fmt::format("interpolated = {} (expected 0 or 1)", i));
        p.interpolated = i == 1;
      }
      p.dcfs.resize(dates.size());
    }
    for (std::size_t k = 0; k < dates.size(); ++k) {
      const std::size_t end = k + 1 < first.size() ? first[k + 1] : t.rows();
      if (end - first[k] != npairs)
        throw InputError(t.where(first[k]), fmt::format("{} node pairs at {}, {} at {} (expected the same pairs at every date)",
                                                        end - first[k], date_text(dates[k]), npairs, date_text(dates[0])));
      for (std::size_t q = 0; q < npairs; ++q) {
        const std::size_t r = first[k] + q;
        if (static_cast<std::uint64_t>(t.integer(r, c_node)) != fh.pairs[q].node)
          throw InputError(t.where(r), fmt::format("node {} where {} has node {} (expected the same pairs at every date, in the "
                                                   "same order)", t.text(r, c_node), date_text(dates[0]), fh.pairs[q].node));
        fh.pairs[q].dcfs[k] = checked_cfs_MPa(t, r, c_cfs) * kMPa;
      }
    }
    if (h.dates.empty()) {
      h.dates = dates;
    } else if (dates != h.dates) {
      throw InputError(path, fmt::format("its {} dates ({} .. {}) differ from those of {} ({} dates, {} .. {}) (expected the "
                                         "per-pair CSVs of one run)", dates.size(), date_text(dates.front()),
                                         date_text(dates.back()), h.faults.front().source, h.dates.size(),
                                         date_text(h.dates.front()), date_text(h.dates.back())));
    }
    h.faults.push_back(std::move(fh));
  }
  if (h.faults.empty()) throw InputError("", "no fault results given");
  return h;
}

StressHistory read_faults_h5(const std::string& path, const std::string& mesh_path) {
  const FieldSeriesReader r(path);
  StressHistory h;
  const auto& steps = r.steps();
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const auto d = parse_iso_date(steps[k].date);
    if (!d) throw InputError(path, fmt::format("step {} has the date '{}' (expected ISO 8601)", k, steps[k].date));
    if (!h.dates.empty() && *d <= h.dates.back())
      throw InputError(path, fmt::format("step {} ({}) does not follow {} (expected dates increasing)", k, steps[k].date,
                                         date_text(h.dates.back())));
    h.dates.push_back(*d);
  }
  require_two_dates(h.dates, path);
  const std::size_t nn = r.num_nodes();
  const auto x = r.coordinates();
  const auto tags = r.node_tags();
  if (x.size() != nn || tags.size() != nn) throw InputError(path, "the mesh's coordinates and node tags differ in number");
  const auto types = r.cell_types();
  const auto materials = r.materials();
  // Triangles and their fault tags (cells in output order: the triangles' rows among them).
  std::vector<std::uint32_t> tri;
  std::vector<std::int32_t> tri_tag;
  std::size_t offset = 0;
  for (ElementType type : types) {
    const auto c = r.cells(type);
    const std::size_t npe = static_cast<std::size_t>(nodes_per_element(type)), n = c.size() / npe;
    if (type == ElementType::Triangle) {
      if (materials.size() < offset + n) throw InputError(path, "fewer cell materials than cells");
      tri = c;
      for (std::size_t i = 0; i < n; ++i) tri_tag.push_back(materials[offset + i]);
    }
    offset += n;
  }
  if (tri.empty()) throw InputError(path, "has no fault triangles (expected the faults HDF5 of a faulted ugs-solve run, <output>_faults.h5)");
  for (auto v : tri)
    if (v >= nn) throw InputError(path, fmt::format("a triangle names node index {} of {} nodes", v, nn));
  std::optional<Mesh> mesh;
  if (!mesh_path.empty()) mesh = read_msh(mesh_path);
  auto fault_name = [&](std::int32_t tag) {
    if (mesh)
      for (int dim : {3, 2})
        if (const PhysicalGroup* g = mesh->find_physical_tag(dim, tag); g && g->name.rfind("fault:", 0) == 0) return g->name.substr(6);
    return fmt::format("fault {}", tag);
  };
  // Each node's fault (the fault of its triangles: ugs-solve gives every fault its own surface nodes)
  // and area (a third of each triangle).
  std::vector<std::int32_t> node_tag(nn, 0);
  std::vector<char> used(nn, 0);
  std::vector<double> area(nn, 0.0);
  std::map<std::int32_t, std::size_t> fault_of_tag;
  for (std::size_t i = 0; i < tri_tag.size(); ++i) {
    const Point3 &a = x[tri[3 * i]], &b = x[tri[3 * i + 1]], &c = x[tri[3 * i + 2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double A = 0.5 * std::sqrt(std::pow(u[1] * v[2] - u[2] * v[1], 2) + std::pow(u[2] * v[0] - u[0] * v[2], 2) +
                                     std::pow(u[0] * v[1] - u[1] * v[0], 2));
    if (!std::isfinite(A)) throw InputError(path, fmt::format("triangle {} has a non-finite area", i));
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t n = tri[3 * i + k];
      if (used[n] && node_tag[n] != tri_tag[i])
        throw InputError(path, fmt::format("node {} lies on two faults ({} and {}; expected ugs-solve's fault surfaces)", tags[n],
                                           fault_name(node_tag[n]), fault_name(tri_tag[i])));
      used[n] = 1;
      node_tag[n] = tri_tag[i];
      area[n] += A / 3;
    }
    if (fault_of_tag.emplace(tri_tag[i], fault_of_tag.size()).second) {
      h.faults.emplace_back();
      h.faults.back().name = fault_name(tri_tag[i]);
      h.faults.back().source = path;
    }
  }
  const Field along = r.node_field(0, "along_strike"), down = r.node_field(0, "down_dip"), interp = r.node_field(0, "interpolated");
  for (const Field* f : {&along, &down, &interp})
    if (f->values.size() != nn) throw InputError(path, fmt::format("node field '{}' has {} values for {} nodes", f->name, f->values.size(), nn));
  for (std::size_t n = 0; n < nn; ++n) {
    if (!used[n]) continue;
    PairHistory p;
    p.node = tags[n];
    p.x = x[n];
    p.along_strike = along.values[n];
    p.down_dip = down.values[n];
    p.area = area[n];
    p.interpolated = interp.values[n] != 0;
    p.surface_node = static_cast<std::uint32_t>(n);
    p.dcfs.resize(h.dates.size());
    h.faults[fault_of_tag.at(node_tag[n])].pairs.push_back(std::move(p));
  }
  for (std::size_t k = 0; k < h.dates.size(); ++k) {
    const Field cfs = r.node_field(k, "cfs_change");
    if (cfs.values.size() != nn)
      throw InputError(path, fmt::format("cfs_change at {} has {} values for {} nodes", steps[k].date, cfs.values.size(), nn));
    for (auto& f : h.faults)
      for (auto& p : f.pairs) {
        const double v = cfs.values[p.surface_node];
        if (!(std::abs(v) <= kMaxCfsMPa * kMPa))
          throw InputError(path, fmt::format("cfs_change at {}, node {}: {} Pa (expected a finite Coulomb stress change within "
                                             "+-1e6 MPa)", steps[k].date, p.node, v));
        p.dcfs[k] = v;
      }
  }
  // The surface, for the forecast's node fields: the file's nodes, one triangle block per fault.
  Mesh s;
  s.node_tags = tags;
  s.nodes = x;
  std::vector<int> entity(h.faults.size());
  for (std::size_t f = 0; f < h.faults.size(); ++f) entity[f] = s.entity_for_physical(2, "fault:" + h.faults[f].name);
  for (std::size_t i = 0; i < tri_tag.size(); ++i)
    s.add_element(s.block(2, entity[fault_of_tag.at(tri_tag[i])], ElementType::Triangle), std::span<const std::uint32_t>(&tri[3 * i], 3));
  h.surface = std::move(s);
  return h;
}

StressHistory read_dcfs_csv(const std::string& path, const std::string& name, double area_m2) {
  if (!(area_m2 > 0 && area_m2 <= kMaxAreaM2))
    throw InputError("patch area", fmt::format("{} km2 (expected a positive area up to 1e6 km2)", area_m2 / 1e6));
  const CsvTable t = CsvTable::read(path);
  const std::size_t c_date = t.column("date"), c_cfs = t.column("dcfs_MPa");
  StressHistory h;
  FaultHistory f;
  f.name = name;
  f.source = path;
  f.pairs.resize(1);
  f.pairs[0].area = area_m2;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const std::int64_t d = t.date(r, c_date);
    if (!h.dates.empty() && d <= h.dates.back())
      throw InputError(t.where(r), fmt::format("date {} does not follow {} (expected dates strictly increasing)", date_text(d),
                                               date_text(h.dates.back())));
    h.dates.push_back(d);
    f.pairs[0].dcfs.push_back(checked_cfs_MPa(t, r, c_cfs) * kMPa);
  }
  require_two_dates(h.dates, path);
  h.faults.push_back(std::move(f));
  return h;
}

}  // namespace ugs::seismicity
