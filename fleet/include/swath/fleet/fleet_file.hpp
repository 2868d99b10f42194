#pragma once
// swath-fleet's fleet file (docs/formats.md), read by vehicle::parse_fleet_file: swath plan's fleet
// YAML — home, drones with name, battery_level, endurance_s, speed_m_s, climb/descent speeds, their
// own home — read as simulated drones, plus optional per drone:
//   profile: quad.yaml          # a swath-energy drone profile (power and battery), relative to
//                               # the fleet file; default: swath-energy's defaults
//   max_flight_time_s: 60       # must be home by then (else endurance_s × battery_level)
//   approach_speed_m_s: 2       # within approach_within_m of a target (paper 000 §4.2)
//   approach_within_m: 20
//   accel_m_s2: 2
//   recharge_s: 30              # from landing to a full charge
//   home_m: {x_m: 10, y_m: 0}   # local metres at the world's origin, instead of home
// A drone given only a `capability` cannot be simulated and is refused.

#include <string>
#include <vector>

#include "swath/fleet/envelope.hpp"
#include "swath/fleet/runtime.hpp"
#include "swath/geometry/point.hpp"

namespace swath::fleet {

/// The drones of `text`, their homes in local metres at `origin` (a drone without a home of its
/// own starts at the file's `home`, or at the origin when the file has none). Throws
/// base::InputError naming `source`, the line and the key.
std::vector<DroneSpec> parse_fleet_file(const std::string& text, const std::string& source,
                                        const geometry::GeoPoint& origin);

/// A fleet file read once: its drones (as parse_fleet_file) and its envelope (ceiling_m,
/// separation_m, fence; envelope.hpp).
struct FleetFileContents {
  std::vector<DroneSpec> drones;
  Envelope envelope;
};
FleetFileContents parse_fleet_file_contents(const std::string& text, const std::string& source,
                                            const geometry::GeoPoint& origin);
std::vector<DroneSpec> read_fleet_file(const std::string& path, const geometry::GeoPoint& origin);

/// A weights file (docs/swath-fleet.md): the sub-utilities' weights by name —
///   coverage: 1.0       # × H per assigned request
///   fairness: 0.5       # per second a request has waited
///   avoid_zigzag: 0.0   # seconds per metre from the requests' centre
///   commitment: 5.0     # seconds for a drone keeping its target
///   speculative: 1.0    # per forecast given to a drone: p (H − eta)
///   avoid_mutual: 1.0   # q(i→j) service_j gained, q(i→j)(eta_j + service_j) lost per pair
///   closest: 1          # fixed at 1 (the argmax ignores scale)
/// each in [0, 1000]; absent keys keep the defaults. Throws base::InputError naming the key.
Weights parse_weights(const std::string& text, const std::string& source);
Weights read_weights(const std::string& path);

}  // namespace swath::fleet
