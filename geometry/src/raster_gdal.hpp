#pragma once
// Internal: raster sampling for the GIS module (GDAL's headers stay in raster_gdal.cpp).

#include <string>
#include <vector>

#include "swath/geometry/geotiff.hpp"
#include "swath/geometry/ground.hpp"
#include "swath/geometry/point.hpp"

namespace swath::geometry::detail {

/// Band 1 of the raster at `path` at WGS84 points, bilinear between pixel centres, in metres;
/// NaN outside the raster or next to a nodata pixel. `asked_unit_m`: metres per unit of heights
/// (--dem-units; 0: not given) where the band declares none. `resolution_m`: half the pixel's
/// shorter side, metres. Opened datasets stay open for the process (a plan samples one DEM many
/// times), pixels read a tile at a time. Throws InputError naming the file.
void sample_raster(const std::string& path, double asked_unit_m,
                   const std::vector<GeoPoint>& points, std::vector<double>& values,
                   double& resolution_m);

/// Where the straight line a-b (WGS84) crosses the lines through the raster's pixel centres, as
/// fractions of a-b in (0, 1), increasing: the bilinear surface may bend there, and between two of
/// them it is a quadratic in the fraction (the line taken straight in the raster's CRS: over a leg
/// of 100 m the two lines part by millimetres). Empty where the ends cannot be transformed.
void raster_bends(const std::string& path, double asked_unit_m, const GeoPoint& a,
                  const GeoPoint& b, std::vector<double>& fractions);

/// What sample_raster() has read of `path` so far (zero when it is not open).
DemReads raster_reads(const std::string& path);

/// Closes `path` if open (its file may then change: the fuzz targets reuse one name).
void forget_raster(const std::string& path);

/// The path of a grid PROJ installs (egm96_15.gtx) in PROJ's search paths; throws InputError
/// naming the Debian package when it is absent.
std::string proj_grid(const std::string& name);

/// The GeoTIFF bytes of a raster in the local frame (geotiff.hpp); throws std::runtime_error.
std::string geotiff(const LocalRaster& raster);

}  // namespace swath::geometry::detail
