#pragma once
// Internal to the file writers: positions in WGS84 as written, MAVLink commands and params of
// mission items, text escaping.

#include <array>
#include <string>
#include <vector>

#include "geo_memo.hpp"
#include "swath/mavlink/commands.hpp"
#include "swath/missions/writers.hpp"
#include "swath/planning/survey_files.hpp"

namespace swath::planning::files {

// The MAV_FRAME values items are written in (swath/mavlink/commands.hpp).
constexpr int kFrameGlobal = static_cast<int>(mavlink::MavFrame::global);    // AMSL
constexpr int kFrameMission = static_cast<int>(mavlink::MavFrame::mission);  // no position
constexpr int kFrameRelativeAlt = static_cast<int>(mavlink::MavFrame::global_relative_alt);
constexpr int kFrameTerrainAlt = static_cast<int>(mavlink::MavFrame::global_terrain_alt);

/// The MAVLink command of an item (depends on the firmware for the gimbal).
int mav_command(const MissionItem& item, Firmware firmware);
/// The frame the plan's waypoints are written in (relative without terrain).
AltitudeFrame altitude_frame(const SurveyPlan& plan);
/// The MAVLink frame an item is written in (positions: the plan's altitude frame).
int mav_frame(const SurveyPlan& plan, const MissionItem& item);
/// A positional item's altitude in the plan's altitude frame, metres.
double mav_altitude_m(const SurveyPlan& plan, const MissionItem& item);
/// The seven params of an item; NaN where QGC writes null.
std::array<double, 7> mav_params(const SurveyPlan& plan, const MissionItem& item);
/// The flight as the mission writers take it (swath/missions/writers.hpp): its items' commands,
/// frames and params as written, the drone's home (AMSL altitude) and speed, the fence, the
/// no-fly zones' exclusion fences, the drone's home as rally point.
missions::Mission mission_file(const SurveyPlan& plan, const Flight& flight);
/// The plan's fences (inclusion: the area grown by the margin; exclusion: one per no-fly zone)
/// with the plan's home as return point.
missions::Mission fence_file(const SurveyPlan& plan);
/// QGC's firmware type and altitude mode of the plan.
missions::QgcPlanSettings qgc_settings(const SurveyPlan& plan);

/// waypoints.csv's name for an item.
const char* action_name(ItemKind kind);

/// Markup escaped, and bytes that are not UTF-8 replaced (XML allows no others).
std::string xml_escape(const std::string& text);

/// What a drone flies, as the maps draw it: its sorties one after another (each from home to its
/// resume point, its work, and back home from its cut point), else its one flight.
std::vector<const DroneMission*> drone_flights(const DronePlan& drone);
/// The points of drone_flights(drone) joined, local metres: home to home.
std::vector<geometry::Point2> map_path(const DronePlan& drone);
/// Above home, metres, where the maps draw a drone's path without terrain: the imaging altitude
/// plus its altitude layer (SurveyRequest::layer_spacing_m).
double map_altitude_m(const SurveyPlan& plan, const DronePlan& drone);

/// "lon,lat,alt lon,lat,alt ..." (closed: the first point again at the end).
std::string kml_coordinates(const std::vector<geometry::GeoPoint>& points, double altitude_m,
                            bool close);

/// photos.csv and photos.geojson (survey_files.hpp), made in one pass over the photos.
struct PhotoTexts {
  std::string csv;
  std::string geojson;
};
PhotoTexts photo_texts(const SurveyPlan& plan);

/// A waypoint as the DJI and Litchi exports write it (swath/missions/writers.hpp).
using ExportPoint = missions::ExportPoint;

/// The true bearing of the geodesic from a to b at a (at_end: at b), degrees in [0, 360): an
/// export point's heading.
double bearing_deg(const geometry::GeoPoint& a, const geometry::GeoPoint& b, bool at_end);

/// The export points of a flight (see ExportPoint).
/// `local`, if given, gets each point's position in the plan's frame (metres), in their order.
std::vector<ExportPoint> export_points(const SurveyPlan& plan, const Flight& flight,
                                       std::vector<geometry::Point2>* local = nullptr);

/// DJI's waypoint spacing (DJIMutableWaypointMission addWaypoint; Litchi flies DJI's waypoint
/// missions): adjacent waypoints 0.5 m to 2,000 m apart in three dimensions.
constexpr double kDjiLeastLeg_m = 0.5;
constexpr double kDjiLongestLeg_m = 2000.0;
/// Points are merged below this, 2 % above DJI's least: a distance on a sphere (as an app may
/// measure it) differs from the ellipsoid's geodesic by up to 0.5 %.
constexpr double kDjiMergeBelow_m = 0.51;

/// The export points (and their local positions, in step) fitted to DJI's spacing: a point closer
/// than kDjiMergeBelow_m to the one kept before it is merged into that one (the stop's position,
/// the slower approach, the leg on from the later one), a leg longer than kDjiLongestLeg_m is
/// split by points on it that fly it as its start does (camera, speed). Headings are left to set.
void fit_dji_spacing(const SurveyPlan& plan, double cruise_m_s, std::vector<ExportPoint>& points,
                     std::vector<geometry::Point2>& local);

/// The flight's camera trigger value on photo legs: metres between photos (distance mode) or
/// seconds (time mode); 0 in hover mode.
double trigger_value(const Flight& flight);

}  // namespace swath::planning::files
