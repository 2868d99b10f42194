#pragma once
// The files `swath plan` writes (DESIGN.md §8), as text. Deterministic: the same plan gives the
// same bytes. Coordinates go out in WGS84 degrees rounded to 1e-9° (~0.1 mm), altitudes relative
// to home.

#include <string>
#include <utility>
#include <vector>

#include "swath/planning/survey.hpp"

namespace swath::planning {

/// QGroundControl plan (fileType "Plan", version 1; mission version 2): takeoff 22, waypoints 16
/// (frame 3, relative altitude), camera trigger distance 206 on/off (frame 2), RTL 20; geoFence
/// and rallyPoints empty with version 2. MAV_AUTOPILOT 3 (ArduPilot) or 12 (PX4); MAV_TYPE 2
/// (quadrotor) or 1 (fixed wing).
std::string qgc_plan(const SurveyPlan& plan, const DroneMission& mission);

/// QGC WPL 110 text: tab-separated, 12 columns; row 0 is home.
std::string wpl_110(const SurveyPlan& plan, const DroneMission& mission);

/// drone,seq,lat,lon,alt_m,x_m,y_m,action for every drone: seq 0 is home, then the mission items
/// (positions empty for trigger and RTL items).
std::string waypoints_csv(const SurveyPlan& plan);

/// FeatureCollection with "role": area, path (drone i, home to home), sweep (drone i,
/// footprint_width_m), home.
std::string mission_geojson(const SurveyPlan& plan);

/// KML document: the area, each drone's path (relative altitude), home.
std::string mission_kml(const SurveyPlan& plan);

/// Every figure of the plan (DESIGN.md §8) as JSON; `files`, the names of the set written with it
/// (DESIGN.md §14 "Output directory"), under "files" when given.
std::string summary_json(const SurveyPlan& plan, const std::vector<std::string>& files = {});

/// All of the above with their file names, in writing order.
std::vector<std::pair<std::string, std::string>> survey_files(const SurveyPlan& plan);

}  // namespace swath::planning
