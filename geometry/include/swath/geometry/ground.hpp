#pragma once
// The ground under a flight (docs/swath-plan.md): an interface, so that the planner samples
// a raster DEM in a program and a closed-form surface in a test alike, and its DEM implementation
// through the GIS module (GDAL, opened on the first DEM like any GIS file).

#include <memory>
#include <string>
#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::geometry {

/// Heights of the ground above mean sea level (orthometric, the EGM96 geoid as zero).
class Ground {
 public:
  virtual ~Ground() = default;
  /// The height at each WGS84 point (lat_deg/lon_deg; alt_m ignored), metres above mean sea
  /// level; NaN where the ground has no data (outside the DEM, nodata pixels).
  virtual std::vector<double> heights_m(const std::vector<GeoPoint>& points) const = 0;
  /// The spacing, metres, of samples that resolve the surface (a DEM: half its pixel); > 0.
  virtual double resolution_m() const = 0;
  /// What it is, for messages and the summary ("dem.tif").
  virtual std::string source() const = 0;
};

/// What a DEM's heights are measured from.
enum class DemHeights {
  geoid,      ///< mean sea level: SRTM, Copernicus DEM, swissALTI3D, most national DEMs
  ellipsoid,  ///< the WGS84 ellipsoid (GNSS heights): the EGM96 undulation is subtracted
};

/// A single-band raster DEM any GDAL driver reads (GeoTIFF, ASCII grid, .hgt, VRT, ...), in any
/// CRS GDAL can transform WGS84 into, heights in metres, or in feet or US survey feet when the
/// band's unit type says so (converted; another unit is refused). Sampled bilinearly between pixel
/// centres (within half a pixel of the border: the border pixels); NaN outside it or next to
/// nodata. Throws base::InputError (one sentence naming the file) when GDAL cannot open it as a
/// raster or its CRS cannot be reached from WGS84; std::runtime_error when the GIS module is
/// missing.
std::shared_ptr<const Ground> dem_ground(const std::string& path,
                                         DemHeights heights = DemHeights::geoid);

/// The EGM96 geoid's height above the WGS84 ellipsoid (N), metres, at each point, from PROJ's
/// 15' grid egm96_15.gtx (Debian proj-data) interpolated bilinearly (accuracy ~1 m against the
/// full model). Throws base::InputError when the grid is not installed.
std::vector<double> geoid_undulation_m(const std::vector<GeoPoint>& points);

}  // namespace swath::geometry
