#pragma once
// Internal to the file writers: positions in WGS84 as written, MAVLink commands and params of
// mission items, text escaping.

#include <array>
#include <string>
#include <vector>

#include "swath/planning/survey_files.hpp"

namespace swath::planning::files {

constexpr int kFrameGlobal = 0;       // MAV_FRAME_GLOBAL: AMSL (fence and rally items)
constexpr int kFrameMission = 2;      // MAV_FRAME_MISSION: no position
constexpr int kFrameRelativeAlt = 3;  // MAV_FRAME_GLOBAL_RELATIVE_ALT

/// A local point in WGS84, rounded to 1e-9 degrees as every file writes it.
geometry::GeoPoint geo(const SurveyPlan& plan, geometry::Point2 p);
geometry::GeoPoint rounded(const geometry::GeoPoint& g);

/// The MAVLink command of an item (depends on the firmware for the gimbal).
int mav_command(const MissionItem& item, Firmware firmware);
/// The MAVLink frame an item is written in.
int mav_frame(const MissionItem& item);
/// The seven params of an item; NaN where QGC writes null.
std::array<double, 7> mav_params(const SurveyPlan& plan, const MissionItem& item);
/// waypoints.csv's name for an item.
const char* action_name(ItemKind kind);

/// Markup escaped, and bytes that are not UTF-8 replaced (XML allows no others).
std::string xml_escape(const std::string& text);

/// "lon,lat,alt lon,lat,alt ..." (closed: the first point again at the end).
std::string kml_coordinates(const std::vector<geometry::GeoPoint>& points, double altitude_m,
                            bool close);

/// A QGC WPL 110 row: index, current, frame, command, seven params (NaN as 0), autocontinue 1.
std::string wpl_row(std::size_t index, int current, int frame, int command,
                    const std::array<double, 7>& params);

}  // namespace swath::planning::files
