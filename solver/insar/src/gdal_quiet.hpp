// GDAL helpers private to ugs_insar: registration, errors kept off stderr (library code never
// prints), spatial references in traditional GIS axis order.
#pragma once
#include <string>

#include <ogr_spatialref.h>

namespace ugs::insar {

void gdal_register();

class GdalQuiet {
public:
  GdalQuiet();
  ~GdalQuiet();
  GdalQuiet(const GdalQuiet&) = delete;
  GdalQuiet& operator=(const GdalQuiet&) = delete;
};
std::string gdal_last_error();

OGRSpatialReference srs_of(const std::string& wkt);
std::string wkt_of_srs(const OGRSpatialReference& s);

}  // namespace ugs::insar
