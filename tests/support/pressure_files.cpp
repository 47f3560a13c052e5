#include "pressure_files.hpp"

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"

namespace ugs::testcase {
namespace fs = std::filesystem;
namespace {

Mesh tetrahedra_where(const Mesh& m, const std::function<bool(const std::string& group)>& keep) {
  Mesh s;
  std::vector<std::int64_t> local(m.num_nodes(), -1);
  for (const auto& b : m.blocks) {
    if (b.type != ElementType::Tetrahedron) continue;
    const std::string name = m.physical_name_of(b.entity_dim, b.entity_tag);
    if (!keep(name)) continue;
    const int e = s.entity_for_physical(3, name);
    for (std::size_t i = 0; i < b.size(); ++i) {
      std::uint32_t n[4];
      const auto el = b.element(i);
      for (int k = 0; k < 4; ++k) {
        if (local[el[k]] < 0) local[el[k]] = s.add_node(m.nodes[el[k]], m.node_tags[el[k]]);
        n[k] = static_cast<std::uint32_t>(local[el[k]]);
      }
      s.add_element(s.block(3, e, ElementType::Tetrahedron), n, b.tags[i]);
    }
  }
  s.update_entity_bboxes();
  return s;
}

}  // namespace

Mesh submesh(const Mesh& m, const std::vector<std::string>& materials) {
  return tetrahedra_where(m, [&](const std::string& group) {
    for (const auto& mat : materials)
      if (group == "mat:" + mat) return true;
    return false;
  });
}

Mesh tetrahedra_of(const Mesh& m) {
  return tetrahedra_where(m, [](const std::string&) { return true; });
}

Series uniform_series(std::vector<std::string> dates, std::vector<double> dp_Pa) {
  return {std::move(dates), [dp = std::move(dp_Pa)](const Point3&, std::size_t k) { return dp.at(k); }};
}

void write_pressure(const fs::path& path, const Mesh& sub, const Series& s, const FieldSeriesOptions& o) {
  FieldSeriesWriter w(path.string(), sub, o);
  for (std::size_t k = 0; k < s.dates.size(); ++k) {
    Field f{"dp", 1, std::vector<double>(sub.num_nodes())};
    for (std::size_t v = 0; v < sub.num_nodes(); ++v) f.values[v] = s.dp(sub.nodes[v], k);
    const Field nodes[] = {f};
    w.add_step(s.dates[k], static_cast<double>(*parse_iso_date(s.dates[k])), nodes);
  }
  w.commit();
}

std::vector<std::string> monthly(int y0, int m0, int y1, int m1) {
  std::vector<std::string> d;
  for (int y = y0, m = m0; y < y1 || (y == y1 && m <= m1);) {
    d.push_back(fmt::format("{:04d}-{:02d}-01", y, m));
    if (++m == 13) m = 1, ++y;
  }
  return d;
}

}  // namespace ugs::testcase
