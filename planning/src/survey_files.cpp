#include "swath/planning/survey_files.hpp"

#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/utf8.hpp"
#include "swath/planning/plan_features.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

namespace swath::planning {

using base::round_to;

using base::fixed_text;
namespace {

using geometry::GeoPoint;
using geometry::Point2;
using nlohmann::ordered_json;

GeoPoint geo(const SurveyPlan& plan, Point2 p) {
  return plan.request.field.frame->to_geo(p);
}

int mav_command(ItemKind kind) {
  switch (kind) {
    case ItemKind::takeoff:
      return 22;  // MAV_CMD_NAV_TAKEOFF
    case ItemKind::waypoint:
      return 16;  // MAV_CMD_NAV_WAYPOINT
    case ItemKind::trigger_start:
    case ItemKind::trigger_stop:
      return 206;  // MAV_CMD_DO_SET_CAM_TRIGG_DIST
    case ItemKind::return_to_launch:
      return 20;  // MAV_CMD_NAV_RETURN_TO_LAUNCH
  }
  return 0;
}

bool positional(ItemKind kind) {
  return kind == ItemKind::takeoff || kind == ItemKind::waypoint;
}

const char* action_name(ItemKind kind) {
  switch (kind) {
    case ItemKind::takeoff:
      return "takeoff";
    case ItemKind::waypoint:
      return "waypoint";
    case ItemKind::trigger_start:
      return "trigger_start";
    case ItemKind::trigger_stop:
      return "trigger_stop";
    case ItemKind::return_to_launch:
      return "return_to_launch";
  }
  return "";
}

// The seven MAVLink params of an item; NaN where QGC writes null (yaw: keep heading).
std::array<double, 7> params(const SurveyPlan& plan, const MissionItem& item) {
  const double nan = std::nan("");
  if (positional(item.kind)) {
    const GeoPoint g = geo(plan, item.position);
    return {
        0, 0, 0, nan, round_to(g.lat_deg, 9), round_to(g.lon_deg, 9), round_to(item.altitude_m, 3)};
  }
  if (item.kind == ItemKind::trigger_start)
    return {round_to(item.trigger_distance_m, 3), 0, 1, 0, 0, 0, 0};
  return {0, 0, 0, 0, 0, 0, 0};
}

constexpr int kFrameMission = 2;      // MAV_FRAME_MISSION: no position
constexpr int kFrameRelativeAlt = 3;  // MAV_FRAME_GLOBAL_RELATIVE_ALT

// Markup escaped, and bytes that are not UTF-8 replaced (XML allows no others).
std::string xml_escape(const std::string& text) {
  const std::string s = base::valid_utf8(text);
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string kml_coordinates(const std::vector<GeoPoint>& points, double altitude_m, bool close) {
  std::string s;
  auto add = [&](const GeoPoint& g) {
    s += fixed_text(g.lon_deg, 9);
    s += ',';
    s += fixed_text(g.lat_deg, 9);
    s += ',';
    s += fixed_text(altitude_m, 3);
    s += ' ';
  };
  for (const GeoPoint& g : points) add(g);
  if (close && !points.empty()) add(points.front());
  if (!s.empty()) s.pop_back();
  return s;
}

std::vector<GeoPoint> geo_points(const SurveyPlan& plan, const std::vector<Point2>& points) {
  std::vector<GeoPoint> out;
  out.reserve(points.size());
  for (const Point2& p : points) out.push_back(geo(plan, p));
  return out;
}

// The area's ring r in WGS84: the file's own positions.
const std::vector<GeoPoint>& area_ring(const SurveyPlan& plan, std::size_t r) {
  return plan.request.field.geo_rings.at(r);
}

const char* to_string(LinePlacement p) {
  return p == LinePlacement::centered ? "centered" : "paper";
}
const char* to_string(AngleSearch a) {
  return a == AngleSearch::exact ? "exact" : a == AngleSearch::scan ? "scan" : "fixed";
}

ordered_json optional_number(const std::optional<double>& v, int decimals) {
  return v ? ordered_json(round_to(*v, decimals)) : ordered_json();
}

}  // namespace

std::string qgc_plan(const SurveyPlan& plan, const DroneMission& mission) {
  ordered_json items = ordered_json::array();
  int jump_id = 1;
  for (const MissionItem& item : mission.items) {
    ordered_json j;
    const bool has_position = positional(item.kind);
    if (has_position) {
      j["AMSLAltAboveTerrain"] = nullptr;
      j["Altitude"] = round_to(item.altitude_m, 3);
      j["AltitudeMode"] = 1;  // relative to home
    }
    j["autoContinue"] = true;
    j["command"] = mav_command(item.kind);
    j["doJumpId"] = jump_id++;
    j["frame"] = has_position ? kFrameRelativeAlt : kFrameMission;
    ordered_json p = ordered_json::array();
    for (double v : params(plan, item))
      p.push_back(std::isnan(v) ? ordered_json() : ordered_json(v));
    j["params"] = p;
    j["type"] = "SimpleItem";
    items.push_back(j);
  }
  const bool multirotor = plan.request.vehicle == Vehicle::multirotor;
  ordered_json m;
  m["cruiseSpeed"] = round_to(plan.speed_m_s, 3);
  m["firmwareType"] = plan.request.firmware == Firmware::ardupilot ? 3 : 12;
  m["globalPlanAltitudeMode"] = 1;
  m["hoverSpeed"] = round_to(plan.speed_m_s, 3);
  m["items"] = items;
  m["plannedHomePosition"] = {round_to(plan.home.lat_deg, 9), round_to(plan.home.lon_deg, 9), 0};
  m["vehicleType"] = multirotor ? 2 : 1;
  m["version"] = 2;
  ordered_json root;
  root["fileType"] = "Plan";
  root["geoFence"] = {
      {"circles", ordered_json::array()}, {"polygons", ordered_json::array()}, {"version", 2}};
  root["groundStation"] = "swath";
  root["mission"] = m;
  root["rallyPoints"] = {{"points", ordered_json::array()}, {"version", 2}};
  root["version"] = 1;
  return base::json_text(root, 4) + "\n";
}

std::string wpl_110(const SurveyPlan& plan, const DroneMission& mission) {
  std::string out = "QGC WPL 110\n";
  auto row = [&](std::size_t index, int current, int frame, int command,
                 const std::array<double, 7>& p) {
    out += std::to_string(index) + "\t" + std::to_string(current) + "\t" + std::to_string(frame) +
           "\t" + std::to_string(command);
    for (int k = 0; k < 7; ++k) {
      const double v =
          std::isnan(p[static_cast<std::size_t>(k)]) ? 0.0 : p[static_cast<std::size_t>(k)];
      out += '\t';
      out += fixed_text(v, k == 4 || k == 5 ? 9 : 6);
    }
    out += "\t1\n";
  };
  row(0, 1, 0, 16, {0, 0, 0, 0, round_to(plan.home.lat_deg, 9), round_to(plan.home.lon_deg, 9), 0});
  std::size_t index = 1;
  for (const MissionItem& item : mission.items)
    row(index++, 0, positional(item.kind) ? kFrameRelativeAlt : kFrameMission,
        mav_command(item.kind), params(plan, item));
  return out;
}

std::string waypoints_csv(const SurveyPlan& plan) {
  std::string out = "drone,seq,lat,lon,alt_m,x_m,y_m,action\n";
  for (const DroneMission* m : missions_of(plan)) {
    const std::string drone = std::to_string(m->drone);
    auto row = [&](std::size_t seq, const MissionItem* item, Point2 p, double alt,
                   const char* action) {
      out += drone + "," + std::to_string(seq) + ",";
      if (item == nullptr || positional(item->kind)) {
        const GeoPoint g = geo(plan, p);
        out += fixed_text(g.lat_deg, 9) + "," + fixed_text(g.lon_deg, 9) + "," +
               fixed_text(alt, 3) + "," + fixed_text(p.x, 3) + "," + fixed_text(p.y, 3);
      } else {
        out += ",,,,";
      }
      out += std::string(",") + action + "\n";
    };
    row(0, nullptr, m->home, 0.0, "home");
    std::size_t seq = 1;
    for (const MissionItem& item : m->items)
      row(seq++, &item, item.position, item.altitude_m, action_name(item.kind));
  }
  return out;
}

std::string mission_geojson(const SurveyPlan& plan) {
  return mission_geojson(plan_features(plan));
}

std::string mission_kml(const SurveyPlan& plan) {
  const geometry::Polygon& area = plan.request.field.polygon;
  std::string s =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<kml "
      "xmlns=\"http://www.opengis.net/kml/2.2\">\n<Document>\n";
  s += "  <name>swath survey of " + xml_escape(plan.request.field.source) + "</name>\n";
  s += "  <Placemark>\n    <name>Area</name>\n    <Polygon>\n      "
       "<outerBoundaryIs><LinearRing><coordinates>" +
       kml_coordinates(area_ring(plan, 0), 0.0, true) +
       "</coordinates></LinearRing></outerBoundaryIs>\n";
  for (std::size_t h = 1; h < geometry::ring_count(area); ++h)
    s += "      <innerBoundaryIs><LinearRing><coordinates>" +
         kml_coordinates(area_ring(plan, h), 0.0, true) +
         "</coordinates></LinearRing></innerBoundaryIs>\n";
  s += "    </Polygon>\n  </Placemark>\n";
  for (const DroneMission* m : missions_of(plan)) {
    s += "  <Placemark>\n    <name>Drone " + std::to_string(m->drone) +
         " path</name>\n    <LineString>\n" +
         "      <altitudeMode>relativeToGround</altitudeMode>\n      <coordinates>" +
         kml_coordinates(geo_points(plan, m->path), plan.imaging.altitude_m, false) +
         "</coordinates>\n    </LineString>\n  </Placemark>\n";
  }
  s += "  <Placemark>\n    <name>Home</name>\n    <Point><coordinates>" +
       kml_coordinates({plan.home}, 0.0, false) +
       "</coordinates></Point>\n  </Placemark>\n</Document>\n</kml>\n";
  return s;
}

std::string summary_json(const SurveyPlan& plan, const std::vector<std::string>& files) {
  const geometry::AreaFacts& f = plan.facts;
  const SurveyRequest& r = plan.request;
  ordered_json j;
  j["swath_version"] = "0.1.0";
  j["field"] = r.field.source;
  j["area"] = {{"type", std::string(geometry::to_string(f.classification.type))},
               {"vertices", f.vertex_count},
               {"holes", r.field.polygon.holes.size()},
               {"area_m2", optional_number(f.area_m2, 3)},
               {"regularity",
                f.regularity ? ordered_json(round_to(f.regularity->overall, 6)) : ordered_json()},
               {"concave_mode", r.concave == ConcaveMode::split  ? "split"
                                : r.concave == ConcaveMode::hull ? "hull"
                                                                 : "reject"},
               {"handling", plan.handling},
               {"no_fly_zones", r.exclusions.size()},
               {"repaired_pieces", plan.extra_pieces.empty() && !r.repair
                                       ? ordered_json()
                                       : ordered_json(1 + plan.extra_pieces.size())},
               {"cells", plan.cells.size()},
               {"flown_area_m2", round_to(geometry::area(plan.flown_area), 3)}};
  j["sweep"] = {{"bearing_deg", round_to(geometry::line_bearing_deg(plan.sweep.angle_deg), 6)},
                {"angle_local_deg", round_to(plan.sweep.angle_deg, 6)},
                {"angle_search", plan.handling == "split" && r.angle_search != AngleSearch::fixed
                                     ? "shortest-path"
                                     : to_string(r.angle_search)},
                {"directions_evaluated", plan.direction_candidates},
                {"height_m", round_to(plan.sweep.height_m, 4)},
                {"line_placement", to_string(r.placement)},
                {"lines", plan.sweep.lines.size()},
                {"turnaround_m", round_to(r.turnaround_m, 3)}};
  const Imaging& im = plan.imaging;
  j["camera"] = {
      {"name", r.camera.name},
      {"mode", std::holds_alternative<PhotogrammetryMode>(r.mode) ? "photogrammetry" : "detection"},
      {"orientation", r.orientation == ImageOrientation::landscape ? "landscape" : "portrait"},
      {"altitude_m", round_to(im.altitude_m, 4)},
      {"gsd_cm_per_px", round_to(im.gsd_m * 100, 5)},
      {"footprint_across_m", round_to(im.footprint_across_m, 4)},
      {"footprint_along_m", round_to(im.footprint_along_m, 4)},
      {"line_spacing_m", round_to(im.line_spacing_m, 4)},
      {"trigger_distance_m", round_to(im.trigger_distance_m, 4)},
      {"h_min_m", optional_number(im.h_min_m, 4)},
      {"h_max_m", optional_number(im.h_max_m, 4)}};
  ordered_json drones = ordered_json::array();
  for (const DroneMission* m : missions_of(plan)) {
    const std::size_t i = static_cast<std::size_t>(m->drone - 1);
    const bool divided = !plan.drone_work.empty();
    ordered_json d = {
        {"drone", m->drone},
        {"name", divided ? plan.drone_names[i] : "drone-1"},
        {"share", divided ? round_to(plan.drone_work[i].share, 6) : 1.0},
        {"speed_m_s", round_to(divided ? plan.drone_speeds_m_s[i] : plan.speed_m_s, 3)},
        {"path_length_m", round_to(m->path_length_m, 3)},
        {"work_length_m", round_to(m->work_length_m, 3)},
        {"transit_length_m", round_to(m->transit_length_m, 3)},
        {"flight_time_s", round_to(m->flight_time_s, 2)},
        {"lines", m->lines.size()},
        {"turns", m->lines.empty() ? 0 : m->lines.size() - 1},
        {"waypoints", m->waypoint_count},
        {"region_area_m2", nullptr},
        {"home_cost_m", nullptr},
        {"budget_m", nullptr}};
    if (divided) {
      const DroneWork& w = plan.drone_work[i];
      if (!w.region.empty()) {
        double a = 0;
        for (const geometry::Ring& piece : w.region) a += geometry::signed_area(piece);
        d["region_area_m2"] = round_to(a, 3);
      }
      d["home_cost_m"] = round_to(w.home_cost_m, 3);
      d["budget_m"] = optional_number(w.budget_m, 3);
    }
    drones.push_back(d);
  }
  j["drones"] = drones;
  if (!plan.drone_work.empty()) {
    double longest = 0, shortest = std::numeric_limits<double>::infinity();
    for (const DroneMission* m : missions_of(plan)) {
      longest = std::max(longest, m->flight_time_s);
      if (!m->lines.empty()) shortest = std::min(shortest, m->flight_time_s);
    }
    const DivisionResult& dv = plan.division;
    j["division"] = {
        {"mode", r.division == DivisionMode::path ? "path" : "region"},
        {"balance", r.balance == Balance::makespan ? "makespan" : "capability"},
        {"makespan_s", round_to(longest, 2)},
        {"max_over_min_flight_time", shortest > 0 && std::isfinite(shortest)
                                         ? ordered_json(round_to(longest / shortest, 4))
                                         : ordered_json()},
        {"estimated_makespan_s", round_to(dv.makespan_s, 2)},
        {"proportional_estimated_makespan_s", round_to(dv.proportional_makespan_s, 2)},
        {"shorter_than_proportional_percent",
         ordered_json(dv.proportional_makespan_s > 0
                          ? round_to(100 * (1 - dv.makespan_s / dv.proportional_makespan_s), 3)
                          : 0.0)},
        {"unflown_path_m", round_to(dv.unflown_path_m, 3)}};
  }
  j["home"] = {{"lat_deg", round_to(plan.home.lat_deg, 9)},
               {"lon_deg", round_to(plan.home.lon_deg, 9)}};
  const CoverageMeasure& c = plan.coverage;
  j["coverage"] = {
      {"covered_fraction", round_to(c.covered_fraction, 6)},
      {"outside_fraction", round_to(c.outside_fraction, 6)},
      {"uncovered_area_m2", round_to(c.area_m2 - c.covered_area_m2, 3)},
      {"swath_area_m2", round_to(c.swath_area_m2, 3)},
      {"line_length_m", round_to(c.line_length_m, 3)},
      {"line_length_outside_m", round_to(c.line_length_outside_m, 3)},
      {"transit_outside_m", round_to(plan.transit_outside_m, 3)},
      {"line_outside_fraction",
       round_to(c.line_length_m > 0 ? c.line_length_outside_m / c.line_length_m : 0.0, 6)}};
  j["warnings"] = plan.warnings;
  if (!files.empty()) j["files"] = files;
  return base::json_text(j, 2) + "\n";
}

std::vector<std::pair<std::string, std::string>> survey_files(const SurveyPlan& plan) {
  std::vector<std::pair<std::string, std::string>> files{{"mission.geojson", mission_geojson(plan)},
                                                         {"summary.json", summary_json(plan)}};
  for (const DroneMission* m : missions_of(plan)) {
    const std::string drone = "drone-" + std::to_string(m->drone);
    files.push_back({drone + ".plan", qgc_plan(plan, *m)});
    files.push_back({drone + ".waypoints", wpl_110(plan, *m)});
  }
  files.push_back({"waypoints.csv", waypoints_csv(plan)});
  files.push_back({"mission.kml", mission_kml(plan)});
  return files;
}

}  // namespace swath::planning
