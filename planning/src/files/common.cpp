#include "common.hpp"

#include <GeographicLib/Geodesic.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "swath/base/number_text.hpp"
#include "swath/base/utf8.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/mavlink/commands.hpp"

namespace swath::planning::files {

using base::fixed_text;
using base::round_to;
using mavlink::Cmd;

namespace {

Cmd mav_cmd(const MissionItem& item, Firmware firmware) {
  switch (item.kind) {
    case ItemKind::takeoff:
      return Cmd::nav_takeoff;
    case ItemKind::waypoint:
      return Cmd::nav_waypoint;
    case ItemKind::change_speed:
      return Cmd::do_change_speed;
    case ItemKind::gimbal_pitch:
      // DO_MOUNT_CONTROL for ArduPilot; PX4 takes the gimbal manager's command.
      return firmware == Firmware::ardupilot ? Cmd::do_mount_control
                                             : Cmd::do_gimbal_manager_pitchyaw;
    case ItemKind::trigger_start:
      return item.trigger == TriggerMode::time ? Cmd::image_start_capture
                                               : Cmd::do_set_cam_trigg_dist;
    case ItemKind::trigger_stop:
      return item.trigger == TriggerMode::time ? Cmd::image_stop_capture
                                               : Cmd::do_set_cam_trigg_dist;
    case ItemKind::camera_shot:
      return item.command == CameraCommand::digicam ? Cmd::do_digicam_control
                                                    : Cmd::image_start_capture;
    case ItemKind::land_start:
      return Cmd::do_land_start;
    case ItemKind::land:
      return Cmd::nav_land;
    case ItemKind::return_to_launch:
      return Cmd::nav_return_to_launch;
  }
  return Cmd{};
}

}  // namespace

geometry::GeoPoint rounded(const geometry::GeoPoint& g) {
  return {round_to(g.lat_deg, 9), round_to(g.lon_deg, 9), 0.0};
}

namespace {

// The positions geo() found for one plan's points, by their coordinates' bits.
struct PointBits {
  std::uint64_t x, y;
  bool operator==(const PointBits&) const = default;
};
struct PointBitsHash {
  std::size_t operator()(const PointBits& k) const {
    return std::hash<std::uint64_t>()(k.x * 0x9e3779b97f4a7c15ULL ^ k.y);
  }
};
struct Memo {
  const SurveyPlan* plan = nullptr;
  std::unordered_map<PointBits, geometry::GeoPoint, PointBitsHash> positions;
};
thread_local Memo* t_memo = nullptr;

geometry::GeoPoint converted(const SurveyPlan& plan, geometry::Point2 p) {
  return rounded(plan.request.field.frame->to_geo(p));
}

}  // namespace

GeoMemo::GeoMemo(const SurveyPlan& plan) {
  if (t_memo != nullptr) return;
  t_memo = new Memo{&plan, {}};
  owner_ = true;
}

GeoMemo::~GeoMemo() {
  if (!owner_) return;
  delete t_memo;
  t_memo = nullptr;
}

geometry::GeoPoint geo_unshared(const SurveyPlan& plan, geometry::Point2 p) {
  return converted(plan, p);
}

geometry::GeoPoint geo(const SurveyPlan& plan, geometry::Point2 p) {
  if (t_memo == nullptr || t_memo->plan != &plan) return converted(plan, p);
  const PointBits key{std::bit_cast<std::uint64_t>(p.x), std::bit_cast<std::uint64_t>(p.y)};
  const auto [it, added] = t_memo->positions.try_emplace(key);
  if (added) it->second = converted(plan, p);
  return it->second;
}

int mav_command(const MissionItem& item, Firmware firmware) {
  return static_cast<int>(mav_cmd(item, firmware));
}

AltitudeFrame altitude_frame(const SurveyPlan& plan) {
  return plan.terrain ? plan.terrain->frame : AltitudeFrame::relative;
}

int mav_frame(const SurveyPlan& plan, const MissionItem& item) {
  if (item.kind == ItemKind::land_start) return kFrameRelativeAlt;
  if (!positional(item.kind)) return kFrameMission;
  switch (altitude_frame(plan)) {
    case AltitudeFrame::relative:
      return kFrameRelativeAlt;
    case AltitudeFrame::amsl:
      return kFrameGlobal;
    case AltitudeFrame::terrain:
      return kFrameTerrainAlt;
  }
  return kFrameRelativeAlt;
}

double mav_altitude_m(const SurveyPlan& plan, const MissionItem& item) {
  switch (altitude_frame(plan)) {
    case AltitudeFrame::relative:
      return round_to(item.altitude_m, 3);
    case AltitudeFrame::amsl:
      return round_to(item.altitude_amsl_m, 3);
    case AltitudeFrame::terrain:
      return round_to(plan.terrain->height_above_ground_m, 3);
  }
  return round_to(item.altitude_m, 3);
}

std::array<double, 7> mav_params(const SurveyPlan& plan, const MissionItem& item) {
  const double nan = std::nan("");
  const bool fixed_wing = plan.request.vehicle == Vehicle::fixedwing;
  auto at = [&](double p1) {
    const geometry::GeoPoint g = geo(plan, item.position);
    return std::array<double, 7>{p1, 0, 0, nan, g.lat_deg, g.lon_deg, mav_altitude_m(plan, item)};
  };
  switch (item.kind) {
    case ItemKind::takeoff:
      return at(0);
    case ItemKind::waypoint:
      return at(round_to(item.value, 3));  // param1: hold, seconds
    case ItemKind::land:
      return at(0);
    case ItemKind::land_start: {
      const geometry::GeoPoint g = geo(plan, item.position);
      return {0, 0, 0, 0, g.lat_deg, g.lon_deg, 0};
    }
    case ItemKind::change_speed:
      // param1: 1 ground speed (multirotor), 0 airspeed (fixed-wing); param3 -1: throttle kept.
      return {fixed_wing ? 0.0 : 1.0, round_to(item.value, 3), -1, 0, 0, 0, 0};
    case ItemKind::gimbal_pitch:
      if (plan.request.firmware == Firmware::ardupilot)  // pitch, roll, yaw; mode 2: MAVLink
        return {round_to(item.value, 3), 0, 0, 0, 0, 0, 2};
      return {round_to(item.value, 3), nan, nan, nan, 0, 0, 0};  // pitch, yaw kept, rates kept
    case ItemKind::trigger_start:
      if (item.trigger == TriggerMode::time) return {0, round_to(item.value, 3), 0, 0, 0, 0, 0};
      return {round_to(item.value, 3), 0, 1, 0, 0, 0, 0};  // param3 1: one photo at once
    case ItemKind::trigger_stop:
      return {0, 0, 0, 0, 0, 0, 0};
    case ItemKind::camera_shot:
      if (item.command == CameraCommand::digicam) return {0, 0, 0, 0, 1, 0, 0};  // param5: shoot
      return {0, 0, 1, 0, 0, 0, 0};                                              // one image
    case ItemKind::return_to_launch:
      return {0, 0, 0, 0, 0, 0, 0};
  }
  return {0, 0, 0, 0, 0, 0, 0};
}

namespace {

missions::AltitudeFrame item_altitude_frame(const SurveyPlan& plan, const MissionItem& item) {
  if (!positional(item.kind)) return missions::AltitudeFrame::none;
  switch (altitude_frame(plan)) {
    case AltitudeFrame::relative:
      return missions::AltitudeFrame::relative;
    case AltitudeFrame::amsl:
      return missions::AltitudeFrame::amsl;
    case AltitudeFrame::terrain:
      return missions::AltitudeFrame::terrain;
  }
  return missions::AltitudeFrame::relative;
}

void add_fences(const SurveyPlan& plan, missions::Mission& m) {
  for (const geometry::Ring& ring : plan.fence) {
    std::vector<geometry::GeoPoint> geo_ring;
    for (const geometry::Point2& p : ring) geo_ring.push_back(geo(plan, p));
    m.inclusion_fences.push_back(std::move(geo_ring));
  }
  for (const auto& zone : plan.exclusion_fences_geo) {
    std::vector<geometry::GeoPoint> geo_ring;
    for (const geometry::GeoPoint& g : zone) geo_ring.push_back(rounded(g));
    m.exclusion_fences.push_back(std::move(geo_ring));
  }
}

}  // namespace

missions::Mission mission_file(const SurveyPlan& plan, const Flight& flight) {
  const DronePlan& d = *flight.drone;
  missions::Mission m;
  m.source = flight.file_stem;
  m.home = rounded(d.home_geo);
  m.home_amsl_m = round_to(flight.mission->home_amsl_m, 3);
  m.home_amsl_known = true;
  m.cruise_speed_m_s = round_to(d.speed_m_s, 3);
  m.fixed_wing = plan.request.vehicle != Vehicle::multirotor;
  for (const MissionItem& item : flight.mission->items) {
    const std::array<double, 7> p = mav_params(plan, item);
    missions::Item written;
    written.command = mav_command(item, plan.request.firmware);
    written.frame = mav_frame(plan, item);
    written.altitude_frame = item_altitude_frame(plan, item);
    written.params = {p[0], p[1], p[2], p[3]};
    written.position = {p[4], p[5], 0.0};
    written.altitude_m = p[6];
    m.items.push_back(written);
  }
  add_fences(plan, m);
  m.rally_points.push_back(m.home);  // the drone's own home (docs/swath-plan.md)
  return m;
}

missions::Mission fence_file(const SurveyPlan& plan) {
  missions::Mission m;
  m.home = rounded(plan.home);
  add_fences(plan, m);
  return m;
}

missions::QgcPlanSettings qgc_settings(const SurveyPlan& plan) {
  missions::QgcPlanSettings s;
  s.firmware_type = plan.request.firmware == Firmware::ardupilot ? 3 : 12;
  // QGroundControl's AltMode: 1 relative, 2 absolute (AMSL), 4 terrain frame (3 is its own
  // "calculated above terrain", which it turns into AMSL altitudes itself).
  switch (altitude_frame(plan)) {
    case AltitudeFrame::relative:
      s.altitude_mode = 1;
      break;
    case AltitudeFrame::amsl:
      s.altitude_mode = 2;
      break;
    case AltitudeFrame::terrain:
      s.altitude_mode = 4;
      break;
  }
  return s;
}

const char* action_name(ItemKind kind) {
  switch (kind) {
    case ItemKind::takeoff:
      return "takeoff";
    case ItemKind::waypoint:
      return "waypoint";
    case ItemKind::change_speed:
      return "change_speed";
    case ItemKind::gimbal_pitch:
      return "gimbal_pitch";
    case ItemKind::trigger_start:
      return "trigger_start";
    case ItemKind::trigger_stop:
      return "trigger_stop";
    case ItemKind::camera_shot:
      return "camera_shot";
    case ItemKind::land_start:
      return "land_start";
    case ItemKind::land:
      return "land";
    case ItemKind::return_to_launch:
      return "return_to_launch";
  }
  return "";
}

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

std::vector<const DroneMission*> drone_flights(const DronePlan& drone) {
  std::vector<const DroneMission*> out;
  for (const Sortie& s : drone.sorties) out.push_back(&s.mission);
  if (out.empty()) out.push_back(&drone.mission);
  return out;
}

std::vector<geometry::Point2> map_path(const DronePlan& drone) {
  std::vector<geometry::Point2> out;
  for (const DroneMission* m : drone_flights(drone)) {
    // Home once between two sorties: the one lands where the next takes off.
    const bool lands_there = !out.empty() && !m->path.empty() && out.back() == m->path.front();
    out.insert(out.end(), m->path.begin() + (lands_there ? 1 : 0), m->path.end());
  }
  return out;
}

double map_altitude_m(const SurveyPlan& plan, const DronePlan& drone) {
  return plan.imaging.altitude_m + drone.layer_m;
}

std::string kml_coordinates(const std::vector<geometry::GeoPoint>& points, double altitude_m,
                            bool close) {
  std::string s;
  const std::string altitude = fixed_text(altitude_m, 3);
  auto add = [&](const geometry::GeoPoint& g) {
    base::append_fixed_text(s, g.lon_deg, 9);
    s += ',';
    base::append_fixed_text(s, g.lat_deg, 9);
    s += ',';
    s += altitude;
    s += ' ';
  };
  for (const geometry::GeoPoint& g : points) add(g);
  if (close && !points.empty()) add(points.front());
  if (!s.empty()) s.pop_back();
  return s;
}

double bearing_deg(const geometry::GeoPoint& a, const geometry::GeoPoint& b, bool at_end) {
  double azi1 = 0, azi2 = 0;
  GeographicLib::Geodesic::WGS84().Inverse(a.lat_deg, a.lon_deg, b.lat_deg, b.lon_deg, azi1, azi2);
  const double azi = at_end ? azi2 : azi1;
  return azi < 0 ? azi + 360.0 : azi;
}

namespace {

// The legs' headings: each point faces along the leg it starts, the last along the leg it ends;
// a point where the flight does not move (a leg shorter than a millimetre) keeps the heading
// before it.
void set_headings(std::vector<ExportPoint>& points) {
  constexpr double kSamePoint_m = 1e-3;
  double previous = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const bool last = i + 1 == points.size();
    const ExportPoint& a = last ? (i > 0 ? points[i - 1] : points[i]) : points[i];
    const ExportPoint& b = last ? points[i] : points[i + 1];
    if (geometry::geodesic_distance_m(a.geo, b.geo) >= kSamePoint_m)
      previous = bearing_deg(a.geo, b.geo, last);
    points[i].heading_deg = previous;
  }
}

// DJI and Litchi fly out to their first waypoint at its leg's speed (the check reads them so:
// missions/src/mission.cpp, dji_kmz.cpp). Where the flight's first leg is slowed (its approach to
// a stop beside a zone begins there), that would fly the whole way out from home slowly, minutes
// longer than the .plan and into the next drone's launch: such a flight first rises above home to
// the .plan's take-off altitude, as the .plan does, and flies out from there at the flight's
// speed.
void start_at_take_off(const SurveyPlan& plan, const Flight& flight,
                       std::vector<ExportPoint>& points, std::vector<geometry::Point2>& local) {
  const std::vector<MissionItem>& items = flight.mission->items;
  if (points.empty() || items.empty() || items.front().kind != ItemKind::takeoff) return;
  const double cruise_m_s = flight.drone->speed_m_s;
  if (!(points.front().speed_m_s > 0) || points.front().speed_m_s == cruise_m_s) return;
  const MissionItem& take_off = items.front();
  points.insert(points.begin(), ExportPoint{geo(plan, take_off.position), take_off.altitude_m, 0.0,
                                            false, 0.0, false, cruise_m_s});
  local.insert(local.begin(), take_off.position);
}

}  // namespace

std::vector<ExportPoint> export_points(const SurveyPlan& plan, const Flight& flight,
                                       std::vector<geometry::Point2>* local) {
  std::vector<ExportPoint> points;
  std::vector<geometry::Point2> own_local;
  if (local == nullptr) local = &own_local;
  bool camera_on = false;
  double speed_m_s = 0.0;  // in force: a change after a waypoint sets the leg that follows it
  const auto add = [&](const MissionItem& item, double altitude_m, double hold_s) {
    if (!points.empty()) points.back().photo_leg = camera_on;
    points.push_back({geo(plan, item.position), altitude_m, 0.0, false, hold_s, false, speed_m_s});
    local->push_back(item.position);
  };
  local->clear();
  for (const MissionItem& item : flight.mission->items) {
    switch (item.kind) {
      case ItemKind::waypoint:
        add(item, item.altitude_m, item.value);
        break;
      case ItemKind::land:  // the home at the altitude flown, where the app's landing lands
        if (!points.empty()) add(item, points.back().altitude_m, 0.0);
        break;
      case ItemKind::change_speed:
        speed_m_s = item.value;
        if (!points.empty()) points.back().speed_m_s = speed_m_s;
        break;
      case ItemKind::trigger_start:
        camera_on = true;
        break;
      case ItemKind::trigger_stop:
        camera_on = false;
        break;
      case ItemKind::camera_shot:
        if (!points.empty()) points.back().shot = true;
        break;
      default:
        break;
    }
  }
  start_at_take_off(plan, flight, points, *local);
  fit_dji_spacing(plan, flight.drone->speed_m_s, points, *local);
  set_headings(points);
  return points;
}

double trigger_value(const Flight& flight) {
  for (const MissionItem& item : flight.mission->items)
    if (item.kind == ItemKind::trigger_start) return item.value;
  return 0.0;
}

}  // namespace swath::planning::files
