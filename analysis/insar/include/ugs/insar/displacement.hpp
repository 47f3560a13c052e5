// The displacement over time on the top surface, read from a results file (HDF5 + XDMF written
// by ugs-solve: the node field `u` in m of the full results, or `u_mm` of its top-surface file,
// east, north, up) at every step, restricted to the surface nodes (matched by node tag), and its
// linear interpolation in time.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ugs/formats/fields.hpp"
#include "ugs/insar/surface.hpp"

namespace ugs::insar {

// Date of a step as seconds since 1970 (its ISO date if it parses, else its time attribute).
std::int64_t step_time(const FieldStep& s);

// value(t) = (1 - w) v[i0] + w v[i1]; nullopt when t lies outside [times.front(), times.back()].
struct TimeBracket {
  std::size_t i0 = 0, i1 = 0;
  double w = 0;
};
std::optional<TimeBracket> bracket_time(const std::vector<std::int64_t>& times, std::int64_t t);

class SurfaceDisplacement {
public:
  // `field` "" picks "u", else "displacement", else "u_mm" (ugs-solve's top-surface file; a name
  // ending in _mm is in mm and converted to m). InputError when the file, the field or a surface
  // node is missing, or when the surface's nodes sit elsewhere in the results (another mesh).
  SurfaceDisplacement(const std::string& h5_path, const TopSurface& surface, const std::string& field = "");
  ~SurfaceDisplacement();

  const std::vector<std::int64_t>& times() const { return times_; }
  const std::vector<FieldStep>& steps() const;
  const std::string& field() const { return field_; }
  const TopSurface& surface() const { return surface_; }
  const std::string& path() const;
  FieldSeriesReader& reader();

  // 3 values per surface node (m), read once per step and kept.
  const std::vector<double>& at_step(std::size_t step);
  // Interpolated in time; nullopt outside the results' time range.
  std::optional<std::vector<double>> at_time(std::int64_t t);

private:
  std::unique_ptr<FieldSeriesReader> reader_;
  const TopSurface& surface_;
  std::string field_;
  double scale_ = 1.0;
  std::vector<std::int64_t> times_;
  std::vector<std::uint32_t> rows_;               // results row of each surface node
  std::vector<std::vector<double>> cache_;
};

}  // namespace ugs::insar
