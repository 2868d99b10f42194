#pragma once
// The ground under a flight (docs/swath-plan.md): an interface, so that the planner samples
// a raster DEM in a program and a closed-form surface in a test alike, and its DEM implementation
// through the GIS module (GDAL, opened on the first DEM like any GIS file).

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::geometry {

/// The least height above the ground a leg may pass at, metres: what swath plan's check and swath
/// verify demand (preflight::CheckOptions::min_height_m, --min-height's default); terrain following
/// refuses an altitude less --terrain-tolerance below it. In geometry, below both of them.
inline constexpr double kLeastHeightAboveGround_m = 5.0;

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
  /// Where the ground along the straight line a-b may bend, as fractions of a-b in (0, 1),
  /// increasing: between two of them it is a quadratic in the fraction (a DEM, bilinear between
  /// pixel centres, bends where the line crosses a row or column of centres). nullopt: the ground
  /// does not say; it is then sampled every resolution_m and taken as straight between samples.
  virtual std::optional<std::vector<double>> bends(const GeoPoint& a, const GeoPoint& b) const;
};

/// The ground under a straight leg, sampled where its worst point can be found (ground_profile).
struct GroundProfile {
  /// A stretch of the leg where the ground is a quadratic in t:
  /// ground(t) = g0_m + slope_m * (t - t0) + curve_m * (t - t0) * (t - t_mid).
  struct Piece {
    double t0 = 0, t1 = 0, t_mid = 0;
    double g0_m = 0, slope_m = 0, curve_m = 0;
    double at(double x) const {
      return g0_m + slope_m * (x - t0) + curve_m * (x - t0) * (x - t_mid);
    }
  };
  std::vector<double> t;         ///< fractions of the leg, 0 and 1 first and last, increasing
  std::vector<double> ground_m;  ///< the ground at each, metres above mean sea level; NaN: none
  std::vector<Piece> pieces;     ///< covering 0..1 in order
  /// Adds a sample at t (0 < t < 1) with the ground its piece gives; its index.
  std::size_t add(double t);
};

/// The ground under the straight leg `at`(0) to `at`(1) (`length_m` long): every resolution_m,
/// at every bend the ground reports (in stretches of at most 100 m, so that a leg straight in the
/// caller's frame stays straight in the DEM's within millimetres) and half way between bends.
GroundProfile ground_profile(const Ground& ground, const std::function<GeoPoint(double)>& at,
                             double length_m);

/// The least and the most of (a line's height - the ground) over the profile between samples
/// `first` and `last`, the line going from z_first_m to z_last_m (metres above mean sea level),
/// and where (fractions of the leg): within a quadratic piece its extreme, not only its samples.
struct HeightAboveGround {
  double least_m = 0, most_m = 0;
  double t_least = 0, t_most = 0;
};
HeightAboveGround height_above_ground(const GroundProfile& profile, std::size_t first,
                                      std::size_t last, double z_first_m, double z_last_m);

/// What a DEM's heights are measured from.
enum class DemHeights {
  geoid,      ///< mean sea level: SRTM, Copernicus DEM, swissALTI3D, most national DEMs
  ellipsoid,  ///< the WGS84 ellipsoid (GNSS heights): the EGM96 undulation is subtracted
};

/// Metres per foot and per US survey foot (exact), for `--dem-units`.
inline constexpr double kFoot_m = 0.3048;
inline constexpr double kUsSurveyFoot_m = 1200.0 / 3937.0;

/// Metres per unit of a `--dem-units` name: m, ft, us-ft; 0 for anything else.
double dem_unit_m(const std::string& name);

/// A single-band raster DEM any GDAL driver reads (GeoTIFF, ASCII grid, .hgt, VRT, ...), in any
/// CRS GDAL can transform WGS84 into. Heights in the unit the band declares (GDAL unit type: m,
/// ft, US survey foot; converted to metres; another unit is refused), else in `unit_m` metres per
/// unit (--dem-units; 0: metres); a declared unit that a given `unit_m` contradicts is refused.
/// Sampled bilinearly between pixel centres (within half a pixel of the border: the border
/// pixels); NaN outside it or next to nodata. Pixels are read a 64 x 64 tile at a time, only
/// where sampled. Throws base::InputError (one sentence naming the file) when GDAL cannot open
/// or read it (GDAL's reason, the row), its CRS cannot be reached from WGS84, or a height is no
/// ground (beyond -430..8,850 m, or a one-pixel needle or pit: an undeclared void);
/// std::runtime_error when the GIS module is missing.
std::shared_ptr<const Ground> dem_ground(const std::string& path,
                                         DemHeights heights = DemHeights::geoid,
                                         double unit_m = 0.0);

/// What the DEM reader has read of a DEM: RasterIO calls (tiles) and pixels, so that tests can
/// bound the work by the area flown instead of by time.
struct DemReads {
  std::uint64_t tiles = 0;
  std::uint64_t pixels = 0;
};

/// The reads of `path` (as given to dem_ground) so far in this process.
DemReads dem_reads(const std::string& path);

/// Closes `path` if open, so that its file may change (the fuzz targets reuse one name).
void forget_dem(const std::string& path);

/// The EGM96 geoid's height above the WGS84 ellipsoid (N), metres, at each point, from PROJ's
/// 15' grid egm96_15.gtx (Debian proj-data) interpolated bilinearly (accuracy ~1 m against the
/// full model). Throws base::InputError when the grid is not installed.
std::vector<double> geoid_undulation_m(const std::vector<GeoPoint>& points);

}  // namespace swath::geometry
