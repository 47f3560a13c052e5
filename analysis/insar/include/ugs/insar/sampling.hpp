// Sampling the simulated displacement at PS points: each point is located on the top surface
// and the displacement is interpolated linearly on its triangle, at every result step or at
// given dates (linear in time between steps), relative to a reference date.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ugs/insar/displacement.hpp"
#include "ugs/insar/los.hpp"
#include "ugs/insar/ps_data.hpp"
#include "ugs/insar/surface.hpp"

namespace ugs::insar {

struct LocatedPoint {
  PsPoint point;
  SurfaceHit hit;
};

struct Located {
  std::vector<LocatedPoint> sampled;   // inside the surface, plus outside ones when kept
  std::vector<LocatedPoint> outside;   // outside and not kept (reported)
};

Located locate_points(const SurfaceLocator& locator, const std::vector<PsPoint>& points, bool keep_outside);

// InputError(data.path, "none of the N PS points lies on the model's top surface (x .., y ..);
// wrong CRS?") when no point of `data` is inside `surface`'s plan footprint.
void require_some_on_surface(const TopSurface& surface, const PsData& data);

struct Samples {
  std::vector<LocatedPoint> points;
  std::vector<std::int64_t> dates;
  std::optional<std::int64_t> reference;  // series are u(t) - u(reference) when set
  std::vector<double> enu;                // points x dates x 3 (m); NaN where the results do not reach
  const double* at(std::size_t p, std::size_t d) const { return enu.data() + (p * dates.size() + d) * 3; }
};

// `dates` empty = every result step. A reference outside the results' time range is an InputError.
Samples sample_displacement(SurfaceDisplacement& results, const std::vector<LocatedPoint>& points,
                            std::vector<std::int64_t> dates, std::optional<std::int64_t> reference);

// The sample table (one row per point and date), as ugs-sample writes it:
//   pid,date,x_m,y_m,x_surface_m,y_surface_m,z_surface_m,offset_m,inside,east_mm,north_mm,up_mm[,los_<name>_mm...]
// Dates where every point is NaN (beyond the results) are left out.
void write_samples_csv(const std::string& path, const Samples& samples, const std::vector<LosGeometry>& los,
                       const std::vector<std::string>& comments);

// Reads such a table back (ugs-report): points with their sampled location, dates, and east,
// north, up in metres. InputError for a table that is not one.
Samples read_samples_csv(const std::string& path);

}  // namespace ugs::insar
