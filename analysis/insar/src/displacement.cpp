#include "ugs/insar/displacement.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"

namespace ugs::insar {

std::int64_t step_time(const FieldStep& s) {
  if (auto t = parse_iso_date(s.date)) return *t;
  return static_cast<std::int64_t>(std::llround(s.time));
}

std::optional<TimeBracket> bracket_time(const std::vector<std::int64_t>& times, std::int64_t t) {
  if (times.empty() || t < times.front() || t > times.back()) return std::nullopt;
  const auto it = std::lower_bound(times.begin(), times.end(), t);
  const std::size_t i = static_cast<std::size_t>(it - times.begin());
  if (times[i] == t) return TimeBracket{i, i, 0.0};
  return TimeBracket{i - 1, i, double(t - times[i - 1]) / double(times[i] - times[i - 1])};
}

SurfaceDisplacement::SurfaceDisplacement(const std::string& h5, const TopSurface& surface, const std::string& field)
    : reader_(std::make_unique<FieldSeriesReader>(h5)), surface_(surface), field_(field) {
  const auto& steps = reader_->steps();
  if (steps.empty()) throw InputError(h5, "has no output steps");
  for (const auto& s : steps) {
    times_.push_back(step_time(s));
    if (times_.size() > 1 && times_.back() <= times_[times_.size() - 2])
      throw InputError(h5, fmt::format("steps are not in increasing date order at {}", s.date));
  }
  const auto names = reader_->node_field_names(0);
  if (field_.empty()) {
    for (const char* n : {"u", "displacement", "u_mm"})
      if (std::find(names.begin(), names.end(), n) != names.end()) {
        field_ = n;
        break;
      }
    if (field_.empty()) {
      std::string have;
      for (const auto& n : names) have += (have.empty() ? "" : ", ") + n;
      throw InputError(h5, fmt::format("no displacement node field 'u' (node fields: {})", have.empty() ? "none" : have));
    }
  }
  // Names say the unit: "u_mm" (ugs-solve's top-surface file) is in mm, anything else in m.
  if (field_.size() > 3 && field_.compare(field_.size() - 3, 3, "_mm") == 0) scale_ = 1e-3;
  // Surface nodes -> results rows, by tag; their coordinates must agree (same model).
  const auto tags = reader_->node_tags();
  const auto x = reader_->coordinates();
  std::unordered_map<std::uint64_t, std::uint32_t> row_of;
  row_of.reserve(tags.size());
  for (std::uint32_t i = 0; i < tags.size(); ++i) row_of.emplace(tags[i], i);
  const auto e = surface.extent();
  const double tol = 1e-6 * std::max({e[1] - e[0], e[3] - e[2], 1.0});
  rows_.resize(surface.points.size());
  for (std::size_t k = 0; k < surface.points.size(); ++k) {
    const auto it = row_of.find(surface.node_tags[k]);
    if (it == row_of.end())
      throw InputError(h5, fmt::format("no node {} of the top surface ({}): results and mesh are from different models",
                                       surface.node_tags[k], surface.source));
    const auto& a = x[it->second];
    const auto& b = surface.points[k];
    if (std::abs(a[0] - b[0]) > tol || std::abs(a[1] - b[1]) > tol || std::abs(a[2] - b[2]) > tol)
      throw InputError(h5, fmt::format("node {} is at ({:.3f}, {:.3f}, {:.3f}) but at ({:.3f}, {:.3f}, {:.3f}) in {}: results "
                                       "and mesh are from different models", surface.node_tags[k], a[0], a[1], a[2], b[0],
                                       b[1], b[2], surface.source));
    rows_[k] = it->second;
  }
  cache_.resize(steps.size());
}

SurfaceDisplacement::~SurfaceDisplacement() = default;

const std::vector<FieldStep>& SurfaceDisplacement::steps() const { return reader_->steps(); }
const std::string& SurfaceDisplacement::path() const { return reader_->path(); }
FieldSeriesReader& SurfaceDisplacement::reader() { return *reader_; }

const std::vector<double>& SurfaceDisplacement::at_step(std::size_t step) {
  auto& c = cache_.at(step);
  if (!c.empty()) return c;
  const Field f = reader_->node_field(step, field_);
  if (f.components != 3)
    throw InputError(reader_->path(), fmt::format("node field '{}' has {} components, expected 3", field_, f.components));
  c.resize(rows_.size() * 3);
  for (std::size_t k = 0; k < rows_.size(); ++k)
    for (int j = 0; j < 3; ++j) {
      const double v = f.values[3 * std::size_t(rows_[k]) + j];
      if (!std::isfinite(v))
        throw InputError(reader_->path(), fmt::format("node field '{}' at step {}: top-surface node {} has component {} = {} "
                                                      "(expected finite values)", field_, reader_->steps()[step].date,
                                                      surface_.node_tags[k], j, v));
      c[3 * k + j] = scale_ * v;
    }
  return c;
}

std::optional<std::vector<double>> SurfaceDisplacement::at_time(std::int64_t t) {
  const auto b = bracket_time(times_, t);
  if (!b) return std::nullopt;
  const auto& a = at_step(b->i0);
  if (b->w == 0) return a;
  const auto& c = at_step(b->i1);
  std::vector<double> v(a.size());
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = (1 - b->w) * a[i] + b->w * c[i];
  return v;
}

}  // namespace ugs::insar
