#include "swath/energy/budget.hpp"

#include "swath/base/file_text.hpp"

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include <optional>

#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/utf8.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/mavlink/commands.hpp"
#include "swath/missions/mission.hpp"
#include "swath/missions/mission_geojson.hpp"

namespace swath::energy {
namespace {

using base::InputError;
using geometry::GeoPoint;
using geometry::Point2;
using nlohmann::json;

// Checked lookups: a hand-edited file is input like any other (no const operator[], no value()
// that throws a library type_error for a member of another type).
std::string text_or(const json& object, const char* key, const std::string& fallback) {
  const json* v = base::json_find(object, key);
  return v != nullptr && v->is_string() ? v->get<std::string>() : fallback;
}

// A mission GeoJSON's flight (read by swath::missions) in metres about its home. swath's paths
// start and end at home: the take-off and landing legs are implied.
WaypointMission from_geojson_flight(const missions::GeoJsonFlight& flight) {
  WaypointMission m;
  m.drone = flight.drone;
  m.home = flight.home;
  const geometry::LocalFrame frame(m.home);
  for (std::size_t k = 0; k < flight.points.size(); ++k) {
    m.points.push_back(frame.to_local(flight.points[k]));
    m.altitudes_m.push_back(flight.altitudes_m[k]);
    m.speeds_m_s.push_back(flight.speed_m_s);
  }
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
  return m;
}

std::vector<WaypointMission> parse_geojson(const std::string& text, const std::string& source) {
  std::vector<WaypointMission> out;
  for (const missions::GeoJsonFlight& flight : missions::parse_geojson_flights(text, source))
    out.push_back(from_geojson_flight(flight));
  return out;
}

}  // namespace

// A mission file's items as the budget flies them: take-off (22), waypoint (16), loiter (19), land
// (21) and return to launch (20) move the drone, change speed (178) sets its speed; altitudes above
// home from each item's frame (AMSL less the home's altitude; terrain-relative read as above home,
// the budget having no ground); holds (param1 of 16, 19, 93, 112) hovered at the point reached
// (a delay before any: at the first). Camera, gimbal and other actions take no flight time here.
WaypointMission waypoint_mission(const missions::Mission& file) {
  WaypointMission m;
  m.drone = std::filesystem::path(file.source).stem().string();
  m.home = file.home;
  m.returns_home = false;
  const geometry::LocalFrame frame(m.home);
  double speed = file.cruise_speed_m_s;
  double early_hold_s = 0.0;  // delays before the first point
  auto hold = [&](double seconds) {
    if (!(seconds > 0)) return;
    (m.holds_s.empty() ? early_hold_s : m.holds_s.back()) += seconds;
  };
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
        m.holds_s.push_back(m.holds_s.empty() ? early_hold_s : 0.0);
        if (land) return m;  // landing ends the mission
        if (item.command != static_cast<int>(mavlink::Cmd::nav_takeoff)) hold(item.params[0]);
        break;
      }
      case mavlink::Cmd::nav_delay:
      case mavlink::Cmd::condition_delay:
        hold(item.params[0]);
        break;
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
  if (text_or(root, "type", "") == "FeatureCollection") return parse_geojson(text, source);
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
  const double hover_w =
      level_flight_power_w(power.mechanical, std::hypot(wind.x, wind.y)) + always_w;

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
    if (i < mission.holds_s.size() && mission.holds_s[i] > 0)
      segment(at, alt, mission.holds_s[i], hover_w, "hovering");
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
