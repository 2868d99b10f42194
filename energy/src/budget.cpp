#include "swath/energy/budget.hpp"

#include "swath/base/file_text.hpp"

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include <map>
#include <optional>

#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/utf8.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/mavlink/commands.hpp"
#include "swath/missions/mission.hpp"

namespace swath::energy {
namespace {

using base::InputError;
using geometry::GeoPoint;
using geometry::Point2;
using nlohmann::json;

double finite_number(const json& j, const std::string& where) {
  if (!j.is_number() || !std::isfinite(j.get<double>()))
    throw InputError(where + " must be a number");
  return j.get<double>();
}

// Checked lookups: a hand-edited file is input like any other (no const operator[], no value()
// that throws a library type_error for a member of another type).
std::string text_or(const json& object, const char* key, const std::string& fallback) {
  const json* v = base::json_find(object, key);
  return v != nullptr && v->is_string() ? v->get<std::string>() : fallback;
}

const json& member_or_null(const json& object, const char* key) {
  static const json null;
  const json* v = base::json_find(object, key);
  return v != nullptr ? *v : null;
}

std::string role_of(const json& feature) {
  return text_or(member_or_null(feature, "properties"), "role", "");
}

GeoPoint lon_lat(const json& c, const std::string& where) {
  if (!c.is_array() || c.size() < 2)
    throw InputError(where + ": a position is [lon, lat] or [lon, lat, alt]");
  const GeoPoint g{finite_number(c[1], where + " (latitude)"),
                   finite_number(c[0], where + " (longitude)"), 0.0};
  if (std::abs(g.lat_deg) > 90 || std::abs(g.lon_deg) > 180)
    throw InputError(where + ": latitude must be within ±90 and longitude within ±180 degrees");
  return g;
}

std::vector<WaypointMission> parse_geojson(const json& root, const std::string& source) {
  const json& features = member_or_null(root, "features");
  if (!features.is_array())
    throw InputError(source + ": a mission GeoJSON is a FeatureCollection with 'features'");
  // The plan's home, and each drone's own where it differs (swath writes those with "drone").
  std::optional<GeoPoint> home;
  std::map<long long, GeoPoint> drone_homes;
  for (std::size_t i = 0; i < features.size(); ++i) {
    const json& f = features[i];
    if (role_of(f) != "home") continue;
    const GeoPoint at = lon_lat(member_or_null(member_or_null(f, "geometry"), "coordinates"),
                                source + ": feature " + std::to_string(i));
    const json& drone = member_or_null(member_or_null(f, "properties"), "drone");
    if (drone.is_number_integer()) {
      drone_homes[drone.get<long long>()] = at;
    } else {
      home = at;
    }
  }
  std::vector<WaypointMission> out;
  for (std::size_t i = 0; i < features.size(); ++i) {
    const json& f = features[i];
    const std::string where = source + ": feature " + std::to_string(i);
    if (role_of(f) != "path") continue;
    const json& geometry = member_or_null(f, "geometry");
    const json& coords = member_or_null(geometry, "coordinates");
    if (text_or(geometry, "type", "") != "LineString" || !coords.is_array() || coords.size() < 2)
      throw InputError(where + ": a path is a LineString of at least two positions");
    const json& props = member_or_null(f, "properties");
    WaypointMission m;
    const json& drone = member_or_null(props, "drone");
    m.drone = drone.is_number_integer() && drone.get<long long>() >= 0 &&
                      drone.get<long long>() < 1'000'000
                  ? "drone-" + std::to_string(drone.get<long long>())
                  : "drone-" + std::to_string(out.size() + 1);
    if (const json* name = base::json_find(props, "name");
        name && name->is_string() && !name->get<std::string>().empty())
      m.drone = base::valid_utf8(name->get<std::string>());
    const auto own =
        drone.is_number_integer() ? drone_homes.find(drone.get<long long>()) : drone_homes.end();
    m.home = own != drone_homes.end() ? own->second : home ? *home : lon_lat(coords[0], where);
    const geometry::LocalFrame frame(m.home);
    const bool has_alt = base::json_find(props, "altitude_m") != nullptr;
    const double alt =
        has_alt ? finite_number(member_or_null(props, "altitude_m"), where + ": altitude_m") : 0.0;
    const double speed =
        base::json_find(props, "speed_m_s")
            ? finite_number(member_or_null(props, "speed_m_s"), where + ": speed_m_s")
            : 0.0;
    if (speed < 0) throw InputError(where + ": speed_m_s must be >= 0");
    for (std::size_t k = 0; k < coords.size(); ++k) {
      const std::string at = where + ", position " + std::to_string(k);
      const GeoPoint g = lon_lat(coords[k], at);
      double a = alt;
      if (!has_alt) {
        if (coords[k].size() < 3)
          throw InputError(where +
                           ": the path has no altitude (give properties.altitude_m or "
                           "[lon, lat, alt] positions)");
        a = finite_number(coords[k][2], at + " (altitude)");
      }
      m.points.push_back(frame.to_local(g));
      m.altitudes_m.push_back(a);
      m.speeds_m_s.push_back(speed);
    }
    // swath's paths start and end at home: the take-off and landing legs are implied.
    const double home_gap = std::hypot(m.points.front().x, m.points.front().y);
    if (home_gap < 0.5) {
      m.points.erase(m.points.begin());
      m.altitudes_m.erase(m.altitudes_m.begin());
      m.speeds_m_s.erase(m.speeds_m_s.begin());
    }
    const Point2 last = m.points.back();
    m.returns_home = std::hypot(last.x, last.y) < 0.5;
    if (m.returns_home && m.points.size() > 1) {
      m.points.pop_back();
      m.altitudes_m.pop_back();
      m.speeds_m_s.pop_back();
    }
    out.push_back(std::move(m));
  }
  if (out.empty()) throw InputError(source + ": no feature with role 'path' (a drone's flight)");
  return out;
}

}  // namespace

// A mission file's items as the budget flies them: take-off (22), waypoint (16), loiter (19), land
// (21) and return to launch (20) move the drone, change speed (178) sets its speed; altitudes above
// home from each item's frame (AMSL less the home's altitude; terrain-relative read as above home,
// the budget having no ground). Camera, gimbal and other actions take no flight time here.
WaypointMission waypoint_mission(const missions::Mission& file) {
  WaypointMission m;
  m.drone = std::filesystem::path(file.source).stem().string();
  m.home = file.home;
  m.returns_home = false;
  const geometry::LocalFrame frame(m.home);
  double speed = file.cruise_speed_m_s;
  for (const missions::Item& item : file.items) {
    const bool here = item.position.lat_deg == 0 && item.position.lon_deg == 0;
    const Point2 last = m.points.empty() ? Point2{0.0, 0.0} : m.points.back();
    switch (static_cast<mavlink::Cmd>(item.command)) {
      case mavlink::Cmd::nav_takeoff:
      case mavlink::Cmd::nav_waypoint:
      case mavlink::Cmd::nav_loiter_time:
      case mavlink::Cmd::nav_land: {
        const bool land = item.command == static_cast<int>(mavlink::Cmd::nav_land);
        m.points.push_back(here ? last : frame.to_local(item.position));
        m.altitudes_m.push_back(land ? 0.0
                                     : missions::above_home_m(item, missions::home_amsl_m(file)));
        m.speeds_m_s.push_back(speed);
        if (land) return m;  // landing ends the mission
        break;
      }
      case mavlink::Cmd::nav_return_to_launch:
        m.returns_home = true;
        return m;
      case mavlink::Cmd::do_change_speed:  // param2 m/s, -1 keeps it
        if (item.params[1] > 0) speed = item.params[1];
        break;
      default:
        break;
    }
  }
  return m;
}

namespace {

BudgetPoint point_at(const geometry::LocalFrame& frame, double t, Point2 p, double alt, double soc,
                     double energy) {
  return {t, p, frame.to_geo(p, alt), alt, soc, energy};
}

}  // namespace

std::vector<WaypointMission> parse_waypoint_missions(const std::string& text,
                                                     const std::string& source) {
  auto mission_file = [&] {
    WaypointMission m = waypoint_mission(missions::parse_mission(text, source));
    if (m.points.empty()) throw InputError(source + ": the mission has no positional item");
    return std::vector<WaypointMission>{std::move(m)};
  };
  if (text.rfind("QGC WPL", 0) == 0) return mission_file();
  const json root = base::parse_json_document(text, source);
  if (!root.is_object()) throw InputError(source + ": expected a JSON object");
  if (text_or(root, "type", "") == "FeatureCollection") return parse_geojson(root, source);
  if (text_or(root, "fileType", "") == "Plan") return mission_file();
  throw InputError(source +
                   ": neither a GeoJSON FeatureCollection (mission.geojson), a QGC plan nor a QGC "
                   "WPL 110 file");
}

std::vector<WaypointMission> read_waypoint_missions(const std::string& path) {
  return parse_waypoint_missions(base::read_text_file(path, "mission file"), path);
}

DroneBudget budget(const WaypointMission& mission, const DroneProfile& profile) {
  const vehicle::Drone& drone = profile.drone;
  const geometry::LocalFrame frame(mission.home);
  const Battery& b = profile.battery;
  const PowerProfile& power = profile.power;
  const double always_w =
      power.payload_w + computations_power_w(power.computations, profile.computation_parameters);
  const double climb_w = climbing_power_w(power);
  const double descent_w = descending_power_w(power);
  const Point2 wind = profile.wind.velocity_m_s();

  DroneBudget out;
  out.drone = mission.drone;
  double t = 0.0, soc = b.initial_soc, energy = 0.0;
  Point2 at{0.0, 0.0};
  double alt = 0.0;
  out.timeline.push_back(point_at(frame, t, at, alt, soc, energy));

  // Flies from (at, alt) to (to, to_alt) in `seconds` at `watts`, noting the reserve and empty
  // crossings on the way.
  auto segment = [&](Point2 to, double to_alt, double seconds, double watts,
                     const std::string& what) {
    if (std::isnan(battery_current_a(b, watts)))
      throw InputError(profile.source + ": " + mission.drone + " would draw " +
                       base::fixed_text(watts, 0) + " W " + what +
                       ", beyond what the battery can deliver (" +
                       base::fixed_text(max_power_w(b), 0) + " W)");
    auto crossing = [&](double level) -> std::optional<BudgetPoint> {
      const double s = seconds_to_soc(b, soc, level, watts);
      if (soc <= level || s > seconds) return std::nullopt;
      const double f = seconds > 0 ? s / seconds : 0.0;
      const Point2 p{at.x + f * (to.x - at.x), at.y + f * (to.y - at.y)};
      return point_at(frame, t + s, p, alt + f * (to_alt - alt), level, energy + watts * s);
    };
    if (!out.reserve_crossed) out.reserve_crossed = crossing(b.reserve_soc);
    if (!out.battery_empty) out.battery_empty = crossing(0.0);
    soc = soc_after(b, soc, watts, seconds);
    energy += watts * seconds;
    t += seconds;
    at = to;
    alt = to_alt;
  };
  auto vertical = [&](double to_alt) {
    if (to_alt > alt)
      segment(at, to_alt, (to_alt - alt) / drone.climb_speed_m_s, climb_w + always_w, "climbing");
    else if (to_alt < alt)
      segment(at, to_alt, (alt - to_alt) / drone.descent_speed_m_s, descent_w + always_w,
              "descending");
  };
  auto leg = [&](Point2 to, double leg_speed) {
    const double dx = to.x - at.x, dy = to.y - at.y;
    const double length = std::hypot(dx, dy);
    if (length < 1e-9) return;
    const double speed = drone.speed_m_s.value_or(leg_speed);
    if (!(speed > 0))
      throw InputError(profile.source + ": the mission gives no speed for " + mission.drone +
                       "; set speed_m_s in the drone profile");
    const auto cs = course_speed({dx / length, dy / length}, wind, speed, drone.max_airspeed_m_s);
    if (!cs)
      throw InputError(profile.source + ": the wind is stronger than " + mission.drone +
                       "'s maximum airspeed on one of its legs");
    const double watts = level_flight_power_w(power.mechanical, cs->airspeed_m_s) + always_w;
    out.distance_m += length;
    segment(to, alt, length / cs->ground_speed_m_s, watts, "in cruise");
  };

  for (std::size_t i = 0; i < mission.points.size(); ++i) {
    const double target_alt = mission.altitudes_m[i];
    const bool first = i == 0;
    if (first) vertical(target_alt);  // take off, then fly over
    leg(mission.points[i], mission.speeds_m_s[i]);
    if (!first) vertical(target_alt);
    out.timeline.push_back(point_at(frame, t, at, alt, soc, energy));
  }
  if (mission.returns_home) {
    leg({0.0, 0.0}, mission.speeds_m_s.back());
    out.timeline.push_back(point_at(frame, t, at, alt, soc, energy));
  }
  vertical(0.0);
  out.timeline.push_back(point_at(frame, t, at, alt, soc, energy));
  out.flight_time_s = t;
  out.energy_j = energy;
  out.landing_soc = soc;
  out.reserve_margin = soc - b.reserve_soc;
  return out;
}

}  // namespace swath::energy
