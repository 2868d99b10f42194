#include "swath/fleet/fleet_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/yaml_input.hpp"
#include "swath/base/yaml_map.hpp"
#include "swath/energy/sim_config.hpp"
#include "swath/fleet/envelope.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/vehicle/fleet_file.hpp"

namespace swath::fleet {

using base::InputError;
using base::YamlMap;

namespace {

// A drone's `mavlink: {url: udp:HOST:PORT | tcp:HOST:PORT, sysid: 1..255}` (docs/swath-fleet.md):
// --vehicles' grammar; sysid defaults to the drone's place + 1 as there. The system id is given
// once: in `sysid`, or as the url's /SYSID.
VehicleAddress vehicle_of(const vehicle::FleetFileLink& link, std::size_t index) {
  VehicleAddress a;
  const auto default_sysid = static_cast<std::uint8_t>(std::min<std::size_t>(index + 1, 255));
  const std::string why = parse_vehicle_address(link.url, default_sysid, a);
  if (!why.empty())
    throw InputError(link.url_where + ": \"" + link.url + "\" " + why +
                     " (use udp:HOST:PORT or tcp:HOST:PORT)");
  if (link.sysid) {
    if (a.sysid_given)
      throw InputError(link.sysid_where + ": the system id is given twice (sysid and the url's /" +
                       std::to_string(a.sysid) + "); give it once");
    const double s = *link.sysid;
    if (s != std::floor(s))
      throw InputError(link.sysid_where + ": " + base::shortest_text(s) +
                       " is not a whole number in 1..255");
    a.sysid = static_cast<std::uint8_t>(s);
    a.sysid_given = true;
  }
  return a;
}

// A swath-energy drone profile (power, battery, speeds), relative to the fleet file.
void apply_profile(const std::string& profile, const std::string& source, DroneSpec& d) {
  std::filesystem::path p = profile;
  if (p.is_relative()) p = std::filesystem::path(source).parent_path() / p;
  const energy::DroneProfile prof = energy::read_drone_profile(p.string());
  d.power = prof.power;
  d.battery = prof.battery;
  if (prof.drone.speed_m_s) d.drone.speed_m_s = prof.drone.speed_m_s;
  d.drone.climb_speed_m_s = prof.drone.climb_speed_m_s;
  d.drone.descent_speed_m_s = prof.drone.descent_speed_m_s;
}

// The fleet file's values over the profile's, the profile's over the defaults: the file's drone
// is kept whole, with the speeds it does not give taken from the profile or the defaults.
void apply_flight_keys(const vehicle::FleetFileDrone& f, DroneSpec& d) {
  d.battery.initial_soc = f.drone.battery_level.value_or(d.battery.initial_soc);
  if (d.battery.reserve_soc >= d.battery.initial_soc)
    d.battery.reserve_soc = 0.5 * d.battery.initial_soc;
  const vehicle::Drone before = d.drone;
  d.drone = f.drone;  // accel_m_s2: the file's, else Kinematics' (fleet_file_rules)
  if (!f.drone.speed_m_s) d.drone.speed_m_s = before.speed_m_s;
  if (!f.climb_given && f.profile) d.drone.climb_speed_m_s = before.climb_speed_m_s;
  if (!f.descent_given && f.profile) d.drone.descent_speed_m_s = before.descent_speed_m_s;
  d.approach_m_s =
      std::min(d.kinematics().cruise_m_s, f.approach_speed_m_s.value_or(d.approach_m_s));
  d.approach_within_m = f.approach_within_m.value_or(d.approach_within_m);
  d.recharge_s = f.recharge_s.value_or(d.recharge_s);
  if (f.drone.endurance_s) d.max_flight_time_s = *f.drone.endurance_s * d.battery.initial_soc;
  d.max_flight_time_s = f.max_flight_time_s.value_or(d.max_flight_time_s);
}

// Drones sharing the file's home stand in a row east of it, `spacing_m` apart (envelope.hpp).
Vec3 home_of(const vehicle::FleetFileDrone& f, const geometry::LocalFrame& frame,
             const geometry::GeoPoint& fleet_home, double spacing_m, int& shared_home) {
  if (f.home_m) return {f.home_m->x, f.home_m->y, 0};
  geometry::Point2 p = frame.to_local(f.drone.home.value_or(fleet_home));
  if (!f.drone.home) p.x += spacing_m * shared_home++;
  if (std::hypot(p.x, p.y) > 1e5)
    throw InputError(f.where_home + ": " + f.drone.name + "'s home is " +
                     std::to_string(static_cast<long long>(std::hypot(p.x, p.y) / 1000)) +
                     " km from the world's origin (at most 100 km)");
  return {p.x, p.y, 0};
}

bool same_link(const VehicleAddress& a, const VehicleAddress& b) {
  return a.tcp == b.tcp && a.host == b.host && a.port == b.port;
}

// swath-fleet's vertical speeds when the file gives none are the flight defaults (leg.hpp),
// not the planner's (docs/formats.md).
vehicle::FleetFileRules fleet_file_rules() {
  vehicle::FleetFileRules rules;
  rules.climb_speed_m_s = Kinematics{}.climb_m_s;
  rules.descent_speed_m_s = Kinematics{}.descent_m_s;
  rules.accel_m_s2 = Kinematics{}.accel_m_s2;
  rules.flights = true;
  return rules;
}

}  // namespace

FleetFileContents parse_fleet_file_contents(const std::string& text, const std::string& source,
                                            const geometry::GeoPoint& origin) {
  const vehicle::FleetFile file = vehicle::parse_fleet_file(text, source, fleet_file_rules());
  FleetFileContents contents;
  contents.envelope = envelope_of(file);
  const geometry::LocalFrame frame(origin);
  const geometry::GeoPoint fleet_home = file.home.value_or(origin);
  // separation_m + 1 m: the separation rule's margin (envelope.hpp).
  const double spacing_m = contents.envelope.separation_m + 1;
  int shared_home = 0;
  std::vector<DroneSpec>& out = contents.drones;
  for (std::size_t i = 0; i < file.drones.size(); ++i) {
    const vehicle::FleetFileDrone& f = file.drones[i];
    DroneSpec d;
    if (f.profile) apply_profile(*f.profile, source, d);
    apply_flight_keys(f, d);
    d.home_m = home_of(f, frame, fleet_home, spacing_m, shared_home);
    if (f.mavlink) {
      d.vehicle = vehicle_of(*f.mavlink, i);
      for (const DroneSpec& before : out)
        if (before.vehicle && same_link(*before.vehicle, *d.vehicle))
          throw InputError(f.mavlink->where + ": " + d.drone.name + "'s url is also " +
                           before.drone.name + "'s (one vehicle per link)");
    }
    out.push_back(std::move(d));
  }
  return contents;
}

std::vector<DroneSpec> parse_fleet_file(const std::string& text, const std::string& source,
                                        const geometry::GeoPoint& origin) {
  return parse_fleet_file_contents(text, source, origin).drones;
}

Weights parse_weights(const std::string& text, const std::string& source) {
  return base::yaml_guard(source, [&] {
    const YAML::Node doc = base::load_yaml(text, source);
    if (!doc.IsMap())
      throw InputError(source + ": a weights file is a YAML mapping (coverage: 1, ...)");
    const YamlMap m(doc, source, "");
    m.allow({"coverage", "closest", "fairness", "avoid_zigzag", "commitment", "speculative",
             "avoid_mutual"});
    Weights w;
    w.coverage = m.number("coverage", w.coverage, 0, 1000);
    w.fairness = m.number("fairness", w.fairness, 0, 1000);
    w.avoid_zigzag = m.number("avoid_zigzag", w.avoid_zigzag, 0, 1000);
    w.commitment = m.number("commitment", w.commitment, 0, 1000);
    w.speculative = m.number("speculative", w.speculative, 0, 1000);
    w.avoid_mutual = m.number("avoid_mutual", w.avoid_mutual, 0, 1000);
    if (m.has("closest") && m.number("closest", 1, 0, 1000) != 1.0)
      throw InputError(m.where("closest") + ": closest is fixed at 1 (scale the others instead)");
    return w;
  });
}

Weights read_weights(const std::string& path) {
  return parse_weights(base::read_text_file(path, "weights file"), path);
}

std::vector<DroneSpec> read_fleet_file(const std::string& path, const geometry::GeoPoint& origin) {
  return parse_fleet_file(base::read_text_file(path, "fleet file"), path, origin);
}

}  // namespace swath::fleet
