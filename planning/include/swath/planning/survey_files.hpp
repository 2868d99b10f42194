#pragma once
// The files `swath plan` writes (docs/formats.md and docs/swath-plan.md), one writer per format in
// planning/src/files/. Numbers are rounded to fixed decimals: same plan, same bytes.

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

/// Whether the plan can be written as a QGroundControl Survey complex item (--qgc-survey): one
/// drone, one flight, a convex area without holes or no-fly zones, no terrain; else `why` says.
bool qgc_survey_possible(const SurveyPlan& plan, std::string* why = nullptr);

/// QGroundControl plan with the flight as a Survey complex item (--qgc-survey, editable in QGC):
/// the take-off, then a ComplexItem "survey" version 5 (the area's outline as its polygon, the
/// lines' bearing as its angle, turnaround, crosshatch, the camera as a "Custom Camera" CameraCalc
/// version 1 with its sensor, focal length, image size, GSD, overlaps, spacing and trigger
/// distance, and swath's own items as the TransectStyleComplexItem's Items, which QGC flies as
/// they are until the survey is edited), then the return or landing; fence and rally as in
/// qgc_plan(). Requires qgc_survey_possible().
std::string qgc_survey_plan(const SurveyPlan& plan, const Flight& flight);

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

/// Litchi's largest mission, waypoints.
inline constexpr std::size_t kLitchiMaxWaypoints = 99;
/// Litchi's (DJI's waypoint missions') fastest waypoint speed, m/s.
inline constexpr double kLitchiMaxSpeed_m_s = 15.0;
/// Litchi's highest waypoint altitude above the take-off point, m.
inline constexpr double kLitchiMaxAltitude_m = 500.0;
/// Litchi's and DJI Pilot 2's lowest waypoint altitude relative to the take-off point, m.
inline constexpr double kDjiMinAltitude_m = -200.0;
/// The most points a DJI WPML wayline numbers (wpml:index 0 to 65535).
inline constexpr std::size_t kWpmlMaxWaypoints = 65'536;

/// Litchi mission CSV (--litchi, docs/swath-plan.md): Litchi's column set (latitude, longitude,
/// altitude(m), heading(deg), curvesize(m), rotationdir, gimbalmode, gimbalpitchangle,
/// actiontype1..15/actionparam1..15, altitudemode, speed(m/s), poi_*, photo_timeinterval,
/// photo_distinterval), one row per waypoint of the flight (Litchi takes off and returns or lands
/// itself: its finish action is a mission setting the CSV does not hold; with --land the home is
/// the last row, to land there). Altitudes relative to the take-off point (altitudemode 0),
/// headings along the leg each point starts (degrees from true north), the gimbal pitch at every
/// point (gimbalmode 2), the drone's speed, holds as stay actions, hover shots as photo actions,
/// photo_distinterval (distance) or photo_timeinterval (time) on the waypoints whose next leg the
/// camera triggers on, -1 elsewhere. One text per part of at most kLitchiMaxWaypoints rows; part
/// k + 1 starts at the point part k ends at, after the way back out to it where part k ends with a
/// way home round the no-fly zones (rows of their own, camera off: Litchi flies home straight from
/// a part's last row). Throws base::InputError where no point within a part's rows has a way home
/// that keeps clear and fits.
std::vector<std::string> litchi_csv(const SurveyPlan& plan, const Flight& flight);

/// DJI WPML (--dji, docs/swath-plan.md): wpmz/waylines.wpml (what the aircraft executes) and
/// wpmz/template.kml (the waypoint template DJI Pilot 2 edits) of a flight: the points as for
/// Litchi, heights relativeToStartPoint, the drone's speed, followWayline heading (the leg's
/// bearing in waypointHeadingAngle), a stop at every point, gimbalRotate to the gimbal pitch at
/// the first point, takePhoto every trigger distance (multipleDistance) or interval
/// (multipleTiming) from each run of photo legs' first point to its last, hover and takePhoto at
/// hover points; finishAction goHome, or autoLand with --land; droneInfo/payloadInfo from the
/// camera's DJI enums when it has them (omitted otherwise: export_warnings() says so).
std::string dji_waylines_wpml(const SurveyPlan& plan, const Flight& flight);
std::string dji_template_kml(const SurveyPlan& plan, const Flight& flight);
/// The KMZ: a zip (libzip) of wpmz/template.kml and wpmz/waylines.wpml; same plan, same bytes.
std::string dji_kmz(const SurveyPlan& plan, const Flight& flight);

/// Every figure of the plan (docs/formats.md and docs/swath-plan.md) as JSON; `files`, the names of
/// the set written with it (docs/swath-plan.md), under "files" when given.
std::string summary_json(const SurveyPlan& plan, const std::vector<std::string>& files = {});

struct FileOptions {
  bool fence_files = false;  ///< also the Mission Planner fence and rally files
  bool litchi = false;       ///< also <flight>-litchi.csv (split: <flight>-litchi-<k>.csv)
  bool dji = false;          ///< also <flight>.kmz
  bool qgc_survey = false;   ///< also <flight>-survey.plan (qgc_survey_plan())
};

/// Throws base::InputError (one sentence naming the option) when the plan cannot be exported as
/// `options` asks: Litchi and DJI Pilot 2 fly multirotors only; Litchi flies at most
/// kLitchiMaxSpeed_m_s and kLitchiMaxAltitude_m; neither below kDjiMinAltitude_m; a WPML wayline
/// holds kWpmlMaxWaypoints;
/// --qgc-survey needs qgc_survey_possible().
void check_exports(const SurveyPlan& plan, const FileOptions& options);

/// Warnings about the exports `options` asks for: a --dji camera without DJI enums.
std::vector<std::string> export_warnings(const SurveyPlan& plan, const FileOptions& options);

/// All of the above with their file names, in writing order (summary.json second, without
/// "files": the caller knows the whole set only after adding its own). Calls check_exports().
std::vector<std::pair<std::string, std::string>> survey_files(const SurveyPlan& plan,
                                                              const FileOptions& options = {});

}  // namespace swath::planning
