#pragma once
// The files `swath plan` writes (DESIGN.md §8, §14), one writer per format in planning/src/files/.
// Numbers are rounded to fixed decimals: same plan, same bytes.

#include <string>
#include <utility>
#include <vector>

#include "swath/planning/survey.hpp"

namespace swath::planning {

/// One flight a drone makes: its whole mission, or one of its sorties; named for its files.
struct Flight {
  const DronePlan* drone = nullptr;
  const DroneMission* mission = nullptr;
  const std::vector<PhotoPoint>* photos = nullptr;
  int sortie = 0;         ///< 1-based; 0 for a drone flying its whole mission at once
  std::string file_stem;  ///< "alpha", "alpha-2", "drone-1"
};

/// Every flight of the plan, drone by drone, sorties in order.
std::vector<Flight> flights_of(const SurveyPlan& plan);

/// QGroundControl plan (fileType "Plan", mission version 2): the flight's items (take-off, speed,
/// gimbal, waypoints, camera per line, RTL or land) with the drone's own home as
/// plannedHomePosition and its speed as cruise and hover speed, the inclusion fence and one
/// exclusion per no-fly zone, and the drone's home as rally point.
std::string qgc_plan(const SurveyPlan& plan, const Flight& flight);

/// QGC WPL 110 (Mission Planner): row 0 the drone's own home, then the same items.
std::string wpl_110(const SurveyPlan& plan, const Flight& flight);

/// waypoints.csv: drone,flight,seq,lat,lon,alt_m,x_m,y_m,action for every flight.
std::string waypoints_csv(const SurveyPlan& plan);

/// photos.csv: drone,flight,line,photo,lat,lon,alt_m,x_m,y_m; photos.geojson: the same as Points.
std::string photos_csv(const SurveyPlan& plan);
std::string photos_geojson(const SurveyPlan& plan);

/// mission.geojson (plan_features.hpp): the area, no-fly zones, cells, regions, paths, sweeps,
/// homes.
std::string mission_geojson(const SurveyPlan& plan);

/// KML document: the area, the no-fly zones, each drone's path (relative altitude), homes.
std::string mission_kml(const SurveyPlan& plan);

/// Mission Planner / ArduPilot fence and rally files (--fence-files): fence.waypoints (QGC WPL
/// 110 with NAV_FENCE_POLYGON_VERTEX_INCLUSION 5001 and _EXCLUSION 5002 items, as ArduPilot 4
/// stores polygon fences), fence.fen (the legacy list: return point, then the inclusion polygon
/// closed) and rally.waypoints (NAV_RALLY_POINT 5100 at each drone's home).
std::string fence_waypoints(const SurveyPlan& plan);
std::string fence_fen(const SurveyPlan& plan);
std::string rally_waypoints(const SurveyPlan& plan);

/// Every figure of the plan (DESIGN.md §8, §14) as JSON; `files`, the names of the set written with
/// it (DESIGN.md §14 "Output directory"), under "files" when given.
std::string summary_json(const SurveyPlan& plan, const std::vector<std::string>& files = {});

struct FileOptions {
  bool fence_files = false;  ///< also the Mission Planner fence and rally files
};

/// All of the above with their file names, in writing order (summary.json second, without
/// "files": the caller knows the whole set only after adding its own).
std::vector<std::pair<std::string, std::string>> survey_files(const SurveyPlan& plan,
                                                              const FileOptions& options = {});

}  // namespace swath::planning
