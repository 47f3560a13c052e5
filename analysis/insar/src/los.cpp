#include "ugs/insar/los.hpp"

#include <charconv>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "ugs/formats/csv.hpp"
#include "ugs/formats/error.hpp"

namespace ugs::insar {

std::array<double, 3> los_unit_vector(double incidence_deg, double heading_deg) {
  const double d = std::numbers::pi / 180.0;
  const double th = incidence_deg * d, al = heading_deg * d;
  return {-std::sin(th) * std::cos(al), std::sin(th) * std::sin(al), std::cos(th)};
}

double los_displacement(const std::array<double, 3>& u, const LosGeometry& g) {
  const auto l = los_unit_vector(g);
  return u[0] * l[0] + u[1] * l[1] + u[2] * l[2];
}

namespace {
// The one finite-number parser of option and case text (formats/csv.hpp).
bool to_double(std::string_view s, double& v) {
  const auto parsed = parse_finite_number(s);
  if (parsed) v = *parsed;
  return parsed.has_value();
}
}  // namespace

LosGeometry parse_los_geometry(const std::string& name, const std::string& text, const std::string& where) {
  const auto slash = text.find('/');
  LosGeometry g;
  g.name = name;
  if (slash == std::string::npos || !to_double(std::string_view(text).substr(0, slash), g.incidence_deg) ||
      !to_double(std::string_view(text).substr(slash + 1), g.heading_deg))
    throw InputError(where, fmt::format("'{}' is not INCIDENCE/HEADING in degrees (e.g. 35/-10)", text));
  if (!(g.incidence_deg >= 0 && g.incidence_deg < 90))
    throw InputError(where, fmt::format("incidence {} deg outside [0, 90)", g.incidence_deg));
  if (!(g.heading_deg >= -360 && g.heading_deg <= 360))
    throw InputError(where, fmt::format("heading {} deg outside [-360, 360]", g.heading_deg));
  return g;
}

}  // namespace ugs::insar
