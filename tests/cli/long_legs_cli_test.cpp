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

#include <nlohmann/json.hpp>

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

// A 2.3 km field at 65 N with a 14 x 10 m hole 5.1 m south of the middle of an east-west line:
// the line's leg, written whole (its bow, 0.22 m, is below kMaxBow_m), bows south towards the
// hole on the track ArduPilot flies by more than the line keeps beyond the 5 m clearance, and
// the preflight check refused the plan ("comes within 4.88 m of hole 1"). Measured here from the
// written .waypoints alone: ArduPilot's track of every leg, under both its conversions (the mean
// latitude's cosine, the origin's), keeps the clearance from the hole as drawn.
TEST(LongLegs, ALongLineBesideAHoleAtSixtyFiveNorthKeepsTheClearanceOnArduPilotsTrack) {
  const std::string dir = fresh_dir("long-legs-hole");
  std::filesystem::create_directories(dir);
  const double south = 65.00021344, north = 65.0003032, west = 10.0243, east = 10.0245;
  std::ofstream(dir + "/field.geojson")
      << R"({"type":"Polygon","coordinates":[[[10.0,65.0],[10.04889,65.0],[10.04889,65.0036],)"
      << R"([10.0,65.0036],[10.0,65.0]],[[10.0243,65.00021344],[10.0245,65.00021344],)"
      << R"([10.0245,65.0003032],[10.0243,65.0003032],[10.0243,65.00021344]]]})";
  const CliRun run = run_swath("plan " + dir + "/field.geojson --camera dji-phantom-4-pro " +
                               "--altitude 60 --angle 90 -o " + dir + "/out");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::vector<LatLon> at = flown_positions(read_text(dir + "/out/drone-1.waypoints"));
  ASSERT_GT(at.size(), 10u);
  const LatLon home = at.front();
  // Metres from the hole (its edges parallels and meridians 14 and 10 m long).
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  double m_lat = 0, m_lon = 0;
  g.Inverse(south, west, south + 1e-4, west, m_lat);
  g.Inverse(south, west, south, west + 1e-4, m_lon);
  m_lat *= 1e4, m_lon *= 1e4;
  const auto from_hole_m = [&](LatLon p) {
    const double dy = std::max({south - p.lat, p.lat - north, 0.0}) * m_lat;
    const double dx = std::max({west - p.lon, p.lon - east, 0.0}) * m_lon;
    return std::hypot(dx, dy);
  };
  double least = 1e9;
  for (const bool mean_latitude : {true, false}) {
    const auto scale = [&](double lat) {
      return std::cos((mean_latitude ? (lat + home.lat) / 2 : home.lat) * kDeg);
    };
    for (std::size_t k = 0; k + 1 < at.size(); ++k) {
      const LatLon a{at[k].lat - home.lat, (at[k].lon - home.lon) * scale(at[k].lat)};
      const LatLon b{at[k + 1].lat - home.lat, (at[k + 1].lon - home.lon) * scale(at[k + 1].lat)};
      for (int i = 0; i <= 512; ++i) {
        const double t = i / 512.0;
        const double lat = home.lat + a.lat + (b.lat - a.lat) * t;
        const double east_deg = a.lon + (b.lon - a.lon) * t;
        least = std::min(least, from_hole_m({lat, home.lon + east_deg / scale(lat)}));
      }
    }
  }
  EXPECT_GE(least, 5.0 - 0.005);  // 1 mm for positions written, the rest for the test's models
  EXPECT_LT(least, 5.2);          // the line passes that close: the case meant
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

// Long edges are straight in longitude and latitude: as GeoJSON draws them (RFC 7946) and as
// ArduPilot and PX4 test fences. Measured here from the written .plan alone, in latitude and
// longitude, with the test's own tests (no frame of swath's).
namespace swath::test {
namespace {

struct PlanRead {
  std::vector<LatLon> waypoints;                          // home first, then every position
  std::vector<std::vector<LatLon>> inclusion, exclusion;  // geoFence polygons
};

PlanRead read_plan(const std::string& path) {
  const nlohmann::json plan = nlohmann::json::parse(read_text(path));
  PlanRead out;
  const auto& home = plan["mission"]["plannedHomePosition"];
  out.waypoints.push_back({home[0].get<double>(), home[1].get<double>()});
  for (const auto& item : plan["mission"]["items"])
    if (item.value("command", 0) == 16)
      out.waypoints.push_back({item["params"][4].get<double>(), item["params"][5].get<double>()});
  for (const auto& polygon : plan["geoFence"]["polygons"]) {
    std::vector<LatLon> ring;
    for (const auto& p : polygon["polygon"])
      ring.push_back({p[0].get<double>(), p[1].get<double>()});
    (polygon["inclusion"].get<bool>() ? out.inclusion : out.exclusion).push_back(ring);
  }
  return out;
}

// Ray casting in latitude and longitude, as AC_PolyFence_loader and PX4's geofence do.
bool inside_lat_lon(LatLon p, const std::vector<LatLon>& ring) {
  bool inside = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
    if ((ring[i].lat > p.lat) != (ring[j].lat > p.lat) &&
        p.lon < ring[j].lon + (ring[i].lon - ring[j].lon) * (p.lat - ring[j].lat) /
                                  (ring[i].lat - ring[j].lat))
      inside = !inside;
  return inside;
}

// Metres of latitude per degree at `lat_deg` on WGS84 (the meridian's radius of curvature).
double metres_per_degree_lat(double lat_deg) {
  const double a = 6378137.0, f = 1 / 298.257223563, e2 = f * (2 - f);
  const double s = std::sin(lat_deg * kDeg);
  return a * (1 - e2) / std::pow(1 - e2 * s * s, 1.5) * kDeg;
}

// A 600 m field at 65 N crossed by a 10 m no-fly corridor 4.7 km long along the parallel, two
// vertices a side: its long edges, parallels as drawn, bow 0.9 m north of the chord between
// their ends (the lines stopped 4.0 m from the zone, 5 m asked). Every leg keeps the clearance
// from the corridor as drawn, measured in latitude (its edges are parallels).
TEST(LongEdges, AThinZoneAtSixtyFiveNorthIsKeptClearAsDrawn) {
  const std::string dir = fresh_dir("long-edge-zone");
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/field.geojson")
      << R"({"type":"Polygon","coordinates":[[[9.993623,64.997306],[10.006377,64.997306],)"
      << R"([10.006377,65.002694],[9.993623,65.002694],[9.993623,64.997306]]]})";
  const double south = 64.999955034, north = 65.000044966, west = 9.95, east = 10.05;
  std::ofstream(dir + "/zone.geojson")
      << R"({"type":"Polygon","coordinates":[[[9.95,64.999955034],[10.05,64.999955034],)"
      << R"([10.05,65.000044966],[9.95,65.000044966],[9.95,64.999955034]]]})";
  const CliRun run =
      run_swath("plan " + dir + "/field.geojson --camera dji-phantom-4-pro " +
                "--altitude 60 --angle 0 --exclude " + dir + "/zone.geojson -o " + dir + "/out");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const PlanRead plan = read_plan(dir + "/out/drone-1.plan");
  ASSERT_GT(plan.waypoints.size(), 10u);
  const double m_per_deg = metres_per_degree_lat(65.0);
  const auto clearance_m = [&](LatLon p) {
    if (p.lon < west || p.lon > east) return 1e9;
    if (p.lat > south && p.lat < north) return 0.0;
    return std::min(std::abs(p.lat - south), std::abs(p.lat - north)) * m_per_deg;
  };
  double least = 1e9;
  for (std::size_t k = 0; k + 1 < plan.waypoints.size(); ++k) {
    const LatLon a = plan.waypoints[k], b = plan.waypoints[k + 1];
    least = std::min({least, clearance_m(a), clearance_m(b)});
    const bool crosses = (a.lat < south) != (b.lat < south) || (a.lat > north) != (b.lat > north);
    if (crosses && std::max(a.lon, b.lon) >= west && std::min(a.lon, b.lon) <= east) least = 0;
  }
  EXPECT_GE(least, 5.0 - 0.06);  // 5 cm for the edges followed, 1 cm for positions written
  // The exclusion fence holds the corridor as drawn where it bows most, in latitude and longitude.
  ASSERT_FALSE(plan.exclusion.empty());
  for (const LatLon p : {LatLon{south + 2e-7, 10.0}, LatLon{north - 2e-7, 10.0}})
    EXPECT_TRUE(std::any_of(plan.exclusion.begin(), plan.exclusion.end(),
                            [&](const auto& ring) { return inside_lat_lon(p, ring); }))
        << p.lat << "," << p.lon;
}

// A 300 m square and a home 87 km away: the inclusion fence's 86 km edges, written with two
// vertices, bowed 40 m across the route in latitude and longitude. Every waypoint lies inside the
// written fence as the autopilot tests it.
TEST(LongEdges, AFarHomesRouteStaysInsideItsFenceInLatitudeAndLongitude) {
  const std::string dir = fresh_dir("long-edge-fence");
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/field.geojson")
      << R"({"type":"Polygon","coordinates":[[[-0.007982031,47.107651018],)"
      << R"([-0.004017969,47.107651018],[-0.004017969,47.110348982],)"
      << R"([-0.007982031,47.110348982],[-0.007982031,47.107651018]]]})";
  for (const std::string firmware : {"ardupilot", "px4"}) {
    const CliRun run = run_swath("plan " + dir + "/field.geojson --camera parrot-sequoia-rgb " +
                                 "--altitude 120 --home 47.181121612,1.129817403 --far-home " +
                                 "--firmware " + firmware + " -o " + dir + "/" + firmware);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const PlanRead plan = read_plan(dir + "/" + firmware + "/drone-1.plan");
    ASSERT_EQ(plan.inclusion.size(), 1u);
    ASSERT_GT(plan.waypoints.size(), 20u);
    std::size_t outside = 0;
    for (const LatLon& p : plan.waypoints) outside += !inside_lat_lon(p, plan.inclusion.front());
    EXPECT_EQ(outside, 0u) << firmware;
  }
}

// A .plan the planner wrote before fences followed their long edges (trimmed to its way home):
// its waypoints lie inside the chords of the fence's 86 km edges, up to 40 m outside the fence
// ArduPilot tests. swath verify reads the fence's edges as the autopilot does and refuses it.
TEST(LongEdges, VerifyRefusesWaypointsOutsideAFencesLongEdgesInLatitudeAndLongitude) {
  const std::string dir = fresh_dir("long-edge-verify");
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(source_path("tests/fixtures/farhome-old.plan"), dir + "/drone-1.plan");
  const CliRun run = run_swath("verify " + dir + "/drone-1.plan");
  EXPECT_EQ(run.exit_code, 4) << run.out << run.err;
  const std::size_t at = run.out.find("m outside the inclusion fence");
  ASSERT_NE(at, std::string::npos) << run.out;
  const std::size_t figure = run.out.find("reaches ");
  ASSERT_NE(figure, std::string::npos) << run.out;
  EXPECT_GT(std::stod(run.out.substr(figure + 8)), 30.0) << run.out;
}

}  // namespace
}  // namespace swath::test
