#include "swath/fleet/fleet_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/yaml_input.hpp"
#include "swath/base/yaml_map.hpp"
#include "swath/energy/sim_config.hpp"
#include "swath/fleet/envelope.hpp"
#include "swath/geometry/local_frame.hpp"

namespace swath::fleet {

using base::InputError;
using base::YamlMap;

namespace {

geometry::GeoPoint geo(const YamlMap& m) {
  m.allow({"lat", "lon", "alt"});
  return {m.number("lat", 0, -90, 90), m.number("lon", 0, -180, 180),
          m.number("alt", 0, -500, 9000)};
}

// A drone's `mavlink: {url: udp:HOST:PORT | tcp:HOST:PORT, sysid: 1..255}` (docs/swath-fleet.md):
// --vehicles' grammar; sysid defaults to the drone's place + 1 as there. The system id is given
// once: in `sysid`, or as the url's /SYSID.
VehicleAddress vehicle_of(const YamlMap& drone, std::size_t index) {
  if (!drone.node()["mavlink"].IsMap())
    throw InputError(drone.where("mavlink") +
                     ": a mapping {url: udp:HOST:PORT or tcp:HOST:PORT, sysid: 1..255}");
  const YamlMap m = drone.map("mavlink");
  m.allow({"url", "sysid"});
  if (!m.has("url"))
    throw InputError(drone.where("mavlink") + ": no url (udp:HOST:PORT or tcp:HOST:PORT)");
  const std::string url = m.text("url", "");
  VehicleAddress a;
  const auto default_sysid = static_cast<std::uint8_t>(std::min<std::size_t>(index + 1, 255));
  const std::string why = parse_vehicle_address(url, default_sysid, a);
  if (!why.empty())
    throw InputError(m.where("url") + ": \"" + url + "\" " + why +
                     " (use udp:HOST:PORT or tcp:HOST:PORT)");
  if (m.has("sysid")) {
    if (a.sysid_given)
      throw InputError(m.where("sysid") + ": the system id is given twice (sysid and the url's /" +
                       std::to_string(a.sysid) + "); give it once");
    const double s = m.number("sysid", 1, 1, 255);
    if (s != std::floor(s))
      throw InputError(m.where("sysid") + ": " + base::shortest_text(s) +
                       " is not a whole number in 1..255");
    a.sysid = static_cast<std::uint8_t>(s);
    a.sysid_given = true;
  }
  return a;
}

}  // namespace

std::vector<DroneSpec> parse_fleet_file(const std::string& text, const std::string& source,
                                        const geometry::GeoPoint& origin) {
  return base::yaml_guard(source, [&] {
    const YAML::Node doc = base::load_yaml(text, source);
    if (!doc.IsMap()) throw InputError(source + ": a fleet file is a YAML mapping (home, drones)");
    const YamlMap root(doc, source, "");
    root.allow({"home", "drones", "ceiling_m", "separation_m", "fence"});  // envelope.hpp
    const geometry::LocalFrame frame(origin);
    const geometry::GeoPoint fleet_home = root.has("home") ? geo(root.map("home")) : origin;
    const YAML::Node list = doc["drones"];
    if (!list || !list.IsSequence() || list.size() == 0)
      throw InputError(source + ": the fleet has no drones (a list under 'drones:')");
    if (list.size() > 100)
      throw InputError(source + ": " + std::to_string(list.size()) +
                       " drones; swath-fleet simulates at most 100");
    std::vector<DroneSpec> out;
    std::set<std::string> names;
    // Drones sharing the file's home stand in a row east of it, separation_m + 1 m apart
    // (envelope.hpp).
    const double spacing_m =
        root.number("separation_m", Envelope{}.separation_m, 0, 1000, true) + 1;
    int shared_home = 0;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string place = "drones[" + std::to_string(i) + "]";
      if (!list[i].IsMap())
        throw InputError(source + ": " + base::yaml_line(list[i]) + ": " + place +
                         " is not a mapping");
      const YamlMap m(list[i], source, place);
      m.allow({"name", "capability", "battery_level", "endurance_s", "speed_m_s", "home", "home_m",
               "climb_speed_m_s", "descent_speed_m_s", "max_airspeed_m_s", "profile",
               "max_flight_time_s", "approach_speed_m_s", "approach_within_m", "accel_m_s2",
               "recharge_s", "mavlink"});
      DroneSpec d;
      d.name = m.text("name", "drone-" + std::to_string(i + 1));
      if (!names.insert(d.name).second)
        throw InputError(m.where("name") + ": the name \"" + d.name + "\" is given twice");
      const bool physical = m.has("battery_level") || m.has("endurance_s") || m.has("speed_m_s") ||
                            m.has("profile") || m.has("max_flight_time_s");
      if (m.has("capability") && !physical)
        throw InputError(m.where("capability") + ": " + d.name +
                         " has only a capability; swath-fleet flies drones with a speed_m_s, "
                         "battery_level and endurance_s (or a profile)");
      if (m.has("profile")) {
        std::filesystem::path p = m.text("profile", "");
        if (p.is_relative()) p = std::filesystem::path(source).parent_path() / p;
        const energy::DroneProfile prof = energy::read_drone_profile(p.string());
        d.power = prof.power;
        d.battery = prof.battery;
        if (prof.drone.speed_m_s) d.kinematics.cruise_m_s = *prof.drone.speed_m_s;
        d.kinematics.climb_m_s = prof.drone.climb_speed_m_s;
        d.kinematics.descent_m_s = prof.drone.descent_speed_m_s;
      }
      d.battery.initial_soc = m.number("battery_level", d.battery.initial_soc, 0, 1, true);
      if (d.battery.reserve_soc >= d.battery.initial_soc)
        d.battery.reserve_soc = 0.5 * d.battery.initial_soc;
      d.kinematics.cruise_m_s = m.number("speed_m_s", d.kinematics.cruise_m_s, 0.5, 100);
      d.kinematics.climb_m_s = m.number("climb_speed_m_s", d.kinematics.climb_m_s, 0.1, 30);
      d.kinematics.descent_m_s = m.number("descent_speed_m_s", d.kinematics.descent_m_s, 0.1, 30);
      d.kinematics.approach_m_s =
          std::min(d.kinematics.cruise_m_s,
                   m.number("approach_speed_m_s", d.kinematics.approach_m_s, 0.1, 100));
      d.kinematics.approach_within_m =
          m.number("approach_within_m", d.kinematics.approach_within_m, 0, 1000);
      d.kinematics.accel_m_s2 = m.number("accel_m_s2", d.kinematics.accel_m_s2, 0, 50);
      d.recharge_s = m.number("recharge_s", d.recharge_s, 0, 86400);
      if (m.has("endurance_s"))
        d.max_flight_time_s = m.number("endurance_s", 0, 1, 604800, true) * d.battery.initial_soc;
      d.max_flight_time_s = m.number("max_flight_time_s", d.max_flight_time_s, 1, 604800, true);
      if (m.has("home_m")) {
        const YamlMap h = m.map("home_m");
        h.allow({"x_m", "y_m"});
        d.home_m = {h.number("x_m", 0, -1e5, 1e5), h.number("y_m", 0, -1e5, 1e5), 0};
      } else {
        const geometry::GeoPoint g = m.has("home") ? geo(m.map("home")) : fleet_home;
        geometry::Point2 p = frame.to_local(g);
        if (!m.has("home")) p.x += spacing_m * shared_home++;
        if (std::hypot(p.x, p.y) > 1e5)
          throw InputError(m.where(m.has("home") ? "home" : "name") + ": " + d.name +
                           "'s home is " +
                           std::to_string(static_cast<long long>(std::hypot(p.x, p.y) / 1000)) +
                           " km from the world's origin (at most 100 km)");
        d.home_m = {p.x, p.y, 0};
      }
      if (m.has("mavlink")) {
        d.vehicle = vehicle_of(m, i);
        for (std::size_t j = 0; j < out.size(); ++j)
          if (out[j].vehicle && out[j].vehicle->tcp == d.vehicle->tcp &&
              out[j].vehicle->host == d.vehicle->host && out[j].vehicle->port == d.vehicle->port)
            throw InputError(m.where("mavlink") + ": " + d.name + "'s url is also " + out[j].name +
                             "'s (one vehicle per link)");
      }
      out.push_back(std::move(d));
    }
    return out;
  });
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
