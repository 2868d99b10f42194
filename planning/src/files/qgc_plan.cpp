// QGroundControl .plan (DESIGN.md §8, §14): the items, the drone's home and speed, fences, rally.
#include <nlohmann/json.hpp>

#include <cmath>

#include "common.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"

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
  for (const auto& zone : plan.no_fly_geo)
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

std::string qgc_plan(const SurveyPlan& plan, const Flight& flight) {
  const Firmware firmware = plan.request.firmware;
  ordered_json items = ordered_json::array();
  int jump_id = 1;
  for (const MissionItem& item : flight.mission->items) {
    ordered_json j;
    if (positional(item.kind)) {
      j["AMSLAltAboveTerrain"] = nullptr;
      j["Altitude"] = files::mav_altitude_m(plan, item);
      j["AltitudeMode"] = qgc_altitude_mode(plan);
    }
    j["autoContinue"] = true;
    j["command"] = files::mav_command(item, firmware);
    j["doJumpId"] = jump_id++;
    j["frame"] = files::mav_frame(plan, item);
    ordered_json p = ordered_json::array();
    for (double v : files::mav_params(plan, item))
      p.push_back(std::isnan(v) ? ordered_json() : ordered_json(v));
    j["params"] = p;
    j["type"] = "SimpleItem";
    items.push_back(j);
  }
  const DronePlan& d = *flight.drone;
  const geometry::GeoPoint home = files::rounded(d.home_geo);
  ordered_json m;
  m["cruiseSpeed"] = round_to(d.speed_m_s, 3);
  m["firmwareType"] = firmware == Firmware::ardupilot ? 3 : 12;
  m["globalPlanAltitudeMode"] = qgc_altitude_mode(plan);
  m["hoverSpeed"] = round_to(d.speed_m_s, 3);
  m["items"] = items;
  m["plannedHomePosition"] = {home.lat_deg, home.lon_deg,
                              round_to(flight.mission->home_amsl_m, 3)};  // AMSL
  m["vehicleType"] = plan.request.vehicle == Vehicle::multirotor ? 2 : 1;
  m["version"] = 2;
  ordered_json root;
  root["fileType"] = "Plan";
  root["geoFence"] = geofence_json(plan);
  root["groundStation"] = "swath";
  root["mission"] = m;
  // The rally point is the drone's own home (DESIGN.md §14 "Fences").
  root["rallyPoints"] = {{"points", {{home.lat_deg, home.lon_deg, 0}}}, {"version", 2}};
  root["version"] = 1;
  return base::json_text(root, 4) + "\n";
}

}  // namespace swath::planning
