#pragma once
// Energy, time and state of charge of waypoint missions (swath's mission.geojson or a
// QGroundControl .plan), drone by drone.

#include <optional>
#include <string>
#include <vector>

#include "swath/energy/sim_config.hpp"
#include "swath/geometry/point.hpp"
#include "swath/missions/mission.hpp"

namespace swath::energy {

/// One drone's flight as the mission file gives it, in a local frame at `home` (metres, x east,
/// y north). The drone takes off at home, climbs to the first point's altitude, flies the points
/// in order, hovering at each for its hold, and, when `returns_home`, flies back and lands at home.
struct WaypointMission {
  std::string drone;  ///< "drone-1", or the file name for a .plan
  geometry::GeoPoint home;
  std::vector<geometry::Point2> points;  ///< local metres, in flight order
  std::vector<double> altitudes_m;       ///< above home, one per point
  std::vector<double> speeds_m_s;        ///< ground speed of the leg into each point; 0: unknown
  std::vector<double> holds_s;           ///< hover at each point on reaching it, s (absent: none)
  bool returns_home = true;
};

/// Reads every drone's mission: a GeoJSON FeatureCollection (features with role "path", their
/// "drone", "altitude_m" and "speed_m_s" properties, and a "home" point; a LineString with 3-D
/// coordinates needs no altitude_m), a QGC .plan or a WPL 110 file (read by swath::missions, each
/// item's altitude frame honoured). Throws base::InputError naming the
/// file, the feature or item, and the problem.
std::vector<WaypointMission> read_waypoint_missions(const std::string& path);
std::vector<WaypointMission> parse_waypoint_missions(const std::string& text,
                                                     const std::string& source);

/// One mission file's flight as the budget flies it: take-off, waypoints, loiters, landing and
/// return to launch, speeds from DO_CHANGE_SPEED, altitudes above home from each item's frame
/// (AMSL less the file's home altitude; terrain-relative read as above home); the holds of
/// waypoints and LOITER_TIME (param1), NAV_DELAY and CONDITION_DELAY (param1, held at the point
/// before them, or at the first point when none is) hovered.
WaypointMission waypoint_mission(const missions::Mission& mission);

/// A moment of the flight.
struct BudgetPoint {
  double t_s = 0.0;
  geometry::Point2 position;  ///< local metres
  geometry::GeoPoint geo;
  double altitude_m = 0.0;
  double soc = 0.0;
  double energy_j = 0.0;  ///< used so far
};

/// A drone's budget. Legs are flown at constant speed (accelerations and corner turns are not
/// modelled), climbs and descents vertically at the profile's rates, holds at the power of level
/// flight at the wind's speed (hovering in place is flying against the wind).
struct DroneBudget {
  std::string drone;
  double distance_m = 0.0;  ///< horizontal
  double flight_time_s = 0.0;
  double energy_j = 0.0;
  double landing_soc = 0.0;     ///< negative: the charge it would lack (it cannot finish)
  double reserve_margin = 0.0;  ///< landing_soc - reserve_soc (negative: into the reserve)
  std::optional<BudgetPoint> reserve_crossed;  ///< where the SoC falls to the reserve
  std::optional<BudgetPoint> battery_empty;    ///< where it falls to 0
  std::vector<BudgetPoint> timeline;           ///< take-off, every point, landing
  bool can_finish() const { return !reserve_crossed; }
};

/// The budget of one mission with one drone profile. Throws base::InputError when the drone
/// cannot fly a leg at all (wind stronger than its airspeed, power beyond the battery's maximum).
DroneBudget budget(const WaypointMission& mission, const DroneProfile& drone);

}  // namespace swath::energy
