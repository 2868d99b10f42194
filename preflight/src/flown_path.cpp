#include "swath/preflight/flown_path.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/mavlink/commands.hpp"

namespace swath::preflight {
namespace {

using mavlink::Cmd;
using missions::AltitudeFrame;
using missions::Item;

// A flight of more items flown (DO_JUMPs unrolled) or more legs (LOITER_TURNS' sides) is refused:
// one that long is not one to check leg by leg (and its path would take gigabytes).
constexpr std::size_t kMaxFlownItems = 100000;
constexpr std::size_t kMaxLegs = 1000000;
// LOITER_TURNS' circle is flown on tangents, one per this angle, radians (5 degrees: their
// corners lie 0.1 % of the radius outside it, 6 cm at 60 m).
constexpr double kCircleStepRad = std::numbers::pi / 36;

constexpr int cmd(Cmd c) {
  return static_cast<int>(c);
}

// Names of commands verify refuses, for the message (MAVLink's MAV_CMD names).
const char* command_name(int command) {
  static const std::pair<int, const char*> names[] = {{17, "NAV_LOITER_UNLIM"},
                                                      {30, "NAV_CONTINUE_AND_CHANGE_ALT"},
                                                      {31, "NAV_LOITER_TO_ALT"},
                                                      {82, "NAV_SPLINE_WAYPOINT"},
                                                      {84, "NAV_VTOL_TAKEOFF"},
                                                      {85, "NAV_VTOL_LAND"},
                                                      {92, "NAV_GUIDED_ENABLE"},
                                                      {94, "NAV_PAYLOAD_PLACE"},
                                                      {113, "CONDITION_CHANGE_ALT"},
                                                      {114, "CONDITION_DISTANCE"},
                                                      {176, "DO_SET_MODE"},
                                                      {177, "DO_JUMP"},
                                                      {179, "DO_SET_HOME"},
                                                      {181, "DO_SET_RELAY"},
                                                      {183, "DO_SET_SERVO"},
                                                      {192, "DO_REPOSITION"},
                                                      {214, "DO_SET_CAM_TRIGG_INTERVAL"},
                                                      {3000, "DO_VTOL_TRANSITION"}};
  for (const auto& [number, name] : names)
    if (number == command) return name;
  return "unknown";
}

// Commands that move nothing the checks look at: camera, gimbal, region of interest, yaw, and
// DO_LAND_START (a marker an autopilot's RTL may jump to, passed over in the mission's course).
bool moves_nothing(int command) {
  switch (static_cast<Cmd>(command)) {
    case Cmd::condition_yaw:
    case Cmd::do_land_start:
    case Cmd::do_set_roi_location:
    case Cmd::do_set_roi_none:
    case Cmd::do_set_roi:
    case Cmd::do_digicam_configure:
    case Cmd::do_digicam_control:
    case Cmd::do_mount_configure:
    case Cmd::do_mount_control:
    case Cmd::do_gimbal_manager_pitchyaw:
    case Cmd::do_gimbal_manager_configure:
      return true;
    default:
      return false;
  }
}

[[noreturn]] void refuse(const Item& item) {
  throw base::InputError(item.place + ": command " + std::to_string(item.command) + " (" +
                         command_name(item.command) +
                         ") is not modelled by swath verify; its flight cannot be checked");
}

// ArduCopter's LOITER_TURNS as AP_Mission stores it: whole turns, at least 1 (param1), and the
// radius in whole metres, above 255 m in tens of metres (|param3|; its sign the direction).
int loiter_turns(const Item& item) {
  const double turns = item.params[0];
  return std::isfinite(turns) ? static_cast<int>(std::clamp(std::floor(turns), 1.0, 255.0)) : 1;
}

double loiter_radius_m(const Item& item) {
  const double r = std::isfinite(item.params[2]) ? std::floor(std::abs(item.params[2])) : 0.0;
  return r <= 255 ? r : std::min(255.0, std::floor(r / 10)) * 10;
}

double horizontal_m(const Leg& leg) {
  return geometry::distance(leg.from.xy(), leg.to.xy());
}

// Time over `length_m` at cruise speed v with a trapezoidal profile: a stop at either end costs
// v / (2 a) (the distance v^2 / (2 a) flown at half speed); a leg too short to reach v is flown
// accelerating then braking.
double horizontal_time_s(double length_m, double v, double a, bool stop_start, bool stop_end) {
  const int stops = int{stop_start} + int{stop_end};
  if (length_m <= 0 || v <= 0) return 0.0;
  if (length_m >= stops * v * v / (2 * a)) return length_m / v + stops * v / (2 * a);
  return stops == 2 ? 2 * std::sqrt(length_m / a) : std::sqrt(2 * length_m / a);
}

// The fastest the vehicle can fly at the end of a leg of `length_m` commanded at `speed_m_s`, m/s,
// having begun it at up to `start_m_s` (0 from rest): a speed cut (DO_CHANGE_SPEED) slows it by
// braking at no more than `a`, v^2 = start^2 - 2 a length, never below the speed commanded (and
// a speed raised is taken as reached at once: the bound stays safe). ArduCopter SITL came 2 to
// 7 cm inside a zone's clearance at stops whose slow approach began a few decimetres before them.
double speed_at_end_m_s(double start_m_s, double speed_m_s, double length_m, double a) {
  const double braked_sq = start_m_s * start_m_s - 2 * a * length_m;
  return std::max(speed_m_s, std::sqrt(std::max(braked_sq, 0.0)));
}

double turn_deg(const Leg& in, const Leg& out) {
  const geometry::Point2 a = in.to.xy() - in.from.xy(), b = out.to.xy() - out.from.xy();
  return std::abs(std::atan2(geometry::cross(a, b), geometry::dot(a, b))) * 180 / std::numbers::pi;
}

class PathBuilder {
 public:
  PathBuilder(const missions::Mission& m, const geometry::LocalFrame& frame,
              const FlightModel& model, const geometry::Ground* ground)
      : mission_(m), frame_(frame), model_(model), heights_(m, ground) {
    path_.source = m.source;
    const geometry::Point2 h = frame.to_local(m.home);
    path_.home = at_ = {h.x, h.y, 0.0};
    speed_ = m.cruise_speed_m_s > 0 ? m.cruise_speed_m_s : model.speed_m_s;
    climb_m_s_ = model.climb_m_s;
    descent_m_s_ = model.descent_m_s;
  }

  FlownPath build() {
    const std::vector<Item>& items = mission_.items;
    std::vector<int> jumps_done(items.size(), 0);
    std::size_t flown = 0;
    for (std::size_t i = 0; i < items.size() && !ended_; ++flown) {
      if (flown == kMaxFlownItems || path_.legs.size() > kMaxLegs)
        throw base::InputError(items[i].place + ": flying the file to here takes more than " +
                               std::to_string(kMaxFlownItems) + " items or " +
                               std::to_string(kMaxLegs) +
                               " legs (its DO_JUMPs, LOITER_TURNS); its flight cannot be checked");
      if (items[i].command == cmd(Cmd::do_jump)) {
        i = after_jump(i, jumps_done);
        continue;
      }
      add(items[i]);
      ++i;
    }
    if (!ended_) return_to_launch("return to launch after " + mission_.source + "'s last item");
    time_legs();
    return std::move(path_);
  }

 private:
  // Where an item flies to; (0, 0) means "where the vehicle is" (take-off, land).
  geometry::Point2 target_xy(const Item& item) const {
    if (item.position.lat_deg == 0 && item.position.lon_deg == 0) return at_.xy();
    return frame_.to_local(item.position);
  }

  // The item flown after the DO_JUMP at `i`: its target while it has repeats left (ArduPilot
  // counts them over the whole flight, never resetting them), else the next item. param1 is the
  // target's sequence number: home is 0, the file's first item 1.
  std::size_t after_jump(std::size_t i, std::vector<int>& jumps_done) const {
    const Item& jump = mission_.items[i];
    const double target = jump.params[0], repeats = jump.params[1];
    const std::size_t n = mission_.items.size();
    if (!(target >= 1 && target <= static_cast<double>(n) && target == std::floor(target)))
      throw base::InputError(jump.place + ": DO_JUMP (177) goes to item " +
                             base::shortest_text(target) + ", which the file does not have (1 to " +
                             std::to_string(n) + ")");
    if (!(repeats >= 0))
      throw base::InputError(jump.place + ": DO_JUMP (177) repeats " +
                             base::shortest_text(repeats) +
                             " times (-1: forever); a flight that never ends cannot be checked");
    if (jumps_done[i] >= static_cast<int>(std::floor(repeats))) return i + 1;
    ++jumps_done[i];
    return static_cast<std::size_t>(target) - 1;
  }

  void leg(Point3 to, LegKind kind, const std::string& place, double hold_s = 0.0) {
    if (kind != LegKind::hold &&
        std::abs(to.x - at_.x) + std::abs(to.y - at_.y) + std::abs(to.z_m - at_.z_m) < 1e-6)
      return;
    Leg l;
    l.from = at_;
    l.to = to;
    l.kind = kind;
    l.place = place;
    l.speed_m_s = speed_;
    l.climb_m_s = climb_m_s_;
    l.descent_m_s = descent_m_s_;
    l.trigger_distance_m = trigger_distance_m_;
    l.trigger_interval_s = trigger_interval_s_;
    l.trigger_started = trigger_started_;
    l.photo_at_start = photo_at_start_;
    trigger_started_ = photo_at_start_ = false;
    path_.legs.push_back(l);
    holds_s_.push_back(hold_s);
    at_ = to;
  }

  void take_off_to(double z_m, const std::string& place) {
    leg({at_.x, at_.y, z_m}, LegKind::climb, place);
    airborne_ = true;
  }

  void add(const Item& item) {
    switch (static_cast<Cmd>(item.command)) {
      case Cmd::do_change_speed:
        change_speed(item);
        break;
      case Cmd::do_set_cam_trigg_dist:
        trigger_distance_m_ = std::max(0.0, item.params[0]);
        trigger_started_ = trigger_distance_m_ > 0;
        photo_at_start_ = trigger_started_ && item.params[2] > 0;
        break;
      case Cmd::image_start_capture:
        if (item.params[1] > 0) {
          trigger_interval_s_ = item.params[1];
          trigger_started_ = photo_at_start_ = true;
        }
        break;
      case Cmd::image_stop_capture:
        trigger_interval_s_ = 0.0;
        break;
      case Cmd::nav_takeoff:
        take_off_to(heights_.above_home_m(item), item.place);
        fly_to(item);
        break;
      case Cmd::nav_waypoint:
      case Cmd::nav_loiter_time:
        if (!airborne_) take_off_to(heights_.above_home_m(item), item.place);
        fly_to(item);
        if (item.params[0] > 0) leg(at_, LegKind::hold, item.place, item.params[0]);
        break;
      case Cmd::nav_loiter_turns:
        if (!airborne_) take_off_to(heights_.above_home_m(item), item.place);
        circle(item);
        break;
      case Cmd::nav_delay:
      case Cmd::condition_delay:
        if (item.params[0] > 0) leg(at_, LegKind::hold, item.place, item.params[0]);
        break;
      case Cmd::nav_land: {
        const geometry::Point2 p = target_xy(item);
        leg({p.x, p.y, at_.z_m}, LegKind::cruise, item.place);
        leg({p.x, p.y, 0.0}, LegKind::descent, item.place);
        ended_ = true;
        break;
      }
      case Cmd::nav_return_to_launch:
        return_to_launch(item.place);
        break;
      default:
        if (!moves_nothing(item.command)) refuse(item);
        break;
    }
  }

  // ArduCopter's ModeAuto::do_change_speed: param1 0 (airspeed) and 1 (ground speed) set the
  // horizontal speed, 2 the climb and 3 the descent speed; other types, and speeds not above 0,
  // change nothing. A type left empty (NaN) is read as horizontal.
  void change_speed(const Item& item) {
    const double type = item.params[0], v = item.params[1];
    if (!(v > 0)) return;
    if (type == 0 || type == 1 || std::isnan(type))
      speed_ = v;
    else if (type == 2)
      climb_m_s_ = v;
    else if (type == 3)
      descent_m_s_ = v;
  }

  // LOITER_TURNS: to the circle's edge nearest the vehicle (along its course when it is at the
  // centre), then round it its whole turns (positive radius clockwise) on sides tangent to the
  // circle, their corners outside it: the path contains the circle, so a zone it misses the
  // circle misses too.
  void circle(const Item& item) {
    const double radius_m = loiter_radius_m(item);
    if (radius_m <= 0)
      throw base::InputError(item.place +
                             ": LOITER_TURNS (18) with radius 0 flies the autopilot's "
                             "CIRCLE_RADIUS, which swath verify does not know; give param3");
    const geometry::Point2 c = target_xy(item);
    const double z = heights_.above_home_m(item);
    geometry::Point2 out = at_.xy() - c;
    if (std::hypot(out.x, out.y) < 1e-6) out = course();
    double angle = std::atan2(out.y, out.x);
    leg({c.x + radius_m * std::cos(angle), c.y + radius_m * std::sin(angle), z}, LegKind::cruise,
        item.place);
    const double sweep = loiter_turns(item) * 2 * std::numbers::pi;
    const int sides = static_cast<int>(std::ceil(sweep / kCircleStepRad - 1e-9));
    const double step = (item.params[2] < 0 ? 1.0 : -1.0) * sweep / sides;  // clockwise: -
    const double corner_m = radius_m / std::cos(step / 2);
    for (int k = 0; k < sides; ++k) {
      const double mid = angle + step / 2;
      leg({c.x + corner_m * std::cos(mid), c.y + corner_m * std::sin(mid), z}, LegKind::cruise,
          item.place);
      angle += step;
      leg({c.x + radius_m * std::cos(angle), c.y + radius_m * std::sin(angle), z}, LegKind::cruise,
          item.place);
    }
  }

  // The direction the vehicle last moved in horizontally (north before it has).
  geometry::Point2 course() const {
    for (auto l = path_.legs.rbegin(); l != path_.legs.rend(); ++l) {
      const geometry::Point2 d = l->to.xy() - l->from.xy();
      if (std::hypot(d.x, d.y) > 1e-6) return d;
    }
    return {0.0, 1.0};
  }

  void fly_to(const Item& item) {
    const geometry::Point2 p = target_xy(item);
    leg({p.x, p.y, heights_.above_home_m(item)}, LegKind::cruise, item.place);
  }

  // Where RTL flies from here: ArduPilot's AP_Rally::calc_best_rally_or_home_location with its
  // defaults, the nearest rally point if it lies within RALLY_LIMIT_KM (ArduCopter 0.3 km,
  // ArduPlane 5 km), home instead where home is nearer and RALLY_INCL_HOME is set (ArduCopter 1,
  // ArduPlane 0). Other autopilots' files are flown home.
  geometry::Point2 return_point_xy() const {
    const geometry::Point2 home = path_.home.xy();
    if (mission_.autopilot != missions::Autopilot::ardupilot || mission_.rally_points.empty())
      return home;
    const double limit_m = mission_.fixed_wing ? 5000.0 : 300.0;
    const bool include_home = !mission_.fixed_wing;
    const auto distance_m = [&](geometry::Point2 p) {
      return std::hypot(p.x - at_.x, p.y - at_.y);
    };
    std::optional<geometry::Point2> nearest;
    for (const geometry::GeoPoint& r : mission_.rally_points) {
      const geometry::Point2 p = frame_.to_local(r);
      if (!nearest || distance_m(p) < distance_m(*nearest)) nearest = p;
    }
    if (distance_m(*nearest) > limit_m) return home;
    if (include_home && distance_m(home) < distance_m(*nearest)) return home;
    return *nearest;
  }

  // The height RTL climbs to: PX4's RTL_RETURN_ALT default, 60 m (navigator/rtl_params.c; its
  // cone, RTL_CONE_ANG, lowers it near home: the highest it climbs), else the model's RTL_ALT.
  double rtl_altitude_m() const {
    constexpr double kPx4ReturnAlt_m = 60.0;
    return mission_.autopilot == missions::Autopilot::px4 ? kPx4ReturnAlt_m : model_.rtl_altitude_m;
  }

  void return_to_launch(const std::string& place) {
    const double z = std::max(at_.z_m, mission_.return_altitude_m.value_or(rtl_altitude_m()));
    const geometry::Point2 to = return_point_xy();
    leg({at_.x, at_.y, z}, LegKind::rtl, place);
    leg({to.x, to.y, z}, LegKind::rtl, place);
    leg({to.x, to.y, 0.0}, LegKind::descent, place);
    ended_ = true;
  }

  bool stops_after(std::size_t i) const {
    const Leg& l = path_.legs[i];
    if (i + 1 == path_.legs.size()) return true;
    const Leg& next = path_.legs[i + 1];
    if (next.kind == LegKind::hold || horizontal_m(next) < 1e-6) return true;
    return turn_deg(l, next) > model_.sharp_turn_deg;
  }

  void time_legs() {
    const double a = model_.deceleration_m_s2;
    double t = 0.0;
    bool stopped = true;
    double reach_m_s = 0.0;     // the fastest the vehicle can be at the end of the leg before
    double since_stop_m = 0.0;  // flown since the last stop, to the end of this leg
    for (std::size_t i = 0; i < path_.legs.size(); ++i) {
      Leg& l = path_.legs[i];
      const double h = horizontal_m(l), dz = l.to.z_m - l.from.z_m;
      l.stops_at_end = h > 0 && stops_after(i);
      const double th = horizontal_time_s(h, l.speed_m_s, a, stopped, l.stops_at_end);
      const double tv = dz > 0 ? dz / l.climb_m_s : -dz / l.descent_m_s;
      l.t_start_s = t;
      t += l.kind == LegKind::hold ? holds_s_[i] : std::max(th, tv);
      l.t_end_s = t;
      // Accelerating from the last stop at no more than a, it reaches at most sqrt(2 a s) over s.
      since_stop_m = (stopped ? 0.0 : since_stop_m) + h;
      reach_m_s = std::min(speed_at_end_m_s(stopped ? 0.0 : reach_m_s, l.speed_m_s, h, a),
                           std::sqrt(2 * a * since_stop_m));
      stopped = h <= 0 || l.stops_at_end;
      if (l.stops_at_end && !mission_.fixed_wing) {
        const double run_m = missions::stopping_distance_m(reach_m_s, a);
        const geometry::Point2 d = (l.to.xy() - l.from.xy()) * (run_m / h);
        path_.overruns.push_back({l.to, {l.to.x + d.x, l.to.y + d.y, l.to.z_m}, l.place});
      }
    }
    path_.duration_s = t;
  }

  const missions::Mission& mission_;
  const geometry::LocalFrame& frame_;
  FlightModel model_;
  HeightConverter heights_;
  FlownPath path_;
  std::vector<double> holds_s_;
  Point3 at_;
  double speed_ = 0.0, climb_m_s_ = 0.0, descent_m_s_ = 0.0;
  double trigger_distance_m_ = 0.0, trigger_interval_s_ = 0.0;
  bool airborne_ = false, ended_ = false;
  bool trigger_started_ = false, photo_at_start_ = false;  // for the next leg (Leg)
};

}  // namespace

HeightConverter::HeightConverter(const missions::Mission& mission, const geometry::Ground* ground)
    : mission_(mission),
      ground_(ground),
      home_amsl_m_(mission.home_amsl_m),
      home_amsl_known_(mission.home_amsl_known) {
  // With a DEM an AMSL altitude is measured against the DEM's ground, home's included: a file's
  // home altitude is often 0 or off by the autopilot's GPS, and the clearances are the DEM's.
  if (ground_ != nullptr) {
    const double h = ground_->heights_m({mission.home}).at(0);
    if (std::isfinite(h)) {
      home_amsl_m_ = h;
      home_amsl_known_ = true;
    }
  }
}

double HeightConverter::ground_above_home_m(const geometry::GeoPoint& p) const {
  if (ground_ == nullptr) return 0.0;
  const auto h = ground_->heights_m({p, mission_.home});
  return std::isfinite(h[0]) && std::isfinite(h[1]) ? h[0] - h[1] : 0.0;
}

double HeightConverter::above_home_m(const Item& item) const {
  return missions::above_home_m(
      item, home_amsl_known_ ? std::optional<double>(home_amsl_m_) : std::nullopt,
      item.altitude_frame == AltitudeFrame::terrain ? ground_above_home_m(item.position) : 0.0);
}

FlownPath fly(const missions::Mission& mission, const geometry::LocalFrame& frame,
              const FlightModel& model, const geometry::Ground* ground) {
  return PathBuilder(mission, frame, model, ground).build();
}

bool modelled_command(int command) {
  switch (static_cast<Cmd>(command)) {
    case Cmd::nav_waypoint:
    case Cmd::nav_loiter_turns:
    case Cmd::nav_loiter_time:
    case Cmd::nav_return_to_launch:
    case Cmd::nav_land:
    case Cmd::nav_takeoff:
    case Cmd::nav_delay:
    case Cmd::condition_delay:
    case Cmd::do_jump:
    case Cmd::do_change_speed:
    case Cmd::do_set_cam_trigg_dist:
    case Cmd::image_start_capture:
    case Cmd::image_stop_capture:
      return true;
    default:
      return moves_nothing(command);
  }
}

Point3 position_at(const FlownPath& path, double t_s) {
  if (path.legs.empty() || t_s <= path.legs.front().t_start_s) return path.home;
  if (t_s >= path.legs.back().t_end_s) return path.legs.back().to;
  const auto it = std::upper_bound(path.legs.begin(), path.legs.end(), t_s,
                                   [](double t, const Leg& l) { return t < l.t_end_s; });
  const Leg& l = *it;
  const double span = l.t_end_s - l.t_start_s;
  const double f = span > 0 ? (t_s - l.t_start_s) / span : 1.0;
  return {l.from.x + f * (l.to.x - l.from.x), l.from.y + f * (l.to.y - l.from.y),
          l.from.z_m + f * (l.to.z_m - l.from.z_m)};
}

}  // namespace swath::preflight
