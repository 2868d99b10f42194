// QGroundControl .plan writer (docs/formats.md and docs/swath-plan.md): the items, home and speed,
// fences, rally points, and QGC's Survey complex item; read back by mission.cpp (parse_mission).
#include <nlohmann/json.hpp>

#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <utility>

#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/missions/writers.hpp"

namespace swath::missions {
namespace {

using nlohmann::ordered_json;

ordered_json polygon_json(const std::vector<geometry::GeoPoint>& ring) {
  ordered_json points = ordered_json::array();
  for (const geometry::GeoPoint& g : ring) points.push_back({g.lat_deg, g.lon_deg});
  return points;
}

// QGC's GeoFence: the inclusion polygons, then the exclusions.
ordered_json geofence_json(const Mission& m) {
  ordered_json polygons = ordered_json::array();
  for (const auto& ring : m.inclusion_fences)
    polygons.push_back({{"inclusion", true}, {"polygon", polygon_json(ring)}, {"version", 1}});
  for (const auto& ring : m.exclusion_fences)
    polygons.push_back({{"inclusion", false}, {"polygon", polygon_json(ring)}, {"version", 1}});
  return {{"circles", ordered_json::array()}, {"polygons", std::move(polygons)}, {"version", 2}};
}

// One item as QGC writes a SimpleItem (MissionItem::save): positions carry their altitude mode.
ordered_json simple_item(const Item& item, int altitude_mode, int jump_id) {
  ordered_json j;
  if (item.altitude_frame != AltitudeFrame::none) {
    j["AMSLAltAboveTerrain"] = nullptr;
    j["Altitude"] = item.altitude_m;
    j["AltitudeMode"] = altitude_mode;
  }
  j["autoContinue"] = true;
  j["command"] = item.command;
  j["doJumpId"] = jump_id;
  j["frame"] = item.frame;
  ordered_json p = ordered_json::array();
  const std::array<double, 7> params = {
      item.params[0],        item.params[1],        item.params[2], item.params[3],
      item.position.lat_deg, item.position.lon_deg, item.altitude_m};
  for (double v : params) p.push_back(std::isnan(v) ? ordered_json() : ordered_json(v));
  j["params"] = p;
  j["type"] = "SimpleItem";
  return j;
}

// QGC's CameraCalc, version 1 (every QGC from 4.0 loads it; 4.2 and later convert it to 2): a
// "Custom Camera", so that QGC recomputes the same spacing and trigger distance when the survey
// is edited (CameraCalc::_recalcTriggerDistance).
ordered_json camera_calc(const QgcSurvey& s) {
  ordered_json j;
  j["AdjustedFootprintFrontal"] = s.adjusted_footprint_frontal_m;
  j["AdjustedFootprintSide"] = s.adjusted_footprint_side_m;
  j["CameraName"] = "Custom Camera";
  j["DistanceToSurface"] = s.distance_to_surface_m;
  j["DistanceToSurfaceRelative"] = true;
  j["FixedOrientation"] = false;
  j["FocalLength"] = s.focal_length_mm;
  j["FrontalOverlap"] = s.frontal_overlap_pct;
  j["ImageDensity"] = s.image_density_cm_px;
  j["ImageHeight"] = s.image_height_px;
  j["ImageWidth"] = s.image_width_px;
  j["Landscape"] = s.landscape;
  j["MinTriggerInterval"] = s.min_trigger_interval_s;
  j["SensorHeight"] = s.sensor_height_mm;
  j["SensorWidth"] = s.sensor_width_mm;
  j["SideOverlap"] = s.side_overlap_pct;
  j["ValueSetIsDistance"] = true;
  j["version"] = 1;
  return j;
}

// The Survey complex item around its items (jump ids continuing from `jump_id`).
ordered_json survey_item(const Mission& m, const QgcSurvey& s, int altitude_mode, int& jump_id) {
  ordered_json inner = ordered_json::array();
  for (std::size_t k = s.first; k < s.last; ++k)
    inner.push_back(simple_item(m.items[k], altitude_mode, jump_id++));
  ordered_json tsci;
  tsci["CameraCalc"] = camera_calc(s);
  tsci["CameraShots"] = s.camera_shots;
  tsci["CameraTriggerInTurnAround"] = s.trigger_in_turnaround;
  tsci["HoverAndCapture"] = s.hover_and_capture;
  tsci["Items"] = inner;
  tsci["Refly90Degrees"] = s.refly_90_degrees;
  tsci["TurnAroundDistance"] = s.turnaround_m;
  tsci["VisualTransectPoints"] = polygon_json(s.transect_points);
  tsci["version"] = 2;
  ordered_json survey;
  survey["TransectStyleComplexItem"] = tsci;
  survey["angle"] = s.angle_deg;
  survey["complexItemType"] = "survey";
  survey["entryLocation"] = 0;
  survey["flyAlternateTransects"] = false;
  survey["polygon"] = polygon_json(s.polygon);
  survey["splitConcavePolygons"] = false;
  survey["type"] = "ComplexItem";
  survey["version"] = 5;
  return survey;
}

// The mission's items without a Survey item, as json_text(items_json(...), 4) writes them where
// they stand in the .plan (the array's members at 12 spaces, its closing bracket at 8), written
// directly instead of through a tree: building and dumping one was most of the writer's time.
std::string items_text(const Mission& m, int altitude_mode) {
  if (m.items.empty()) return "[]";
  std::string out = "[\n";
  int jump_id = 1;
  for (const Item& item : m.items) {
    if (jump_id > 1) out += ",\n";
    out += "            {\n";
    if (item.altitude_frame != AltitudeFrame::none) {
      out += "                \"AMSLAltAboveTerrain\": null,\n                \"Altitude\": ";
      base::append_json_number(out, item.altitude_m);
      out += ",\n                \"AltitudeMode\": ";
      base::append_integer_text(out, altitude_mode);
      out += ",\n";
    }
    out += "                \"autoContinue\": true,\n                \"command\": ";
    base::append_integer_text(out, item.command);
    out += ",\n                \"doJumpId\": ";
    base::append_integer_text(out, jump_id++);
    out += ",\n                \"frame\": ";
    base::append_integer_text(out, item.frame);
    out += ",\n                \"params\": [\n";
    const std::array<double, 7> params = {
        item.params[0],        item.params[1],        item.params[2], item.params[3],
        item.position.lat_deg, item.position.lon_deg, item.altitude_m};
    for (std::size_t k = 0; k < params.size(); ++k) {
      out += k == 0 ? "                    " : ",\n                    ";
      base::append_json_number(out, params[k]);
    }
    out += "\n                ],\n                \"type\": \"SimpleItem\"\n            }";
  }
  out += "\n        ]";
  return out;
}

// Where items_text goes in the tree's text: a string no other value of the .plan holds (the values
// before it are numbers and swath's own constants).
constexpr const char* kItemsMark = "@swath-qgc-items@";

ordered_json items_json(const Mission& m, int altitude_mode, const QgcSurvey* survey) {
  ordered_json items = ordered_json::array();
  int jump_id = 1;
  const std::size_t first = survey ? survey->first : m.items.size();
  const std::size_t last = survey ? survey->last : m.items.size();
  for (std::size_t k = 0; k < first; ++k)
    items.push_back(simple_item(m.items[k], altitude_mode, jump_id++));
  if (survey) items.push_back(survey_item(m, *survey, altitude_mode, jump_id));
  for (std::size_t k = last; k < m.items.size(); ++k)
    items.push_back(simple_item(m.items[k], altitude_mode, jump_id++));
  return items;
}

}  // namespace

std::string write_qgc_plan(const Mission& m, const QgcPlanSettings& settings,
                           const QgcSurvey* survey) {
  ordered_json mission;
  mission["cruiseSpeed"] = m.cruise_speed_m_s;
  mission["firmwareType"] = settings.firmware_type;
  mission["globalPlanAltitudeMode"] = settings.altitude_mode;
  mission["hoverSpeed"] = m.cruise_speed_m_s;
  // A Survey item goes through the tree; plain items are written directly (items_text).
  mission["items"] =
      survey ? items_json(m, settings.altitude_mode, survey) : ordered_json(kItemsMark);
  mission["plannedHomePosition"] = {m.home.lat_deg, m.home.lon_deg, m.home_amsl_m};  // AMSL
  mission["vehicleType"] = m.fixed_wing ? 1 : 2;
  mission["version"] = 2;
  ordered_json rally = ordered_json::array();
  for (const geometry::GeoPoint& g : m.rally_points) rally.push_back({g.lat_deg, g.lon_deg, 0});
  ordered_json root;
  root["fileType"] = "Plan";
  root["geoFence"] = geofence_json(m);
  root["groundStation"] = "swath";
  root["mission"] = std::move(mission);  // moved: a copy was a tenth of the writer
  root["rallyPoints"] = {{"points", std::move(rally)}, {"version", 2}};
  root["version"] = 1;
  std::string text = base::json_text(root, 4) + "\n";
  if (!survey) {
    const std::string mark = '"' + std::string(kItemsMark) + '"';
    text.replace(text.find(mark), mark.size(), items_text(m, settings.altitude_mode));
  }
  return text;
}

}  // namespace swath::missions
