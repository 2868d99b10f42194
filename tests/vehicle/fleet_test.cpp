// The planner's fleet reader and swath-fleet's keys: one fleet file serves both programs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "swath/base/input_error.hpp"
#include "swath/vehicle/drone.hpp"
#include "swath/vehicle/fleet_file.hpp"

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

// The envelope keys (ceiling_m, separation_m, fence) are read by the one reader: swath-fleet's
// rules read the fence's GeoJSON next to the fleet file; swath plan's check the numbers the same
// way and never open the fence (a plan does not fly it).
TEST(FleetFileEnvelope, FlightsReadTheFencePlansIgnoreIt) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "swath-vehicle-fence-test";
  fs::create_directories(dir);
  std::ofstream(dir / "fence.geojson")
      << R"({"type":"MultiPolygon","coordinates":[[[[8.5,47.3],[8.6,47.3],[8.6,47.4],[8.5,47.3]]],)"
         R"([[[8.51,47.31],[8.52,47.31],[8.52,47.32]]]]})";
  const std::string text = kPlain + "ceiling_m: 60\nseparation_m: 7\n" +
                           "fence: {geojson: fence.geojson, max_altitude_m: 50}\n";
  const std::string source = (dir / "fleet.yaml").string();
  swath::vehicle::FleetFileRules flights;
  flights.flights = true;
  const swath::vehicle::FleetFile f = swath::vehicle::parse_fleet_file(text, source, flights);
  EXPECT_EQ(f.ceiling_m, 60);
  EXPECT_EQ(f.separation_m, 7);
  ASSERT_TRUE(f.fence.has_value());
  EXPECT_EQ(f.fence->max_altitude_m, 50);
  ASSERT_EQ(f.fence->polygons.size(), 2u);
  EXPECT_EQ(f.fence->polygons[0].ring_deg.size(), 3u);  // closed ring: the repeat dropped
  EXPECT_EQ(f.fence->polygons[0].ring_deg[1].lon_deg, 8.6);
  EXPECT_EQ(f.fence->polygons[0].ring_deg[1].lat_deg, 47.3);
  EXPECT_TRUE(f.fence->polygons[1].inclusion);  // a bare geometry is an inclusion
  // Without the fence file: flights name it, the planner does not look for it.
  fs::remove(dir / "fence.geojson");
  try {
    swath::vehicle::parse_fleet_file(text, source, flights);
    ADD_FAILURE() << "a missing fence file was accepted";
  } catch (const swath::base::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fence.geojson"), std::string::npos) << e.what();
  }
  const swath::vehicle::FleetFile plan =
      swath::vehicle::parse_fleet_file(text, source, swath::vehicle::FleetFileRules{});
  EXPECT_FALSE(plan.fence.has_value());
  EXPECT_EQ(plan.ceiling_m, 60);
  EXPECT_EQ(plan.drones.size(), 2u);
  fs::remove_all(dir);
}

}  // namespace
