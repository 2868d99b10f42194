#include "swath/control/mission.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/energy/budget.hpp"
#include "swath/energy/plan.hpp"
#include "swath/energy/sim_config.hpp"
#include "swath/energy/simulation.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/missions/mission_geojson.hpp"
#include "swath/vehicle/random.hpp"

namespace swath::control {
namespace {

using base::InputError;
using geometry::Point2;

constexpr double kMaxRandomSide_m = 100'000;
constexpr int kMaxRandomWaypoints = 100'000;
constexpr double kDefaultAltitude_m = 5.0;  // paper 002 §7's missions

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::size_t distinct_points(const std::vector<std::vector<Vec3>>& legs) {
  std::vector<Vec3> seen;
  for (const auto& leg : legs)
    for (const Vec3& p : leg)
      if (std::none_of(seen.begin(), seen.end(), [&](const Vec3& q) { return norm(p - q) < 1e-6; }))
        seen.push_back(p);
  return seen.size();
}

// The drone `wanted` (name or 1-based number) among the file's missions.
const energy::WaypointMission& choose_drone(const std::vector<energy::WaypointMission>& all,
                                            const std::string& wanted, const std::string& path) {
  if (all.empty()) throw InputError(path + ": holds no drone's mission");
  if (wanted.empty()) return all.front();
  for (const auto& m : all)
    if (m.drone == wanted) return m;
  double number = 0;
  if (base::parse_number(wanted, number) && number == std::floor(number) && number >= 1 &&
      number <= static_cast<double>(all.size()))
    return all[static_cast<std::size_t>(number) - 1];
  std::string names;
  for (const auto& m : all) names += (names.empty() ? "" : ", ") + m.drone;
  throw InputError(path + ": no drone \"" + wanted + "\" (it holds " + names +
                   "; give a name or a number from 1 to " + std::to_string(all.size()) + ")");
}

FlightMission from_waypoints(const energy::WaypointMission& m, const MissionOptions& options,
                             const std::string& path) {
  FlightMission out;
  out.name = path + (m.drone.empty() ? "" : ", " + m.drone);
  auto height = [&](std::size_t i) {
    return options.altitude_m > 0 ? options.altitude_m : m.altitudes_m[i];
  };
  if (m.points.empty()) throw InputError(path + ": drone " + m.drone + " has no waypoint");
  // Take-off and landing are not flown: the flight starts in hover above home at the first
  // point's height and ends there when the mission returns home (docs/swath-control.md).
  std::vector<Vec3> points{{0, 0, height(0)}};
  for (std::size_t i = 0; i < m.points.size(); ++i)
    points.push_back({m.points[i].x, m.points[i].y, height(i)});
  if (m.returns_home) points.push_back({0, 0, height(m.points.size() - 1)});
  for (std::size_t k = 0; k + 1 < points.size(); ++k)
    if (norm(points[k + 1] - points[k]) > 1e-6) out.legs.push_back({points[k], points[k + 1]});
  for (double v : m.speeds_m_s)
    if (v > 0) out.speed_m_s = std::max(out.speed_m_s, v);
  return out;
}

std::vector<Point2> local_ring(const geometry::LocalFrame& frame,
                               const std::vector<geometry::GeoPoint>& ring) {
  std::vector<Point2> out;
  for (const auto& g : ring) out.push_back(frame.to_local(g));
  return out;
}

// The area and no-fly zones of swath's mission.geojson, in the mission's frame (at its home).
void add_plan_geometry(FlightMission& out, const std::string& text, const std::string& path,
                       const geometry::GeoPoint& home) {
  missions::PlanFeatures features;
  try {
    features = missions::parse_mission_geojson(text, path);
  } catch (const InputError&) {
    return;  // a waypoint GeoJSON without swath's area: nothing to check against
  }
  const geometry::LocalFrame frame(home);
  for (const auto& ring : features.area) out.area.push_back(local_ring(frame, ring));
  for (const auto& ring : features.no_fly) out.no_fly.push_back(local_ring(frame, ring));
}

FlightMission from_stage_plan(const std::string& path, const MissionOptions& options,
                              std::vector<std::string>* warnings) {
  const energy::Plan plan = energy::read_plan(path, warnings);
  energy::SimConfig config;
  config.source = path;
  config.speed_m_s = options.stage_speed_m_s;
  config.max_airspeed_m_s = std::max(config.max_airspeed_m_s, 2 * options.stage_speed_m_s);
  config.start = options.start_m;
  // Points about every 0.5 m: dense enough for a carrot, light enough for a long flight.
  config.output_interval_s = std::max(config.time_step_s, 0.5 / options.stage_speed_m_s);
  const std::vector<Point2> path2 = energy::guided_path(plan, config);
  const double z = options.altitude_m > 0 ? options.altitude_m : kDefaultAltitude_m;
  FlightMission out;
  out.name = path;
  out.speed_m_s = options.stage_speed_m_s;
  std::vector<Vec3> leg;
  for (Point2 p : path2)
    if (leg.empty() || std::hypot(p.x - leg.back().x, p.y - leg.back().y) > 1e-6)
      leg.push_back({p.x, p.y, z});
  out.legs.push_back(std::move(leg));
  return out;
}

}  // namespace

std::optional<RandomSpec> parse_random_spec(const std::string& text) {
  const std::string prefix = "random:";
  if (text.rfind(prefix, 0) != 0) return std::nullopt;
  const std::string rest = text.substr(prefix.size());
  const auto at = rest.find('@'), x = rest.find('x', at == std::string::npos ? 0 : at);
  RandomSpec spec;
  double n = 0;
  const std::string usage = "mission \"" + text +
                            "\": expected random:N@WxH (N waypoints, 2 to 100000, in a W by H "
                            "metre box, each 0 < side <= 100000), e.g. random:8@20x20";
  if (at == std::string::npos || x == std::string::npos ||
      !base::parse_number(rest.substr(0, at), n) ||
      !base::parse_number(rest.substr(at + 1, x - at - 1), spec.width_m) ||
      !base::parse_number(rest.substr(x + 1), spec.height_m))
    throw InputError(usage);
  if (!(n >= 2 && n <= kMaxRandomWaypoints && n == std::floor(n)) || !(spec.width_m > 0) ||
      !(spec.height_m > 0) || spec.width_m > kMaxRandomSide_m || spec.height_m > kMaxRandomSide_m)
    throw InputError(usage);
  spec.waypoints = static_cast<int>(n);
  return spec;
}

FlightMission random_mission(const RandomSpec& spec, double altitude_m, std::uint64_t seed) {
  auto random = vehicle::SplitMix64::stream(seed, "mission");
  std::vector<Vec3> points;
  for (int k = 0; k < spec.waypoints; ++k) {
    const double x = random.uniform(0, spec.width_m), y = random.uniform(0, spec.height_m);
    points.push_back({x, y, altitude_m});
  }
  FlightMission out;
  out.name = "random:" + std::to_string(spec.waypoints) + "@" + base::shortest_text(spec.width_m) +
             "x" + base::shortest_text(spec.height_m);
  for (std::size_t k = 0; k + 1 < points.size(); ++k)
    out.legs.push_back({points[k], points[k + 1]});
  return out;
}

FlightMission read_flight_mission(const std::string& mission, const MissionOptions& options,
                                  std::uint64_t seed, std::vector<std::string>* warnings) {
  FlightMission out;
  if (const auto spec = parse_random_spec(mission)) {
    out = random_mission(*spec, options.altitude_m > 0 ? options.altitude_m : kDefaultAltitude_m,
                         seed);
  } else if (const std::string ext = lower_extension(mission);
             ext == ".stages" || ext == ".yaml" || ext == ".yml") {
    out = from_stage_plan(mission, options, warnings);
  } else {
    const std::string text = base::read_text_file(mission, "mission file");
    const auto all = energy::parse_waypoint_missions(text, mission);
    const energy::WaypointMission& chosen = choose_drone(all, options.drone, mission);
    out = from_waypoints(chosen, options, mission);
    if (ext == ".geojson" || ext == ".json") add_plan_geometry(out, text, mission, chosen.home);
  }
  if (distinct_points(out.legs) < 2)
    throw InputError(mission + ": the mission has fewer than 2 distinct points to fly");
  return out;
}

FlightMission closed_for_loop(FlightMission mission) {
  const Vec3 first = mission.legs.front().front(), last = mission.legs.back().back();
  if (norm(last - first) > 1e-6) mission.legs.push_back({last, first});
  return mission;
}

}  // namespace swath::control
