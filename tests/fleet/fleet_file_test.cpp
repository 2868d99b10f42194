// The fleet file's per-drone `mavlink {url, sysid}` (docs/swath-fleet.md): read with --vehicles'
// grammar (the same parser: each URL --vehicles accepts reads to the same address here), and each
// bad value refused naming the file, the line and the key.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "swath/base/input_error.hpp"
#include "swath/fleet/fleet_file.hpp"
#include "swath/fleet/vehicle_address.hpp"
#include "swath/vehicle/drone.hpp"

namespace swath::fleet {
namespace {

const geometry::GeoPoint kOrigin{42.3601, -71.0942, 0};

std::vector<DroneSpec> parse(const std::string& drones) {
  return parse_fleet_file("drones:\n" + drones, "f.yaml", kOrigin);
}

TEST(FleetFile, MavlinkUrlAndSysidAreRead) {
  const auto d = parse(
      "  - {name: a, speed_m_s: 10, mavlink: {url: 'tcp:127.0.0.1:5760', sysid: 7}}\n"
      "  - {name: b, speed_m_s: 10, mavlink: {url: 'udp:0.0.0.0:14551'}}\n"
      "  - {name: c, speed_m_s: 10, mavlink: {url: 'udp:0.0.0.0:14552/9'}}\n"
      "  - {name: d, speed_m_s: 10}\n");
  ASSERT_EQ(d.size(), 4u);
  ASSERT_TRUE(d[0].vehicle && d[1].vehicle && d[2].vehicle);
  EXPECT_FALSE(d[3].vehicle);
  EXPECT_TRUE(d[0].vehicle->tcp);
  EXPECT_EQ(d[0].vehicle->host, "127.0.0.1");
  EXPECT_EQ(d[0].vehicle->port, 5760);
  EXPECT_EQ(d[0].vehicle->sysid, 7);
  EXPECT_FALSE(d[1].vehicle->tcp);
  EXPECT_EQ(d[1].vehicle->host, "0.0.0.0");
  EXPECT_EQ(d[1].vehicle->port, 14551);
  EXPECT_EQ(d[1].vehicle->sysid, 2);  // --vehicles' default: its place + 1
  EXPECT_EQ(d[2].vehicle->sysid, 9);
  EXPECT_EQ(vehicle_address_text(*d[0].vehicle), "tcp:127.0.0.1:5760");
}

// Every value's problem names file, line and key, in one sentence.
TEST(FleetFile, BadMavlinkValuesAreRefusedWithFileLineAndKey) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"  - {speed_m_s: 10, mavlink: 'udp:0.0.0.0:14550'}\n",
       "f.yaml: line 2: drones[0].mavlink: a mapping {url"},
      {"  - {speed_m_s: 10, mavlink: {sysid: 3}}\n", "line 2: drones[0].mavlink: no url"},
      {"  - {speed_m_s: 10, mavlink: {url: 'serial:/dev/ttyUSB0'}}\n",
       "line 2: drones[0].mavlink.url: \"serial:/dev/ttyUSB0\" is neither udp: nor tcp:"},
      {"  - {speed_m_s: 10, mavlink: {url: 'udp:14550'}}\n", "has no HOST:PORT"},
      {"  - {speed_m_s: 10, mavlink: {url: 'udp:h:70000'}}\n",
       "has a port that is not a number in 1..65535"},
      {"  - {speed_m_s: 10, mavlink: {url: 'udp:h:1/0'}}\n",
       "has a system id that is not a number in 1..255"},
      {"  - {speed_m_s: 10, mavlink: {url: 'udp:h:1', sysid: 256}}\n",
       "drones[0].mavlink.sysid must be in"},
      {"  - {speed_m_s: 10, mavlink: {url: 'udp:h:1', sysid: 2.5}}\n",
       "drones[0].mavlink.sysid: 2.5 is not a whole number in 1..255"},
      {"  - {speed_m_s: 10, mavlink: {url: 'udp:h:1/2', sysid: 2}}\n",
       "the system id is given twice"},
      {"  - {speed_m_s: 10, mavlink: {url: 'udp:h:1', autopilot: ardupilot}}\n", "autopilot"},
      {"  - {name: a, speed_m_s: 10, mavlink: {url: 'udp:h:1'}}\n"
       "  - {name: b, speed_m_s: 10,\n     mavlink: {url: 'udp:h:1'}}\n",
       "line 4: drones[1].mavlink: b's url is also a's (one vehicle per link)"}};
  for (const auto& [drones, sentence] : cases) {
    try {
      parse(drones);
      ADD_FAILURE() << "accepted: " << drones;
    } catch (const base::InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(sentence), std::string::npos) << what;
      EXPECT_EQ(what.rfind("f.yaml: ", 0), 0u) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

// The fleet file and --vehicles share one grammar: on a table of URLs (good and bad), the
// fleet file accepts exactly those the address parser accepts, with the same address.
TEST(FleetFile, MavlinkUrlsFollowTheVehiclesGrammar) {
  for (const std::string url : {"udp:0.0.0.0:14550", "tcp:localhost:5770", "udp:h:65535", "udp:h:0",
                                "udp::1", "tcp:h:", "tcp:h:12x", "udp:a:b:1", "udp:h:1/255",
                                "udp:h:1/", "UDP:h:1", "tcp:[::1]:5760"}) {
    VehicleAddress expect;
    const bool good = parse_vehicle_address(url, 1, expect).empty();
    try {
      const auto d = parse("  - {speed_m_s: 10, mavlink: {url: '" + url + "'}}\n");
      EXPECT_TRUE(good) << url;
      EXPECT_EQ(d[0].vehicle->host, expect.host) << url;
      EXPECT_EQ(d[0].vehicle->port, expect.port) << url;
      EXPECT_EQ(d[0].vehicle->tcp, expect.tcp) << url;
      EXPECT_EQ(d[0].vehicle->sysid, expect.sysid) << url;
    } catch (const base::InputError& e) {
      EXPECT_FALSE(good) << url << ": " << e.what();
    }
  }
}

// One reader for swath plan and swath-fleet (vehicle::parse_fleet_file): on random fleets (fixed
// seed), both programs read the values written into the text, and a vertical speed the file
// does not give is each program's documented default (docs/formats.md: swath plan 2.5 m/s up,
// 1.5 m/s down; swath-fleet 3 m/s both ways).
std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

TEST(FleetFile, SwathPlanAndSwathFleetReadTheSameDrones) {
  std::mt19937 rng(46);
  std::uniform_real_distribution<double> level(0.05, 1), endurance(60, 3600), speed(1, 20),
      vertical(0.5, 8);
  for (int fleet = 0; fleet < 40; ++fleet) {
    const int n = 1 + static_cast<int>(rng() % 6);
    struct Written {
      double level, endurance, speed;
      std::optional<double> climb, descent;
    };
    std::vector<Written> written;
    std::string text = "home: {lat: 42.3601, lon: -71.0942}\ndrones:\n";
    for (int i = 0; i < n; ++i) {
      Written w{level(rng), endurance(rng), speed(rng), {}, {}};
      if (rng() % 2) w.climb = vertical(rng);
      if (rng() % 2) w.descent = vertical(rng);
      text += "  - {name: d" + std::to_string(i) + ", battery_level: " + number_text(w.level) +
              ", endurance_s: " + number_text(w.endurance) + ", speed_m_s: " + number_text(w.speed);
      if (w.climb) text += ", climb_speed_m_s: " + number_text(*w.climb);
      if (w.descent) text += ", descent_speed_m_s: " + number_text(*w.descent);
      text += "}\n";
      written.push_back(w);
    }
    const vehicle::Fleet plan = vehicle::parse_fleet(text, "f.yaml");
    const std::vector<DroneSpec> flown = parse_fleet_file(text, "f.yaml", kOrigin);
    ASSERT_EQ(plan.drones.size(), written.size());
    ASSERT_EQ(flown.size(), written.size());
    for (std::size_t i = 0; i < written.size(); ++i) {
      const Written& w = written[i];
      const vehicle::Drone& p = plan.drones[i];
      const DroneSpec& f = flown[i];
      EXPECT_EQ(p.name, f.drone.name);
      EXPECT_EQ(*p.battery_level, w.level);
      EXPECT_EQ(f.battery.initial_soc, w.level);
      EXPECT_EQ(*p.endurance_s, w.endurance);
      EXPECT_EQ(f.max_flight_time_s, w.endurance * w.level);
      EXPECT_EQ(*p.speed_m_s, w.speed);
      EXPECT_EQ(f.kinematics().cruise_m_s, w.speed);
      EXPECT_EQ(p.climb_speed_m_s, w.climb.value_or(2.5));
      EXPECT_EQ(f.kinematics().climb_m_s, w.climb.value_or(3.0));
      EXPECT_EQ(p.descent_speed_m_s, w.descent.value_or(1.5));
      EXPECT_EQ(f.kinematics().descent_m_s, w.descent.value_or(3.0));
    }
  }
}

// A drone's profile gives the vertical speeds the fleet file does not; the file's own win.
TEST(FleetFile, TheFileSpeedsOverTheProfiles) {
  const auto dir = std::filesystem::temp_directory_path() / "swath-fleet-file-profile-test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "quad.yaml") << "name: quad\nclimb_speed_m_s: 4\ndescent_speed_m_s: 2\n";
  const auto d = parse_fleet_file(
      "drones:\n  - {name: a, profile: quad.yaml}\n"
      "  - {name: b, profile: quad.yaml, climb_speed_m_s: 6}\n",
      (dir / "fleet.yaml").string(), kOrigin);
  EXPECT_EQ(d[0].kinematics().climb_m_s, 4);
  EXPECT_EQ(d[0].kinematics().descent_m_s, 2);
  EXPECT_EQ(d[1].kinematics().climb_m_s, 6);
  EXPECT_EQ(d[1].kinematics().descent_m_s, 2);
  std::filesystem::remove_all(dir);
}

// A key both programs read is refused by both in the same sentence: one reader.
TEST(FleetFile, BothProgramsRefuseABadDroneInOneSentence) {
  const std::string head = "home: {lat: 42.3601, lon: -71.0942}\ndrones:\n";
  const std::string good = "{battery_level: 1, endurance_s: 600, speed_m_s: 5";
  const std::vector<std::string> bad_drones{
      "  - " + good + ", sped_m_s: 5}\n",
      "  - {battery_level: 1, endurance_s: 600, speed_m_s: 0}\n",
      "  - {battery_level: 2, endurance_s: 600, speed_m_s: 5}\n",
      "  - {battery_level: 1, endurance_s: -1, speed_m_s: 5}\n",
      "  - " + good + ", climb_speed_m_s: 0}\n",
      "  - " + good + ", descent_speed_m_s: fast}\n",
      "  - " + good + ", home: {lat: 91, lon: 0}}\n",
      "  - " + good + ", recharge_s: -3}\n",
      "  - " + good + ", mavlink: {url: 'udp:h:1', autopilot: px4}}\n",
      "  - {name: a, " + good.substr(1) + "}\n  - {name: a, " + good.substr(1) + "}\n"};
  const auto error = [](const auto& read) {
    try {
      read();
    } catch (const base::InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  for (const std::string& drones : bad_drones) {
    const std::string text = head + drones;
    const std::string plan = error([&] { vehicle::parse_fleet(text, "f.yaml"); });
    const std::string flown = error([&] { parse_fleet_file(text, "f.yaml", kOrigin); });
    EXPECT_NE(plan, "accepted") << drones;
    EXPECT_EQ(plan, flown) << drones;
    EXPECT_EQ(plan.rfind("f.yaml", 0), 0u) << plan;
  }
}

}  // namespace
}  // namespace swath::fleet
