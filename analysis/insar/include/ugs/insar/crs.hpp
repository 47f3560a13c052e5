// Coordinate reference systems for PS points: any CRS a user names (projected or geographic),
// and point transformations through OGR/PROJ with x = easting/longitude, y = northing/latitude
// whatever the CRS's official axis order (traditional GIS order).
#pragma once
#include <memory>
#include <string>
#include <vector>

namespace ugs::insar {

// WKT of "EPSG:4326", "EPSG:3035", a WKT or PROJ string, ...; InputError(where) if unknown.
std::string any_crs_wkt(const std::string& user_crs, const std::string& where);
// "EPSG:3035" when the CRS has an authority code, else its name; "no CRS" for "".
std::string crs_name(const std::string& wkt);
bool is_geographic(const std::string& wkt);

class CoordinateTransform {
public:
  // Identity when either side is empty or both are the same CRS.
  CoordinateTransform(const std::string& from_wkt, const std::string& to_wkt, const std::string& where);
  ~CoordinateTransform();
  CoordinateTransform(const CoordinateTransform&) = delete;
  CoordinateTransform& operator=(const CoordinateTransform&) = delete;

  bool identity() const { return !impl_; }
  // In place; InputError(where_of(i)) for a point PROJ cannot transform.
  void apply(std::vector<double>& x, std::vector<double>& y, const std::vector<std::string>& where_of) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string where_;
};

}  // namespace ugs::insar
