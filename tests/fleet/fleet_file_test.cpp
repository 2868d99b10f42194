// The fleet file's per-drone `mavlink {url, sysid}` (docs/swath-fleet.md): read with --vehicles'
// grammar (the same parser: each URL --vehicles accepts reads to the same address here), and each
// bad value refused naming the file, the line and the key.
#include <gtest/gtest.h>

#include "swath/base/input_error.hpp"
#include "swath/fleet/fleet_file.hpp"
#include "swath/fleet/vehicle_address.hpp"

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

}  // namespace
}  // namespace swath::fleet
