#pragma once
// One drone, as every program sees it (docs/architecture.md: one concept, one type): its name,
// home, speeds and how much it can fly, read from a fleet file (swath plan, swath-fleet) or a drone
// profile (swath-energy budget, with energy's battery and power models beside it); and a fleet.

#include <optional>
#include <string>
#include <vector>

#include "swath/base/range_check.hpp"
#include "swath/geometry/point.hpp"
#include "swath/vehicle/kinematics.hpp"

namespace swath::vehicle {

namespace limits {
// The ranges a fleet file's numbers must lie in (docs/reliability.md).
inline constexpr base::Range kDrones{1, 100, "drones", "one file set per drone"};
inline constexpr base::Range kEndurance_s{1, 604'800, "s", "a week"};
inline constexpr base::Range kBatteryLevel{0, 1, "", "a fraction of a full charge"};
inline constexpr base::Range kSpeed_m_s{0.5, 100, "m/s", "hover-and-capture to fast fixed-wing"};
inline constexpr base::Range kVerticalSpeed_m_s{0.1, 30, "m/s", "climb and descent"};
}  // namespace limits

struct Drone {
  std::string name;
  /// Share of the work in (0, 1] as the paper gives it; or derived from the three below.
  std::optional<double> capability;
  std::optional<double> battery_level;     ///< [0, 1] of a full charge
  std::optional<double> endurance_s;       ///< flight time on a full charge, seconds
  std::optional<double> speed_m_s;         ///< cruise speed, m/s (> 0)
  std::optional<geometry::GeoPoint> home;  ///< its own take-off point; the fleet's otherwise
  /// Vertical speeds, > 0. Defaults: ArduCopter's WPNAV_SPEED_UP and WPNAV_SPEED_DN, what an
  /// autopilot flies when nothing says otherwise (a mission file carries no climb rate).
  double climb_speed_m_s = kDefaultClimb_m_s;
  double descent_speed_m_s = kDefaultDescent_m_s;
  double max_airspeed_m_s = 25.0;  ///< the airframe's limit through the air, > 0
  /// Horizontal acceleration and braking, m/s² (the legs from rest to rest, kinematics.hpp).
  /// Default: ArduCopter's WPNAV_ACCEL, kDefaultAccel_m_s2 (swath plan's); swath-fleet's is 2
  /// unless the fleet file gives accel_m_s2 (FleetFileRules).
  double accel_m_s2 = kDefaultAccel_m_s2;

  /// Maximum distance it can fly: level x endurance x speed; empty when only a capability is given.
  std::optional<double> range_m() const;
};

struct Fleet {
  geometry::GeoPoint home;
  std::vector<Drone> drones;
};

/// Parses a fleet YAML document:
///   home: {lat: 47.397, lon: 8.541, alt: 0}
///   drones:
///     - name: alpha
///       battery_level: 0.9
///       endurance_s: 1500
///       speed_m_s: 8
///     - name: bravo
///       capability: 0.4
///       home: {lat: 47.398, lon: 8.542}
/// Every drone gives either `capability` or all of battery_level, endurance_s, speed_m_s, and all
/// drones the same kind; climb_speed_m_s, descent_speed_m_s and max_airspeed_m_s are optional.
/// The keys only swath-fleet's flights read (mavlink, recharge_s, profile, max_flight_time_s,
/// approach_speed_m_s, approach_within_m, accel_m_s2) are accepted and not used, so one fleet
/// file serves both programs; home_m is refused (a survey needs a home in latitude/longitude).
/// Throws base::InputError naming `source`, the drone and the key: capability <= 0 or > 1, level
/// outside [0, 1], endurance or speed <= 0, zero drones, bad coordinates, unknown keys.
Fleet parse_fleet(const std::string& yaml_text, const std::string& source);

/// `n` equal drones (capability 1/n each) sharing `home`. Throws InputError when n < 1.
Fleet equal_fleet(int n, const geometry::GeoPoint& home);

}  // namespace swath::vehicle
