#include "swath/planning/mission.hpp"

#include <gtest/gtest.h>

#include <cmath>

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
  for (const double l : legs) expected += l / 4 + 4 / kAcceleration_m_s2;
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

}  // namespace
}  // namespace swath::planning
