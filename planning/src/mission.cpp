#include "swath/planning/mission.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "swath/base/number_text.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/vehicle/kinematics.hpp"

namespace swath::planning {

double turn_deg(geometry::Point2 a, geometry::Point2 b, geometry::Point2 c) {
  const geometry::Point2 u = b - a, v = c - b;
  const double nu = std::hypot(u.x, u.y), nv = std::hypot(v.x, v.y);
  if (nu == 0 || nv == 0) return 0;
  const double cosine = std::clamp(geometry::dot(u, v) / (nu * nv), -1.0, 1.0);
  return std::acos(cosine) * 180 / 3.14159265358979323846;  // π
}

namespace {

using geometry::Point2;

// How much longer braking from v to `slow` at a takes than flying its (v² - slow²) / (2 a) at v,
// seconds: (v - slow) / a - (v² - slow²) / (2 a v) = (v - slow)² / (2 a v).
double braking_s(double v, double slow, double a) {
  return (v - slow) * (v - slow) / (2 * a * v);
}

// Builds the items and the path of one mission step by step.
// Approaches to stops beside the zones (MissionBuilder::slow_approaches): the least distance
// before the stop the slow speed is set and how far past it the cruise speed is set again, metres
// (the slowest speed set is MissionSettings::slowest_approach_m_s).
constexpr double kSlowApproach_m = 0.5;
// How far a stop with less free run than the overrun at kSlowestApproach_m_s (8 mm at 2.5 m/s²)
// is moved back along its incoming leg at most, metres (MissionBuilder::slow_approaches); a
// slower least approach speed (--dji: 1 m/s, 20 cm) adds its longer overrun to it.
constexpr double kMostNudge_m = 0.02;
constexpr double kMergeWithin_m = 0.05;
// Braking room kept beyond what braking to the slow speed takes, metres: the files' rounding and
// the 2 cm a stop before may still be moved (MissionBuilder::nudged).
constexpr double kBrakeMargin_m = 0.05;

class MissionBuilder {
 public:
  MissionBuilder(int drone, Point2 home, const MissionSettings& s) : s_(s) {
    m_.drone = drone;
    m_.home = home;
    m_.items.push_back({ItemKind::takeoff, home, s.altitude_m});
    m_.path.push_back(home);
    holds_.push_back(0);
    // The drone's own speed right after take-off: without it ArduCopter flies WPNAV_SPEED
    // (10 m/s), not the speed the trigger distance and the flight time were planned for.
    m_.items.push_back({ItemKind::change_speed, {}, 0.0, s.speed_m_s});
    m_.items.push_back({ItemKind::gimbal_pitch, {}, 0.0, s.triggering.gimbal_pitch_deg});
  }

  Point2 at() const { return m_.path.back(); }

  void waypoint(Point2 p, double hold_s = 0) {
    // Beside zones, a waypoint within kMergeWithin_m of the last one is that one (its hold the
    // longer): the leg between them, written in rounded degrees, would point anywhere, and the
    // overrun past a stop runs along the leg into it.
    if (s_.free_run_m && m_.path.size() > 1 && geometry::distance(p, at()) < kMergeWithin_m) {
      for (auto it = m_.items.rbegin(); it != m_.items.rend(); ++it)
        if (it->kind == ItemKind::waypoint) {
          it->value = std::max(it->value, hold_s);
          break;
        }
      holds_.back() = std::max(holds_.back(), hold_s);
      return;
    }
    through_to(p);
    m_.items.push_back({ItemKind::waypoint, p, s_.altitude_m, hold_s});
    m_.path.push_back(p);
    holds_.push_back(hold_s);
  }

  // Waypoints flown through on the way from here to `p` where the straight leg would stray
  // (MissionSettings::bow_m): it bows as the square of its length, so n equal legs stray 1/n^2
  // of it.
  // Past that, as many as keep each leg's track out of the zones' clearance band
  // (MissionSettings::pieces_kept_clear).
  void through_to(Point2 p) {
    if (m_.path.empty()) return;
    const Point2 from = at();
    int n = 1;
    if (s_.bow_m) {
      const double bow = s_.bow_m(from, p);
      if (bow > kMaxBow_m)
        n = static_cast<int>(std::min(1000.0, std::ceil(std::sqrt(bow / kSplitBow_m))));
    }
    if (s_.pieces_kept_clear) n = std::max(n, s_.pieces_kept_clear(from, p, n));
    for (int k = 1; k < n; ++k) {
      const Point2 q = from + (p - from) * (static_cast<double>(k) / n);
      m_.items.push_back({ItemKind::waypoint, q, s_.altitude_m, 0.0});
      m_.path.push_back(q);
      holds_.push_back(0);
    }
  }

  void route_to(Point2 target, const LegRoute& route) {
    if (route)
      for (const Point2& p : route(at(), target)) waypoint(p);
  }

  void camera(bool on) {
    if (on == camera_on_ || s_.triggering.mode == TriggerMode::hover) return;
    camera_on_ = on;
    const double value = s_.triggering.mode == TriggerMode::distance
                             ? s_.trigger_distance_m
                             : s_.trigger_distance_m / s_.speed_m_s;
    m_.items.push_back({on ? ItemKind::trigger_start : ItemKind::trigger_stop,
                        {},
                        0.0,
                        on ? value : 0.0,
                        s_.triggering.mode});
  }

  // Hover mode: the line from here to `end` flown photo point by photo point, a held waypoint
  // and a shot at each.
  void hover_line(Point2 end) {
    const std::vector<Point2> shots = photo_positions(at(), end, s_.trigger_distance_m);
    for (std::size_t k = 0; k < shots.size(); ++k) {
      if (k == 0) {  // the line's start, already a waypoint: hold there too
        holds_.back() = s_.triggering.hover_hold_s;
        m_.items.back().value = s_.triggering.hover_hold_s;
      } else {
        waypoint(shots[k], s_.triggering.hover_hold_s);
      }
      m_.items.push_back(
          {ItemKind::camera_shot, {}, 0.0, 0.0, TriggerMode::hover, s_.triggering.command});
    }
    if (!(shots.back() == end)) waypoint(end);
  }

  DroneMission finish(const LegRoute& route) {
    camera(false);
    route_to(m_.home, route);
    through_to(m_.home);  // the way home, to the landing or the return to launch
    home_stop();
    if (s_.land) {
      if (s_.vehicle == Vehicle::fixedwing)
        m_.items.push_back({ItemKind::land_start, m_.home, 0.0});
      m_.items.push_back({ItemKind::land, m_.home, 0.0});
    } else {
      m_.items.push_back({ItemKind::return_to_launch, {}, 0.0});
    }
    m_.path.push_back(m_.home);
    holds_.push_back(0);
    const double slowed_s = slow_approaches();
    for (std::size_t i = 0; i + 1 < m_.path.size(); ++i)
      m_.path_length_m += geometry::distance(m_.path[i], m_.path[i + 1]);
    m_.transit_length_m = m_.path_length_m - m_.work_length_m;
    m_.flight_time_s =
        path_time_s(m_.path, holds_, s_.speed_m_s, s_.vehicle, s_.accel_m_s2) + slowed_s;
    if (s_.vehicle == Vehicle::multirotor)
      m_.flight_time_s += s_.altitude_m / s_.climb_speed_m_s + s_.altitude_m / s_.descent_speed_m_s;
    for (const MissionItem& item : m_.items) m_.waypoint_count += positional(item.kind);
    return std::move(m_);
  }

  DroneMission& mission() { return m_; }

 private:
  // The flight ends with a stop at home (the return to launch or the landing there), which may run
  // on past home along the leg into it as any stop does: where that overrun would reach a zone's
  // clearance band (a default home keeps only the clearance), the flight flies to home as a
  // waypoint first, so that slow_approaches() approaches it slowly (a DO_CHANGE_SPEED before it:
  // ArduCopter's RTL flies at RTL_SPEED, not the speed the mission set), and returns or lands
  // from there.
  void home_stop() {
    if (!s_.free_run_m || s_.vehicle != Vehicle::multirotor || m_.path.size() < 2) return;
    const Point2 from = at();
    const double in_m = geometry::distance(from, m_.home);
    if (!(in_m >= kMergeWithin_m)) return;
    const double free_m = s_.free_run_m(m_.home, (m_.home - from) * (1 / in_m));
    // From a stop just before (a hold, a turn a degree sharper than kStopTurn_deg, as stops_at())
    // the drone reaches no more than sqrt(2 a d) over the d to home, as the check reckons it.
    double arrive_m_s = s_.speed_m_s;
    const Point2 before = m_.path[m_.path.size() - 2];
    if (holds_.back() > 0 || (geometry::distance(before, from) > 0 &&
                              turn_deg(before, from, m_.home) > kStopTurn_deg + 1))
      arrive_m_s = std::min(arrive_m_s, std::sqrt(2 * s_.accel_m_s2 * in_m));
    if (free_m >= stop_overrun_m(arrive_m_s, s_.accel_m_s2) + 0.01) return;
    waypoint(m_.home);
  }

  // Stops (a hold, a turn sharper than kStopTurn_deg) where the overrun at the cruise speed would
  // reach a zone's clearance band (s.free_run_m) are approached slowly: the speed cut to what stops
  // within the free run (at least s.slowest_approach_m_s) early enough that the vehicle, braking at
  // no more than s.accel_m_s2 from the cruise speed, is that slow at the stop (reachable_speed_m_s;
  // a cut kSlowApproach_m before the stop left ArduCopter SITL flights 2 to 7 cm inside the
  // clearance), and back to the cruise speed at a waypoint kSlowApproach_m past it. A
  // DO_CHANGE_SPEED after a waypoint takes effect at that waypoint or (ArduPilot runs DO items
  // while flying to the waypoint before them) earlier: the cut follows a waypoint added that far
  // before the stop on its incoming leg, or where that leg is too short, an earlier waypoint far
  // enough back or the stop before (at rest there anyway). Fast again from no earlier than the stop
  // itself. Returns the time the slow legs add, seconds.
  double slow_approaches() {
    if (!s_.free_run_m || s_.vehicle != Vehicle::multirotor || m_.path.size() < 3) return 0.0;
    const double v = s_.speed_m_s, a = s_.accel_m_s2;
    const double overrun_m = stop_overrun_m(v, a);
    const double slowest_overrun_m = stop_overrun_m(s_.slowest_approach_m_s, a);
    std::vector<std::size_t> item_of{0};  // path index -> item index (0: takeoff at home)
    for (std::size_t k = 1; k < m_.items.size(); ++k)
      if (m_.items[k].kind == ItemKind::waypoint) item_of.push_back(k);
    // Even the slowest approach runs slowest_overrun_m on: a stop with less free run (on the
    // clearance band's edge: a line start entered from the home leg, the bend of a route, a line
    // end that could not be drawn back) moves back along its incoming leg by what that needs and
    // 2 mm, at most most_nudge_m() (the preflight check refused such plans 1 to 8 mm short: half of
    // a test's random layouts with zones). First, in flight order: a stop moved turns the leg
    // into the next one, and with it the direction that stop overruns in.
    for (std::size_t i = 1; i + 1 < m_.path.size() && i < item_of.size(); ++i) {
      const Point2 p = m_.path[i], before = m_.path[i - 1];
      const double in_m = geometry::distance(before, p);
      if (!stop_here(i) || !(geometry::distance(p, m_.path[i + 1]) > 0)) continue;
      const Point2 u = (p - before) * (1 / in_m);
      if (s_.free_run_m(p, u) >= slowest_overrun_m + 1e-3) continue;
      const auto q = nudged(p, before, u, slowest_overrun_m);
      if (q && geometry::distance(before, *q) > 0) nudge(i, item_of[i], *q);
    }
    cut_after_.assign(m_.path.size(), 0);
    speed_after_.assign(m_.path.size(), v);
    double added_s = 0;
    // Backwards, so that insertions leave the indices still to visit as they were.
    for (std::size_t i = m_.path.size() - 2; i >= 1 && i < item_of.size(); --i) {
      const Point2 p = m_.path[i];
      const Point2 before = m_.path[i - 1], after = m_.path[i + 1];
      const double in_m = geometry::distance(before, p);
      const double out_m = geometry::distance(p, after);
      if (!stop_here(i)) continue;
      const Point2 u = (p - before) * (1 / in_m);
      const double free_m = s_.free_run_m(p, u);
      if (free_m >= overrun_m) continue;
      const double slow_m_s =
          std::max(s_.slowest_approach_m_s, std::sqrt(2 * a * std::max(free_m - 0.05, 0.0)));
      if (slow_m_s >= v) continue;
      const double brake_m = (v * v - slow_m_s * slow_m_s) / (2 * a) + kBrakeMargin_m;
      const double lead_m = std::max(kSlowApproach_m, brake_m);
      const double past_m = std::min(kSlowApproach_m, out_m / 2);
      if (!cut_after_[i] && !ends_flight(i)) fast_again(i, item_of, p, after, out_m, past_m);
      if (lead_m < in_m - kMergeWithin_m) {
        // Items: ..., w_in, slow, p, (its DO items), w_out, cruise, (the next waypoint) ...
        const Point2 w_in = p - u * lead_m;
        m_.items.insert(m_.items.begin() + static_cast<long>(item_of[i]),
                        {{ItemKind::waypoint, w_in, s_.altitude_m, 0.0},
                         {ItemKind::change_speed, {}, 0.0, slow_m_s}});
        m_.path.insert(m_.path.begin() + static_cast<long>(i), w_in);
        holds_.insert(holds_.begin() + static_cast<long>(i), 0.0);
        cut_after_.insert(cut_after_.begin() + static_cast<long>(i), 0);
        speed_after_.insert(speed_after_.begin() + static_cast<long>(i), slow_m_s);
        added_s += braking_s(v, slow_m_s, a) +
                   (lead_m - (brake_m - kBrakeMargin_m) + past_m) * (1 / slow_m_s - 1 / v);
        continue;
      }
      // The incoming leg is too short to brake on: slow from the waypoint back along the path
      // where braking has room, or from the stop before, whichever comes first.
      std::size_t j = i - 1;
      double back_m = in_m;
      while (j > 0 && back_m < brake_m && !stops_at(j)) {
        back_m += geometry::distance(m_.path[j - 1], m_.path[j]);
        --j;
      }
      m_.items.insert(m_.items.begin() + static_cast<long>(item_of[j + 1]),
                      {ItemKind::change_speed, {}, 0.0, slow_m_s});
      for (std::size_t k = j + 1; k < i; ++k) ++item_of[k];
      cut_after_[j] = 1;
      // A stop passed on the way back (a turn just over kStopTurn_deg, which the walk does not
      // take for sure) gets the speed up to no more than this one's again.
      for (std::size_t k = j; k < i; ++k) speed_after_[k] = std::min(speed_after_[k], slow_m_s);
      // Braking from the cruise speed where the walk found room, else from rest at the stop before.
      added_s += back_m >= brake_m
                     ? braking_s(v, slow_m_s, a) +
                           (back_m - (brake_m - kBrakeMargin_m) + past_m) * (1 / slow_m_s - 1 / v)
                     : (back_m + past_m) * (1 / slow_m_s - 1 / v);
    }
    return added_s;
  }

  // Back to the cruise speed (speed_after_) after the stop at path point i: at a waypoint past_m
  // along the outgoing leg (a next waypoint on the stop itself: after that one instead).
  void fast_again(std::size_t i, const std::vector<std::size_t>& item_of, Point2 p, Point2 after,
                  double out_m, double past_m) {
    const std::size_t next = i + 1 < item_of.size() ? item_of[i + 1] : m_.items.size() - 1;
    if (!(out_m > 0)) {
      m_.items.insert(m_.items.begin() + static_cast<long>(next) + 1,
                      {ItemKind::change_speed, {}, 0.0, speed_after_[i]});
      return;
    }
    const Point2 w_out = p + (after - p) * (past_m / out_m);
    m_.items.insert(m_.items.begin() + static_cast<long>(next),
                    {{ItemKind::waypoint, w_out, s_.altitude_m, 0.0},
                     {ItemKind::change_speed, {}, 0.0, speed_after_[i]}});
    m_.path.insert(m_.path.begin() + static_cast<long>(i) + 1, w_out);
    holds_.insert(holds_.begin() + static_cast<long>(i) + 1, 0.0);
    cut_after_.insert(cut_after_.begin() + static_cast<long>(i) + 1, 0);
    speed_after_.insert(speed_after_.begin() + static_cast<long>(i) + 1, speed_after_[i]);
  }

  // Whether path point i is a stop slow_approaches() looks at: a hold (on it, or on a waypoint
  // repeated there) or a turn sharper than kStopTurn_deg, entered along a leg of some length.
  bool stop_here(std::size_t i) const {
    const Point2 before = m_.path[i - 1], p = m_.path[i], after = m_.path[i + 1];
    const double out_m = geometry::distance(p, after);
    if (!(geometry::distance(before, p) > 0)) return false;
    const bool held = holds_[i] > 0 || (out_m <= 0 && holds_[i + 1] > 0);
    return held || ends_flight(i) || (out_m > 0 && turn_deg(before, p, after) > kStopTurn_deg);
  }

  // Whether path point i is a waypoint on home right before the return or landing there
  // (home_stop()): the flight's last stop, with no cruise speed again after it.
  bool ends_flight(std::size_t i) const {
    return i + 2 == m_.path.size() && !(geometry::distance(m_.path[i], m_.path[i + 1]) > 0);
  }

  // Whether the vehicle surely stops at path point j (a hold, or a turn a degree sharper than
  // kStopTurn_deg: the check of the written files, reading rounded degrees, must agree).
  bool stops_at(std::size_t j) const {
    if (holds_[j] > 0) return true;
    const Point2 b = m_.path[j - 1], p = m_.path[j], c = m_.path[j + 1];
    return geometry::distance(b, p) > 0 && geometry::distance(p, c) > 0 &&
           turn_deg(b, p, c) > kStopTurn_deg + 1;
  }

  // Where a stop at p, entered from `before` (direction u), has the free run the slowest approach
  // needs and 2 mm more: moved along its line (into it from a start, back from an end; a line's
  // ends stay on it, inside the area) or, off the lines, back along u; at most kMostNudge_m and
  // half the way to the next point on that side. Where the line does not do (an approach grazing
  // the clearance band, so that moving along the line adds almost nothing to the free run ahead:
  // 0.7 mm for 1 cm on a traced field), back along u, which adds to it all it moves, over the
  // leg already flown: a line's end then moves up to kMostNudge_m off its line. None where
  // neither does.
  std::optional<Point2> nudged(Point2 p, Point2 before, Point2 u, double slowest_m) const {
    double room_m = geometry::distance(before, p) / 2;
    for (const SweepLine& l : m_.lines)
      if (l.start == p || l.end == p) {
        const Point2 other = l.start == p ? l.end : l.start;
        const double line_room_m = geometry::distance(p, other) / 2;
        if (!(line_room_m > 0)) return std::nullopt;  // a line of no length: nowhere to go
        if (auto q = nudged_along(p, before, (other - p) * (1 / (2 * line_room_m)), line_room_m,
                                  slowest_m))
          return q;
        break;
      }
    return nudged_along(p, before, u * -1.0, room_m, slowest_m);
  }

  // nudged() in the direction d (a unit vector) with room_m to move in.
  std::optional<Point2> nudged_along(Point2 p, Point2 before, Point2 d, double room_m,
                                     double slowest_m) const {
    double t = 0;
    for (int round = 0; round < 4; ++round) {
      const Point2 q = p + d * t;
      const double in_m = geometry::distance(before, q);
      if (!(in_m > 0 && std::isfinite(in_m))) return std::nullopt;
      const double free_m = s_.free_run_m(q, (q - before) * (1 / in_m));
      if (free_m >= slowest_m + 1e-3) return t > 0 ? std::optional<Point2>(q) : std::nullopt;
      t += slowest_m + 2e-3 - free_m;
      if (t > most_nudge_m() || t >= room_m) return std::nullopt;
    }
    return std::nullopt;
  }

  // kMostNudge_m, and the overrun a least approach speed above kSlowestApproach_m_s adds.
  double most_nudge_m() const {
    return kMostNudge_m + (stop_overrun_m(s_.slowest_approach_m_s, s_.accel_m_s2) -
                           stop_overrun_m(kSlowestApproach_m_s, s_.accel_m_s2));
  }

  // Moves path point i (item k, and a line starting or ending there) to q; returns q.
  Point2 nudge(std::size_t i, std::size_t k, Point2 q) {
    const Point2 old = m_.path[i];
    m_.path[i] = q;
    m_.items[k].position = q;
    for (SweepLine& l : m_.lines) {
      if (l.start == old) l.start = q;
      if (l.end == old) l.end = q;
    }
    return q;
  }

  const MissionSettings& s_;
  DroneMission m_;
  std::vector<double> holds_;
  // slow_approaches(): path points right after whose items a later stop's speed cut was put (no
  // cruise speed again there).
  std::vector<char> cut_after_;
  // slow_approaches(): the speed set again after each path point's stop (the cruise speed, or
  // less before a later stop whose cut lies further back).
  std::vector<double> speed_after_;
  bool camera_on_ = false;
};

}  // namespace

bool positional(ItemKind kind) {
  return kind == ItemKind::takeoff || kind == ItemKind::waypoint || kind == ItemKind::land;
}

double SurveyPath::length_m() const {
  double length = 0;
  for (std::size_t i = 0; i + 1 < points.size(); ++i)
    length += geometry::distance(points[i], points[i + 1]);
  return length;
}

SurveyPath survey_path(const std::vector<SweepLine>& lines,
                       std::optional<double> waypoint_spacing_m, const LegRoute& route) {
  SurveyPath path;
  auto add = [&](Point2 p, bool on_line) {
    if (!path.points.empty()) path.on_line.push_back(on_line);
    path.points.push_back(p);
  };
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (i > 0 && route)
      for (const Point2& p : route(path.points.back(), lines[i].start)) add(p, false);
    const std::vector<Point2> points = line_waypoints(lines[i], waypoint_spacing_m);
    for (std::size_t k = 0; k < points.size(); ++k) add(points[k], k > 0);
  }
  return path;
}

std::vector<SurveyPath> cut_path(const SurveyPath& path, const std::vector<double>& cuts_m) {
  std::vector<SurveyPath> pieces(1);
  std::size_t next_cut = 0;
  double walked = 0;
  pieces.back().points.push_back(path.points.front());
  for (std::size_t i = 0; i + 1 < path.points.size(); ++i) {
    const Point2 a = path.points[i], b = path.points[i + 1];
    const double length = geometry::distance(a, b);
    // Every cut inside this segment ends a piece at a new point and starts the next one there.
    while (next_cut < cuts_m.size() && cuts_m[next_cut] < walked + length) {
      const double t = std::clamp((cuts_m[next_cut] - walked) / length, 0.0, 1.0);
      const Point2 cut = a + (b - a) * t;
      if (!(cut == pieces.back().points.back())) {
        pieces.back().points.push_back(cut);
        pieces.back().on_line.push_back(path.on_line[i]);
      }
      pieces.emplace_back();
      pieces.back().points.push_back(cut);
      ++next_cut;
    }
    if (!(b == pieces.back().points.back())) {
      pieces.back().points.push_back(b);
      pieces.back().on_line.push_back(path.on_line[i]);
    }
    walked += length;
  }
  while (pieces.size() < cuts_m.size() + 1) pieces.push_back({{path.points.back()}, {}});
  return pieces;
}

namespace {

// Whether the segment [a, b] has a point inside or on one of `rings`.
bool meets_rings(Point2 a, Point2 b, const std::vector<geometry::Ring>& rings) {
  for (const geometry::Ring& ring : rings) {
    if (geometry::locate_point(a, ring) != geometry::Containment::outside) return true;
    for (std::size_t k = 0; k < ring.size(); ++k)
      if (geometry::segments_intersect(a, b, ring[k], ring[(k + 1) % ring.size()])) return true;
  }
  return false;
}

// The run of line segments [from, to) of the piece becomes a transit where none meets `rings`.
void transit_if_outside(SurveyPath& piece, std::size_t from, std::size_t to,
                        const std::vector<geometry::Ring>& rings) {
  for (std::size_t k = from; k < to; ++k)
    if (meets_rings(piece.points[k], piece.points[k + 1], rings)) return;
  for (std::size_t k = from; k < to; ++k) piece.on_line[k] = 0;
}

}  // namespace

void transit_stubs_outside(SurveyPath& piece, const std::vector<geometry::Ring>& rings) {
  const std::size_t n = piece.on_line.size();
  if (rings.empty() || n == 0) return;
  std::size_t first_end = 0;
  while (first_end < n && piece.on_line[first_end]) ++first_end;
  std::size_t last_start = n;
  while (last_start > 0 && piece.on_line[last_start - 1]) --last_start;
  if (first_end > 0) transit_if_outside(piece, 0, first_end, rings);
  // A piece of one line throughout was decided above.
  if (last_start < n && last_start > 0) transit_if_outside(piece, last_start, n, rings);
}

std::vector<Point2> photo_positions(Point2 start, Point2 end, double trigger_distance_m) {
  std::vector<Point2> out{start};
  const double length = geometry::distance(start, end);
  if (!(trigger_distance_m > 0) || length == 0) return out;
  const auto count = static_cast<std::size_t>(std::floor(length / trigger_distance_m + 1e-9));
  for (std::size_t k = 1; k <= count; ++k)
    out.push_back(start + (end - start) * (static_cast<double>(k) * trigger_distance_m / length));
  return out;
}

std::vector<PhotoPoint> planned_photos(const DroneMission& m, double trigger_distance_m) {
  // The autopilot triggers at the distance the files carry, to the millimetre: over a long line
  // the unrounded spacing put the last photo up to centimetres off, and a line's count one off
  // from what the written file takes (swath verify's count).
  trigger_distance_m = base::round_to(trigger_distance_m, 3);
  std::vector<PhotoPoint> photos;
  Point2 at = m.home;
  bool on = false;
  double since = 0;  // distance flown since the last photo
  int line = -1;
  std::size_t next_line = 0;
  for (const MissionItem& item : m.items) {
    if (positional(item.kind)) {
      const Point2 to = item.position;
      double remaining = geometry::distance(at, to);
      if (on && trigger_distance_m > 0 && remaining > 0) {
        const Point2 step = (to - at) * (1.0 / remaining);
        Point2 cursor = at;
        while (since + remaining >= trigger_distance_m - 1e-9) {
          const double advance = trigger_distance_m - since;
          cursor = cursor + step * advance;
          remaining -= advance;
          photos.push_back({cursor, std::max(line, 0)});
          since = 0;
        }
        since += remaining;
      }
      at = to;
      if (next_line < m.lines.size() && at == m.lines[next_line].start)
        line = static_cast<int>(next_line++);
    } else if (item.kind == ItemKind::trigger_start) {
      on = true;
      since = 0;
      photos.push_back({at, std::max(line, 0)});  // param3 = 1: one photo at once
    } else if (item.kind == ItemKind::trigger_stop) {
      on = false;
    } else if (item.kind == ItemKind::camera_shot) {
      photos.push_back({at, std::max(line, 0)});
    }
  }
  return photos;
}

double path_time_s(const std::vector<Point2>& path, const std::vector<double>& hold_s,
                   double speed_m_s, Vehicle vehicle, double accel_m_s2) {
  double length = 0, time = 0, since_stop = 0;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const double leg = geometry::distance(path[i], path[i + 1]);
    length += leg;
    since_stop += leg;
    const bool last = i + 2 == path.size();
    const double hold = i + 1 < hold_s.size() ? hold_s[i + 1] : 0.0;
    const bool stop = last || hold > 0 ||
                      (vehicle == Vehicle::multirotor &&
                       turn_deg(path[i], path[i + 1], path[i + 2]) > kStopTurn_deg);
    if (vehicle == Vehicle::multirotor && stop) {
      time += vehicle::rest_to_rest_s(since_stop, speed_m_s, accel_m_s2) + hold;
      since_stop = 0;
    }
  }
  return vehicle == Vehicle::multirotor ? time : length / speed_m_s;
}

namespace {

// The path's points with the line ends drawn back along their lines where a stop there would
// overrun into a no-fly zone's clearance band: a multirotor may run stop_overrun_m() past a stop
// (a hold at a line end beside a zone, s.stop_at, or a turn sharper than kStopTurn_deg) along its
// incoming leg, and s.free_run_m says how far it may go; an end is drawn back by the shortfall (at
// most half its segment), where the leg off the line from there stays inside (`inside`; without
// it nothing moves). A line's start is entered along the leg from the point before it (already
// final), so its shortfall is found again from the moved point, a few times. Also which points are
// held stops (their hold is written whether drawn back or not).
struct DrawnBack {
  std::vector<Point2> points;
  std::vector<char> stop;
};

// How far the end p of a segment from `along` must move towards `along` so that a stop there,
// entered from `before`, overruns `overrun_m` no further than the free run allows (0: not at all).
double shortfall_m(const MissionSettings& s, Point2 p, Point2 along, Point2 before, bool end,
                   double overrun_m) {
  const double length_m = geometry::distance(p, along);
  double t = 0;
  for (int round = 0; round < (end ? 1 : 4); ++round) {
    const Point2 q = p + (along - p) * (t / length_m);
    const Point2 in = end ? p - along : q - before;
    const double in_m = std::hypot(in.x, in.y);
    if (in_m <= 0) break;
    // Along the line itself the free run from q is the free run from p plus t.
    const double free_m = s.free_run_m(end ? p : q, in * (1 / in_m)) + (end ? t : 0.0);
    if (free_m >= overrun_m) break;
    t = std::min(t + (overrun_m - free_m) + 1e-3, length_m / 2);
    if (t >= length_m / 2) break;
  }
  return t;
}

DrawnBack stops_drawn_back(const SurveyPath& path, const MissionSettings& s,
                           const InsideTest& inside) {
  DrawnBack out{path.points, std::vector<char>(path.points.size(), 0)};
  const std::size_t n = path.points.size();
  if (!s.stop_at && !s.free_run_m) return out;
  for (std::size_t i = 0; i < n; ++i) {
    const bool from_line = i > 0 && path.on_line[i - 1];
    const bool to_line = i + 1 < n && path.on_line[i];
    if (from_line == to_line) continue;
    const Point2 p = path.points[i];
    out.stop[i] = s.stop_at && s.stop_at(p);
    const bool sharp =
        i > 0 && i + 1 < n && turn_deg(out.points[i - 1], p, path.points[i + 1]) > kStopTurn_deg;
    if (!inside || !s.free_run_m || !(out.stop[i] || sharp || i + 1 == n)) continue;
    const Point2 along = from_line ? path.points[i - 1] : path.points[i + 1];
    const double length_m = geometry::distance(p, along);
    if (length_m <= 0 || (!from_line && i == 0)) continue;
    const Point2 before = from_line ? p : out.points[i - 1];
    const double t =
        shortfall_m(s, p, along, before, from_line, stop_overrun_m(s.speed_m_s, s.accel_m_s2));
    if (t <= 0) continue;
    Point2 q = p + (along - p) * (t / length_m);
    const bool has_off = from_line ? i + 1 < n : i > 0;
    const Point2 off = from_line ? (has_off ? path.points[i + 1] : p) : out.points[i - 1];
    if (has_off && !inside(q, off)) {
      // Too far to draw back with the leg off the line kept inside: the slow approach takes over
      // (slow_approaches()). Even at its slowest it runs stop_overrun_m(s.slowest_approach_m_s) on,
      // 8 mm at 0.2 m/s: where the free run is shorter (an end on the clearance band's edge), the
      // end still moves back by what the slowest stop needs and 2 mm, a centimetre at most, where
      // the leg off the line then stays inside or was outside already (a turn round the end of a
      // zone that cuts the area): the preflight check refused such plans 8 mm short.
      const double small = shortfall_m(s, p, along, before, from_line,
                                       stop_overrun_m(s.slowest_approach_m_s, s.accel_m_s2) + 2e-3);
      if (!(small > 0 && small < t)) continue;
      q = p + (along - p) * (small / length_m);
      if (!inside(q, off) && inside(p, off)) continue;
    }
    out.points[i] = q;
  }
  return out;
}

}  // namespace

DroneMission mission_for_path(int drone, Point2 home, const SurveyPath& path,
                              const MissionSettings& s, const LegRoute& route,
                              const InsideTest& inside) {
  MissionBuilder b(drone, home, s);
  DroneMission& m = b.mission();
  const DrawnBack drawn = stops_drawn_back(path, s, inside);
  const std::vector<Point2>& points = drawn.points;
  const std::size_t n = points.size();
  if (n > 0) b.route_to(points[0], route);
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 p = points[i];
    const bool from_line = i > 0 && path.on_line[i - 1];
    if (from_line) {
      // Consecutive segments on lines are one line (split only by intermediate waypoints).
      if (i > 1 && path.on_line[i - 2]) {
        m.lines.back().end = p;
      } else {
        m.lines.push_back({points[i - 1], p});
      }
      m.work_length_m += geometry::distance(points[i - 1], p);
    }
    const bool to_line = i + 1 < n && path.on_line[i];
    if (s.triggering.mode == TriggerMode::hover && from_line) {
      b.hover_line(p);
    } else {
      const bool line_end = from_line != to_line;
      b.waypoint(p, line_end && drawn.stop[i] ? kStopHold_s : 0.0);
    }
    if (to_line) {
      b.camera(true);
    } else if (from_line) {
      // The end of a line: the camera stays on only through a turn that stays in the area all
      // the way to the next line (photos_in_turns); otherwise it stops before the turn.
      bool keep = false;
      if (s.triggering.photos_in_turns && inside) {
        std::size_t j = i;
        bool all_inside = true;
        while (j + 1 < n && !path.on_line[j]) {
          all_inside = all_inside && inside(points[j], points[j + 1]);
          ++j;
        }
        keep = all_inside && j + 1 < n && path.on_line[j];
      }
      if (!keep) b.camera(false);
    }
  }
  return b.finish(route);
}

DroneMission build_mission(int drone, Point2 home, const std::vector<SweepLine>& lines,
                           const MissionSettings& s, const LegRoute& route) {
  return mission_for_path(drone, home, survey_path(lines, s.waypoint_spacing_m, route), s, route);
}

}  // namespace swath::planning
