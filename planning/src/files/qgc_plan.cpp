// QGroundControl .plan (docs/formats.md and docs/swath-plan.md): the items, the drone's home and
// speed, fences, rally.
#include <nlohmann/json.hpp>

#include <cmath>

#include "common.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/geometry/min_height.hpp"

namespace swath::planning {

using base::round_to;
using nlohmann::ordered_json;

namespace {

ordered_json polygon_json(const SurveyPlan& plan, const geometry::Ring& ring) {
  ordered_json points = ordered_json::array();
  for (const geometry::Point2& p : ring) {
    const geometry::GeoPoint g = files::geo(plan, p);
    points.push_back({g.lat_deg, g.lon_deg});
  }
  return points;
}

ordered_json geo_polygon_json(const std::vector<geometry::GeoPoint>& ring) {
  ordered_json points = ordered_json::array();
  for (const geometry::GeoPoint& g : ring) {
    const geometry::GeoPoint r = files::rounded(g);
    points.push_back({r.lat_deg, r.lon_deg});
  }
  return points;
}

// QGC's GeoFence: inclusion polygons (the area grown by the margin), an exclusion per zone.
ordered_json geofence_json(const SurveyPlan& plan) {
  ordered_json polygons = ordered_json::array();
  for (const geometry::Ring& ring : plan.fence)
    polygons.push_back(
        {{"inclusion", true}, {"polygon", polygon_json(plan, ring)}, {"version", 1}});
  for (const auto& zone : plan.exclusion_fences_geo)
    polygons.push_back({{"inclusion", false}, {"polygon", geo_polygon_json(zone)}, {"version", 1}});
  return {{"circles", ordered_json::array()}, {"polygons", polygons}, {"version", 2}};
}

// QGroundControl's AltMode: 1 relative, 2 absolute (AMSL), 4 terrain frame (3 is its own
// "calculated above terrain", which it turns into AMSL altitudes itself).
int qgc_altitude_mode(const SurveyPlan& plan) {
  switch (files::altitude_frame(plan)) {
    case AltitudeFrame::relative:
      return 1;
    case AltitudeFrame::amsl:
      return 2;
    case AltitudeFrame::terrain:
      return 4;
  }
  return 1;
}

}  // namespace

namespace {

// One item as QGC writes a SimpleItem (MissionItem::save): positions carry their altitude mode.
ordered_json simple_item(const SurveyPlan& plan, const MissionItem& item, int jump_id) {
  ordered_json j;
  if (positional(item.kind)) {
    j["AMSLAltAboveTerrain"] = nullptr;
    j["Altitude"] = files::mav_altitude_m(plan, item);
    j["AltitudeMode"] = qgc_altitude_mode(plan);
  }
  j["autoContinue"] = true;
  j["command"] = files::mav_command(item, plan.request.firmware);
  j["doJumpId"] = jump_id;
  j["frame"] = files::mav_frame(plan, item);
  ordered_json p = ordered_json::array();
  for (double v : files::mav_params(plan, item))
    p.push_back(std::isnan(v) ? ordered_json() : ordered_json(v));
  j["params"] = p;
  j["type"] = "SimpleItem";
  return j;
}

// The file around the items: the drone's home and speed, the fence, the rally point.
std::string plan_file(const SurveyPlan& plan, const Flight& flight, ordered_json items) {
  const DronePlan& d = *flight.drone;
  const geometry::GeoPoint home = files::rounded(d.home_geo);
  ordered_json m;
  m["cruiseSpeed"] = round_to(d.speed_m_s, 3);
  m["firmwareType"] = plan.request.firmware == Firmware::ardupilot ? 3 : 12;
  m["globalPlanAltitudeMode"] = qgc_altitude_mode(plan);
  m["hoverSpeed"] = round_to(d.speed_m_s, 3);
  m["items"] = std::move(items);
  m["plannedHomePosition"] = {home.lat_deg, home.lon_deg,
                              round_to(flight.mission->home_amsl_m, 3)};  // AMSL
  m["vehicleType"] = plan.request.vehicle == Vehicle::multirotor ? 2 : 1;
  m["version"] = 2;
  ordered_json root;
  root["fileType"] = "Plan";
  root["geoFence"] = geofence_json(plan);
  root["groundStation"] = "swath";
  root["mission"] = m;
  // The rally point is the drone's own home (docs/swath-plan.md).
  root["rallyPoints"] = {{"points", {{home.lat_deg, home.lon_deg, 0}}}, {"version", 2}};
  root["version"] = 1;
  return base::json_text(root, 4) + "\n";
}

// QGC's CameraCalc, version 1 (every QGC from 4.0 loads it; 4.2 and later convert it to 2): a
// "Custom Camera" with swath's camera, so that QGC recomputes the same spacing and trigger
// distance when the survey is edited (CameraCalc::_recalcTriggerDistance).
ordered_json camera_calc(const SurveyPlan& plan) {
  const Camera& c = plan.request.camera;
  const Imaging& im = plan.imaging;
  const bool landscape = plan.request.orientation == ImageOrientation::landscape;
  ordered_json j;
  j["AdjustedFootprintFrontal"] = round_to(im.trigger_distance_m, 6);
  j["AdjustedFootprintSide"] = round_to(im.line_spacing_m, 6);
  j["CameraName"] = "Custom Camera";
  j["DistanceToSurface"] = round_to(im.altitude_m, 6);
  j["DistanceToSurfaceRelative"] = true;
  j["FixedOrientation"] = false;
  j["FocalLength"] = c.focal_length_mm;
  j["FrontalOverlap"] = round_to(100.0 * (1.0 - im.trigger_distance_m / im.footprint_along_m), 6);
  j["ImageDensity"] = round_to(im.gsd_m * 100.0, 8);
  j["ImageHeight"] = c.image_height_px;
  j["ImageWidth"] = c.image_width_px;
  j["Landscape"] = landscape;
  j["MinTriggerInterval"] = c.min_trigger_interval_s.value_or(0.0);
  j["SensorHeight"] = c.sensor_height_mm;
  j["SensorWidth"] = c.sensor_width_mm;
  j["SideOverlap"] = round_to(100.0 * (1.0 - im.line_spacing_m / im.footprint_across_m), 6);
  j["ValueSetIsDistance"] = true;
  j["version"] = 1;
  return j;
}

}  // namespace

std::string qgc_plan(const SurveyPlan& plan, const Flight& flight) {
  ordered_json items = ordered_json::array();
  int jump_id = 1;
  for (const MissionItem& item : flight.mission->items)
    items.push_back(simple_item(plan, item, jump_id++));
  return plan_file(plan, flight, std::move(items));
}

bool qgc_survey_possible(const SurveyPlan& plan, std::string* why) {
  auto no = [why](const char* reason) {
    if (why) *why = reason;
    return false;
  };
  if (plan.handling != Handling::convex || !plan.area.holes.empty() || !plan.no_fly.empty() ||
      !plan.extra_pieces.empty())
    return no(
        "QGroundControl's survey item is written for convex areas without holes or "
        "no-fly zones (its own transects would cross them when edited)");
  if (plan.drones.size() != 1) return no("QGroundControl's survey item is one drone's");
  if (!plan.drones[0].sorties.empty()) return no("a survey item cannot hold several sorties");
  if (plan.terrain)
    return no(
        "a survey item keeps one altitude; QGroundControl follows terrain itself with its "
        "survey's terrain altitude mode");
  return true;
}

std::string qgc_survey_plan(const SurveyPlan& plan, const Flight& flight) {
  const auto& items = flight.mission->items;
  // Outside the survey: the take-off before it, the return or landing after it.
  std::size_t first = 0, last = items.size();
  while (first < last && items[first].kind == ItemKind::takeoff) ++first;
  while (last > first &&
         (items[last - 1].kind == ItemKind::return_to_launch ||
          items[last - 1].kind == ItemKind::land || items[last - 1].kind == ItemKind::land_start))
    --last;
  ordered_json outer = ordered_json::array();
  int jump_id = 1;
  for (std::size_t k = 0; k < first; ++k) outer.push_back(simple_item(plan, items[k], jump_id++));
  ordered_json inner = ordered_json::array();
  ordered_json transect_points = ordered_json::array();
  for (std::size_t k = first; k < last; ++k) {
    inner.push_back(simple_item(plan, items[k], jump_id++));
    if (items[k].kind == ItemKind::waypoint) {
      const geometry::GeoPoint g = files::geo(plan, items[k].position);
      transect_points.push_back({g.lat_deg, g.lon_deg});
    }
  }
  const SurveyRequest& r = plan.request;
  ordered_json tsci;
  tsci["CameraCalc"] = camera_calc(plan);
  tsci["CameraShots"] = flight.photos ? flight.photos->size() : 0;
  tsci["CameraTriggerInTurnAround"] = r.triggering.photos_in_turns;
  tsci["HoverAndCapture"] = r.triggering.mode == TriggerMode::hover;
  tsci["Items"] = inner;
  tsci["Refly90Degrees"] = r.crosshatch;
  tsci["TurnAroundDistance"] = round_to(plan.turnaround_m, 6);
  tsci["VisualTransectPoints"] = transect_points;
  tsci["version"] = 2;
  ordered_json survey;
  survey["TransectStyleComplexItem"] = tsci;
  survey["angle"] = round_to(geometry::line_bearing_deg(plan.sweep.angle_deg), 6);
  survey["complexItemType"] = "survey";
  survey["entryLocation"] = 0;
  survey["flyAlternateTransects"] = false;
  std::vector<geometry::GeoPoint> outline = r.field.geo_rings.at(0);
  if (outline.size() > 1 && outline.front() == outline.back()) outline.pop_back();  // QGC: open
  survey["polygon"] = geo_polygon_json(outline);
  survey["splitConcavePolygons"] = false;
  survey["type"] = "ComplexItem";
  survey["version"] = 5;
  outer.push_back(survey);
  for (std::size_t k = last; k < items.size(); ++k)
    outer.push_back(simple_item(plan, items[k], jump_id++));
  return plan_file(plan, flight, std::move(outer));
}

}  // namespace swath::planning
