// Line-of-sight (LOS) projection of a displacement for a SAR acquisition geometry.
//
// Convention (the one EGMS and most PS providers use):
//   - the LOS unit vector points from the ground to the satellite;
//   - incidence angle theta from the vertical at the ground point (degrees);
//   - heading alpha = azimuth of the satellite's flight direction, clockwise from north (degrees);
//   - the radar looks to the right of the flight direction (Sentinel-1, Radarsat, ...).
// The look direction (satellite -> ground) has azimuth alpha + 90 deg, so the ground -> satellite
// direction has azimuth alpha - 90 deg and, in (east, north, up):
//   l = (-sin(theta) cos(alpha),  sin(theta) sin(alpha),  cos(theta))
// d_LOS = u . l is positive when the ground moves towards the satellite.
// Ascending example (heading -10 deg, theta 35 deg): l = (-0.5649, -0.0996, 0.8192): the satellite
// sees from the west, so an eastward motion lengthens the range (negative LOS).
// Descending example (heading 190 deg, theta 40 deg): l = (0.6330, -0.1116, 0.7660).
#pragma once
#include <array>
#include <string>

namespace ugs::insar {

struct LosGeometry {
  std::string name;            // column suffix: "asc" -> los_asc_mm
  double incidence_deg = 0;    // from the vertical, in [0, 90)
  double heading_deg = 0;      // flight direction, clockwise from north
};

// Ground-to-satellite unit vector (east, north, up).
std::array<double, 3> los_unit_vector(double incidence_deg, double heading_deg);
inline std::array<double, 3> los_unit_vector(const LosGeometry& g) { return los_unit_vector(g.incidence_deg, g.heading_deg); }

// u . l for u = (east, north, up).
double los_displacement(const std::array<double, 3>& u_enu, const LosGeometry& g);

// Parses "INCIDENCE/HEADING" in degrees, e.g. "35/-10"; InputError(where) when malformed or out of range.
LosGeometry parse_los_geometry(const std::string& name, const std::string& text, const std::string& where);

}  // namespace ugs::insar
