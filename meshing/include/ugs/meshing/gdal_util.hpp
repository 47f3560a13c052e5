// GDAL/OGR helpers shared by ugs_meshing and ugs_insar: quiet error handling, CRS
// conversions and dataset handles.
#pragma once
#include <memory>
#include <string>

#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>

#include "ugs/meshing/geodata.hpp"

namespace ugs::geo {

void gdal_init();

// GDAL errors go to its last-error slot instead of stderr while this lives (library code never prints).
class QuietGdal {
public:
  QuietGdal();
  ~QuietGdal();
  QuietGdal(const QuietGdal&) = delete;
  QuietGdal& operator=(const QuietGdal&) = delete;
};
std::string gdal_error();

struct GdalClose {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};
using GdalDatasetPtr = std::unique_ptr<GDALDataset, GdalClose>;
GdalDatasetPtr open_vector(const std::string& path);

// x = easting, y = northing whatever the CRS's official axis order.
OGRSpatialReference srs_from_wkt(const std::string& wkt);
std::string wkt_of(const OGRSpatialReference& s);
// nullptr when no transformation is needed (same CRS or one side unknown).
std::unique_ptr<OGRCoordinateTransformation> transformation(const std::string& from_wkt, const std::string& to_wkt,
                                                            const std::string& where);

// Appends the polygons and lines of `g` (multi-parts and collections flattened; points ignored).
void collect_geometry(const OGRGeometry& g, Feature& f);

}  // namespace ugs::geo
