// InSAR persistent scatterers from CSV: the EGMS layout and the generic x,y / lon,lat layout
// (analysis/insar/src/ps_data.cpp), read as ugs-sample and ugs-calibrate read them: once keeping the
// file's coordinates, once reprojected to the model CRS with series required.
#include "fuzz_support.hpp"
#include "ugs/insar/ps_data.hpp"
#include "ugs/meshing/geodata.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string model = ugs::geo::crs_wkt("EPSG:32632", "");
  const std::string path = ugs::fuzz::write_temp("points.csv", data, size);
  auto use = [](const ugs::insar::PsData& d) {
    for (std::size_t p = 0; p < d.points.size(); ++p)
      for (std::size_t k = 0; k < d.dates.size(); ++k) (void)d.value_mm(p, k);
    if (!d.points.empty()) (void)d.find(d.points.back().id);
  };
  ugs::fuzz::outcome([&] { use(ugs::insar::read_ps(path, {})); });
  ugs::fuzz::outcome([&] {
    ugs::insar::PsReadOptions o;
    o.model_crs = model;
    o.require_series = true;
    use(ugs::insar::read_ps(path, o));
  });
  return 0;
}
