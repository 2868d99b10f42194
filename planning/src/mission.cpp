#include "swath/planning/mission.hpp"

namespace swath::planning {

DroneMission build_mission(int drone, geometry::Point2 home, const std::vector<SweepLine>& lines,
                           const MissionSettings& s, const LegRoute& route) {
  DroneMission m;
  m.drone = drone;
  m.home = home;
  m.lines = lines;
  m.items.push_back({ItemKind::takeoff, home, s.altitude_m, 0.0});
  m.path.push_back(home);
  auto leg_to = [&](geometry::Point2 target) {
    if (!route) return;
    for (const geometry::Point2& p : route(m.path.back(), target)) {
      m.items.push_back({ItemKind::waypoint, p, s.altitude_m, 0.0});
      m.path.push_back(p);
    }
  };
  for (std::size_t i = 0; i < lines.size(); ++i) {
    leg_to(lines[i].start);
    const std::vector<geometry::Point2> points = line_waypoints(lines[i], s.waypoint_spacing_m);
    for (std::size_t k = 0; k < points.size(); ++k) {
      m.items.push_back({ItemKind::waypoint, points[k], s.altitude_m, 0.0});
      if (i == 0 && k == 0)
        m.items.push_back({ItemKind::trigger_start, {}, 0.0, s.trigger_distance_m});
      m.path.push_back(points[k]);
    }
    m.work_length_m += geometry::distance(lines[i].start, lines[i].end);
  }
  if (!lines.empty()) m.items.push_back({ItemKind::trigger_stop, {}, 0.0, 0.0});
  leg_to(home);
  m.items.push_back({ItemKind::return_to_launch, {}, 0.0, 0.0});
  m.path.push_back(home);
  for (std::size_t i = 0; i + 1 < m.path.size(); ++i)
    m.path_length_m += geometry::distance(m.path[i], m.path[i + 1]);
  m.transit_length_m = m.path_length_m - m.work_length_m;
  m.flight_time_s = m.path_length_m / s.speed_m_s;
  for (const MissionItem& item : m.items)
    m.waypoint_count += item.kind == ItemKind::takeoff || item.kind == ItemKind::waypoint;
  return m;
}

}  // namespace swath::planning
