// ugs-mesh2d's inputs: vector files read through OGR, reprojected to the model CRS, clipped to the
// domain with GEOS, turned into a PlanSpec.
#include <cmath>
#include <cstdlib>
#include <memory>
#include <optional>

#include <ogrsf_frmts.h>
#include <fmt/format.h>

#include "ugs/meshing/gdal_util.hpp"
#include "ugs/formats/error.hpp"
#include "ugs/meshing/fault_traces.hpp"
#include "ugs/meshing/plan_mesh.hpp"

namespace ugs {

namespace {

struct RawFeature {
  std::int64_t fid = 0;
  std::string name;
  std::optional<double> size;
  std::unique_ptr<OGRGeometry> geom;
};

std::string feature_label(const RawFeature& f) { return fmt::format("feature {} ('{}')", f.fid, f.name); }

std::vector<RawFeature> read_features(const std::string& path, const std::string& model_wkt, const PlanInputs& in) {
  geo::QuietGdal quiet;
  auto ds = geo::open_vector(path);
  std::vector<RawFeature> out;
  for (int li = 0; li < ds->GetLayerCount(); ++li) {
    OGRLayer* layer = ds->GetLayer(li);
    auto ct = geo::transformation(geo::layer_wkt(path, *ds, *layer, true), model_wkt, path);
    const OGRFeatureDefn* defn = layer->GetLayerDefn();
    const int name_i = defn->GetFieldIndex(in.name_field.c_str());
    const int size_i = defn->GetFieldIndex(in.size_field.c_str());
    layer->ResetReading();
    while (std::unique_ptr<OGRFeature> feat{layer->GetNextFeature()}) {
      RawFeature f;
      f.fid = feat->GetFID();
      f.name = name_i >= 0 && feat->IsFieldSetAndNotNull(name_i) ? std::string(feat->GetFieldAsString(name_i))
                                                                  : fmt::format("{}_{}", layer->GetName(), f.fid);
      if (f.name.empty() || f.name.find_first_of("\"\n\r") != std::string::npos)
        throw InputError(path, fmt::format("feature {}: name '{}' is empty or holds quotes or line breaks", f.fid, f.name));
      if (size_i >= 0 && feat->IsFieldSetAndNotNull(size_i)) {
        const auto t = defn->GetFieldDefn(size_i)->GetType();
        if (t != OFTInteger && t != OFTInteger64 && t != OFTReal)
          throw InputError(path, fmt::format("{}: field '{}' is not numeric", feature_label(f), in.size_field));
        f.size = feat->GetFieldAsDouble(size_i);
        if (!(*f.size > 0) || !std::isfinite(*f.size))
          throw InputError(path, fmt::format("{}: {} must be a size in metres, > 0 (got {})", feature_label(f),
                                             in.size_field, *f.size));
      }
      const OGRGeometry* g = feat->GetGeometryRef();
      // A feature without geometry would give a group fewer without a word (GeoJSON coordinates that
      // are not numbers were refused by open_vector, naming the value).
      if (!g || g->IsEmpty()) throw InputError(path, fmt::format("{} has no geometry (expected a polygon or a line)", feature_label(f)));
      f.geom.reset(g->hasCurveGeometry() ? g->getLinearGeometry() : g->clone());
      f.geom->flattenTo2D();
      if (ct && f.geom->transform(ct.get()) != OGRERR_NONE)
        throw InputError(path, fmt::format("{}: cannot transform to the model CRS: {}", feature_label(f), geo::gdal_error()));
      out.push_back(std::move(f));
    }
  }
  return out;
}

bool is_areal(const OGRGeometry& g) {
  const auto t = wkbFlatten(g.getGeometryType());
  return t == wkbPolygon || t == wkbMultiPolygon;
}
bool is_linear(const OGRGeometry& g) {
  const auto t = wkbFlatten(g.getGeometryType());
  return t == wkbLineString || t == wkbMultiLineString || t == wkbLinearRing;
}

}  // namespace

LoadedPlan load_plan_inputs(const PlanInputs& in) {
  geo::gdal_init();
  LoadedPlan out;
  PlanSpec& spec = out.spec;
  spec.grading = in.grading;
  if (!(in.grading > 0) || !std::isfinite(in.grading)) throw InputError("size grading", "must be > 0 (size growth per metre)");
  if (in.hmax < 0 || !std::isfinite(in.hmax)) throw InputError("far-field size", "must be a size in metres, > 0");
  if (in.refine_size < 0 || !std::isfinite(in.refine_size)) throw InputError("refinement size", "must be a size in metres, > 0");

  // Model CRS: given, else the first input that has one, else EPSG:32632.
  std::string model_wkt;
  if (!in.crs.empty()) {
    model_wkt = geo::crs_wkt(in.crs, "model CRS");
  } else {
    std::vector<std::string> files;
    if (!in.use_box) files.push_back(in.domain_file);
    for (const auto* list : {&in.refine_files, &in.trace_files, &in.fault_files, &in.section_files})
      files.insert(files.end(), list->begin(), list->end());
    for (const auto& f : files) {
      model_wkt = geo::vector_crs(f);
      if (!model_wkt.empty()) {
        out.notes.push_back("model CRS " + geo::crs_label(model_wkt) + " (from " + f + ")");
        break;
      }
    }
    if (model_wkt.empty()) {
      model_wkt = geo::crs_wkt("EPSG:32632", "");
      out.notes.push_back("model CRS EPSG:32632 (no input has a CRS; give the model CRS to change it)");
    } else {
      geo::QuietGdal quiet;
      OGRSpatialReference s = geo::srs_from_wkt(model_wkt);
      if (!s.IsProjected())
        throw InputError("model CRS", fmt::format("the inputs are in {}, which is not projected: give the model CRS in "
                                                  "metres (e.g. EPSG:32632)",
                                              geo::crs_label(model_wkt)));
    }
  }
  out.crs = geo::crs_label(model_wkt);

  geo::QuietGdal quiet;
  std::unique_ptr<OGRGeometry> domain;
  std::optional<double> domain_size;
  if (in.use_box) {
    const auto [x0, x1, y0, y1] = in.box;
    if (!(x0 < x1) || !(y0 < y1) || !std::isfinite(x0 + x1 + y0 + y1))
      throw InputError("model box", fmt::format("xmin/xmax/ymin/ymax must be increasing: got {}/{}/{}/{}", x0, x1, y0, y1));
    auto ring = std::make_unique<OGRLinearRing>();
    ring->addPoint(x0, y0);
    ring->addPoint(x1, y0);
    ring->addPoint(x1, y1);
    ring->addPoint(x0, y1);
    ring->closeRings();
    auto poly = std::make_unique<OGRPolygon>();
    poly->addRingDirectly(ring.release());
    domain = std::move(poly);
  } else {
    auto feats = read_features(in.domain_file, model_wkt, in);
    OGRMultiPolygon all;
    for (auto& f : feats) {
      if (!is_areal(*f.geom))
        throw InputError(in.domain_file, fmt::format("{} is not a polygon: the domain is a polygon", feature_label(f)));
      if (!f.geom->IsValid())
        throw InputError(in.domain_file, fmt::format("{}: the polygon is not valid (self-intersecting ring?)", feature_label(f)));
      if (all.IsEmpty()) {
        spec.domain_name = f.name;
        domain_size = f.size;
      }
      if (wkbFlatten(f.geom->getGeometryType()) == wkbPolygon) all.addGeometry(f.geom.get());
      else
        for (const auto* p : *f.geom->toMultiPolygon()) all.addGeometry(p);
    }
    if (all.IsEmpty()) throw InputError(in.domain_file, "has no polygon: the domain is a polygon");
    domain.reset(all.getNumGeometries() == 1 ? all.getGeometryRef(0)->clone() : all.UnionCascaded());
    if (!domain) throw InputError(in.domain_file, "cannot merge the domain polygons: " + geo::gdal_error());
  }
  spec.hmax = in.hmax > 0 ? in.hmax : domain_size.value_or(0);
  if (!(spec.hmax > 0))
    throw InputError(in.use_box ? "model box" : in.domain_file,
                     fmt::format("no size for the far field: give the far-field size or a '{}' field on the domain", in.size_field));
  {
    geo::Feature f;
    geo::collect_geometry(*domain, f);
    spec.domain = std::move(f.polygons);
  }

  // Clips a feature to the domain; nullptr if nothing is left.
  auto clipped = [&](const RawFeature& f, const std::string& path, std::size_t& count) -> std::unique_ptr<OGRGeometry> {
    if (domain->Contains(f.geom.get())) return std::unique_ptr<OGRGeometry>(f.geom->clone());
    std::unique_ptr<OGRGeometry> g(domain->Intersection(f.geom.get()));
    if (!g || g->IsEmpty()) {
      out.warnings.push_back(fmt::format("{}: {} lies outside the domain; ignored", path, feature_label(f)));
      return nullptr;
    }
    ++count;
    return g;
  };

  for (const auto& path : in.refine_files) {
    std::size_t cut = 0;
    for (auto& f : read_features(path, model_wkt, in)) {
      if (!is_areal(*f.geom))
        throw InputError(path, fmt::format("{} is not a polygon: refinement areas are polygons", feature_label(f)));
      if (!f.geom->IsValid())
        throw InputError(path, fmt::format("{}: the polygon is not valid (self-intersecting ring?)", feature_label(f)));
      const double size = f.size ? *f.size : in.refine_size;
      if (!(size > 0))
        throw InputError(path, fmt::format("{} has no '{}' field: give its target size there or the refinement size",
                                           feature_label(f), in.size_field));
      auto g = clipped(f, path, cut);
      if (!g) continue;
      PlanRegion r;
      r.name = f.name;
      r.size = size;
      geo::Feature parts;
      geo::collect_geometry(*g, parts);
      r.polygons = std::move(parts.polygons);
      spec.regions.push_back(std::move(r));
    }
    if (cut) out.notes.push_back(fmt::format("{}: {} refinement areas clipped to the domain", path, cut));
  }

  for (const auto& path : in.trace_files) {
    std::size_t cut = 0;
    for (auto& f : read_features(path, model_wkt, in)) {
      if (!is_areal(*f.geom) && !is_linear(*f.geom))
        throw InputError(path, fmt::format("{} is neither a polygon nor a line", feature_label(f)));
      if (is_areal(*f.geom) && !f.geom->IsValid())
        throw InputError(path, fmt::format("{}: the polygon is not valid (self-intersecting ring?)", feature_label(f)));
      auto g = clipped(f, path, cut);
      if (!g) continue;
      geo::Feature parts;
      geo::collect_geometry(*g, parts);
      if (is_areal(*f.geom)) {
        PlanRegion r;
        r.name = f.name;
        r.size = f.size.value_or(0);
        r.outline_group = "trace:" + f.name;
        r.polygons = std::move(parts.polygons);
        spec.regions.push_back(std::move(r));
      } else {
        spec.lines.push_back({"trace:" + f.name, std::move(parts.lines), f.size.value_or(0)});
      }
    }
    if (cut) out.notes.push_back(fmt::format("{}: {} traces clipped to the domain", path, cut));
  }

  // Faults files through the one faults reader and schema of ugs-meshgen and ugs-faultinsert
  // (fault_traces.hpp): ugs-mesh2d uses name, the line and size_m.
  auto fault_features = [&](const std::string& path) {
    std::vector<RawFeature> out;
    for (const auto& r : read_fault_file(path, model_wkt, in.name_field)) {
      RawFeature f;
      f.fid = std::strtoll(r.where.substr(r.where.rfind(' ') + 1).c_str(), nullptr, 10);
      f.name = r.name;
      if (f.name.find_first_of("\"\n\r") != std::string::npos)
        throw InputError(path, fmt::format("feature {}: name '{}' holds quotes or line breaks", f.fid, f.name));
      f.size = r.size;
      auto ml = std::make_unique<OGRMultiLineString>();
      for (const auto& l : r.lines) {
        auto ls = std::make_unique<OGRLineString>();
        for (const auto& q : l) ls->addPoint(q[0], q[1]);
        ml->addGeometryDirectly(ls.release());
      }
      if (ml->getNumGeometries() == 1) f.geom.reset(ml->getGeometryRef(0)->clone());
      else f.geom = std::move(ml);
      out.push_back(std::move(f));
    }
    return out;
  };
  for (const auto& [kind, files] : {std::pair{"fault", &in.fault_files}, std::pair{"section", &in.section_files}}) {
    for (const auto& path : *files) {
      std::size_t cut = 0;
      for (auto& f : std::string(kind) == "fault" ? fault_features(path) : read_features(path, model_wkt, in)) {
        if (!is_linear(*f.geom))
          throw InputError(path, fmt::format("{} is not a line: {}s are lines (traces)", feature_label(f), kind));
        auto g = clipped(f, path, cut);
        if (!g) continue;
        geo::Feature parts;
        geo::collect_geometry(*g, parts);
        if (parts.lines.empty()) continue;
        spec.lines.push_back({std::string(kind) + ":" + f.name, std::move(parts.lines), f.size.value_or(0)});
      }
      if (cut) out.notes.push_back(fmt::format("{}: {} {}s clipped to the domain", path, cut, kind));
    }
  }
  return out;
}

}  // namespace ugs
