#include "swath/vehicle/drone.hpp"

#include "swath/vehicle/fleet_file.hpp"

namespace swath::vehicle {

std::optional<double> Drone::range_m() const {
  if (!battery_level || !endurance_s || !speed_m_s) return std::nullopt;
  return *battery_level * *endurance_s * *speed_m_s;
}

Fleet parse_fleet(const std::string& text, const std::string& source) {
  FleetFile file = parse_fleet_file(text, source, FleetFileRules{});
  Fleet fleet;
  fleet.home = *file.home;  // the planner's rules need one
  for (FleetFileDrone& d : file.drones) fleet.drones.push_back(std::move(d.drone));
  return fleet;
}

Fleet equal_fleet(int n, const geometry::GeoPoint& home) {
  base::check_range(n, limits::kDrones, "a fleet of");
  Fleet fleet;
  fleet.home = home;
  for (int i = 0; i < n; ++i) {
    Drone d;
    d.name = "drone-" + std::to_string(i + 1);
    d.capability = 1.0 / n;
    fleet.drones.push_back(d);
  }
  return fleet;
}

}  // namespace swath::vehicle
