// DJI WPML KMZ writer (docs/swath-plan.md), beside its reader (dji_kmz.cpp): wpmz/template.kml and
// wpmz/waylines.wpml as DJI Pilot 2 reads them (DJI Cloud API, "DJI WPML": Template.kml,
// Waylines.wpml, Common Elements): a waypoint template whose points are the flight's waypoints,
// heights relative to the take-off point, the drone's speed, the nose along the course, the gimbal
// pitch set at the first point, photos by distance or time from each line's start to its end, and
// go-home (or land) at the end.
#include <algorithm>
#include <cmath>
#include <functional>

#include "swath/base/number_text.hpp"
#include "swath/missions/writers.hpp"
#include "zip_archive.hpp"

namespace swath::missions {
namespace {

using base::fixed_text;

// WPML's limits: globalTransitionalSpeed [0, 15] m/s, takeOffSecurityHeight up to 1500 m (swath
// plan --dji refuses a survey above it: nothing here cuts it short); 2 m at least.
constexpr double kMaxTransitionalSpeed_m_s = kDjiMaxSpeed_m_s;
constexpr double kMinSecurityHeight_m = 2.0, kMaxSecurityHeight_m = kDjiMaxHeight_m;

// What both files describe.
struct Wayline {
  const std::vector<ExportPoint>& points;
  const DjiSettings& settings;
};

std::string element(const std::string& indent, const std::string& name, const std::string& value) {
  return indent + "<wpml:" + name + ">" + value + "</wpml:" + name + ">\n";
}

std::string number(double v, int decimals = 3) {
  return base::shortest_text(base::round_to(v, decimals));
}

std::string mission_config(const Wayline& w) {
  const std::string in = "    ";
  const auto& dji = w.settings.enums;
  std::string s = "    <wpml:missionConfig>\n";
  s += element(in + "  ", "flyToWaylineMode", "safely");
  s += element(in + "  ", "finishAction", w.settings.land ? "autoLand" : "goHome");
  // A lost remote-controller link ends the survey and brings the drone home rather than letting
  // it fly on out of the pilot's control.
  s += element(in + "  ", "exitOnRCLost", "executeLostAction");
  s += element(in + "  ", "executeRCLostAction", "goBack");
  s += element(
      in + "  ", "takeOffSecurityHeight",
      number(std::clamp(w.settings.altitude_m, kMinSecurityHeight_m, kMaxSecurityHeight_m)));
  s += element(in + "  ", "globalTransitionalSpeed",
               number(std::min(w.settings.speed_m_s, kMaxTransitionalSpeed_m_s)));
  s += element(in + "  ", "globalRTHHeight", number(w.settings.altitude_m));
  if (dji) {
    s += in + "  <wpml:droneInfo>\n";
    s += element(in + "    ", "droneEnumValue", std::to_string(dji->drone));
    s += element(in + "    ", "droneSubEnumValue", std::to_string(dji->drone_sub));
    s += in + "  </wpml:droneInfo>\n";
    s += in + "  <wpml:payloadInfo>\n";
    s += element(in + "    ", "payloadEnumValue", std::to_string(dji->payload));
    s += element(in + "    ", "payloadSubEnumValue", "0");
    s += element(in + "    ", "payloadPositionIndex", "0");
    s += in + "  </wpml:payloadInfo>\n";
  }
  return s + "    </wpml:missionConfig>\n";
}

// The nose follows the course (followWayline); the angle, the leg's bearing in WPML's signed
// degrees, says which way that is (DJI reads it only in the heading modes that use it).
std::string heading_param(const std::string& in, double heading_deg, const char* name) {
  const double signed_deg = std::remainder(heading_deg, 360.0);
  std::string s = in + "<wpml:" + name + ">\n";
  s += element(in + "  ", "waypointHeadingMode", "followWayline");
  s += element(in + "  ", "waypointHeadingAngle", std::to_string(std::lround(signed_deg)));
  s += element(in + "  ", "waypointPoiPoint", "0.000000,0.000000,0.000000");
  s += element(in + "  ", "waypointHeadingAngleEnable", "0");
  s += element(in + "  ", "waypointHeadingPathMode", "followBadArc");
  return s + in + "</wpml:" + name + ">\n";
}

std::string action(const std::string& in, int id, const char* func, const std::string& params) {
  return in + "<wpml:action>\n" + element(in + "  ", "actionId", std::to_string(id)) +
         element(in + "  ", "actionActuatorFunc", func) + in +
         "  <wpml:actionActuatorFuncParam>\n" + params + in +
         "  </wpml:actionActuatorFuncParam>\n" + in + "</wpml:action>\n";
}

std::string group(const std::string& in, int id, std::size_t start, std::size_t end,
                  const std::string& trigger, const std::string& trigger_param,
                  const std::string& actions) {
  std::string s = in + "<wpml:actionGroup>\n";
  s += element(in + "  ", "actionGroupId", std::to_string(id));
  s += element(in + "  ", "actionGroupStartIndex", std::to_string(start));
  s += element(in + "  ", "actionGroupEndIndex", std::to_string(end));
  s += element(in + "  ", "actionGroupMode", "sequence");
  s += in + "  <wpml:actionTrigger>\n" + element(in + "    ", "actionTriggerType", trigger);
  if (!trigger_param.empty()) s += element(in + "    ", "actionTriggerParam", trigger_param);
  s += in + "  </wpml:actionTrigger>\n" + actions;
  return s + in + "</wpml:actionGroup>\n";
}

std::string take_photo(const std::string& in, int id) {
  const std::string p = in + "    ";
  return action(in, id, "takePhoto",
                element(p, "fileSuffix", "") + element(p, "payloadPositionIndex", "0") +
                    element(p, "useGlobalPayloadLensIndex", "1"));
}

std::string gimbal_rotate(const std::string& in, int id, double pitch_deg) {
  const std::string p = in + "    ";
  return action(
      in, id, "gimbalRotate",
      element(p, "gimbalHeadingYawBase", "north") +
          element(p, "gimbalRotateMode", "absoluteAngle") +
          element(p, "gimbalPitchRotateEnable", "1") +
          element(p, "gimbalPitchRotateAngle", number(pitch_deg)) +
          element(p, "gimbalRollRotateEnable", "0") + element(p, "gimbalRollRotateAngle", "0") +
          element(p, "gimbalYawRotateEnable", "0") + element(p, "gimbalYawRotateAngle", "0") +
          element(p, "gimbalRotateTimeEnable", "0") + element(p, "gimbalRotateTime", "0") +
          element(p, "payloadPositionIndex", "0"));
}

std::string hover(const std::string& in, int id, double hold_s) {
  return action(in, id, "hover", element(in + "    ", "hoverTime", number(hold_s)));
}

// The action groups declared at point i: the gimbal at the first point; at a point that holds or
// shoots (hover), a hover and a photo on arrival; at the start of each run of photo legs, photos
// every trigger distance (multipleDistance) or interval (multipleTiming) to the run's end.
std::string action_groups(const Wayline& w, std::size_t i, int& next_group) {
  const std::string in = "        ";
  const ExportPoint& p = w.points[i];
  std::string s;
  if (i == 0)
    s += group(in, next_group++, 0, 0, "reachPoint", "",
               gimbal_rotate(in + "  ", 0, w.settings.gimbal_pitch_deg));
  if (p.hold_s > 0 || p.shot) {
    std::string actions;
    int id = 0;
    if (p.hold_s > 0) actions += hover(in + "  ", id++, p.hold_s);
    if (p.shot) actions += take_photo(in + "  ", id++);
    s += group(in, next_group++, i, i, "reachPoint", "", actions);
  }
  if (p.photo_leg && (i == 0 || !w.points[i - 1].photo_leg)) {
    std::size_t end = i;
    while (end + 1 < w.points.size() && w.points[end].photo_leg) ++end;
    const bool timed = w.settings.trigger == TriggerMode::time;
    s += group(in, next_group++, i, end, timed ? "multipleTiming" : "multipleDistance",
               number(w.settings.trigger_value), take_photo(in + "  ", 0));
  }
  return s;
}

std::string coordinates(const ExportPoint& p) {
  return fixed_text(p.geo.lon_deg, 9) + "," + fixed_text(p.geo.lat_deg, 9);
}

// The Placemarks of both files: the point and its index, `body`'s elements, the action groups.
std::string placemarks(
    const Wayline& w,
    const std::function<std::string(const ExportPoint&, const std::string&)>& body) {
  std::string s;
  int next_group = 0;
  const std::string in = "        ";
  for (std::size_t i = 0; i < w.points.size(); ++i) {
    const ExportPoint& p = w.points[i];
    s += "      <Placemark>\n" + in + "<Point>\n" + in + "  <coordinates>" + coordinates(p) +
         "</coordinates>\n" + in + "</Point>\n";
    s += element(in, "index", std::to_string(i));
    s += body(p, in);
    s += action_groups(w, i, next_group);
    s += "      </Placemark>\n";
  }
  return s;
}

std::string document_start(const std::string& author_lines) {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
         "<kml xmlns=\"http://www.opengis.net/kml/2.2\" "
         "xmlns:wpml=\"http://www.dji.com/wpmz/1.0.2\">\n  <Document>\n" +
         author_lines;
}

// A waypoint's speed: its leg's to the next waypoint (DJI's waypointSpeed), the point's own where
// the mission slows to a stop beside a no-fly zone, else the flight's.
double leg_speed_m_s(const ExportPoint& p, const DjiSettings& s) {
  return p.speed_m_s > 0 ? p.speed_m_s : s.speed_m_s;
}

}  // namespace

std::string write_dji_waylines_wpml(const std::vector<ExportPoint>& points,
                                    const DjiSettings& settings) {
  const Wayline w{points, settings};
  std::string s = document_start("") + mission_config(w);
  s += "    <Folder>\n";
  s += element("      ", "templateId", "0");
  s += element("      ", "executeHeightMode", "relativeToStartPoint");
  s += element("      ", "waylineId", "0");
  s += element("      ", "autoFlightSpeed", number(w.settings.speed_m_s));
  s += placemarks(w, [&](const ExportPoint& p, const std::string& in) {
    std::string b = element(in, "executeHeight", number(p.altitude_m));
    b += element(in, "waypointSpeed", number(leg_speed_m_s(p, w.settings)));
    b += heading_param(in, p.heading_deg, "waypointHeadingParam");
    // Straight legs, a stop at every point: the lines are flown as planned and photographed by
    // distance along them; no corner is cut into a no-fly zone's clearance.
    b += in + "<wpml:waypointTurnParam>\n" +
         element(in + "  ", "waypointTurnMode", "toPointAndStopWithDiscontinuityCurvature") +
         element(in + "  ", "waypointTurnDampingDist", "0") + in + "</wpml:waypointTurnParam>\n";
    return b + element(in, "useStraightLine", "1");
  });
  return s + "    </Folder>\n  </Document>\n</kml>\n";
}

std::string write_dji_template_kml(const std::vector<ExportPoint>& points,
                                   const DjiSettings& settings) {
  const Wayline w{points, settings};
  std::string s = document_start("    <wpml:author>swath</wpml:author>\n") + mission_config(w);
  s += "    <Folder>\n";
  s += element("      ", "templateType", "waypoint");
  s += element("      ", "templateId", "0");
  s += "      <wpml:waylineCoordinateSysParam>\n" + element("        ", "coordinateMode", "WGS84") +
       element("        ", "heightMode", "relativeToStartPoint") +
       element("        ", "positioningType", "GPS") + "      </wpml:waylineCoordinateSysParam>\n";
  s += element("      ", "autoFlightSpeed", number(w.settings.speed_m_s));
  s += element("      ", "globalHeight", number(w.settings.altitude_m));
  s += element("      ", "gimbalPitchMode", "usePointSetting");
  s += heading_param("      ", 0.0, "globalWaypointHeadingParam");
  s += element("      ", "globalWaypointTurnMode", "toPointAndStopWithDiscontinuityCurvature");
  s += placemarks(w, [&](const ExportPoint& p, const std::string& in) {
    const bool global_height =
        base::round_to(p.altitude_m, 3) == base::round_to(w.settings.altitude_m, 3);
    std::string b = element(in, "useGlobalHeight", global_height ? "1" : "0");
    if (!global_height)  // relative heights: Pilot 2 recomputes the ellipsoid height at take-off
      b += element(in, "ellipsoidHeight", number(p.altitude_m)) +
           element(in, "height", number(p.altitude_m));
    b += element(in, "useGlobalSpeed", "0");
    b += element(in, "waypointSpeed", number(leg_speed_m_s(p, w.settings)));
    b += element(in, "useGlobalHeadingParam", "0");
    b += heading_param(in, p.heading_deg, "waypointHeadingParam");
    b += element(in, "useGlobalTurnParam", "1");
    return b + element(in, "gimbalPitchAngle", number(settings.gimbal_pitch_deg));
  });
  return s + "    </Folder>\n  </Document>\n</kml>\n";
}

std::string write_dji_kmz(const std::vector<ExportPoint>& points, const DjiSettings& settings) {
  return zip_archive({{"wpmz/template.kml", write_dji_template_kml(points, settings)},
                      {"wpmz/waylines.wpml", write_dji_waylines_wpml(points, settings)}});
}

}  // namespace swath::missions
