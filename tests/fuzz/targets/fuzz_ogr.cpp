// GeoJSON (and any vector input OGR reads) given to the tools: the input is a /vsimem/ file that
// only the GeoJSON driver may open, read as
//   - ugs-mesh2d reads its domain, refinement, trace, fault and section files
//     (meshing/plan/src/plan_inputs.cpp, through meshing/common/src/geodata.cpp),
//   - the faults file of ugs-meshgen and ugs-faultinsert (meshing/common/src/fault_traces_ogr.cpp),
//   - a polygon / feature file (geo::read_vector, --inside of ugs-calibrate, material polygons),
//   - the PS points of ugs-sample (analysis/insar/src/ps_data.cpp, OGR layout).
#include <cpl_vsi.h>
#include <gdal_priv.h>

#include "fuzz_support.hpp"
#include "ugs/insar/ps_data.hpp"
#include "ugs/meshing/fault_traces.hpp"
#include "ugs/meshing/gdal_util.hpp"
#include "ugs/meshing/geodata.hpp"
#include "ugs/meshing/plan_mesh.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ugs::geo::gdal_init();
  // Only the GeoJSON driver: the other drivers' own parsers are GDAL's business, not ours.
  GDALDriverManager* m = GetGDALDriverManager();
  for (int i = m->GetDriverCount() - 1; i >= 0; --i) {
    GDALDriver* d = m->GetDriver(i);
    if (std::string(d->GetDescription()) != "GeoJSON") {
      m->DeregisterDriver(d);
      delete d;  // as GDALDestroyDriverManager would
    }
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string model = ugs::geo::crs_wkt("EPSG:32632", "");
  const char* path = "/vsimem/fuzz.geojson";
  VSILFILE* f = VSIFileFromMemBuffer(path, const_cast<GByte*>(data), size, FALSE);
  if (!f) return 0;
  VSIFCloseL(f);

  ugs::fuzz::outcome([&] { (void)ugs::geo::vector_crs(path); });
  ugs::fuzz::outcome([&] { (void)ugs::geo::read_vector(path, model); });
  ugs::fuzz::outcome([&] { (void)ugs::geo::read_vector(path, model, "name = 'Pool C'"); });
  ugs::fuzz::outcome([&] { (void)ugs::read_fault_traces(path, model); });
  ugs::fuzz::outcome([&] {
    ugs::PlanInputs in;
    in.domain_file = path;
    in.hmax = 5000;
    in.refine_size = 600;
    in.refine_files = {path};
    in.trace_files = {path};
    in.fault_files = {path};
    in.section_files = {path};
    (void)ugs::load_plan_inputs(in);
  });
  ugs::fuzz::outcome([&] {
    ugs::PlanInputs in;  // the CRS from the file, a box domain: the lines alone
    in.use_box = true;
    in.box = {400000, 700000, 4900000, 5200000};
    in.hmax = 5000;
    in.fault_files = {path};
    (void)ugs::load_plan_inputs(in);
  });
  ugs::fuzz::outcome([&] {
    ugs::insar::PsReadOptions o;
    o.model_crs = model;
    (void)ugs::insar::read_ps(path, o);
  });
  VSIUnlink(path);
  return 0;
}
