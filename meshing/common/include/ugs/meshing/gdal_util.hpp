// GDAL/OGR helpers shared by ugs_meshing and ugs_insar: quiet error handling, CRS
// conversions and dataset handles.
#pragma once
#include <memory>
#include <string>

#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogrsf_frmts.h>
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
// Opens a vector file; a GeoJSON file is also checked for coordinates that are not numbers (GDAL
// would drop such a geometry silently): InputError naming the feature and the value.
GdalDatasetPtr open_vector(const std::string& path);
// The layer's CRS as WKT ("" if none). When `used` (the coordinates will be transformed with it):
// InputError when a GeoJSON file has no "crs" member but coordinates that are not longitude/latitude
// (GDAL takes such a file as WGS 84 and PROJ would fail with "Invalid coordinate").
std::string layer_wkt(const std::string& path, GDALDataset& ds, OGRLayer& layer, bool used);

// x = easting, y = northing whatever the CRS's official axis order.
OGRSpatialReference srs_from_wkt(const std::string& wkt);
std::string wkt_of(const OGRSpatialReference& s);
// nullptr when no transformation is needed (same CRS or one side unknown).
std::unique_ptr<OGRCoordinateTransformation> transformation(const std::string& from_wkt, const std::string& to_wkt,
                                                            const std::string& where);

// Appends the polygons and lines of `g` (multi-parts and collections flattened; points ignored).
void collect_geometry(const OGRGeometry& g, Feature& f);

}  // namespace ugs::geo
