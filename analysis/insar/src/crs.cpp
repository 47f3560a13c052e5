#include "ugs/insar/crs.hpp"

#include <cmath>
#include <mutex>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <fmt/format.h>

#include "gdal_quiet.hpp"
#include "ugs/formats/error.hpp"

namespace ugs::insar {

std::string any_crs_wkt(const std::string& user, const std::string& where) {
  GdalQuiet quiet;
  OGRSpatialReference s;
  if (user.empty() || s.SetFromUserInput(user.c_str()) != OGRERR_NONE)
    throw InputError(where, fmt::format("unknown coordinate reference system '{}' (e.g. \"EPSG:32632\")", user));
  return wkt_of_srs(s);
}

std::string crs_name(const std::string& wkt) {
  if (wkt.empty()) return "no CRS";
  GdalQuiet quiet;
  OGRSpatialReference s = srs_of(wkt);
  s.AutoIdentifyEPSG();
  const char* auth = s.GetAuthorityName(nullptr);
  const char* code = s.GetAuthorityCode(nullptr);
  if (auth && code) return fmt::format("{}:{}", auth, code);
  const char* name = s.GetName();
  return name ? name : "unnamed CRS";
}

bool is_geographic(const std::string& wkt) {
  if (wkt.empty()) return false;
  GdalQuiet quiet;
  return srs_of(wkt).IsGeographic();
}

struct CoordinateTransform::Impl {
  std::unique_ptr<OGRCoordinateTransformation> ct;
  std::mutex mutex;  // an OGRCoordinateTransformation is not thread-safe
};

CoordinateTransform::CoordinateTransform(const std::string& from, const std::string& to, const std::string& where)
    : where_(where) {
  if (from.empty() || to.empty() || from == to) return;
  GdalQuiet quiet;
  OGRSpatialReference a = srs_of(from), b = srs_of(to);
  if (a.IsSame(&b)) return;
  impl_ = std::make_unique<Impl>();
  impl_->ct.reset(OGRCreateCoordinateTransformation(&a, &b));
  if (!impl_->ct)
    throw InputError(where, fmt::format("no transformation from {} to {}: {}", crs_name(from), crs_name(to),
                                        gdal_last_error()));
}

CoordinateTransform::~CoordinateTransform() = default;

void CoordinateTransform::apply(std::vector<double>& x, std::vector<double>& y,
                                const std::vector<std::string>& where_of) const {
  if (!impl_ || x.empty()) return;
  GdalQuiet quiet;
  std::lock_guard lock(impl_->mutex);
  std::vector<int> ok(x.size(), 0);
  impl_->ct->Transform(static_cast<int>(x.size()), x.data(), y.data(), nullptr, ok.data());
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!ok[i] || !std::isfinite(x[i]) || !std::isfinite(y[i]))
      throw InputError(i < where_of.size() ? where_of[i] : where_, "point cannot be transformed to the model CRS");
}

}  // namespace ugs::insar
