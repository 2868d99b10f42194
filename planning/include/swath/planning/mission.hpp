#pragma once
// A drone's mission: take off at home, fly the sweep lines with the camera triggering by
// distance, return to launch.

#include <functional>
#include <optional>
#include <vector>

#include "swath/planning/sweep.hpp"

namespace swath::planning {

enum class ItemKind { takeoff, waypoint, trigger_start, trigger_stop, return_to_launch };

struct MissionItem {
  ItemKind kind = ItemKind::waypoint;
  geometry::Point2 position;  ///< local metres (takeoff: home); unused by trigger and RTL items
  double altitude_m = 0.0;    ///< above home
  double trigger_distance_m = 0.0;  ///< trigger_start only
};

struct MissionSettings {
  double altitude_m = 0.0;                   ///< > 0, above home
  double speed_m_s = 0.0;                    ///< > 0, cruise speed over the whole path
  double trigger_distance_m = 0.0;           ///< > 0
  std::optional<double> waypoint_spacing_m;  ///< intermediate waypoints on long lines
};

struct DroneMission {
  int drone = 1;  ///< 1-based
  geometry::Point2 home;
  std::vector<SweepLine> lines;        ///< in flight order and direction
  std::vector<MissionItem> items;      ///< what the autopilot gets, in order
  std::vector<geometry::Point2> path;  ///< home -> every waypoint -> home, local metres
  double work_length_m = 0.0;          ///< along the sweep lines (camera over the area)
  double transit_length_m = 0.0;       ///< home legs and the legs between lines
  double path_length_m = 0.0;          ///< work + transit
  double flight_time_s = 0.0;      ///< path at cruise speed (climb, descent and turns not modelled)
  std::size_t waypoint_count = 0;  ///< items with a position (takeoff and waypoints)
};

/// A flight path over the survey, without the legs to and from home: points, and for each segment
/// between two points whether it lies on a sweep line (camera work) or is a turn or transit.
struct SurveyPath {
  std::vector<geometry::Point2> points;
  std::vector<char> on_line;  ///< points.size() - 1 flags
  double length_m() const;
};

/// Points strictly between a and b that a leg from a to b flies through (empty: straight).
using LegRoute = std::function<std::vector<geometry::Point2>(geometry::Point2, geometry::Point2)>;

/// The lines in flight order joined by turns (through `route`'s points when given), with
/// intermediate points every `waypoint_spacing_m` at most along the lines.
SurveyPath survey_path(const std::vector<SweepLine>& ordered_lines,
                       std::optional<double> waypoint_spacing_m, const LegRoute& route = {});

/// Cuts a path at increasing distances from its start (each in (0, length)), inserting a point at
/// every cut: consecutive pieces that together are the path.
std::vector<SurveyPath> cut_path(const SurveyPath& path, const std::vector<double>& cuts_m);

/// Builds the mission for a survey path: takeoff at home to the survey altitude, the path's first
/// point, camera trigger by distance on, every point, trigger off, return to launch. The legs from
/// and to home go through `route`'s points when given. settings.waypoint_spacing_m is not used
/// here (survey_path() applies it).
DroneMission mission_for_path(int drone, geometry::Point2 home, const SurveyPath& path,
                              const MissionSettings& settings, const LegRoute& route = {});

/// mission_for_path(survey_path(ordered_lines, settings.waypoint_spacing_m, route), ...).
DroneMission build_mission(int drone, geometry::Point2 home,
                           const std::vector<SweepLine>& ordered_lines,
                           const MissionSettings& settings, const LegRoute& route = {});

}  // namespace swath::planning
