#include "swath/vehicle/fleet_file.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/utf8.hpp"
#include "swath/base/yaml_input.hpp"
#include "swath/base/yaml_map.hpp"
#include "swath/geometry/classification.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/geometry/polygon.hpp"

namespace swath::vehicle {
namespace {

using base::InputError;
using base::YamlMap;
using json = nlohmann::json;

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
  for (const auto& kv : n)
    if (kv.first.Scalar() != "lat" && kv.first.Scalar() != "lon" && kv.first.Scalar() != "alt")
      throw InputError(where + ", " + line_of(kv.first) + ": unknown key '" + kv.first.Scalar() +
                       "' in a home (lat, lon, alt)");
  geometry::GeoPoint p{number(n["lat"], where, "lat"), number(n["lon"], where, "lon"),
                       n["alt"] ? number(n["alt"], where, "alt") : 0.0};
  if (std::abs(p.lat_deg) > 90 || std::abs(p.lon_deg) > 180)
    throw InputError(where + ", " + line_of(n) +
                     ": home latitude must be within ±90 and longitude within ±180 degrees");
  return p;
}

// Every key a drone of the format may have; home_m only where drones are flown (a survey needs
// a home in latitude/longitude: planning from the fleet's home instead would be another plan).
void check_drone_keys(const YAML::Node& d, const std::string& where, const FleetFileRules& rules) {
  static const std::set<std::string> known{"name",
                                           "capability",
                                           "battery_level",
                                           "endurance_s",
                                           "speed_m_s",
                                           "home",
                                           "home_m",
                                           "climb_speed_m_s",
                                           "descent_speed_m_s",
                                           "max_airspeed_m_s",
                                           "mavlink",
                                           "recharge_s",
                                           "profile",
                                           "max_flight_time_s",
                                           "approach_speed_m_s",
                                           "accel_m_s2",
                                           "approach_within_m"};
  base::check_plain_unique_keys(d, where);
  for (const auto& kv : d) {
    const std::string key = kv.first.Scalar();
    if (key == "home_m" && !rules.flights)
      throw InputError(where + ", " + line_of(kv.first) +
                       ": home_m (metres from swath-fleet's origin) cannot place a survey; give "
                       "home: {lat, lon}");
    if (!known.count(key))
      throw InputError(where + ", " + line_of(kv.first) + ": unknown key '" + key + "'");
  }
}

// battery_level, endurance_s and speed_m_s: each checked when given; a plan needs all three
// unless the drone gives a capability (then they are not used).
void read_range(const YAML::Node& d, const std::string& where, const FleetFileRules& rules,
                Drone& drone) {
  const std::string named = where + " (" + drone.name + "): ";
  auto value = [&](const char* key, const base::Range& range) -> std::optional<double> {
    if (!d[key]) return std::nullopt;
    const double v = number(d[key], where, key);
    base::check_range(v, range, named + key);
    return v;
  };
  const auto level = value("battery_level", limits::kBatteryLevel);
  const auto endurance = value("endurance_s", limits::kEndurance_s);
  const auto speed = value("speed_m_s", limits::kSpeed_m_s);
  if (rules.flights && level && *level == 0)
    throw InputError(named + "battery_level 0: a drone flown needs some charge (> 0)");
  if (!rules.flights && drone.capability) return;
  if (!rules.flights && !(level && endurance && speed))
    throw InputError(named + "give a capability, or battery_level, endurance_s and speed_m_s");
  drone.battery_level = level;
  drone.endurance_s = endurance;
  drone.speed_m_s = speed;
}

void read_capability(const YAML::Node& d, const std::string& where, Drone& drone) {
  if (!d["capability"]) return;
  drone.capability = number(d["capability"], where, "capability");
  if (!(*drone.capability > 0 && *drone.capability <= 1))
    throw InputError(where + " (" + drone.name + "): capability " +
                     std::to_string(*drone.capability) + " is outside (0, 1]");
}

void read_speeds(const YAML::Node& d, const std::string& where, const FleetFileRules& rules,
                 FleetFileDrone& out) {
  Drone& drone = out.drone;
  drone.climb_speed_m_s = rules.climb_speed_m_s;
  drone.descent_speed_m_s = rules.descent_speed_m_s;
  drone.accel_m_s2 = rules.accel_m_s2;
  const std::string named = where + " (" + drone.name + "): ";
  auto speed = [&](const char* key, double& value, const base::Range& range) {
    if (!d[key]) return false;
    value = number(d[key], where, key);
    base::check_range(value, range, named + key);
    return true;
  };
  out.climb_given = speed("climb_speed_m_s", drone.climb_speed_m_s, limits::kVerticalSpeed_m_s);
  out.descent_given =
      speed("descent_speed_m_s", drone.descent_speed_m_s, limits::kVerticalSpeed_m_s);
  speed("max_airspeed_m_s", drone.max_airspeed_m_s, limits::kSpeed_m_s);
}

std::optional<double> optional_number(const YamlMap& m, const char* key, double lo, double hi,
                                      bool open_lo = false) {
  if (!m.has(key)) return std::nullopt;
  return m.number(key, 0, lo, hi, open_lo);
}

// `mavlink: {url, sysid}`: its shape here, its URL grammar in swath-fleet.
FleetFileLink read_link(const YamlMap& drone) {
  if (!drone.node()["mavlink"].IsMap())
    throw InputError(drone.where("mavlink") +
                     ": a mapping {url: udp:HOST:PORT or tcp:HOST:PORT, sysid: 1..255}");
  const YamlMap m = drone.map("mavlink");
  m.allow({"url", "sysid"});
  if (!m.has("url"))
    throw InputError(drone.where("mavlink") + ": no url (udp:HOST:PORT or tcp:HOST:PORT)");
  FleetFileLink link;
  link.url = m.text("url", "");
  if (m.has("sysid")) link.sysid = m.number("sysid", 1, 1, 255);
  link.where = drone.where("mavlink");
  link.url_where = m.where("url");
  link.sysid_where = m.where("sysid");
  return link;
}

// The keys only flights read (the planner accepts them and plans without them).
void read_flight_keys(const YamlMap& m, const FleetFileRules& rules, FleetFileDrone& out) {
  if (m.has("profile")) out.profile = m.text("profile", "");
  out.max_flight_time_s = optional_number(m, "max_flight_time_s", 1, 604800, true);
  out.approach_speed_m_s = optional_number(m, "approach_speed_m_s", 0.1, 100);
  out.approach_within_m = optional_number(m, "approach_within_m", 0, 1000);
  const auto accel_m_s2 = optional_number(m, "accel_m_s2", 0, 50);
  if (accel_m_s2 && rules.flights) out.drone.accel_m_s2 = *accel_m_s2;
  out.recharge_s = optional_number(m, "recharge_s", 0, 86400);
  if (m.has("home_m")) {
    const YamlMap h = m.map("home_m");
    h.allow({"x_m", "y_m"});
    out.home_m = geometry::Point2{h.number("x_m", 0, -1e5, 1e5), h.number("y_m", 0, -1e5, 1e5)};
  }
  if (m.has("mavlink")) out.mavlink = read_link(m);
}

// swath-fleet flies what has a speed, a battery or a flight time; a capability alone (a share
// of a survey) says nothing it could fly.
void check_flyable(const YamlMap& m, const Drone& drone) {
  const bool physical = m.has("battery_level") || m.has("endurance_s") || m.has("speed_m_s") ||
                        m.has("profile") || m.has("max_flight_time_s");
  if (m.has("capability") && !physical)
    throw InputError(m.where("capability") + ": " + drone.name +
                     " has only a capability; swath-fleet flies drones with a speed_m_s, "
                     "battery_level and endurance_s (or a profile)");
}

FleetFileDrone read_drone(const YAML::Node& d, std::size_t i, const std::string& source,
                          const FleetFileRules& rules) {
  const std::string where = source + ": drone " + std::to_string(i + 1);
  if (!d.IsMap()) throw InputError(where + ", " + line_of(d) + ": a drone is a mapping");
  check_drone_keys(d, where, rules);
  const YamlMap m(d, source, "drones[" + std::to_string(i) + "]");
  FleetFileDrone out;
  Drone& drone = out.drone;
  // Names reach JSON, KML and the terminal: keep them valid UTF-8 (a stray Latin-1 byte
  // becomes U+FFFD instead of aborting the plan).
  drone.name =
      d["name"] ? base::valid_utf8(d["name"].as<std::string>()) : "drone-" + std::to_string(i + 1);
  read_capability(d, where, drone);
  if (rules.flights) check_flyable(m, drone);
  read_range(d, where, rules, drone);
  if (d["home"]) drone.home = point(d["home"], where);
  read_speeds(d, where, rules, out);
  read_flight_keys(m, rules, out);
  out.where_home = m.where(m.has("home") ? "home" : "name");
  return out;
}

void check_names_once(const YAML::Node& drones, const std::vector<FleetFileDrone>& read,
                      const std::string& source) {
  std::set<std::string> names;
  for (std::size_t i = 0; i < read.size(); ++i)
    if (!names.insert(read[i].drone.name).second)
      throw InputError(
          YamlMap(drones[i], source, "drones[" + std::to_string(i) + "]").where("name") +
          ": the name \"" + read[i].drone.name + "\" is given twice");
}

// A plan shares the work by capability or by range, one way for the whole fleet.
void check_one_kind(const std::vector<FleetFileDrone>& drones, const std::string& source) {
  bool any_capability = false, any_range = false;
  for (const FleetFileDrone& d : drones) {
    any_capability = any_capability || d.drone.capability.has_value();
    any_range = any_range || !d.drone.capability.has_value();
  }
  if (any_capability && any_range)
    throw InputError(source +
                     ": give every drone a capability, or every drone battery_level, endurance_s "
                     "and speed_m_s, not a mix");
}

// A member of a JSON object, or null when the value is not an object or lacks it (a fence file
// is read, never trusted: json's value() throws on a non-object or a member of another type).
json member(const json& j, const char* key) {
  return j.is_object() && j.contains(key) ? j.at(key) : json();
}
std::string type_of(const json& j) {
  const json t = member(j, "type");
  return t.is_string() ? t.get<std::string>() : std::string();
}

// A GeoJSON linear ring: [[lon, lat], ...], at least 3 distinct vertices, closed or not.
std::vector<geometry::GeoPoint> ring_of(const json& coords, const std::string& where) {
  if (!coords.is_array()) throw InputError(where + ": a ring is a list of [lon, lat] positions");
  std::vector<geometry::GeoPoint> out;
  for (const json& p : coords) {
    if (!p.is_array() || p.size() < 2 || !p[0].is_number() || !p[1].is_number())
      throw InputError(where + ": a position is [lon, lat] in degrees");
    const double lon = p[0].get<double>(), lat = p[1].get<double>();
    if (!(std::abs(lat) <= 90) || !(std::abs(lon) <= 180))
      throw InputError(where + ": [" + base::shortest_text(lon) + ", " + base::shortest_text(lat) +
                       "] is not a lon/lat in degrees");
    out.push_back({lat, lon, 0});
  }
  if (out.size() > 1 && out.front() == out.back()) out.pop_back();
  if (out.size() < 3) throw InputError(where + ": a fence polygon needs at least 3 vertices");
  return out;
}

// A fence ring that crosses or touches itself (a bow-tie) has no inside the runtime, the checker
// and an autopilot agree on: refused with the place, as swath plan refuses such a zone.
void refuse_crossing_ring(const std::vector<geometry::GeoPoint>& ring_deg,
                          const std::string& where) {
  const geometry::LocalFrame frame(ring_deg.front());
  geometry::Ring local;
  for (const geometry::GeoPoint& g : ring_deg) local.push_back(frame.to_local(g));
  const geometry::Ring normal = geometry::normalise_ring(local, true).ring;
  if (normal.size() < 3) throw InputError(where + ": the fence polygon encloses no area");
  const auto crossing = geometry::find_crossing(geometry::Polygon{normal, {}});
  if (!crossing) return;
  const geometry::GeoPoint p = frame.to_geo(crossing->point);
  std::ostringstream s;
  s.precision(8);
  s << where << ": the fence polygon crosses itself at " << p.lat_deg << ", " << p.lon_deg
    << " (lat, lon); a fence polygon must be a simple polygon: fix the vertex order";
  throw InputError(s.str());
}

// A geometry's polygons (outer rings; holes are refused: give an exclusion instead).
void add_geometry(const json& g, bool inclusion, const std::string& where,
                  std::vector<FencePolygon>& out) {
  const std::string type = type_of(g);
  std::size_t part = 0;
  const auto polygon = [&](const json& rings) {
    if (!rings.is_array() || rings.empty())
      throw InputError(where + ": a Polygon's coordinates are a list of rings");
    if (rings.size() > 1)
      throw InputError(where + ": a fence polygon with holes; give each hole as an exclusion");
    const std::string named =
        type == "MultiPolygon" ? where + " polygon " + std::to_string(part++) : where;
    std::vector<geometry::GeoPoint> ring = ring_of(rings[0], named);
    refuse_crossing_ring(ring, named);
    out.push_back({std::move(ring), inclusion});
  };
  if (type == "Polygon") {
    polygon(member(g, "coordinates"));
  } else if (type == "MultiPolygon") {
    const json polygons = member(g, "coordinates");
    if (!polygons.is_array())
      throw InputError(where + ": a MultiPolygon's coordinates are a list of polygons");
    for (const json& p : polygons) polygon(p);
  } else {
    throw InputError(where + ": a fence is a Polygon or MultiPolygon, not \"" + type + "\"");
  }
}

// `fence: {geojson: FILE, max_altitude_m: M}`, the GeoJSON relative to the fleet file.
FleetFileFence read_fence(const YamlMap& top, const std::string& source) {
  if (!top.node()["fence"].IsMap())
    throw InputError(top.where("fence") + ": a mapping {geojson: FILE, max_altitude_m: M}");
  const YamlMap f = top.map("fence");
  f.allow({"geojson", "max_altitude_m"});
  if (!f.has("geojson"))
    throw InputError(top.where("fence") + ": no geojson (the fence's polygons)");
  std::filesystem::path p = f.text("geojson", "");
  if (p.is_relative()) p = std::filesystem::path(source).parent_path() / p;
  FleetFileFence fence;
  fence.polygons = parse_fence_geojson(
      base::read_text_file(p.string(), "fence file", base::kMaxConfigFileBytes), p.string());
  if (f.has("max_altitude_m")) fence.max_altitude_m = f.number("max_altitude_m", 0, 0, 10000, true);
  return fence;
}

// swath-fleet's envelope keys, after the drones (their errors come first): the ceiling checked
// for every program, the fence's GeoJSON opened only where drones are flown.
void read_envelope(const YamlMap& top, const std::string& source, const FleetFileRules& rules,
                   FleetFile& fleet) {
  if (top.has("ceiling_m")) fleet.ceiling_m = top.number("ceiling_m", 0, 0, 10000, true);
  if (top.has("fence") && rules.flights) fleet.fence = read_fence(top, source);
}

FleetFile fleet_from_yaml(const std::string& text, const std::string& source,
                          const FleetFileRules& rules) {
  const YAML::Node root = base::load_yaml(text, source);
  if (!root.IsMap()) throw InputError(source + ": a fleet file is a YAML mapping (home, drones)");
  const YamlMap top(root, source, "");
  top.allow({"home", "drones", "ceiling_m", "separation_m", "fence"});  // fence: swath-fleet's
  if ((!rules.flights && !root["home"]) || !root["drones"])
    throw InputError(source + ": a fleet file needs 'home' and 'drones'");
  FleetFile fleet;
  if (root["home"]) fleet.home = point(root["home"], source);
  if (top.has("separation_m")) fleet.separation_m = top.number("separation_m", 0, 0, 1000, true);
  const YAML::Node drones = root["drones"];
  if (!drones.IsSequence() || drones.size() == 0)
    throw InputError(source + ": 'drones' must list at least one drone");
  base::check_range(static_cast<double>(drones.size()), limits::kDrones, source + ": the fleet of");
  for (std::size_t i = 0; i < drones.size(); ++i)
    fleet.drones.push_back(read_drone(drones[i], i, source, rules));
  check_names_once(drones, fleet.drones, source);
  if (!rules.flights) check_one_kind(fleet.drones, source);
  read_envelope(top, source, rules, fleet);
  return fleet;
}

}  // namespace

FleetFile parse_fleet_file(const std::string& text, const std::string& source,
                           const FleetFileRules& rules) {
  return base::yaml_guard(source, [&] { return fleet_from_yaml(text, source, rules); });
}

std::vector<FencePolygon> parse_fence_geojson(const std::string& text, const std::string& source) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception&) {
    throw InputError(source + ": not JSON (a GeoJSON fence: Polygon or MultiPolygon features)");
  }
  std::vector<FencePolygon> out;
  const auto feature = [&](const json& f, const std::string& where) {
    bool inclusion = true;
    if (f.contains("properties") && f["properties"].is_object() &&
        f["properties"].contains("fence")) {
      const json& kind = f["properties"]["fence"];
      if (kind == "exclusion")
        inclusion = false;
      else if (kind != "inclusion")
        throw InputError(where + ": properties.fence is \"inclusion\" or \"exclusion\"");
    }
    add_geometry(member(f, "geometry"), inclusion, where, out);
  };
  const std::string type = type_of(doc);
  if (type == "FeatureCollection") {
    const json features = member(doc, "features");
    if (!features.is_array())
      throw InputError(source + ": a FeatureCollection's features are a list");
    for (std::size_t i = 0; i < features.size(); ++i)
      feature(features[i], source + ": features[" + std::to_string(i) + "]");
  } else if (type == "Feature") {
    feature(doc, source);
  } else {
    add_geometry(doc, true, source, out);
  }
  if (out.empty()) throw InputError(source + ": the fence has no polygons");
  return out;
}

}  // namespace swath::vehicle
