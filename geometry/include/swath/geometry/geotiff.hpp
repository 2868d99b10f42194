#pragma once
// A georeferenced raster of swath's local frame as GeoTIFF bytes (docs/swath-plan.md),
// written by GDAL through the GIS module. The CRS is the local frame itself: PROJ's ellipsoidal
// orthographic projection about the frame's origin (+proj=ortho on WGS84), whose easting and
// northing are the east and north of GeographicLib's LocalCartesian frame for points on the
// ellipsoid, so a GIS places every cell where swath computed it.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::geometry {

struct LocalRaster {
  GeoPoint origin;                     ///< the local frame's origin (LocalFrame::origin())
  double west_m = 0.0, north_m = 0.0;  ///< top-left corner, local metres
  double cell_m = 0.0;                 ///< square cells, > 0
  int width = 0, height = 0;           ///< cells; row 0 northernmost
  /// Bands: a description and width x height values, row by row.
  std::vector<std::pair<std::string, std::vector<std::uint16_t>>> bands;
};

/// The GeoTIFF (UInt16 bands, DEFLATE) of `raster`; same raster, same bytes. Throws
/// std::runtime_error when the GIS module is missing or GDAL fails.
std::string geotiff_bytes(const LocalRaster& raster);

}  // namespace swath::geometry
