#include "swath/planning/mission.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "random_polygons.hpp"
#include "steps/leg_within.hpp"
#include "swath/geometry/offset.hpp"
#include "swath/geometry/predicates.hpp"

namespace swath::planning {
namespace {

using K = ItemKind;

const std::vector<SweepLine> kTwoLines{{{0, 0}, {100, 0}}, {{100, 20}, {0, 20}}};

MissionSettings settings() {
  MissionSettings s;
  s.altitude_m = 60;
  s.speed_m_s = 4;
  s.trigger_distance_m = 15;
  return s;
}

std::vector<ItemKind> kinds_of(const DroneMission& m) {
  std::vector<ItemKind> kinds;
  for (const MissionItem& i : m.items) kinds.push_back(i.kind);
  return kinds;
}

TEST(BuildMission, SpeedGimbalAndTheCameraOnEachLineOnly) {
  const DroneMission m = build_mission(1, {-30, -40}, kTwoLines, settings());
  EXPECT_EQ(kinds_of(m), (std::vector<ItemKind>{
                             K::takeoff, K::change_speed, K::gimbal_pitch, K::waypoint,
                             K::trigger_start, K::waypoint, K::trigger_stop, K::waypoint,
                             K::trigger_start, K::waypoint, K::trigger_stop, K::return_to_launch}));
  EXPECT_DOUBLE_EQ(m.items[1].value, 4);    // the drone's speed, m/s
  EXPECT_DOUBLE_EQ(m.items[2].value, -90);  // nadir
  EXPECT_DOUBLE_EQ(m.items[4].value, 15);   // trigger distance
  EXPECT_DOUBLE_EQ(m.work_length_m, 200);
  // home (-30,-40) -> (0,0): 50; lines 200; connector 20; (0,20) -> home: hypot(30, 60).
  EXPECT_NEAR(m.path_length_m, 50 + 200 + 20 + std::hypot(30.0, 60.0), 1e-9);
  EXPECT_NEAR(m.transit_length_m, m.path_length_m - 200, 1e-9);
  EXPECT_EQ(m.waypoint_count, 5u);
  EXPECT_EQ(m.path.front(), m.path.back());
}

// The flight time against the closed form: every corner of this path is a right angle or
// sharper, so the drone stops at each (v = 4 m/s, a = 2.5 m/s²: v²/a = 6.4 m, so every leg
// reaches cruise speed and takes L/v + v/a), plus the climb and descent of 60 m.
TEST(BuildMission, FlightTimeIsTheTrapezoidOfEachLegPlusClimbAndDescent) {
  const DroneMission m = build_mission(1, {0, -50}, kTwoLines, settings());
  const double legs[] = {50, 100, 20, 100, std::hypot(0.0, 70.0)};
  double expected = 60 / 2.5 + 60 / 1.5;  // ArduCopter's WPNAV_SPEED_UP and _DN
  for (const double l : legs) expected += l / 4 + 4 / swath::vehicle::kDefaultAccel_m_s2;
  EXPECT_NEAR(m.flight_time_s, expected, 1e-9);
  // The drone's own vertical speeds (a fleet's climb_speed_m_s, descent_speed_m_s).
  MissionSettings quick = settings();
  quick.climb_speed_m_s = 5;
  quick.descent_speed_m_s = 3;
  EXPECT_NEAR(build_mission(1, {0, -50}, kTwoLines, quick).flight_time_s,
              expected - (60 / 2.5 + 60 / 1.5) + (60 / 5.0 + 60 / 3.0), 1e-9);
  // A short leg never reaches cruise speed: 2 sqrt(L / a).
  EXPECT_NEAR(path_time_s({{0, 0}, {4, 0}}, {}, 4, Vehicle::multirotor), 2 * std::sqrt(4 / 2.5),
              1e-12);
  // Fixed-wing: no stops.
  EXPECT_NEAR(path_time_s({{0, 0}, {100, 0}, {100, 100}}, {}, 20, Vehicle::fixedwing), 10, 1e-12);
}

TEST(BuildMission, TimeTriggerHoverShotsAndLanding) {
  MissionSettings s = settings();
  s.triggering.mode = TriggerMode::time;
  const DroneMission timed = build_mission(1, {0, -10}, kTwoLines, s);
  int starts = 0;
  for (const MissionItem& i : timed.items)
    if (i.kind == K::trigger_start) {
      ++starts;
      EXPECT_EQ(i.trigger, TriggerMode::time);
      EXPECT_DOUBLE_EQ(i.value, 15.0 / 4.0);  // seconds between photos at 4 m/s
    }
  EXPECT_EQ(starts, 2);

  s.triggering.mode = TriggerMode::hover;
  s.triggering.command = CameraCommand::image_capture;
  s.land = true;
  const DroneMission hover = build_mission(1, {0, -10}, kTwoLines, s);
  // Photos at 0, 15, ..., 90 on each 100 m line: 7 each, each a held waypoint and a shot.
  int shots = 0, held = 0;
  for (const MissionItem& i : hover.items) {
    shots += i.kind == K::camera_shot;
    held += i.kind == K::waypoint && i.value == 1.0;
    EXPECT_NE(i.kind, K::trigger_start);
  }
  EXPECT_EQ(shots, 14);
  EXPECT_EQ(held, 14);
  EXPECT_EQ(hover.items.back().kind, K::land);
  EXPECT_EQ(hover.items.back().position, hover.home);
  EXPECT_EQ(planned_photos(hover, 15).size(), 14u);

  s.vehicle = Vehicle::fixedwing;
  s.triggering.mode = TriggerMode::distance;
  const DroneMission fw = build_mission(1, {0, -10}, kTwoLines, s);
  EXPECT_EQ(fw.items[fw.items.size() - 2].kind, K::land_start);
  EXPECT_EQ(fw.items.back().kind, K::land);
}

// The autopilot's rule: a photo where the trigger starts, then every trigger distance flown, until
// it stops; none in turns unless the camera stays on through them.
TEST(PlannedPhotos, EveryTriggerDistanceOnTheLinesOnly) {
  const DroneMission m = build_mission(1, {0, -10}, kTwoLines, settings());
  const std::vector<PhotoPoint> photos = planned_photos(m, 15);
  ASSERT_EQ(photos.size(), 14u);  // 0, 15, .., 90 on each line
  for (const PhotoPoint& p : photos) {
    EXPECT_TRUE(p.position.y == 0 || p.position.y == 20) << "a photo off the lines";
    EXPECT_EQ(p.line, p.position.y == 0 ? 0 : 1);
  }
  EXPECT_NEAR(photos[1].position.x, 15, 1e-9);
  EXPECT_NEAR(photos[7].position.x, 100, 1e-9);  // the second line starts at x = 100
  EXPECT_NEAR(photos[8].position.x, 85, 1e-9);

  // Photos in turns: the turn (100,0) -> (100,20) stays inside, so the camera stays on and the
  // spacing carries on through it: 6 photos to x = 90, then 10 m to the line end, 5 m up the turn.
  MissionSettings s = settings();
  s.triggering.photos_in_turns = true;
  const DroneMission on = mission_for_path(1, {0, -10}, survey_path(kTwoLines, std::nullopt), s, {},
                                           [](geometry::Point2, geometry::Point2) { return true; });
  int starts = 0;
  for (const MissionItem& i : on.items) starts += i.kind == K::trigger_start;
  EXPECT_EQ(starts, 1);
  const std::vector<PhotoPoint> through = planned_photos(on, 15);
  ASSERT_GE(through.size(), 8u);
  EXPECT_NEAR(through[7].position.x, 100, 1e-9);
  EXPECT_NEAR(through[7].position.y, 5, 1e-9);
}

// The speed still reachable after a speed cut, against braking stepped in time (0.1 ms steps of
// v -= a dt, x += v dt) over random speeds, cuts, distances and decelerations (fixed seed).
TEST(ReachableSpeed, AgreesWithBrakingSteppedInTime) {
  EXPECT_NEAR(reachable_speed_m_s(5, 0.2, 0.5), std::sqrt(22.5), 1e-12);  // 25 - 2 x 2.5 x 0.5
  EXPECT_DOUBLE_EQ(reachable_speed_m_s(5, 0.2, 5), 0.2);  // braked to a stop: the commanded speed
  EXPECT_DOUBLE_EQ(reachable_speed_m_s(5, 8, 1), 8);      // a speed raised: reached at once
  EXPECT_DOUBLE_EQ(reachable_speed_m_s(5, 0.2, 0), 5);
  std::mt19937 rng(45);
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  for (int k = 0; k < 200; ++k) {
    const double before = uniform(0.5, 12), commanded = uniform(0.2, before);
    const double d = uniform(0, 30), a = uniform(1, 5), dt = 1e-4;
    double v = before, x = 0;
    while (x < d && v > commanded) {
      v = std::max(v - a * dt, commanded);
      x += v * dt;
    }
    EXPECT_NEAR(reachable_speed_m_s(before, commanded, d, a), v, 2 * a * dt)
        << before << " -> " << commanded << " m/s over " << d << " m at " << a << " m/s²";
  }
}

// Lines 5 m apart at 8 m/s, every stop 1 m from a zone's clearance band (free_run_m): the speed
// at each stop, read back from the items (the speed in force and where each DO_CHANGE_SPEED took
// effect: at the waypoint before it) and braked at 2.5 m/s² from the speed before, overruns it by
// at most that metre. A cut 0.5 m before the stop (the old slow approach) left the vehicle at
// 7.85 m/s: a 12 m overrun.
TEST(SlowApproaches, EveryStopIsReachedSlowEnoughToStopWithinItsFreeRun) {
  const std::vector<SweepLine> lines{
      {{0, 0}, {100, 0}}, {{100, 5}, {0, 5}}, {{0, 10}, {100, 10}}, {{100, 40}, {0, 40}}};
  MissionSettings s = settings();
  s.speed_m_s = 8;
  s.free_run_m = [](geometry::Point2, geometry::Point2) { return 1.0; };
  const DroneMission m = build_mission(1, {-30, -40}, lines, s);
  geometry::Point2 at{-30, -40};
  double speed = 0, arrival = 0;
  std::vector<geometry::Point2> points{at};
  std::vector<double> arrivals{0};
  for (const MissionItem& it : m.items) {
    if (it.kind == K::change_speed) speed = it.value;
    if (it.kind != K::waypoint) continue;
    const double leg_m = geometry::distance(at, it.position);
    // From a stop (a turn sharper than 45 degrees at the point before) the vehicle starts at rest.
    const std::size_t n = points.size();
    const bool from_stop =
        n < 2 || turn_deg(points[n - 2], points[n - 1], it.position) > kStopTurn_deg;
    const double start = std::max(from_stop ? 0.0 : arrival, speed);
    arrival = std::max(speed, std::sqrt(std::max(0.0, start * start - 2 * 2.5 * leg_m)));
    points.push_back(it.position);
    arrivals.push_back(arrival);
    at = it.position;
  }
  points.push_back({-30, -40});
  int stops = 0;
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    if (turn_deg(points[i - 1], points[i], points[i + 1]) <= kStopTurn_deg) continue;
    ++stops;
    EXPECT_LE(arrivals[i] * arrivals[i] / (2 * 2.5), 1.0)
        << "stop at " << points[i].x << ", " << points[i].y;
  }
  EXPECT_EQ(stops, 8);  // both ends of every line (the first's start turns 53 degrees from home)
}

// A line whose start lies on a zone's clearance band, the line running along the band's edge and
// the leg from home grazing it at 12 degrees (a traced field's hole: the preflight check refused
// its plan 2 mm short). Moving the start into its line adds nothing to the free run ahead, so it
// moves back along the leg from home: the stop there, approached at the slowest speed, overruns
// no further than the band. The band is the half-plane below y = tan(12°) x (free_run_m: the ray's
// distance to its edge, 0 inside).
TEST(SlowApproaches, AStopOnTheBandWhereTheApproachGrazesItIsMovedBackAlongTheApproach) {
  const double k = std::tan(12 * std::numbers::pi / 180);
  const geometry::Point2 start{0, 0}, end{-100 * std::cos(12 * std::numbers::pi / 180),
                                          -100 * std::sin(12 * std::numbers::pi / 180)};
  const geometry::Point2 home{-300, 0};  // the approach heads +x: 12 degrees off the edge
  const auto free_run = [k](geometry::Point2 q, geometry::Point2 u) {
    const double outside = q.y - k * q.x;  // >= 0 outside the band
    if (outside < 0) return 0.0;
    const double closing = k * u.x - u.y;  // how fast the ray nears the edge
    return closing > 0 ? outside / closing : std::numeric_limits<double>::infinity();
  };
  MissionSettings s = settings();
  s.speed_m_s = 5;
  s.free_run_m = free_run;
  const DroneMission m = build_mission(1, home, {{start, end}}, s);
  // The first waypoint near the line's start is the stop; the one before it, the way in.
  std::vector<geometry::Point2> waypoints{home};
  for (const MissionItem& it : m.items)
    if (it.kind == K::waypoint) waypoints.push_back(it.position);
  std::size_t stop = 0;
  for (std::size_t i = 1; i < waypoints.size(); ++i)
    if (geometry::distance(waypoints[i], start) < 0.05) {
      stop = i;
      break;
    }
  ASSERT_GT(stop, 0u);
  const geometry::Point2 p = waypoints[stop], before = waypoints[stop - 1];
  const geometry::Point2 u = (p - before) * (1 / geometry::distance(before, p));
  EXPECT_GE(free_run(p, u), stop_overrun_m(0.2, s.accel_m_s2))
      << "stop at " << p.x << ", " << p.y << " entered along " << u.x << ", " << u.y;
  EXPECT_LE(geometry::distance(p, start), 0.02);  // moved a centimetre or two at most
}

// The fence step's leg test answers legs in the clear interior of a ring without measuring: the
// same answers as the measurement (length inside the rings at least the leg's length less 1e-6 m,
// or for a point leg, the point in a closed ring) on random legs: across concave notches, between
// rings, along and just off edges (within the 1 mm the shortcut leaves to the measurement),
// through vertices, and point legs.
TEST(LegWithin, AgreesWithTheLengthInside) {
  test::Rng rng(52);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t inside = 0, outside = 0;
  for (int trial = 0; trial < 60; ++trial) {
    std::vector<geometry::Ring> rings{test::random_star_polygon(rng, 5 + trial % 30, 20, 100)};
    if (trial % 3 == 0)
      rings.push_back(
          test::transformed(test::random_star_polygon(rng, 8, 10, 40), 0, 150 * unit(rng), 0));
    // Fences come either way round: some rings clockwise.
    if (trial % 4 == 1) std::reverse(rings.front().begin(), rings.front().end());
    const geometry::Ring& ring = rings.front();
    auto on_ring = [&](double offset_m) {
      const std::size_t i = static_cast<std::size_t>(unit(rng) * static_cast<double>(ring.size()));
      const geometry::Point2 a = ring[i % ring.size()], b = ring[(i + 1) % ring.size()];
      const geometry::Point2 d = b - a;
      const double length = geometry::distance(a, b);
      const geometry::Point2 normal{-d.y / length, d.x / length};  // in for a CCW ring
      return a + d * unit(rng) + normal * offset_m;
    };
    auto any_point = [&]() -> geometry::Point2 {
      switch (static_cast<int>(unit(rng) * 6)) {
        case 0:
          return ring[static_cast<std::size_t>(unit(rng) * static_cast<double>(ring.size())) %
                      ring.size()];
        case 1:
          return on_ring(0.0);
        case 2:
          return on_ring((unit(rng) - 0.5) * 4e-3);  // within the clearance
        case 3:
          return on_ring((unit(rng) - 0.5) * 1e-9);
        default:
          return {-120 + 270 * unit(rng), -120 + 240 * unit(rng)};
      }
    };
    for (int k = 0; k < 400; ++k) {
      const geometry::Point2 a = any_point();
      const geometry::Point2 b = k % 20 == 0 ? a : any_point();
      const double length_m = geometry::distance(a, b);
      const bool measured =
          length_m > 0 ? geometry::length_inside({a, b}, rings) >= length_m - 1e-6
                       : std::any_of(rings.begin(), rings.end(), [a](const geometry::Ring& r) {
                           return geometry::locate_point(a, r) != geometry::Containment::outside;
                         });
      ASSERT_EQ(steps::detail::leg_within(a, b, rings), measured)
          << "trial " << trial << " leg " << k << ": (" << a.x << ", " << a.y << ") - (" << b.x
          << ", " << b.y << ")";
      (measured ? inside : outside) += 1;
    }
  }
  // Both answers well represented.
  EXPECT_GT(inside, 3000u);
  EXPECT_GT(outside, 3000u);
}

}  // namespace
}  // namespace swath::planning
