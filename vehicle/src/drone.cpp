#include "swath/vehicle/drone.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>

#include "swath/base/input_error.hpp"
#include "swath/base/utf8.hpp"
#include "swath/base/yaml_input.hpp"

namespace swath::vehicle {
namespace {

using base::InputError;

std::string line_of(const YAML::Node& n) {
  return "line " + std::to_string(n.Mark().line + 1);
}

double number(const YAML::Node& n, const std::string& where, const std::string& key) {
  try {
    const double v = n.as<double>();
    if (!std::isfinite(v)) throw YAML::Exception(n.Mark(), "not finite");
    return v;
  } catch (const YAML::Exception&) {
    throw InputError(where + ", " + line_of(n) + ": " + key + " must be a number");
  }
}

geometry::GeoPoint point(const YAML::Node& n, const std::string& where) {
  if (!n.IsMap() || !n["lat"] || !n["lon"])
    throw InputError(where + ", " + line_of(n) + ": a home is {lat: DEG, lon: DEG[, alt: M]}");
  geometry::GeoPoint p{number(n["lat"], where, "lat"), number(n["lon"], where, "lon"),
                       n["alt"] ? number(n["alt"], where, "alt") : 0.0};
  if (std::abs(p.lat_deg) > 90 || std::abs(p.lon_deg) > 180)
    throw InputError(where + ", " + line_of(n) +
                     ": home latitude must be within ±90 and longitude within ±180 degrees");
  return p;
}

}  // namespace

std::optional<double> Drone::range_m() const {
  if (!battery_level || !endurance_s || !speed_m_s) return std::nullopt;
  return *battery_level * *endurance_s * *speed_m_s;
}

namespace {

Fleet fleet_from_yaml(const std::string& text, const std::string& source) {
  const YAML::Node root = base::load_yaml(text, source);
  base::check_plain_unique_keys(root, source);
  if (!root.IsMap() || !root["home"] || !root["drones"])
    throw InputError(source + ": a fleet file needs 'home' and 'drones'");
  Fleet fleet;
  fleet.home = point(root["home"], source);
  const YAML::Node drones = root["drones"];
  if (!drones.IsSequence() || drones.size() == 0)
    throw InputError(source + ": 'drones' must list at least one drone");
  base::check_range(static_cast<double>(drones.size()), limits::kDrones, source + ": the fleet of");
  static const std::set<std::string> known{
      "name", "capability",      "battery_level",     "endurance_s",     "speed_m_s",
      "home", "climb_speed_m_s", "descent_speed_m_s", "max_airspeed_m_s"};
  // What only swath-fleet's flights read (fleet/fleet_file.hpp): one fleet file serves both
  // programs, so the planner accepts these keys and plans without them. `home_m` (a home in the
  // fleet's local metres) is not among them: planning from the fleet's home instead would be a
  // different plan, so it is refused with what to give instead.
  static const std::set<std::string> flight_only{
      "mavlink",           "recharge_s", "profile", "max_flight_time_s", "approach_speed_m_s",
      "approach_within_m", "accel_m_s2"};
  bool any_capability = false, any_range = false;
  for (std::size_t i = 0; i < drones.size(); ++i) {
    const YAML::Node d = drones[i];
    const std::string where = source + ": drone " + std::to_string(i + 1);
    if (!d.IsMap()) throw InputError(where + ", " + line_of(d) + ": a drone is a mapping");
    base::check_plain_unique_keys(d, where);
    for (const auto& kv : d) {
      const std::string key = kv.first.Scalar();
      if (key == "home_m")
        throw InputError(where + ", " + line_of(kv.first) +
                         ": home_m (metres from swath-fleet's origin) cannot place a survey; give "
                         "home: {lat, lon}");
      if (!known.count(key) && !flight_only.count(key))
        throw InputError(where + ", " + line_of(kv.first) + ": unknown key '" + key + "'");
    }
    Drone drone;
    // Names reach JSON, KML and the terminal: keep them valid UTF-8 (a stray Latin-1 byte
    // becomes U+FFFD instead of aborting the plan).
    drone.name = d["name"] ? base::valid_utf8(d["name"].as<std::string>())
                           : "drone-" + std::to_string(i + 1);
    if (d["capability"]) {
      drone.capability = number(d["capability"], where, "capability");
      if (!(*drone.capability > 0 && *drone.capability <= 1))
        throw InputError(where + " (" + drone.name + "): capability " +
                         std::to_string(*drone.capability) + " is outside (0, 1]");
      any_capability = true;
    } else {
      for (const char* key : {"battery_level", "endurance_s", "speed_m_s"})
        if (!d[key])
          throw InputError(where + " (" + drone.name +
                           "): give a capability, or battery_level, endurance_s and speed_m_s");
      drone.battery_level = number(d["battery_level"], where, "battery_level");
      drone.endurance_s = number(d["endurance_s"], where, "endurance_s");
      drone.speed_m_s = number(d["speed_m_s"], where, "speed_m_s");
      const std::string named = where + " (" + drone.name + "): ";
      base::check_range(*drone.battery_level, limits::kBatteryLevel, named + "battery_level");
      base::check_range(*drone.endurance_s, limits::kEndurance_s, named + "endurance_s");
      base::check_range(*drone.speed_m_s, limits::kSpeed_m_s, named + "speed_m_s");
      any_range = true;
    }
    if (d["home"]) drone.home = point(d["home"], where);
    const std::string named = where + " (" + drone.name + "): ";
    auto speed = [&](const char* key, double& value, const base::Range& range) {
      if (!d[key]) return;
      value = number(d[key], where, key);
      base::check_range(value, range, named + key);
    };
    speed("climb_speed_m_s", drone.climb_speed_m_s, limits::kVerticalSpeed_m_s);
    speed("descent_speed_m_s", drone.descent_speed_m_s, limits::kVerticalSpeed_m_s);
    speed("max_airspeed_m_s", drone.max_airspeed_m_s, limits::kSpeed_m_s);
    fleet.drones.push_back(std::move(drone));
  }
  if (any_capability && any_range)
    throw InputError(source +
                     ": give every drone a capability, or every drone battery_level, endurance_s "
                     "and speed_m_s, not a mix");
  return fleet;
}

}  // namespace

Fleet parse_fleet(const std::string& text, const std::string& source) {
  return base::yaml_guard(source, [&] { return fleet_from_yaml(text, source); });
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
