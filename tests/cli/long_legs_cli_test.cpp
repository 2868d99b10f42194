// A field ringed by no-fly zones (its pocket free); long legs at a high latitude
// (geometry/autopilot_track.hpp, planning's kMaxBow_m): ArduPilot steers a leg straight in latitude
// and longitude, and a 20 km east-west line at 80 N flown so bows 44 m from the line swath planned.
// swath plan writes such legs as several: measured here from the written .waypoints alone, with the
// test's own formula for ArduPilot's track and GeographicLib's geodesic for the line, every leg's
// track stays within kMaxBow_m of it.
#include <gtest/gtest.h>
#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "swath/planning/mission.hpp"

namespace swath::test {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

struct LatLon {
  double lat, lon;
};

// The positions the vehicle flies through, in order: home, every item with a position (take-off
// at home, waypoints), home again (the file ends in a return to launch).
std::vector<LatLon> flown_positions(const std::string& waypoints) {
  std::istringstream in(waypoints);
  std::string line;
  std::getline(in, line);  // QGC WPL 110
  std::vector<LatLon> out;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::vector<double> v;
    for (double x; row >> x;) v.push_back(x);
    if (v.size() < 12) continue;
    const int command = static_cast<int>(v[3]);
    if (v[0] == 0 || command == 16 || command == 22) out.push_back({v[8], v[9]});
  }
  out.push_back(out.front());
  return out;
}

// ArduPilot's track of leg a -> b at its middle (Location::get_distance_NE about home: north and
// east offsets in degrees, east scaled by the cosine of the mean of the point's and home's
// latitudes), and its distance from the middle of the geodesic a -> b, metres.
double bow_m(LatLon home, LatLon a, LatLon b) {
  const auto offset = [&](LatLon p) {
    return LatLon{p.lat - home.lat, (p.lon - home.lon) * std::cos((p.lat + home.lat) / 2 * kDeg)};
  };
  const LatLon oa = offset(a), ob = offset(b);
  const double north = (oa.lat + ob.lat) / 2, east = (oa.lon + ob.lon) / 2;
  const double lat = home.lat + north;
  const LatLon track{lat, home.lon + east / std::cos((lat + home.lat) / 2 * kDeg)};
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  double s12 = 0, azi1 = 0, azi2 = 0, lat_mid = 0, lon_mid = 0;
  g.Inverse(a.lat, a.lon, b.lat, b.lon, s12, azi1, azi2);
  g.Direct(a.lat, a.lon, azi1, s12 / 2, lat_mid, lon_mid);
  double apart = 0;
  g.Inverse(lat_mid, lon_mid, track.lat, track.lon, apart);
  return apart;
}

TEST(LongLegs, AStripAtEightyNorthIsWrittenInLegsArduPilotFliesAsPlanned) {
  const std::string dir = fresh_dir("long-legs");
  std::filesystem::create_directories(dir);
  // 20 km east-west, 600 m north-south.
  std::ofstream(dir + "/strip.geojson")
      << R"({"type":"Polygon","coordinates":[[[19.4844,79.9973],[20.5156,79.9973],)"
      << R"([20.5156,80.0027],[19.4844,80.0027],[19.4844,79.9973]]]})";
  const CliRun run = run_swath("plan " + dir + "/strip.geojson --camera dji-phantom-4-pro " +
                               "--altitude 100 -o " + dir + "/out");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::vector<LatLon> at = flown_positions(read_text(dir + "/out/drone-1.waypoints"));
  ASSERT_GT(at.size(), 10u);
  double worst = 0, longest = 0;
  for (std::size_t k = 0; k + 1 < at.size(); ++k) {
    worst = std::max(worst, bow_m(at.front(), at[k], at[k + 1]));
    double length = 0;
    GeographicLib::Geodesic::WGS84().Inverse(at[k].lat, at[k].lon, at[k + 1].lat, at[k + 1].lon,
                                             length);
    longest = std::max(longest, length);
  }
  EXPECT_LE(worst, planning::kMaxBow_m) << "the longest leg " << longest << " m";
  EXPECT_LT(longest, 5000.0);  // the 20 km lines were split
}

}  // namespace
}  // namespace swath::test

namespace swath::test {
namespace {

// A square field ringed by four no-fly bars 250 m off (their union a frame round a pocket): the
// field and its home lie in the pocket, free to fly. Growing the zones once filled the pocket,
// and the plan was refused: "the no-fly zones cover the whole area".
TEST(ZoneRing, AFieldRingedByZonesIsPlannedInsideTheRing) {
  const std::string dir = fresh_dir("zone-ring");
  std::filesystem::create_directories(dir);
  const double m_lat = 1 / 111320.0, m_lon = 1 / (111320.0 * std::cos(47.0 * kDeg));
  const auto box = [&](double x0, double y0, double x1, double y1) {
    const auto at = [&](double x, double y) {
      return "[" + std::to_string(8.0 + x * m_lon) + "," + std::to_string(47.0 + y * m_lat) + "]";
    };
    return "[[" + at(x0, y0) + "," + at(x1, y0) + "," + at(x1, y1) + "," + at(x0, y1) + "," +
           at(x0, y0) + "]]";
  };
  std::ofstream(dir + "/field.geojson")
      << R"({"type":"Polygon","coordinates":)" << box(0, 0, 200, 200) << "}";
  std::ofstream(dir + "/ring.geojson")
      << R"({"type":"MultiPolygon","coordinates":[)" << box(-300, -300, 500, -250) << ","
      << box(450, -300, 500, 500) << "," << box(-300, 450, 500, 500) << ","
      << box(-300, -300, -250, 500) << "]}";
  const CliRun run =
      run_swath("plan " + dir + "/field.geojson --camera sony-ilce-qx1 " +
                "--altitude 60 --exclude " + dir + "/ring.geojson -o " + dir + "/out");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run_swath("verify " + dir + "/out --exclude " + dir + "/ring.geojson").exit_code, 0);
}

}  // namespace
}  // namespace swath::test
