#pragma once
// A fleet of drones and how much each can fly (DESIGN.md §7).

#include <optional>
#include <string>
#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::planning {

struct Drone {
  std::string name;
  /// Share of the work in (0, 1] as the paper gives it; or derived from the three below.
  std::optional<double> capability;
  std::optional<double> battery_level;     ///< [0, 1] of a full charge
  std::optional<double> endurance_s;       ///< flight time on a full charge, seconds
  std::optional<double> speed_m_s;         ///< cruise speed, m/s (> 0)
  std::optional<geometry::GeoPoint> home;  ///< its own take-off point; the fleet's otherwise

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
/// drones the same kind. Throws base::InputError naming `source`, the drone and the key:
/// capability <= 0 or > 1, level outside [0, 1], endurance or speed <= 0, zero drones, bad
/// coordinates, unknown keys.
Fleet parse_fleet(const std::string& yaml_text, const std::string& source);

/// `n` equal drones (capability 1/n each) sharing `home`. Throws InputError when n < 1.
Fleet equal_fleet(int n, const geometry::GeoPoint& home);

}  // namespace swath::planning
