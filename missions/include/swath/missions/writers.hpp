#pragma once
// Mission files as swath writes them (docs/formats.md, docs/swath-plan.md), beside their readers
// (mission.hpp, dji_kmz.cpp): QGC .plan, WPL 110 missions, fences and rally points, Mission
// Planner's .fen, Litchi CSV, DJI WPML KMZ.
// Written from a Mission value holding the numbers as the file shows them (the caller rounds):
// same value, same bytes. Items are written as MISSION_ITEM's seven params: params[0..3],
// position (param5 latitude, param6 longitude) and altitude_m (param7), whatever the command;
// an item with an altitude_frame other than none is a position QGC gives an altitude mode.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "swath/missions/export_types.hpp"
#include "swath/missions/mission.hpp"

namespace swath::missions {

/// A waypoint of a flight as the DJI and Litchi exports write it (docs/swath-plan.md): their apps
/// take off and return (or land) by themselves, so these are the mission's NAV_WAYPOINTs in order,
/// and with --land the home again at the survey altitude, where the app's landing finish action
/// lands.
struct ExportPoint {
  geometry::GeoPoint geo;   ///< WGS84, rounded to 1e-9 degrees as every file writes it
  double altitude_m = 0.0;  ///< above home (the take-off point)
  /// True bearing of the leg that follows, degrees clockwise from north in [0, 360) (the last
  /// point: of the leg that arrives); the geodesic azimuth at this point (GeographicLib).
  double heading_deg = 0.0;
  /// The camera triggers along the leg that follows (distance or time mode; a sweep line, or a
  /// turn inside the area with --photos-in-turns), as the mission's trigger items say.
  bool photo_leg = false;
  double hold_s = 0.0;  ///< hover: the hold here, seconds
  bool shot = false;    ///< hover: one photo here
  /// The speed of the leg that follows, m/s, where the mission sets one of its own (a slower
  /// approach to a stop beside a no-fly zone); 0: the flight's speed.
  double speed_m_s = 0.0;
};

/// What a Litchi mission says beside its points.
struct LitchiSettings {
  std::size_t max_rows = 99;      ///< Litchi's largest mission, waypoints
  double gimbal_pitch_deg = 0.0;  ///< at every point (gimbalmode 2)
  double speed_m_s = 0.0;         ///< at every point without a speed of its own
  TriggerMode trigger = TriggerMode::distance;
  double trigger_value = 0.0;  ///< metres between photos (distance) or seconds (time)
  /// Whether a part may end at point i (and the next start there): Litchi flies each part from
  /// home straight to its first row and back home from its last, stopping there. None: anywhere.
  std::function<bool(std::size_t)> may_end_at;
};

/// One Litchi mission CSV of `points`, one row each (as write_litchi_csv() writes a part; the
/// last row's leg photographs nothing, it has none); the row `resumed_row`, when given, resumes a
/// part before it: its hold and photo were done at the end of that part and are not repeated.
std::string write_litchi_part(const std::vector<ExportPoint>& points,
                              std::optional<std::size_t> resumed_row,
                              const LitchiSettings& settings);

/// Litchi mission CSV (--litchi): Litchi's column set, one row per point (see
/// planning::litchi_csv for the columns; a row's speed is its leg's to the next row, as Litchi's
/// and DJI's waypoint missions read it); one text per part of at most max_rows rows, part k + 1
/// starting at the point part k ends at: the last point within max_rows that may_end_at allows,
/// or the max_rows-th where none does.
std::vector<std::string> write_litchi_csv(const std::vector<ExportPoint>& points,
                                          const LitchiSettings& settings);

/// DJI WPML's waypoint speeds (waypointSpeed, autoFlightSpeed), m/s: the aircraft flies no
/// slower than 1 m/s, and 15 m/s is the Mavic 3 Enterprise's and the enterprise aircraft's most.
inline constexpr double kDjiMinSpeed_m_s = 1.0;
inline constexpr double kDjiMaxSpeed_m_s = 15.0;
/// WPML's highest takeOffSecurityHeight above the take-off point, m (its range [1.2, 1500]).
inline constexpr double kDjiMaxHeight_m = 1500.0;

/// What a DJI WPML wayline says beside its points.
struct DjiSettings {
  bool land = false;              ///< finishAction autoLand (else goHome)
  std::optional<DjiEnums> enums;  ///< absent: no droneInfo and payloadInfo
  double speed_m_s = 0.0;         ///< every point's, and the transitional speed (at most 15)
  double altitude_m = 0.0;        ///< the survey altitude: global height, RTH and take-off security
  double gimbal_pitch_deg = 0.0;  ///< set at the first point
  TriggerMode trigger = TriggerMode::distance;
  double trigger_value = 0.0;  ///< metres between photos (distance) or seconds (time)
};

/// DJI WPML (--dji; see planning::dji_waylines_wpml for what is written): wpmz/waylines.wpml (what
/// the aircraft executes) and wpmz/template.kml (the template DJI Pilot 2 edits) of the points,
/// and the KMZ, a zip of both (libzip); same points, same bytes.
std::string write_dji_waylines_wpml(const std::vector<ExportPoint>& points,
                                    const DjiSettings& settings);
std::string write_dji_template_kml(const std::vector<ExportPoint>& points,
                                   const DjiSettings& settings);
std::string write_dji_kmz(const std::vector<ExportPoint>& points, const DjiSettings& settings);

/// What a QGC plan says beside the mission's items.
struct QgcPlanSettings {
  int firmware_type = 3;  ///< MAV_AUTOPILOT: 3 ArduPilot, 12 PX4
  int altitude_mode = 1;  ///< QGC's AltMode of the positions: 1 relative, 2 AMSL, 4 terrain frame
};

/// QGC's Survey complex item (ComplexItem "survey" version 5, TransectStyleComplexItem version 2,
/// CameraCalc version 1 with a "Custom Camera"), holding the mission's items [first, last).
struct QgcSurvey {
  std::size_t first = 0, last = 0;
  // CameraCalc
  double adjusted_footprint_frontal_m = 0.0;  ///< the trigger distance
  double adjusted_footprint_side_m = 0.0;     ///< the line spacing
  double distance_to_surface_m = 0.0;
  double focal_length_mm = 0.0;
  double frontal_overlap_pct = 0.0;
  double image_density_cm_px = 0.0;
  int image_height_px = 0;
  int image_width_px = 0;
  bool landscape = true;
  double min_trigger_interval_s = 0.0;
  double sensor_height_mm = 0.0;
  double sensor_width_mm = 0.0;
  double side_overlap_pct = 0.0;
  // TransectStyleComplexItem
  std::size_t camera_shots = 0;
  bool trigger_in_turnaround = false;
  bool hover_and_capture = false;
  bool refly_90_degrees = false;
  double turnaround_m = 0.0;
  std::vector<geometry::GeoPoint> transect_points;  ///< the waypoints inside the survey
  // Survey
  double angle_deg = 0.0;                   ///< the lines' bearing, degrees from true north
  std::vector<geometry::GeoPoint> polygon;  ///< the area's outline, open
};

/// QGroundControl plan (fileType "Plan", mission version 2): the items as SimpleItems (doJumpId
/// from 1), home as plannedHomePosition (AMSL), cruise_speed_m_s as cruise and hover speed,
/// vehicleType 1 for a fixed wing (else 2), the fences as GeoFence polygons, the rally points;
/// with `survey`, its items inside a Survey complex item.
std::string write_qgc_plan(const Mission& mission, const QgcPlanSettings& settings,
                           const QgcSurvey* survey = nullptr);

/// QGC WPL 110 (Mission Planner): row 0 the home (AMSL, frame 0), then the items. A value that is
/// none (NaN) is 0; for a PX4 mission (Mission::autopilot) params 1-4 of none are "NaN".
std::string write_wpl(const Mission& mission);

/// WPL 110 fence file (ArduPilot 4's polygon fences): NAV_FENCE_POLYGON_VERTEX_INCLUSION items
/// for each inclusion fence, then _EXCLUSION for each exclusion fence; param1 the vertex count.
std::string write_wpl_fences(const Mission& mission);

/// WPL 110 rally file: a NAV_RALLY_POINT (relative frame, altitude 0) at each rally point.
std::string write_wpl_rally(const Mission& mission);

/// Mission Planner's legacy fence list (.fen): the home as return point, then the first
/// inclusion fence closed (lat lon a line).
std::string write_fen(const Mission& mission);

}  // namespace swath::missions
