// mission.kml: the area, the no-fly zones, each drone's path, the homes.
#include "common.hpp"

namespace swath::planning {
namespace {

// A drone's path in the altitude mode that matches its frame. Without terrain the heights are
// above the take-off point, which KML cannot say: relativeToGround draws them above the ground
// under each point, exact over flat ground (the description says so). With terrain the
// waypoints' heights above sea level are known: absolute; the terrain frame is relativeToGround.
std::string path_geometry(const SurveyPlan& plan, const DronePlan& d) {
  std::string mode = "relativeToGround", coordinates;
  std::string about =
      "heights above the take-off point, drawn above the ground under each point; plan with "
      "--terrain DEM for heights above sea level";
  if (!plan.terrain) {
    std::vector<geometry::GeoPoint> path;
    for (const geometry::Point2& p : files::map_path(d)) path.push_back(files::geo(plan, p));
    coordinates = files::kml_coordinates(path, files::map_altitude_m(plan, d), false);
  } else {
    const bool agl = plan.terrain->frame == AltitudeFrame::terrain;
    mode = agl ? "relativeToGround" : "absolute";
    about = agl ? "heights above the ground (terrain frame)" : "heights above mean sea level";
    for (const DroneMission* flight : files::drone_flights(d))
      for (const MissionItem& item : flight->items) {
        if (!positional(item.kind)) continue;
        const geometry::GeoPoint g = files::geo(plan, item.position);
        const double h =
            agl ? plan.terrain->height_above_ground_m + d.layer_m : item.altitude_amsl_m;
        if (!coordinates.empty()) coordinates += ' ';
        coordinates += files::kml_coordinates({g}, h, false);
      }
  }
  std::string out = "    <description>";
  out += about;
  out += "</description>\n    <LineString>\n      <altitudeMode>";
  out += mode;
  out += "</altitudeMode>\n      <coordinates>";
  out += coordinates;
  out += "</coordinates>\n    </LineString>\n";
  return out;
}

}  // namespace

std::string mission_kml(const SurveyPlan& plan) {
  const geometry::Polygon& area = plan.request.field.polygon;
  const auto& rings = plan.request.field.geo_rings;
  std::string s =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<kml "
      "xmlns=\"http://www.opengis.net/kml/2.2\">\n<Document>\n";
  s += "  <name>swath survey of " + files::xml_escape(plan.request.field.source) + "</name>\n";
  s += "  <Placemark>\n    <name>Area</name>\n    <Polygon>\n      "
       "<outerBoundaryIs><LinearRing><coordinates>" +
       files::kml_coordinates(rings.at(0), 0.0, true) +
       "</coordinates></LinearRing></outerBoundaryIs>\n";
  for (std::size_t h = 1; h < geometry::ring_count(area); ++h)
    s += "      <innerBoundaryIs><LinearRing><coordinates>" +
         files::kml_coordinates(rings.at(h), 0.0, true) +
         "</coordinates></LinearRing></innerBoundaryIs>\n";
  s += "    </Polygon>\n  </Placemark>\n";
  for (std::size_t k = 0; k < plan.no_fly_geo.size(); ++k)
    s += "  <Placemark>\n    <name>No-fly zone " + std::to_string(k + 1) +
         "</name>\n    <Polygon>\n      <outerBoundaryIs><LinearRing><coordinates>" +
         files::kml_coordinates(plan.no_fly_geo[k], 0.0, true) +
         "</coordinates></LinearRing></outerBoundaryIs>\n    </Polygon>\n  </Placemark>\n";
  for (const DronePlan& d : plan.drones) {
    s += "  <Placemark>\n    <name>Drone " + std::to_string(d.number) +
         (d.name == "drone-" + std::to_string(d.number) ? "" : " " + files::xml_escape(d.name)) +
         " path</name>\n" + path_geometry(plan, d) + "  </Placemark>\n";
  }
  s += "  <Placemark>\n    <name>Home</name>\n    <Point><coordinates>" +
       files::kml_coordinates({plan.home}, 0.0, false) + "</coordinates></Point>\n  </Placemark>\n";
  for (const DronePlan& d : plan.drones)
    if (!(files::rounded(d.home_geo) == files::rounded(plan.home)))
      s += "  <Placemark>\n    <name>Home of " + files::xml_escape(d.name) +
           "</name>\n    <Point><coordinates>" + files::kml_coordinates({d.home_geo}, 0.0, false) +
           "</coordinates></Point>\n  </Placemark>\n";
  return s + "</Document>\n</kml>\n";
}

}  // namespace swath::planning
