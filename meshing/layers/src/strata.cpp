#include "ugs/meshing/strata.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <set>
#include <thread>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/run_beside.hpp"
#include "ugs/formats/toml_reader.hpp"
#include "ugs/meshing/geodata.hpp"
#include "ugs/meshing/horizon_grids.hpp"
#include "ugs/meshing/natural_neighbour.hpp"

namespace ugs {

namespace {

void check_name(const TomlTable& t, const std::string& key, const std::string& name) {
  if (name.empty()) throw t.error(key, "must not be empty");
  if (name.find_first_of("\"\n\r") != std::string::npos) throw t.error(key, "must not contain quotes or line breaks");
}

}  // namespace

Strata read_strata(const std::string& path) {
  const TomlTable root = TomlTable::parse_file(path);
  root.reject_unknown({"crs", "min_thickness", "order_tolerance", "material_overlap", "surface", "unit", "material",
                       "faults", "fault"});
  Strata s;
  s.file = path;
  if (root.has("crs")) {
    s.crs = root.string("crs");
    s.crs_where = root.where("crs");
  }
  s.min_thickness = root.number_or("min_thickness", 0.5);
  if (!(s.min_thickness >= 0) || !std::isfinite(s.min_thickness))
    throw root.error("min_thickness", "must be a thickness in metres, >= 0");
  s.order_tolerance = root.number_or("order_tolerance", 1.0);
  if (!(s.order_tolerance >= 0) || !std::isfinite(s.order_tolerance))
    throw root.error("order_tolerance", "must be a distance in metres, >= 0");
  if (auto o = root.string_opt("material_overlap")) {
    if (*o == "first") s.overlap_first_wins = true;
    else if (*o != "error") throw root.error("material_overlap", "must be \"error\" or \"first\"");
  }

  std::set<std::string> names;
  for (const auto& t : root.tables("surface")) {
    t.reject_unknown({"name", "raster", "band", "grid", "crs", "constant", "picks", "unconformity"});
    StrataSurface f;
    f.where = t.where();
    f.name = t.string("name");
    check_name(t, "name", f.name);
    if (!names.insert(f.name).second) throw t.error("name", "surface '" + f.name + "' is defined twice");
    const int sources = t.has("raster") + t.has("grid") + t.has("constant") + t.has("picks");
    if (sources != 1)
      throw InputError(f.where, fmt::format("surface '{}': give exactly one of raster, grid, constant or picks", f.name));
    if (t.has("crs") && !t.has("grid"))
      throw t.error("crs", fmt::format("surface '{}': crs names the CRS of a grid file (rasters carry their own)", f.name));
    if (t.has("grid")) {
      f.source = StrataSurface::Source::Grid;
      f.path = resolve_relative(path, t.string("grid"));
      if (t.has("crs")) {
        f.crs = t.string("crs");
        f.crs_where = t.where("crs");
      } else if (!root.has("crs")) {
        // IRAP, CPS-3, ZMAP+ and TSurf files carry no CRS a program can read: guessing one would
        // put a horizon delivered in another CRS kilometres away without a word.
        throw InputError(f.where, fmt::format("surface '{}': the grid file {} carries no CRS and none is named: add crs = "
                                              "\"EPSG:...\" to the surface, or at the top of the file for all of them",
                                              f.name, f.path));
      }
      if (t.has("band")) throw t.error("band", "only a raster surface has bands");
    } else if (t.has("raster")) {
      f.source = StrataSurface::Source::Raster;
      f.path = resolve_relative(path, t.string("raster"));
      const long long band = t.integer_opt("band").value_or(1);
      if (band < 1) throw t.error("band", "must be >= 1");
      f.band = static_cast<int>(band);
    } else {
      if (t.has("band")) throw t.error("band", "only a raster surface has bands");
      if (t.has("constant")) {
        f.source = StrataSurface::Source::Constant;
        f.constant = t.number("constant");
        if (!std::isfinite(f.constant)) throw t.error("constant", "must be a finite elevation (m)");
      } else {
        f.source = StrataSurface::Source::Picks;
        f.path = resolve_relative(path, t.string("picks"));
      }
    }
    f.unconformity = t.boolean_or("unconformity", false);
    s.surfaces.push_back(std::move(f));
  }
  if (s.surfaces.size() < 2) throw InputError(root.where(), "needs at least two [[surface]] tables (top and bottom)");

  names.clear();
  for (const auto& t : root.tables("unit")) {
    t.reject_unknown({"name", "layers", "bias"});
    StrataUnit u;
    u.where = t.where();
    u.name = t.string("name");
    check_name(t, "name", u.name);
    if (!names.insert(u.name).second) throw t.error("name", "unit '" + u.name + "' is defined twice");
    const long long layers = t.integer("layers");
    if (layers < 1) throw t.error("layers", fmt::format("unit '{}' needs at least one sub-layer (got {})", u.name, layers));
    if (layers > 10000) throw t.error("layers", fmt::format("unit '{}': {} sub-layers is too many", u.name, layers));
    u.layers = static_cast<int>(layers);
    u.bias = t.number_or("bias", 1.0);
    if (!(u.bias > 0) || !std::isfinite(u.bias))
      throw t.error("bias", fmt::format("unit '{}': the thickness ratio of successive sub-layers must be > 0", u.name));
    s.units.push_back(std::move(u));
  }
  if (s.units.size() + 1 != s.surfaces.size())
    throw InputError(root.where(), fmt::format("{} [[unit]] tables for {} surfaces: each unit lies between two successive "
                                               "surfaces, so there must be {}",
                                               s.units.size(), s.surfaces.size(), s.surfaces.size() - 1));

  for (const auto& t : root.tables("material")) {
    t.reject_unknown({"name", "units", "polygon", "where"});
    MaterialRule m;
    m.where = t.where();
    m.name = t.string("name");
    check_name(t, "name", m.name);
    m.units = t.strings("units");
    if (m.units.empty()) throw t.error("units", "list at least one unit");
    for (const auto& u : m.units)
      if (!names.count(u))
        throw t.error("units", fmt::format("material '{}': no unit named '{}' (units: {})", m.name, u,
                                           fmt::join([&] {
                                             std::vector<std::string> v;
                                             for (const auto& x : s.units) v.push_back(x.name);
                                             return v;
                                           }(),
                                                     ", ")));
    if (t.has("polygon")) m.polygon = resolve_relative(path, t.string("polygon"));
    if (t.has("where")) {
      if (m.polygon.empty()) throw t.error("where", "filters the features of `polygon`, which is missing");
      m.filter = t.string("where");
    }
    s.materials.push_back(std::move(m));
  }
  if (s.materials.empty()) throw InputError(root.where(), "needs at least one [[material]] rule");

  if (root.has("faults")) s.faults_file = resolve_relative(path, root.string("faults"));
  std::set<std::string> fault_names;
  for (const auto& t : root.tables("fault")) {
    t.reject_unknown({"name", "top_m", "bottom_m", "dip_deg", "dip_dir_deg", "trace_z_m", "ends_against", "segment"});
    FaultRange f;
    f.where = t.where();
    f.name = t.string("name");
    check_name(t, "name", f.name);
    if (!fault_names.insert(f.name).second) throw t.error("name", "fault '" + f.name + "' is defined twice");
    f.top = t.number("top_m");
    f.bottom = t.number("bottom_m");
    if (!(f.top >= f.bottom)) throw t.error("bottom_m", fmt::format("fault '{}': bottom_m lies above top_m", f.name));
    if (t.has("dip_deg")) {
      f.dip_deg = t.number("dip_deg");
      if (!(*f.dip_deg > 0 && *f.dip_deg <= 90))
        throw t.error("dip_deg", fmt::format("fault '{}': dip_deg {} is outside (0, 90]", f.name, *f.dip_deg));
    }
    if (t.has("dip_dir_deg")) f.dip_dir_deg = t.number("dip_dir_deg");
    if (t.has("trace_z_m")) f.trace_z = t.number("trace_z_m");
    if (t.has("ends_against")) f.ends_against = t.string("ends_against");
    for (const auto& sg : t.tables("segment")) {
      sg.reject_unknown({"bottom_m", "dip_deg"});
      FaultTrace::Piece pc;
      pc.bottom = sg.number("bottom_m");
      pc.dip_deg = sg.number("dip_deg");
      if (!(pc.dip_deg > 0 && pc.dip_deg <= 90))
        throw sg.error("dip_deg", fmt::format("fault '{}': dip_deg {} is outside (0, 90]", f.name, pc.dip_deg));
      f.segments.push_back(pc);
    }
    if (f.has_dip() && !t.has("dip_dir_deg"))
      throw t.error("dip_dir_deg", fmt::format("fault '{}': a dipping fault needs dip_dir_deg", f.name));
    s.faults.push_back(std::move(f));
  }
  return s;
}

namespace {

std::string column_at(const Plan& plan, std::uint32_t c) {
  return fmt::format("plan node {} at x={:.2f}, y={:.2f}", plan.node_tags[c], plan.xy[c][0], plan.xy[c][1]);
}

// "35 of the 13,532 plan columns, within x 684800 .. 686000, y 4950000 .. 4954000 (first: plan node ...)"
std::string which_columns(const Plan& plan, const std::vector<std::uint32_t>& cols) {
  double x0 = plan.xy[cols[0]][0], x1 = x0, y0 = plan.xy[cols[0]][1], y1 = y0;
  for (auto c : cols) {
    x0 = std::min(x0, plan.xy[c][0]), x1 = std::max(x1, plan.xy[c][0]);
    y0 = std::min(y0, plan.xy[c][1]), y1 = std::max(y1, plan.xy[c][1]);
  }
  return fmt::format("{} of the {} plan columns, within x {:.0f} .. {:.0f}, y {:.0f} .. {:.0f} (first: {})",
                     thousands(cols.size()), thousands(plan.num_columns()), x0, x1, y0, y1, column_at(plan, cols[0]));
}

std::vector<double> evaluate_surface(const StrataSurface& s, const Plan& plan, const std::string& model_wkt,
                                     std::vector<std::string>& warnings, std::vector<std::string>& notes) {
  const std::size_t nc = plan.num_columns();
  auto fail = [&](const std::string& msg) { return InputError(s.where, fmt::format("surface '{}': {}", s.name, msg)); };
  switch (s.source) {
    case StrataSurface::Source::Grid: {
      const std::string surface_wkt = s.crs.empty() ? model_wkt : geo::crs_wkt(s.crs, s.crs_where);
      geo::HorizonSampling h;
      try {
        h = geo::sample_horizon(s.path, surface_wkt, plan.xy, model_wkt);
      } catch (const InputError& e) {
        throw fail(e.what());
      }
      const std::string what = fmt::format("{} ({}, {})", s.path, h.format, geo::crs_label(surface_wkt));
      if (h.outside.size() == nc) {
        double x0 = plan.xy[0][0], x1 = x0, y0 = plan.xy[0][1], y1 = y0;
        for (const auto& p : plan.xy)
          x0 = std::min(x0, p[0]), x1 = std::max(x1, p[0]), y0 = std::min(y0, p[1]), y1 = std::max(y1, p[1]);
        throw fail(fmt::format("{} lies apart from every plan column: it spans x {:.0f} .. {:.0f}, y {:.0f} .. {:.0f}, the "
                               "plan x {:.0f} .. {:.0f}, y {:.0f} .. {:.0f} ({}); if the grid is in another CRS, name it "
                               "with crs = \"EPSG:...\" on the surface",
                               what, h.extent[0], h.extent[2], h.extent[1], h.extent[3], x0, x1, y0, y1,
                               geo::crs_label(model_wkt)));
      }
      if (!h.outside.empty()) throw fail(fmt::format("{} does not cover {}", what, which_columns(plan, h.outside)));
      if (!h.undefined.empty())
        throw fail(fmt::format("{} has undefined nodes under {}", what, which_columns(plan, h.undefined)));
      for (auto& c : h.cleaned) warnings.push_back(fmt::format("surface '{}': {}", s.name, c));
      for (auto& c : h.notes) notes.push_back(fmt::format("surface '{}': {}", s.name, c));
      return h.values;
    }
    case StrataSurface::Source::Constant: return std::vector<double>(nc, s.constant);
    case StrataSurface::Source::Raster: {
      geo::RasterSampling r;
      try {
        r = geo::sample_raster(s.path, s.band, plan.xy, model_wkt);
      } catch (const InputError& e) {
        throw fail(e.what());
      }
      if (!r.outside.empty())
        throw fail(fmt::format("raster {} ({}) does not cover {}", s.path, r.crs, which_columns(plan, r.outside)));
      if (!r.nodata.empty())
        throw fail(fmt::format("raster {} has no-data or NaN values under {}", s.path, which_columns(plan, r.nodata)));
      return r.values;
    }
    case StrataSurface::Source::Picks: {
      std::vector<std::array<double, 3>> picks;
      try {
        const CsvTable t = CsvTable::read(s.path);
        const auto x = t.numbers("x"), y = t.numbers("y"), z = t.numbers("z");
        for (std::size_t i = 0; i < x.size(); ++i) picks.push_back({x[i], y[i], z[i]});
      } catch (const InputError& e) {
        throw fail(e.what());
      }
      std::optional<NaturalNeighbourSurface> nn;
      try {
        nn.emplace(picks);
      } catch (const std::invalid_argument& e) {
        throw fail(fmt::format("picks {}: {}", s.path, e.what()));
      }
      std::vector<double> z(nc);
      std::vector<std::uint32_t> outside;
      for (std::uint32_t c = 0; c < nc; ++c) {
        const auto v = nn->at(plan.xy[c][0], plan.xy[c][1]);
        if (!v) outside.push_back(c);
        else z[c] = *v;
      }
      if (!outside.empty())
        throw fail(fmt::format("picks {} do not cover {}: they lie outside the convex hull of the picks", s.path,
                               which_columns(plan, outside)));
      return z;
    }
  }
  return {};
}

// Which triangles (by centroid) lie inside each rule's polygons; empty for rules without polygon.
std::vector<std::vector<char>> rule_polygons(const Strata& strata, const Plan& plan, const std::string& model_wkt) {
  std::vector<XY> centroids(plan.triangles.size());
  for (std::size_t t = 0; t < centroids.size(); ++t) centroids[t] = plan.centroid(t);
  std::vector<std::vector<char>> inside(strata.materials.size());
  std::map<std::pair<std::string, std::string>, std::vector<char>> cache;
  for (std::size_t r = 0; r < strata.materials.size(); ++r) {
    const auto& rule = strata.materials[r];
    if (rule.polygon.empty()) continue;
    auto key = std::pair{rule.polygon, rule.filter};
    if (auto it = cache.find(key); it != cache.end()) {
      inside[r] = it->second;
      continue;
    }
    geo::VectorData v;
    try {
      v = geo::read_vector(rule.polygon, model_wkt, rule.filter);
    } catch (const InputError& e) {
      throw InputError(rule.where, fmt::format("material '{}': {}", rule.name, e.what()));
    }
    if (v.features.empty())
      throw InputError(rule.where, fmt::format("material '{}': {}{} selects no feature", rule.name, rule.polygon,
                                               rule.filter.empty() ? "" : " with where \"" + rule.filter + "\""));
    std::vector<geo::Polygon> polys;
    for (auto& f : v.features) {
      if (f.polygons.empty())
        throw InputError(rule.where, fmt::format("material '{}': feature {} of {} is not a polygon", rule.name, f.fid,
                                                 rule.polygon));
      for (auto& p : f.polygons) polys.push_back(std::move(p));
    }
    const geo::PolygonSet set(std::move(polys));
    std::vector<char> in(centroids.size());
    for (std::size_t t = 0; t < centroids.size(); ++t) in[t] = set.contains(centroids[t]);
    inside[r] = in;
    cache.emplace(key, std::move(in));
  }
  return inside;
}

}  // namespace

PreparedModel prepare_model(const Strata& strata, const Plan& plan) {
  PreparedModel pm;
  const std::size_t nc = plan.num_columns(), nt = plan.triangles.size(), ns = strata.surfaces.size();

  // Model CRS: given, else the first raster's, else the first grid surface's, else EPSG:32632.
  std::string model_wkt;
  if (!strata.crs.empty()) {
    model_wkt = geo::crs_wkt(strata.crs, strata.crs_where);
  } else {
    for (const auto& s : strata.surfaces)
      if (s.source == StrataSurface::Source::Raster) {
        try {
          model_wkt = geo::raster_crs(s.path);
        } catch (const InputError& e) {
          throw InputError(s.where, fmt::format("surface '{}': {}", s.name, e.what()));
        }
        if (!model_wkt.empty()) break;
      }
    for (const auto& s : strata.surfaces)
      if (model_wkt.empty() && s.source == StrataSurface::Source::Grid && !s.crs.empty()) model_wkt = geo::crs_wkt(s.crs, s.crs_where);
    if (model_wkt.empty()) model_wkt = geo::crs_wkt("EPSG:32632", strata.file);
    pm.notes.push_back("model CRS " + geo::crs_label(model_wkt) + " (no crs in " + strata.file + ")");
  }
  pm.crs = geo::crs_label(model_wkt);

  // Surfaces at the columns, then the order rule and pinch-outs.
  // The surfaces are independent (each its own file): every other one on a second thread (two
  // cores; a raster's read and sampling is most of this step). The first failure in the surfaces'
  // order is reported, as one after the other would.
  auto& z = pm.input.surfaces;
  z.assign(ns, {});
  {
    std::vector<std::exception_ptr> failed(ns);
    std::vector<std::vector<std::string>> warned(ns), noted(ns);
    auto sample = [&](std::size_t first, std::size_t step) {
      for (std::size_t i = first; i < ns; i += step) try {
          z[i] = evaluate_surface(strata.surfaces[i], plan, model_wkt, warned[i], noted[i]);
        } catch (...) {
          failed[i] = std::current_exception();
        }
    };
    if (ns > 1 && std::thread::hardware_concurrency() > 1) {
      run_beside([&] { sample(1, 2); }, [&] { sample(0, 2); });
    } else {
      sample(0, 1);
    }
    for (const auto& f : failed)
      if (f) std::rethrow_exception(f);
    for (std::size_t i = 0; i < ns; ++i) {
      pm.warnings.insert(pm.warnings.end(), warned[i].begin(), warned[i].end());
      pm.notes.insert(pm.notes.end(), noted[i].begin(), noted[i].end());
    }
  }
  std::vector<StackSurface> stack;
  for (const auto& s : strata.surfaces) stack.push_back({s.name, s.where, s.unconformity});
  pm.stack = apply_stack_rules(z, stack, plan, {strata.order_tolerance, strata.min_thickness});
  for (std::size_t i = 0; i < ns; ++i) {
    if (pm.stack.truncated[i])
      pm.notes.push_back(fmt::format("surface '{}' truncated by an unconformity at {} columns", strata.surfaces[i].name,
                                     thousands(pm.stack.truncated[i])));
    if (pm.stack.clamped[i])
      pm.notes.push_back(fmt::format("surface '{}' lowered onto '{}' at {} columns (by up to {:.3f} m)",
                                     strata.surfaces[i].name, strata.surfaces[i - 1].name,
                                     thousands(pm.stack.clamped[i]), pm.stack.max_clamp[i]));
  }
  for (std::size_t u = 0; u < strata.units.size(); ++u) {
    if (pm.stack.collapsed[u] == nc)
      pm.warnings.push_back(fmt::format("unit '{}' is thinner than min_thickness ({} m) everywhere: it has no elements",
                                        strata.units[u].name, strata.min_thickness));
    else if (pm.stack.collapsed[u])
      pm.notes.push_back(fmt::format("unit '{}' pinches out at {} of {} columns", strata.units[u].name,
                                     thousands(pm.stack.collapsed[u]), thousands(nc)));
  }
  for (const auto& u : strata.units) pm.input.units.push_back({u.name, u.layers, u.bias});

  // Materials: the first rule naming the unit whose polygon holds the triangle's centroid.
  std::map<std::string, std::size_t> unit_index;
  for (std::size_t u = 0; u < strata.units.size(); ++u) unit_index[strata.units[u].name] = u;
  std::map<std::string, std::uint32_t> material_index;
  std::vector<std::uint32_t> rule_material(strata.materials.size());
  for (std::size_t r = 0; r < strata.materials.size(); ++r) {
    auto [it, fresh] = material_index.emplace(strata.materials[r].name, pm.input.materials.size());
    if (fresh) pm.input.materials.push_back(strata.materials[r].name);
    rule_material[r] = it->second;
  }
  const auto inside = rule_polygons(strata, plan, model_wkt);
  std::vector<std::vector<std::size_t>> rules_of_unit(strata.units.size());
  for (std::size_t r = 0; r < strata.materials.size(); ++r)
    for (const auto& u : strata.materials[r].units) rules_of_unit[unit_index.at(u)].push_back(r);

  pm.input.material_of.assign(strata.units.size(), std::vector<std::uint32_t>(nt));
  std::vector<std::size_t> rule_used(strata.materials.size(), 0);
  for (std::size_t u = 0; u < strata.units.size(); ++u) {
    const auto& rules = rules_of_unit[u];
    // Partial overlap of two polygon rules naming different materials: which one applies is a
    // matter of order only, which usually means a digitising mistake.
    if (!strata.overlap_first_wins)
      for (std::size_t a = 0; a < rules.size(); ++a)
        for (std::size_t b = a + 1; b < rules.size(); ++b) {
          const auto ra = rules[a], rb = rules[b];
          if (inside[ra].empty() || inside[rb].empty() || rule_material[ra] == rule_material[rb]) continue;
          std::size_t both = 0, only_a = 0, only_b = 0, first_both = 0;
          for (std::size_t t = 0; t < nt; ++t) {
            if (inside[ra][t] && inside[rb][t] && both++ == 0) first_both = t;
            only_a += inside[ra][t] && !inside[rb][t];
            only_b += !inside[ra][t] && inside[rb][t];
          }
          if (both && only_a && only_b) {
            const XY c = plan.centroid(first_both);
            throw InputError(strata.materials[rb].where,
                             fmt::format("material rules '{}' ({}) and '{}' overlap partly in unit '{}': {} plan triangles "
                                         "lie in both polygons (first at x={:.2f}, y={:.2f}) while each also covers "
                                         "triangles the other does not; nest or separate the polygons, or set "
                                         "material_overlap = \"first\" to let the first rule win",
                                         strata.materials[ra].name, strata.materials[ra].where, strata.materials[rb].name,
                                         strata.units[u].name, thousands(both), c[0], c[1]));
          }
        }
    for (std::size_t t = 0; t < nt; ++t) {
      bool found = false;
      for (auto r : rules)
        if (inside[r].empty() || inside[r][t]) {
          pm.input.material_of[u][t] = rule_material[r];
          ++rule_used[r];
          found = true;
          break;
        }
      if (!found) {
        const XY c = plan.centroid(t);
        throw InputError(strata.file, fmt::format("unit '{}' has no material at plan triangle {} (x={:.2f}, y={:.2f}): "
                                                  "add a [[material]] rule without polygon for it as the default",
                                                  strata.units[u].name, plan.triangle_tags[t], c[0], c[1]));
      }
    }
  }
  for (std::size_t r = 0; r < strata.materials.size(); ++r)
    if (!rule_used[r])
      pm.warnings.push_back(fmt::format("{}: material rule '{}' matches no plan triangle", strata.materials[r].where,
                                        strata.materials[r].name));

  // Faults. The faults file and [[fault]] tables give depth ranges and, with a dip, dipping faults
  // built by cutting the layered mesh (docs/dipping-faults.md); plan fault lines of the others are
  // vertical faults over their range.
  const bool have_ranges = !strata.faults_file.empty() || !strata.faults.empty();
  std::optional<std::vector<FaultRecord>> fault_features;
  if (!strata.faults_file.empty()) {
    try {
      fault_features = read_fault_file(strata.faults_file, model_wkt);
    } catch (const InputError& e) {
      throw InputError(strata.file, fmt::format("faults: {}", e.what()));
    }
  }
  auto table_of = [&](const std::string& name) -> const FaultRange* {
    for (const auto& r : strata.faults)
      if (r.name == name) return &r;
    return nullptr;
  };
  // Dipping (cut) faults, in file order then [[fault]] order.
  std::set<std::string> cut_names;
  auto add_cut = [&](FaultTrace tr, const FaultRange* r) {
    if (r) {
      tr.top = r->top;
      tr.bottom = r->bottom;
      if (r->dip_deg) tr.dip_deg = *r->dip_deg;
      if (r->dip_dir_deg) tr.dip_dir_deg = *r->dip_dir_deg;
      if (r->trace_z) tr.trace_z = *r->trace_z;
      if (!r->segments.empty()) tr.pieces = r->segments;
      else if (r->dip_deg) tr.pieces.clear();
      if (!r->ends_against.empty()) tr.ends_against = r->ends_against;
      tr.where = r->where;
    }
    check_fault_trace(tr);
    cut_names.insert(tr.name);
    pm.cut_faults.push_back(std::move(tr));
  };
  if (fault_features)
    for (const auto& feat : *fault_features) {
      const FaultRange* r = table_of(feat.name);
      if (!feat.surface.empty()) {  // a surface (docs/faults.md, "Faults as surfaces"): it is the geometry
        if (r && r->has_dip())
          throw InputError(r->where, fmt::format("fault '{}' is given as a surface ({}): its [[fault]] table cannot give "
                                                 "it a dip",
                                                 feat.name, feat.surface));
        FaultTrace tr = fault_trace_from_record(feat);
        for (const auto& c : tr.surface->cleaned) pm.warnings.push_back(fmt::format("fault '{}': {}", tr.name, c));
        cut_names.insert(tr.name);
        pm.cut_faults.push_back(std::move(tr));
        continue;
      }
      if (!feat.has_dip() && !(r && r->has_dip())) continue;
      FaultTrace tr;
      if (feat.has_dip()) {
        tr = fault_trace_from_record(feat, "a dipping fault needs");
      } else {
        tr.where = feat.where;
        tr.name = feat.name;
        tr.parts = feat.lines;
        tr.trace_z = r->top;
      }
      const bool line = plan.find_line_group("fault:" + tr.name) != nullptr;
      if (tr.vertical() && line && !(r && r->has_dip()) && tr.pieces.empty()) continue;  // vertical from the plan line
      add_cut(std::move(tr), r);
    }
  for (const auto& r : strata.faults) {
    if (!r.has_dip() || cut_names.count(r.name)) continue;
    // The trace from the plan's line group: chain its edges.
    const PlanLineGroup* g = plan.find_line_group("fault:" + r.name);
    if (!g)
      throw InputError(r.where, fmt::format("fault '{}' has a dip but no trace: neither the faults file nor the plan {} "
                                            "has a line for it",
                                            r.name, plan.source));
    FaultTrace tr;
    tr.name = r.name;
    tr.where = r.where;
    tr.trace_z = r.top;
    std::map<std::uint32_t, std::uint32_t> next;
    std::set<std::uint32_t> heads;
    for (const auto& [a, b] : g->edges) {
      next[a] = b;
      heads.insert(a);
    }
    for (const auto& [a, b] : g->edges) heads.erase(b);
    for (auto h : heads) {
      std::vector<std::array<double, 2>> part{plan.xy[h]};
      for (auto it = next.find(h); it != next.end() && part.size() <= g->edges.size(); it = next.find(it->second))
        part.push_back(plan.xy[it->second]);
      tr.parts.push_back(std::move(part));
    }
    if (tr.parts.empty())
      throw InputError(r.where, fmt::format("fault '{}': the plan's line is closed; give its trace in the faults file", r.name));
    add_cut(std::move(tr), &r);
  }
  // Checks of the cut faults: trace inside the plan, depth range inside the model.
  if (!pm.cut_faults.empty()) {
    double ztop = -std::numeric_limits<double>::infinity(), zbot = std::numeric_limits<double>::infinity();
    for (double z : pm.input.surfaces.front()) ztop = std::max(ztop, z);
    for (double z : pm.input.surfaces.back()) zbot = std::min(zbot, z);
    double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin, ymin = xmin, ymax = -xmin;
    for (const auto& p : plan.xy) {
      xmin = std::min(xmin, p[0]);
      xmax = std::max(xmax, p[0]);
      ymin = std::min(ymin, p[1]);
      ymax = std::max(ymax, p[1]);
    }
    const double scale = std::max(xmax - xmin, ymax - ymin);
    auto in_plan = [&](const std::array<double, 2>& x) {
      const double eps = 1e-9 * scale;
      for (const auto& t : plan.triangles) {
        const auto &a = plan.xy[t[0]], &b = plan.xy[t[1]], &c = plan.xy[t[2]];
        auto o = [](const XY& p, const XY& q, const XY& r) {
          return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
        };
        const double l = std::max(std::hypot(b[0] - a[0], b[1] - a[1]), std::hypot(c[0] - a[0], c[1] - a[1]));
        if (o(a, b, x) >= -eps * l && o(b, c, x) >= -eps * l && o(c, a, x) >= -eps * l) return true;
      }
      return false;
    };
    for (const auto& tr : pm.cut_faults) {
      const std::string who = fmt::format("fault '{}'", tr.name);
      if (tr.surface) {  // only its part inside the model is cut; the cut refuses one that misses the mesh
        if (tr.bottom > ztop || tr.top < zbot)
          throw InputError(tr.where, fmt::format("{}: its surface ({:.1f} .. {:.1f} m) lies outside the model ({:.1f} .. "
                                                 "{:.1f} m)",
                                                 who, tr.top, tr.bottom, ztop, zbot));
        pm.notes.push_back(fmt::format("{}: a {} of {} triangles ({:.1f} .. {:.1f} m), cut into the layered mesh", who,
                                       tr.surface->format, tr.surface->mesh.triangles.size(), tr.top, tr.bottom));
        continue;
      }
      if (tr.bottom < zbot - 1e-6 * scale || tr.top > ztop + 1e-6 * scale || tr.bottom > ztop || tr.top < zbot)
        throw InputError(tr.where, fmt::format("{}: its depth range {:.1f} .. {:.1f} m lies outside the model ({:.1f} .. "
                                               "{:.1f} m)",
                                               who, tr.top, tr.bottom, ztop, zbot));
      for (const auto& part : tr.parts)
        for (std::size_t i = 0; i + 1 < part.size(); ++i)
          for (int k = 0; k <= 8; ++k) {
            const double f = k / 8.0;
            const XY x{part[i][0] + f * (part[i + 1][0] - part[i][0]), part[i][1] + f * (part[i + 1][1] - part[i][1])};
            if (!in_plan(x))
              throw InputError(tr.where, fmt::format("{}: the trace leaves the plan at ({:.2f}, {:.2f})", who, x[0], x[1]));
          }
      pm.notes.push_back(fmt::format("{}: dipping ({} piece(s), dip {:.1f} deg toward {:.1f}, {:.1f} .. {:.1f} m{}), cut "
                                     "into the layered mesh",
                                     who, tr.piece_list().size(), tr.dip_deg, tr.dip_dir_deg, tr.top, tr.bottom,
                                     tr.ends_against.empty() ? "" : ", ends against '" + tr.ends_against + "'"));
    }
  }

  for (const auto& g : plan.lines) {
    if (g.name.rfind("fault:", 0) != 0) continue;
    VerticalFault f;
    f.name = g.name.substr(6);
    f.edges = g.edges;
    if (cut_names.count(f.name)) {
      pm.notes.push_back(fmt::format("fault '{}': the plan line is its trace only (the fault dips)", f.name));
      continue;
    }
    if (!have_ranges) {
      pm.notes.push_back(fmt::format("fault '{}' spans the whole model height (no depth ranges in {})", f.name, strata.file));
    } else {
      bool found = false;
      if (const FaultRange* r = table_of(f.name)) {
        f.top = r->top;
        f.bottom = r->bottom;
        found = true;
      }
      if (!found && fault_features) {
        for (const auto& feat : *fault_features) {
          if (feat.name != f.name) continue;
          if (!feat.has_depth_range())
            throw InputError(feat.where, fmt::format("fault '{}': missing field '{}' (ugs-meshgen needs the depth range "
                                                     "top_m, bottom_m of a vertical fault)",
                                                     f.name, feat.top ? "bottom_m" : "top_m"));
          f.top = *feat.top;
          f.bottom = *feat.bottom;
          found = true;
          break;
        }
      }
      if (!found)
        throw InputError(strata.file, fmt::format("the plan {} has fault line '{}' but neither [[fault]] tables nor the "
                                                  "faults file give its depth range (top_m, bottom_m)",
                                                  plan.source, f.name));
    }
    pm.input.faults.push_back(std::move(f));
  }
  for (const auto& r : strata.faults)
    if (!plan.find_line_group("fault:" + r.name) && !cut_names.count(r.name))
      pm.warnings.push_back(fmt::format("{}: fault '{}' is not a line group of the plan {}", r.where, r.name, plan.source));
  pm.input.plan = &plan;
  return pm;
}

}  // namespace ugs
