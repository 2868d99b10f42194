#pragma once
// Terrain following (docs/swath-plan.md): the flight held at a constant height above the
// ground a DEM describes. Every leg between two waypoints is a straight line in space, so the
// planner adds waypoints where the ground departs from the straight line between the waypoints
// kept by more than a tolerance (Douglas-Peucker on the ground profile of the leg, sampled where
// the DEM's surface bends), and where a leg still passes lower than that between the samples:
// nowhere is the height above ground less than the one asked for less the tolerance.

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "swath/geometry/ground.hpp"

namespace swath::planning {

/// The altitude reference of the waypoints written to QGroundControl and Mission Planner files.
enum class AltitudeFrame {
  relative,  ///< above the take-off point (MAV_FRAME_GLOBAL_RELATIVE_ALT, 3): terrain in altitudes
  amsl,      ///< above mean sea level (MAV_FRAME_GLOBAL, 0): DEM height + height above ground
  terrain,   ///< above the ground (MAV_FRAME_GLOBAL_TERRAIN_ALT, 10): the autopilot's own terrain
             ///< data (ArduPilot TERRAIN_ENABLE) keeps the height; swath still adds the waypoints
};

struct TerrainRequest {
  std::shared_ptr<const geometry::Ground> ground;  ///< required
  /// The most the height above ground may depart from the one asked for between waypoints,
  /// metres, > 0. Smaller: more waypoints.
  double tolerance_m = 2.0;
  AltitudeFrame frame = AltitudeFrame::relative;
};

/// What terrain following made of the plan, for the summary and the checks.
struct TerrainFacts {
  std::string source;
  AltitudeFrame frame = AltitudeFrame::relative;
  double height_above_ground_m = 0.0;  ///< asked for (the imaging altitude)
  double tolerance_m = 0.0;
  double ground_min_m = 0.0, ground_max_m = 0.0;  ///< under the flights, above mean sea level
  /// Height above ground along every leg but take-off and landing, between the waypoints as
  /// flown (straight lines): the least and the most over the DEM's surface (ground_profile).
  double agl_min_m = 0.0, agl_max_m = 0.0;
  double gsd_min_m = 0.0, gsd_max_m = 0.0;  ///< the ground sample distance at those heights
  std::size_t waypoints_added = 0;          ///< over every flight (sorties included)
  /// The steepest vertical speed a leg asks for at the drone's speed, m/s (up > 0, down < 0).
  double climb_max_m_s = 0.0, descent_max_m_s = 0.0;
  std::size_t legs_too_steep = 0;  ///< legs asking for more than the drone's climb/descent speed
};

/// Indices of the samples of a profile (along_m increasing, at least two) to keep so that the
/// straight line between consecutive kept samples departs from every sample between them by at
/// most tolerance_m; the first and the last are always kept.
std::vector<std::size_t> profile_breaks(const std::vector<double>& along_m,
                                        const std::vector<double>& height_m, double tolerance_m);

const char* frame_name(AltitudeFrame frame);

}  // namespace swath::planning
