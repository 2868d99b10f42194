#include "swath/planning/mission.hpp"

#include <algorithm>

namespace swath::planning {

double SurveyPath::length_m() const {
  double length = 0;
  for (std::size_t i = 0; i + 1 < points.size(); ++i)
    length += geometry::distance(points[i], points[i + 1]);
  return length;
}

SurveyPath survey_path(const std::vector<SweepLine>& lines,
                       std::optional<double> waypoint_spacing_m, const LegRoute& route) {
  SurveyPath path;
  auto add = [&](geometry::Point2 p, bool on_line) {
    if (!path.points.empty()) path.on_line.push_back(on_line);
    path.points.push_back(p);
  };
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (i > 0 && route)
      for (const geometry::Point2& p : route(path.points.back(), lines[i].start)) add(p, false);
    const std::vector<geometry::Point2> points = line_waypoints(lines[i], waypoint_spacing_m);
    for (std::size_t k = 0; k < points.size(); ++k) add(points[k], k > 0);
  }
  return path;
}

std::vector<SurveyPath> cut_path(const SurveyPath& path, const std::vector<double>& cuts_m) {
  std::vector<SurveyPath> pieces(1);
  std::size_t next_cut = 0;
  double walked = 0;
  pieces.back().points.push_back(path.points.front());
  for (std::size_t i = 0; i + 1 < path.points.size(); ++i) {
    const geometry::Point2 a = path.points[i], b = path.points[i + 1];
    const double length = geometry::distance(a, b);
    // Every cut inside this segment ends a piece at a new point and starts the next one there.
    while (next_cut < cuts_m.size() && cuts_m[next_cut] < walked + length) {
      const double t = std::clamp((cuts_m[next_cut] - walked) / length, 0.0, 1.0);
      const geometry::Point2 cut = a + (b - a) * t;
      if (!(cut == pieces.back().points.back())) {
        pieces.back().points.push_back(cut);
        pieces.back().on_line.push_back(path.on_line[i]);
      }
      pieces.emplace_back();
      pieces.back().points.push_back(cut);
      ++next_cut;
    }
    if (!(b == pieces.back().points.back())) {
      pieces.back().points.push_back(b);
      pieces.back().on_line.push_back(path.on_line[i]);
    }
    walked += length;
  }
  while (pieces.size() < cuts_m.size() + 1) pieces.push_back({{path.points.back()}, {}});
  return pieces;
}

DroneMission mission_for_path(int drone, geometry::Point2 home, const SurveyPath& path,
                              const MissionSettings& s, const LegRoute& route) {
  DroneMission m;
  m.drone = drone;
  m.home = home;
  m.items.push_back({ItemKind::takeoff, home, s.altitude_m, 0.0});
  m.path.push_back(home);
  auto leg_to = [&](geometry::Point2 target) {
    if (!route) return;
    for (const geometry::Point2& p : route(m.path.back(), target)) {
      m.items.push_back({ItemKind::waypoint, p, s.altitude_m, 0.0});
      m.path.push_back(p);
    }
  };
  for (std::size_t i = 0; i < path.points.size(); ++i) {
    if (i == 0) leg_to(path.points[0]);
    m.items.push_back({ItemKind::waypoint, path.points[i], s.altitude_m, 0.0});
    if (i == 0) m.items.push_back({ItemKind::trigger_start, {}, 0.0, s.trigger_distance_m});
    m.path.push_back(path.points[i]);
    if (i > 0 && path.on_line[i - 1]) {
      // Consecutive segments on lines are one line (split only by intermediate waypoints).
      if (i > 1 && path.on_line[i - 2]) {
        m.lines.back().end = path.points[i];
      } else {
        m.lines.push_back({path.points[i - 1], path.points[i]});
      }
      m.work_length_m += geometry::distance(path.points[i - 1], path.points[i]);
    }
  }
  if (!path.points.empty()) m.items.push_back({ItemKind::trigger_stop, {}, 0.0, 0.0});
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

DroneMission build_mission(int drone, geometry::Point2 home, const std::vector<SweepLine>& lines,
                           const MissionSettings& s, const LegRoute& route) {
  return mission_for_path(drone, home, survey_path(lines, s.waypoint_spacing_m, route), s, route);
}

}  // namespace swath::planning
