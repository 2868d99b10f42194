#include "swath/planning/mission.hpp"

#include <gtest/gtest.h>

namespace swath::planning {
namespace {

TEST(BuildMission, TakeoffTriggerOnLinesTriggerOffReturn) {
  const std::vector<SweepLine> lines{{{0, 0}, {100, 0}}, {{100, 20}, {0, 20}}};
  MissionSettings s;
  s.altitude_m = 60;
  s.speed_m_s = 4;
  s.trigger_distance_m = 15;
  const DroneMission m = build_mission(1, {-30, -40}, lines, s);
  std::vector<ItemKind> kinds;
  for (const MissionItem& i : m.items) kinds.push_back(i.kind);
  EXPECT_EQ(kinds,
            (std::vector<ItemKind>{ItemKind::takeoff, ItemKind::waypoint, ItemKind::trigger_start,
                                   ItemKind::waypoint, ItemKind::waypoint, ItemKind::waypoint,
                                   ItemKind::trigger_stop, ItemKind::return_to_launch}));
  EXPECT_DOUBLE_EQ(m.items[2].trigger_distance_m, 15);
  EXPECT_DOUBLE_EQ(m.work_length_m, 200);
  // home (-30,-40) -> (0,0): 50; lines 200; connector 20; (0,20) -> home: hypot(30, 60).
  EXPECT_NEAR(m.path_length_m, 50 + 200 + 20 + std::hypot(30.0, 60.0), 1e-9);
  EXPECT_NEAR(m.transit_length_m, m.path_length_m - 200, 1e-9);
  EXPECT_NEAR(m.flight_time_s, m.path_length_m / 4, 1e-9);
  EXPECT_EQ(m.waypoint_count, 5u);
  EXPECT_EQ(m.path.front(), m.path.back());
}

}  // namespace
}  // namespace swath::planning
