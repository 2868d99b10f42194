#pragma once
// The fleet file (docs/formats.md), read in one place for every program: swath plan plans from
// it, swath-fleet flies it. Every key of the format is read and range-checked here; the program
// says which defaults and rules it applies (FleetFileRules), and turns the drones into what it
// needs (vehicle::Fleet for planning, fleet::DroneSpec for swath-fleet).

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "swath/geometry/point.hpp"
#include "swath/vehicle/drone.hpp"
#include "swath/vehicle/kinematics.hpp"

namespace swath::vehicle {

/// What a program asks of a fleet file. The vertical speeds a drone gets when the file gives
/// none differ by program and are documented per program in docs/formats.md.
struct FleetFileRules {
  double climb_speed_m_s = kDefaultClimb_m_s;      ///< default climb_speed_m_s, m/s
  double descent_speed_m_s = kDefaultDescent_m_s;  ///< default descent_speed_m_s, m/s
  /// The drones' accel_m_s2, m/s²; flights take the file's accel_m_s2 over it (swath plan checks
  /// the key's range and plans with this). Default: ArduCopter's WPNAV_ACCEL.
  double accel_m_s2 = kDefaultAccel_m_s2;
  /// true (swath-fleet): the drones are flown — a drone needs a speed_m_s, battery_level,
  /// endurance_s, profile or max_flight_time_s (a capability alone is refused), any may be
  /// missing (the flight defaults), `home` is optional and `home_m` allowed.
  /// false (swath plan): every drone gives a capability, or every drone battery_level,
  /// endurance_s and speed_m_s; the file needs a `home`; `home_m` is refused.
  bool flights = false;
};

/// A drone's `mavlink: {url, sysid}` as written; its grammar belongs to swath-fleet
/// (fleet/vehicle_address.hpp). The `where` texts place the keys for messages
/// ("f.yaml: line 5: drones[0].mavlink").
struct FleetFileLink {
  std::string url;
  std::optional<double> sysid;
  std::string where, url_where, sysid_where;
};

/// One drone of a fleet file: what every program reads (`drone`, with the rules' vertical speeds
/// when the file gives none) and the keys only swath-fleet's flights read.
struct FleetFileDrone {
  Drone drone;
  bool climb_given = false, descent_given = false;  ///< the file gave the vertical speed
  std::optional<std::string> profile;               ///< as written (relative to the file)
  std::optional<double> max_flight_time_s;          ///< s, (1, 604800]
  std::optional<double> approach_speed_m_s;         ///< m/s, [0.1, 100]
  std::optional<double> approach_within_m;          ///< m, [0, 1000]
  std::optional<double> recharge_s;                 ///< s, [0, 86400]
  std::optional<geometry::Point2> home_m;           ///< local metres at swath-fleet's origin
  std::optional<FleetFileLink> mavlink;
  /// "f.yaml: line N: drones[i].home" (its own home), else the same at its name: where
  /// messages about where it stands point.
  std::string where_home;
};

/// One fence polygon, its outer ring in WGS84 degrees (not closed: the last vertex is not the
/// first again).
struct FencePolygon {
  std::vector<geometry::GeoPoint> ring_deg;
  bool inclusion = true;  ///< false: an exclusion (no target inside)
};

/// The fleet file's `fence: {geojson: FILE, max_altitude_m: M}`, its GeoJSON read.
struct FleetFileFence {
  std::vector<FencePolygon> polygons;
  std::optional<double> max_altitude_m;  ///< above home, m, (0, 10000]
};

struct FleetFile {
  std::optional<geometry::GeoPoint> home;  ///< the fleet's home
  /// swath-fleet's spacing of drones sharing the home (and its envelope's separation), m, > 0.
  std::optional<double> separation_m;
  /// swath-fleet's envelope: the ceiling above home, m, (0, 10000] (checked for every program),
  /// and the geofence, read only where drones are flown (FleetFileRules::flights: swath plan
  /// accepts the key and does not open its GeoJSON).
  std::optional<double> ceiling_m;
  std::optional<FleetFileFence> fence;
  std::vector<FleetFileDrone> drones;
};

/// Reads a fleet file. Throws base::InputError naming `source`, the drone, the line and the key:
/// unknown keys, numbers out of range, bad coordinates, zero or more than 100 drones, names given
/// twice, and what `rules` refuse.
/// `fence` is read from its GeoJSON file, relative to `source`.
FleetFile parse_fleet_file(const std::string& yaml_text, const std::string& source,
                           const FleetFileRules& rules);

/// A fence file: GeoJSON Polygon or MultiPolygon (a geometry, Feature or FeatureCollection),
/// lon/lat degrees; a feature's properties.fence is "inclusion" (default) or "exclusion".
/// Throws base::InputError naming `source` and the feature.
std::vector<FencePolygon> parse_fence_geojson(const std::string& text, const std::string& source);

}  // namespace swath::vehicle
