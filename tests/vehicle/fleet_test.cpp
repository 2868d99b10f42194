// The planner's fleet reader and swath-fleet's keys: one fleet file serves both programs.
#include <gtest/gtest.h>

#include <string>

#include "swath/base/input_error.hpp"
#include "swath/vehicle/drone.hpp"

namespace {

using swath::vehicle::Fleet;
using swath::vehicle::parse_fleet;

const std::string kPlain = R"(home: {lat: 47.3965, lon: 8.5405, alt: 0}
drones:
  - {name: copter-1, battery_level: 0.9, endurance_s: 1500, speed_m_s: 10}
  - {name: copter-2, battery_level: 1.0, endurance_s: 1200, speed_m_s: 8, home: {lat: 47.3982, lon: 8.5468}}
)";

// The same fleet with every key only swath-fleet's flights read.
const std::string kWithFlightKeys = R"(home: {lat: 47.3965, lon: 8.5405, alt: 0}
drones:
  - {name: copter-1, battery_level: 0.9, endurance_s: 1500, speed_m_s: 10,
     mavlink: {url: "tcp:127.0.0.1:5760", sysid: 1}, recharge_s: 60, max_flight_time_s: 1400,
     approach_speed_m_s: 2, approach_within_m: 20, accel_m_s2: 2, profile: quad.yaml}
  - {name: copter-2, battery_level: 1.0, endurance_s: 1200, speed_m_s: 8, home: {lat: 47.3982, lon: 8.5468},
     mavlink: {url: "udp:0.0.0.0:14550"}}
)";

std::string error_of(const std::string& text) {
  try {
    parse_fleet(text, "fleet.yaml");
  } catch (const swath::base::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PlannerFleet, SwathFleetsKeysAreAcceptedAndChangeNothing) {
  const Fleet a = parse_fleet(kPlain, "a.yaml"), b = parse_fleet(kWithFlightKeys, "b.yaml");
  ASSERT_EQ(a.drones.size(), 2u);
  ASSERT_EQ(b.drones.size(), a.drones.size());
  EXPECT_EQ(b.home.lat_deg, a.home.lat_deg);
  EXPECT_EQ(b.home.lon_deg, a.home.lon_deg);
  for (std::size_t i = 0; i < a.drones.size(); ++i) {
    EXPECT_EQ(b.drones[i].name, a.drones[i].name);
    EXPECT_EQ(b.drones[i].battery_level, a.drones[i].battery_level);
    EXPECT_EQ(b.drones[i].endurance_s, a.drones[i].endurance_s);
    EXPECT_EQ(b.drones[i].speed_m_s, a.drones[i].speed_m_s);
    EXPECT_EQ(b.drones[i].home.has_value(), a.drones[i].home.has_value());
    EXPECT_EQ(b.drones[i].range_m(), a.drones[i].range_m());
  }
  EXPECT_DOUBLE_EQ(*b.drones[0].range_m(), 0.9 * 1500 * 10);
}

TEST(PlannerFleet, HomeInMetresAndUnknownKeysAreRefusedByName) {
  std::string with_home_m = kPlain;
  with_home_m.replace(with_home_m.find("speed_m_s: 10}"), 14, "speed_m_s: 10, home_m: [5, 0]}");
  const std::string e = error_of(with_home_m);
  EXPECT_NE(e.find("fleet.yaml: drone 1"), std::string::npos) << e;
  EXPECT_NE(e.find("home_m"), std::string::npos) << e;
  EXPECT_NE(e.find("home: {lat, lon}"), std::string::npos) << e;

  std::string typo = kPlain;
  typo.replace(typo.find("speed_m_s: 8"), 12, "sped_m_s: 8, speed_m_s: 8");
  const std::string u = error_of(typo);
  EXPECT_NE(u.find("drone 2"), std::string::npos) << u;
  EXPECT_NE(u.find("unknown key 'sped_m_s'"), std::string::npos) << u;
}

}  // namespace
