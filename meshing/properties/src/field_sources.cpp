#include "ugs/meshing/field_sources.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <fmt/format.h>

#include "ugs/eclipse/eclipse.hpp"
#include "ugs/formats/corner_point_grid.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/formats/fields.hpp"
#include "ugs/formats/grdecl.hpp"
#include "ugs/formats/horizon_grid.hpp"
#include "ugs/meshing/cell_locator.hpp"

namespace ugs {
namespace {

// A grid and its locator (which holds a view of the grid's corners: both stay where they are).
struct LocatedGrid {
  CornerPointGrid grid;
  std::unique_ptr<HexLocator> locator;
};

}  // namespace

Sampled sample_table(const MaterialField& f, std::span<const FieldSite> sites, double surface_elevation) {
  Sampled r{std::vector<double>(sites.size(), 0.0), std::vector<char>(sites.size(), 0)};
  const auto& rows = f.rows;
  for (std::size_t s = 0; s < sites.size(); ++s) {
    const double at = f.by_depth ? surface_elevation - sites[s].centroid[2] : sites[s].centroid[2];
    if (rows.empty() || at < rows.front().depth || at > rows.back().depth) continue;
    // The row interval holding `at` (the last row: its value).
    const auto hi = std::upper_bound(rows.begin(), rows.end(), at, [](double v, const DepthValue& row) { return v < row.depth; });
    if (hi == rows.end()) {
      r.value[s] = rows.back().value;
    } else {
      const auto lo = hi - 1;
      const double w = (at - lo->depth) / (hi->depth - lo->depth);
      r.value[s] = lo->value + w * (hi->value - lo->value);
    }
    r.covered[s] = 1;
  }
  return r;
}

struct FieldSources::Impl {
  std::map<std::string, std::unique_ptr<GrdeclFile>> grdecl;        // by path
  std::map<std::string, std::unique_ptr<LocatedGrid>> grids;        // by path and offset
  std::map<std::string, std::vector<double>> init_arrays;          // by path, grid and keyword
  std::map<std::string, std::unique_ptr<HorizonGrid>> maps;
  std::map<std::string, std::unordered_map<std::uint64_t, double>> cells;  // by path, step and name
  // The cells of the last sites located in a grid (the fields of one material share them).
  std::string located_key;
  const FieldSite* located_sites = nullptr;
  std::size_t located_count = 0;
  std::vector<std::int64_t> located;

  const GrdeclFile& grdecl_file(const std::string& path) {
    auto& g = grdecl[path];
    if (!g) g = std::make_unique<GrdeclFile>(read_grdecl(path));
    return *g;
  }

  const LocatedGrid& grid(const MaterialField& f, std::string& key) {
    const std::string path = !f.grid.empty() ? f.grid
                             : f.source == MaterialField::Source::Init ? eclipse::default_egrid(f.file)
                                                                       : f.file;
    if (path.empty())
      throw InputError(f.where, fmt::format("'{}': no EGRID beside {} (name it with grid = \"CASE.EGRID\")", f.key, f.file));
    key = fmt::format("{}|{}|{}|{}", path, f.offset_m[0], f.offset_m[1], f.offset_m[2]);
    auto& g = grids[key];
    if (!g) {
      g = std::make_unique<LocatedGrid>();
      const Point3 offset{f.offset_m[0], f.offset_m[1], f.offset_m[2]};
      if (f.source == MaterialField::Source::Init) {
        eclipse::Grid eg = eclipse::read_egrid(path, offset);
        g->grid = std::move(static_cast<CornerPointGrid&>(eg));
      } else {
        g->grid = corner_point_grid(grdecl_file(path), offset);
      }
      g->locator = std::make_unique<HexLocator>(g->grid.corners);
    }
    return *g;
  }

  const std::vector<std::int64_t>& locate(const std::string& key, const LocatedGrid& g, std::span<const FieldSite> sites) {
    if (key == located_key && sites.data() == located_sites && sites.size() == located_count) return located;
    std::vector<Point3> p(sites.size());
    for (std::size_t s = 0; s < sites.size(); ++s) p[s] = sites[s].centroid;
    located = g.locator->locate(p);
    located_key = key, located_sites = sites.data(), located_count = sites.size();
    return located;
  }
};

FieldSources::FieldSources() : impl_(std::make_unique<Impl>()) {}
FieldSources::~FieldSources() = default;

Sampled FieldSources::sample(const MaterialField& f, std::span<const FieldSite> sites, double surface_elevation) {
  using Source = MaterialField::Source;
  Sampled r{std::vector<double>(sites.size(), 0.0), std::vector<char>(sites.size(), 0)};
  const auto relay = [&](const InputError& e) {
    // The source's own message, at the field's line: "case.toml:12: 'c_R': x.GRDECL:3: ...".
    return InputError(f.where, fmt::format("'{}': {}", f.key, e.what()));
  };
  try {
    switch (f.source) {
      case Source::Table: return sample_table(f, sites, surface_elevation);
      case Source::Grdecl:
      case Source::Init: {
        std::string key;
        const LocatedGrid& g = impl_->grid(f, key);
        std::vector<double> by_active;
        if (f.source == Source::Grdecl) {
          const GrdeclFile& file = impl_->grdecl_file(f.file);
          const GrdeclKeyword* k = file.find(f.keyword);
          if (!k) throw InputError(f.file, fmt::format("no keyword {} (keywords: {})", f.keyword, file.names()));
          if (k->values.size() != g.grid.num_cells())
            throw InputError(k->where, fmt::format("{} has {} values, expected one per cell of the {} x {} x {} grid of {} ({})", f.keyword,
                                                   k->values.size(), g.grid.dims[0], g.grid.dims[1], g.grid.dims[2], g.grid.path,
                                                   g.grid.num_cells()));
          by_active.reserve(g.grid.num_active());
          for (const auto c : g.grid.global) by_active.push_back(k->values[c]);
        } else {
          auto& a = impl_->init_arrays[f.file + "|" + key + "|" + f.keyword];
          if (a.empty()) {
            eclipse::Grid eg;
            static_cast<CornerPointGrid&>(eg) = g.grid;
            a = eclipse::read_init_array(f.file, f.keyword, eg);
          }
          by_active = a;
        }
        const auto& cell = impl_->locate(key, g, sites);
        for (std::size_t s = 0; s < sites.size(); ++s)
          if (cell[s] >= 0) r.value[s] = by_active[static_cast<std::size_t>(cell[s])], r.covered[s] = 1;
        return r;
      }
      case Source::Map: {
        auto& m = impl_->maps[f.file];
        if (!m) {
          const HorizonFormat fmt_of = detect_horizon_format(f.file);
          if (fmt_of == HorizonFormat::Irap) m = std::make_unique<HorizonGrid>(read_irap_grid(f.file));
          else if (fmt_of == HorizonFormat::Cps3) m = std::make_unique<HorizonGrid>(read_cps3_grid(f.file));
          else
            throw InputError(f.file, fmt::format("is {} (expected a map as IRAP classic ASCII or CPS-3 ASCII grid)",
                                                 horizon_format_name(fmt_of)));
        }
        for (std::size_t s = 0; s < sites.size(); ++s)
          r.covered[s] = horizon_grid_value(*m, sites[s].centroid[0], sites[s].centroid[1], r.value[s]) == GridPoint::Value;
        return r;
      }
      case Source::Cells: {
        auto& by_tag = impl_->cells[f.file + "|" + f.date + "|" + f.keyword];
        if (by_tag.empty()) {
          const FieldSeriesReader in(f.file);
          if (in.steps().empty()) throw InputError(f.file, "has no step (expected a cell field at a step)");
          const std::size_t step = f.date.empty() ? 0 : in.step(f.date);
          const Field v = in.cell_field(step, f.keyword);
          const auto tags = in.cell_tags();
          if (v.components != 1 || v.values.size() != in.num_cells() || tags.size() != in.num_cells())
            throw InputError(f.file, fmt::format("cell field '{}' at {} has {} values of {} components for {} cells (expected one "
                                                 "value per cell)", f.keyword, in.steps()[step].date, v.values.size(), v.components,
                                                 in.num_cells()));
          for (std::size_t c = 0; c < tags.size(); ++c)
            if (!by_tag.emplace(tags[c], v.values[c]).second)
              throw InputError(f.file, fmt::format("element tag {} twice in /mesh/cell_tags", tags[c]));
        }
        for (std::size_t s = 0; s < sites.size(); ++s)
          if (const auto it = by_tag.find(sites[s].tag); it != by_tag.end()) r.value[s] = it->second, r.covered[s] = 1;
        return r;
      }
    }
  } catch (const InputError& e) {
    throw relay(e);
  }
  return r;
}

}  // namespace ugs
