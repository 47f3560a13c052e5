// GDAL helpers of ugs_insar: those of ugs_meshing (registration, errors kept off stderr — library
// code never prints — and spatial references in traditional GIS axis order) under the names the
// insar sources use.
#pragma once
#include <string>

#include <ogr_spatialref.h>

#include "ugs/meshing/gdal_util.hpp"

namespace ugs::insar {

inline void gdal_register() { geo::gdal_init(); }
using GdalQuiet = geo::QuietGdal;
inline std::string gdal_last_error() { return geo::gdal_error(); }
inline OGRSpatialReference srs_of(const std::string& wkt) { return geo::srs_from_wkt(wkt); }
inline std::string wkt_of_srs(const OGRSpatialReference& s) { return geo::wkt_of(s); }

}  // namespace ugs::insar
