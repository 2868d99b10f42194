#pragma once
// Internal: raster sampling for the GIS module (GDAL's headers stay in raster_gdal.cpp).

#include <string>
#include <vector>

#include "swath/geometry/geotiff.hpp"
#include "swath/geometry/point.hpp"

namespace swath::geometry::detail {

/// Band 1 of the raster at `path` at WGS84 points, bilinear between pixel centres; NaN outside
/// the raster or next to a nodata pixel. `resolution_m`: half the pixel's shorter side, metres.
/// Opened datasets stay open for the process (a plan samples one DEM many times). Throws
/// InputError naming the file.
void sample_raster(const std::string& path, const std::vector<GeoPoint>& points,
                   std::vector<double>& values, double& resolution_m);

/// The path of a grid PROJ installs (egm96_15.gtx) in PROJ's search paths; throws InputError
/// naming the Debian package when it is absent.
std::string proj_grid(const std::string& name);

/// The GeoTIFF bytes of a raster in the local frame (geotiff.hpp); throws std::runtime_error.
std::string geotiff(const LocalRaster& raster);

}  // namespace swath::geometry::detail
