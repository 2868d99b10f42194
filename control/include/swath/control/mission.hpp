#pragma once
// What a simulated multirotor is asked to fly (docs/swath-control.md): legs in a local frame
// (world ENU metres, origin at the mission's home), the speed the file asks for, and — for a swath
// plan — the area and the no-fly zones the flown track is checked against (docs/swath-plan.md,
// 'Missions that fly as planned'; docs/swath-control.md: "fly it before you fly it"). Built from
// swath's mission.geojson or a QGroundControl .plan (one drone of it), a stage plan (the path its
// guidance field flies), or `random:N@WxH` (the paper's missions).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "swath/geometry/point.hpp"
#include "swath/vehicle/vec3.hpp"

namespace swath::control {

using vehicle::Vec3;

struct FlightMission {
  std::string name;  ///< for messages and summary.json: "meadow/mission.geojson, drone alpha"
  /// Legs flown one after the other, each a polyline flown without stopping, world ENU metres.
  /// The flight starts in hover at legs[0][0].
  std::vector<std::vector<Vec3>> legs;
  double speed_m_s = 0;  ///< the file's cruise speed, m/s; 0: the file gives none
  /// For a swath plan: the area (outer ring, then holes) and the no-fly zones, local metres
  /// (x east, y north) in the legs' frame; empty otherwise.
  std::vector<std::vector<geometry::Point2>> area;
  std::vector<std::vector<geometry::Point2>> no_fly;
  double planned_clearance_m = 0;  ///< the plan's own least clearance to no-fly zones; 0: unknown
};

/// `random:N@WxH`: N ≥ 2 waypoints, W and H > 0 metres (≤ 100 km).
struct RandomSpec {
  int waypoints = 8;
  double width_m = 20, height_m = 20;
};
/// The spec, or nullopt when `text` does not start with "random:"; throws base::InputError when
/// it does but is malformed or out of range.
std::optional<RandomSpec> parse_random_spec(const std::string& text);

/// N waypoints uniform in [0, W] × [0, H] at `altitude_m` (paper 002 §7's missions), drawn from
/// the stream "mission" of `seed`; each a leg of its own (the carrot stops at every waypoint).
FlightMission random_mission(const RandomSpec& spec, double altitude_m, std::uint64_t seed);

/// Options for reading a mission file.
struct MissionOptions {
  std::string drone;             ///< name or 1-based number; empty: the only (or first) drone
  double altitude_m = 0;         ///< > 0: every point at this height instead of the file's
  geometry::Point2 start_m;      ///< stage plans: the take-off point, local metres
  double stage_speed_m_s = 5.0;  ///< stage plans: the guidance's speed, m/s
};

/// Reads MISSION: a `random:` spec, swath's mission.geojson, a QGC .plan or .waypoints (one drone:
/// home at the first point's altitude → its points → home when it returns), or a stage plan
/// (.stages or .yaml: one leg along the guided path). The drones' names are listed when
/// `options.drone` names none of them. Throws base::InputError naming the file and the problem
/// (fewer than 2 distinct points, among others).
FlightMission read_flight_mission(const std::string& mission, const MissionOptions& options,
                                  std::uint64_t seed, std::vector<std::string>* warnings);

/// The mission repeated for `--loop`: the legs, then a leg back to the first point when the last
/// one ends elsewhere.
FlightMission closed_for_loop(FlightMission mission);

}  // namespace swath::control
