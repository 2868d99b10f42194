// swath plan's flights as other programs and several drones fly them: Litchi and DJI exports per
// sortie and their split parts, sorties and PX4 fleets of several drones, and the maps' heights and
// legs (docs/swath-plan.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace swath::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

TEST(PlanCli, ExportsPerSortieAndAWarningForACameraWithoutDjiEnums) {
  const std::string out = fresh_dir("exports-sorties");
  const CliRun run = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 40 --sorties "
      "auto --endurance 420 --litchi --dji -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("swath plan: warning: --dji: the camera 'Sony ILCE-QX1' has no DJI enums"),
            std::string::npos)
      << run.err;
  for (int k = 1; k <= 8; ++k) {
    const std::string stem = out + "/drone-1-" + std::to_string(k);
    EXPECT_TRUE(fs::exists(stem + ".kmz")) << k;
    EXPECT_TRUE(fs::exists(stem + "-litchi.csv")) << k;
  }
}

// A flight above Litchi's 99 waypoints is cut where each part's way home from its last row, and
// back out to it, keeps the clearance from a no-fly zone (Litchi flies both straight), and a
// stop's slower approach is carried into the rows: rectangles with a square hole whose cuts at
// the 99th row flew home through the hole, or overran a stop beside it, are planned, and each
// part's way home is measured here from the written rows. (800 x 300 at 40 m, 101 waypoints, now
// fits one file: its slow-downs' points half a metre apart are merged for DJI's spacing.)
TEST(PlanCli, LitchiPartsEndWhereTheWayHomeIsClear) {
  struct Field {
    double width_m, height_m, hole_x, altitude_m;
  };
  const double lat0 = 47.0, lon0 = 8.0, half_m = 40.0, clearance_m = 5.0;
  const double m_per_deg_lat = 111132.0, m_per_deg_lon = 111320.0 * std::cos(lat0 * M_PI / 180);
  for (const Field& f :
       {Field{600, 300, 0.7, 30}, Field{800, 400, 0.5, 30}, Field{800, 300, 0.3, 38}}) {
    SCOPED_TRACE(std::to_string(f.width_m) + " x " + std::to_string(f.height_m));
    const double cx = f.width_m * f.hole_x, cy = f.height_m / 2;
    const auto lon_lat = [&](double x, double y) {
      std::ostringstream o;
      o.precision(12);
      o << "[" << lon0 + x / m_per_deg_lon << "," << lat0 + y / m_per_deg_lat << "]";
      return o.str();
    };
    const std::string field = fresh_dir("litchi-cut") + ".geojson";
    std::ofstream(field) << R"({"type":"Polygon","coordinates":[[)" << lon_lat(0, 0) << ","
                         << lon_lat(f.width_m, 0) << "," << lon_lat(f.width_m, f.height_m) << ","
                         << lon_lat(0, f.height_m) << "," << lon_lat(0, 0) << "],["
                         << lon_lat(cx - half_m, cy - half_m) << ","
                         << lon_lat(cx - half_m, cy + half_m) << ","
                         << lon_lat(cx + half_m, cy + half_m) << ","
                         << lon_lat(cx + half_m, cy - half_m) << ","
                         << lon_lat(cx - half_m, cy - half_m) << "]]}";
    const std::string out = fresh_dir("litchi-cut-out");
    const CliRun run = run_swath("plan " + field + " --camera dji-mavic-3e --altitude " +
                                 std::to_string(f.altitude_m) + " --litchi -o " + out);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const json plan = json::parse(read_text(out + "/drone-1.plan"));
    const json& home_ll = plan["mission"]["plannedHomePosition"];
    const auto local = [&](double lat, double lon) {
      return std::pair{(lon - lon0) * m_per_deg_lon, (lat - lat0) * m_per_deg_lat};
    };
    const auto home = local(home_ll[0].get<double>(), home_ll[1].get<double>());
    // Least distance from the segment a-b to the hole (a square: outside it, the distance to
    // the box; 0 where the segment enters it), sampled every 5 cm.
    const auto to_hole_m = [&](std::pair<double, double> a, std::pair<double, double> b) {
      double least = 1e9;
      const double length = std::hypot(b.first - a.first, b.second - a.second);
      const int n = std::max(1, int(length / 0.05));
      for (int k = 0; k <= n; ++k) {
        const double x = a.first + (b.first - a.first) * k / n;
        const double y = a.second + (b.second - a.second) * k / n;
        const double dx = std::max(std::abs(x - cx) - half_m, 0.0);
        const double dy = std::max(std::abs(y - cy) - half_m, 0.0);
        least = std::min(least, std::hypot(dx, dy));
      }
      return least;
    };
    int parts = 0;
    std::pair<double, double> last_end{};
    for (int k = 1; fs::exists(out + "/drone-1-litchi-" + std::to_string(k) + ".csv"); ++k) {
      std::istringstream csv(read_text(out + "/drone-1-litchi-" + std::to_string(k) + ".csv"));
      std::string line;
      std::getline(csv, line);  // the header
      std::vector<std::pair<double, double>> rows;
      while (std::getline(csv, line)) {
        double lat = 0, lon = 0;
        ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf", &lat, &lon), 2) << line;
        rows.push_back(local(lat, lon));
      }
      ASSERT_LE(rows.size(), 99u) << k;
      if (k > 1) {  // each part starts where the one before ended
        EXPECT_NEAR(rows.front().first, last_end.first, 1e-3) << k;
        EXPECT_NEAR(rows.front().second, last_end.second, 1e-3) << k;
      }
      EXPECT_GE(to_hole_m(rows.back(), home), clearance_m - 0.01) << "part " << k;
      last_end = rows.back();
      ++parts;
    }
    EXPECT_GE(parts, 2) << "a flight of more than 99 waypoints";
  }
}

// The least separation `swath verify DIR` finds between two drones in the air at once (-1 when
// the check did not run).
double verified_separation_m(const std::string& dir) {
  const CliRun run = run_swath("verify " + dir + " --json");
  EXPECT_EQ(run.exit_code, 0) << run.out;
  const json report = json::parse(run.out);
  for (const json& c : report["checks"])
    if (c["check"] == "separation" && c["ran"].get<bool>()) return c["value"].get<double>();
  return -1;
}

TEST(PlanCli, SortiesOfDronesSharingAHomeAreStaggered) {
  // docs/safety-notes.md: each sortie launched at its own time, after the one before it landed
  // and 2 min for the battery change, its climb and descent at home missing the lower layer's drone
  // there.
  const std::string out = fresh_dir("sorties-shared-home");
  const CliRun run = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 40 --sorties auto "
      "--endurance 420 --drones 2 -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  ASSERT_EQ(s["drones"].size(), 2u);
  for (const json& d : s["drones"]) {
    const json& sorties = d["sorties"];
    ASSERT_GE(sorties.size(), 2u);
    EXPECT_EQ(d["launch_offset_s"], sorties[0]["launch_offset_s"]);
    for (std::size_t k = 1; k < sorties.size(); ++k)
      EXPECT_GE(sorties[k]["launch_offset_s"].get<double>(),
                sorties[k - 1]["launch_offset_s"].get<double>() +
                    sorties[k - 1]["flight_time_s"].get<double>() + 120.0)
          << d["name"] << " sortie " << k + 1;
  }
  // The upper drone flies beside the lower one, not after all its sorties.
  const double upper_s = s["drones"][1]["sorties"][0]["launch_offset_s"].get<double>();
  EXPECT_GT(upper_s, 0.0);
  EXPECT_LT(upper_s, s["drones"][0]["sorties"].back()["launch_offset_s"].get<double>());
  EXPECT_NE(run.out.find("sortie 2"), std::string::npos);
  EXPECT_GE(verified_separation_m(out), 10.0);
}

// The seconds after the first launch at which `swath verify DIR` flies `file` (its "flight"
// figure).
double verified_launch_s(const json& report, const std::string& file) {
  for (const json& c : report["checks"]) {
    if (c["check"] != "flight") continue;
    const std::string text = c["text"].get<std::string>();
    const std::size_t at = text.find("/" + file + " ");
    if (at == std::string::npos) return -1;
    const std::size_t t = text.find("from t = ", at);
    return std::stod(text.substr(t + 9));
  }
  return -1;
}

// Two drones of 12 sorties each from one home: swath verify flies each sortie at summary.json's
// launch time, after the one numbered before it (a directory lists drone-1-10.plan before
// drone-1-2.plan: sortie 2 was flown after sortie 12, at home as drone-2's sortie 2 launched
// there, and verify refused what swath plan wrote).
TEST(PlanCli, VerifyFliesSortiesInTheirOrderNotTheDirectorysOrder) {
  const std::string dir = fresh_dir("sorties-in-order");
  fs::create_directories(dir);
  std::ofstream(dir + "/field.geojson")
      << R"({"type":"Polygon","coordinates":[[[8.0,47.0],[8.006,47.0],[8.006,47.004],)"
      << R"([8.0,47.004],[8.0,47.0]]]})";
  const CliRun run = run_swath("plan " + dir +
                               "/field.geojson --camera sentera-6x --altitude 50 --home "
                               "47.002,8.003 --drones 2 --sorties auto --endurance 360 -o " +
                               dir + "/out");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(dir + "/out/summary.json"));
  const CliRun verified = run_swath("verify " + dir + "/out --json");
  EXPECT_EQ(verified.exit_code, 0) << verified.out;
  const json report = json::parse(verified.out);
  for (const json& d : s["drones"]) {
    ASSERT_GE(d["sorties"].size(), 10u) << d["name"];
    for (const json& sortie : d["sorties"])
      EXPECT_NEAR(verified_launch_s(report, sortie["file"].get<std::string>() + ".plan"),
                  sortie["launch_offset_s"].get<double>(), 0.51)
          << sortie["file"];
  }
}

// A cut in a line's 40 m turnaround beyond the area leaves the next flight a stub of the line
// outside the area, flown with the camera off (it was left triggering: swath verify --area refused
// "a transit outside the area"): three drones' division over a narrow point of a field, and one
// drone's sorties over a square.
TEST(PlanCli, AStubOfALineOutsideTheAreaIsATransit) {
  struct Case {
    std::string field, options;
  };
  const std::vector<Case> cases{
      {R"({"type":"Polygon","coordinates":[[[0.000293851,0.006043726],)"
       R"([-0.001713716,0.005131289],[-0.001589737,0.004858509],[0.000145049,0.005646968],)"
       R"([0.001248188,0.003219814],[0.001520968,0.003343793],[0.000293851,0.006043726]]]})",
       "--drones 3"},
      {R"({"type":"Polygon","coordinates":[[[7.997362689,46.998201358],[8.002637311,46.998201358],)"
       R"([8.002637311,47.001798642],[7.997362689,47.001798642],[7.997362689,46.998201358]]]})",
       "--sorties auto --endurance 400"}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.options);
    const std::string dir = fresh_dir("stub-outside-area");
    fs::create_directories(dir);
    std::ofstream(dir + "/field.geojson") << c.field;
    const CliRun run = run_swath("plan " + dir +
                                 "/field.geojson --camera dji-mavic-3e --altitude 80 --turnaround "
                                 "40 " +
                                 c.options + " -o " + dir + "/out");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const CliRun verified = run_swath("verify " + dir + "/out --area " + dir + "/field.geojson");
    EXPECT_EQ(verified.exit_code, 0) << verified.out;
    EXPECT_NE(verified.out.find(" 0 in transits"), std::string::npos) << verified.out;
  }
}

// Drones at homes 700 m apart never wait for each other at home: each drone's next sortie then
// launches as soon as its last has landed (by the estimate and its slack) and the pilot has had
// the 2 min docs/safety-notes.md gives for the battery change.
TEST(PlanCli, SortiesWaitForTheBatteryChange) {
  const std::string dir = fresh_dir("sorties-battery-change");
  fs::create_directories(dir);
  std::ofstream(dir + "/fleet.yaml")
      << "home: {lat: 47.3960, lon: 8.5380}\ndrones:\n"
         "  - {name: a, endurance_s: 420, battery_level: 1.0, speed_m_s: 5}\n"
         "  - {name: b, endurance_s: 420, battery_level: 1.0, speed_m_s: 5,"
         " home: {lat: 47.3990, lon: 8.5460}}\n";
  const CliRun run = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 40 --sorties auto "
      "--fleet " +
      dir + "/fleet.yaml -o " + dir + "/out");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(dir + "/out/summary.json"));
  for (const json& d : s["drones"]) {
    const json& sorties = d["sorties"];
    ASSERT_GE(sorties.size(), 2u);
    for (std::size_t k = 1; k < sorties.size(); ++k)
      EXPECT_GE(sorties[k]["launch_offset_s"].get<double>() -
                    sorties[k - 1]["launch_offset_s"].get<double>() -
                    sorties[k - 1]["flight_time_s"].get<double>(),
                120.0)
          << d["name"] << " sortie " << k + 1;
  }
  EXPECT_GE(verified_separation_m(dir + "/out"), 10.0);
}

TEST(PlanCli, Px4FleetsLandAtHomeInsteadOfClimbingToTheReturnAltitude) {
  // A notched strip at 75 N: the three drones' layers reach 60 m, PX4's RTL_RETURN_ALT, over a
  // home another drone returns to.
  const std::string dir = fresh_dir("px4-fleet");
  fs::create_directories(dir);
  std::ofstream(dir + "/w75.geojson")
      << R"({"type":"Polygon","coordinates":[[[30.0,75.0],[30.086499187,75.0],)"
         R"([30.086499187,75.003583639],[30.044979577,75.003583639],[30.043249593,75.001343865],)"
         R"([30.04151961,75.003583639],[30.0,75.003583639],[30.0,75.0]]]})";
  const std::string args = "plan " + dir +
                           "/w75.geojson --camera dji-phantom-4-pro --altitude 40 --drones 3 "
                           "--division region -o ";
  const CliRun run = run_swath(args + dir + "/px4 --firmware px4");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(dir + "/px4/summary.json"));
  EXPECT_EQ(s["flight"]["end"], "land");
  for (int i = 1; i <= 3; ++i) {
    const json plan =
        json::parse(read_text(dir + "/px4/drone-" + std::to_string(i) + ".plan"))["mission"];
    const json& items = plan["items"];
    EXPECT_EQ(items.back()["command"], 21) << i;  // NAV_LAND at home, no RTL
    EXPECT_NEAR(items.back()["params"][4].get<double>(), plan["plannedHomePosition"][0], 1e-9);
    EXPECT_NEAR(items.back()["params"][5].get<double>(), plan["plannedHomePosition"][1], 1e-9);
  }
  EXPECT_GE(verified_separation_m(dir + "/px4"), 10.0);
  // ArduPilot's RTL keeps the layer's altitude: its files still return to launch.
  ASSERT_EQ(run_swath(args + dir + "/ap").exit_code, 0);
  const json ap = json::parse(read_text(dir + "/ap/drone-1.plan"));
  EXPECT_EQ(ap["mission"]["items"].back()["command"], 20);
  // A plane's landing needs its approach: PX4 fixed wings of a fleet keep their RTL.
  ASSERT_EQ(run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 "
                      "--vehicle fixedwing --firmware px4 --drones 2 -o " +
                      dir + "/px4-plane")
                .exit_code,
            0);
  const json plane = json::parse(read_text(dir + "/px4-plane/drone-1.plan"));
  EXPECT_EQ(plane["mission"]["items"].back()["command"], 20);
}

// The heights (third numbers) of a drone's path in mission.kml, its Placemark named `name`.
std::vector<double> kml_path_heights(const std::string& kml, const std::string& name) {
  const std::size_t at = kml.find("<name>" + name + "</name>");
  const std::size_t from = kml.find("<coordinates>", at) + 13;
  std::istringstream in(kml.substr(from, kml.find("</coordinates>", from) - from));
  std::vector<double> out;
  for (std::string point; in >> point;)
    out.push_back(std::stod(point.substr(point.rfind(',') + 1)));
  return out;
}

// The maps draw each drone's path at the height its mission flies: bravo and charlie fly their
// altitude layers (70 and 80 m), which mission.kml and mission.geojson gave as 60 m.
TEST(PlanCli, MapsDrawEachDronesPathAtItsOwnAltitude) {
  const std::string out = fresh_dir("maps-layers");
  const CliRun run = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 --fleet "
      "share/fleets/three-quads.yaml --division region -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json g = json::parse(read_text(out + "/mission.geojson"));
  const std::string kml = read_text(out + "/mission.kml");
  std::set<double> flown_m;
  for (const json& f : g["features"]) {
    if (f["properties"]["role"] != "path") continue;
    const std::string name = f["properties"]["name"];
    const json plan = json::parse(read_text(out + "/" + name + ".plan"));
    double waypoint_m = -1;  // the altitude of the .plan's waypoints (NAV_WAYPOINT, 16)
    for (const json& item : plan["mission"]["items"])
      if (item["command"] == 16) waypoint_m = item["params"][6].get<double>();
    flown_m.insert(waypoint_m);
    EXPECT_DOUBLE_EQ(f["properties"]["altitude_m"].get<double>(), waypoint_m) << name;
    const int drone = f["properties"]["drone"];
    for (double h : kml_path_heights(kml, "Drone " + std::to_string(drone) + " " + name + " path"))
      EXPECT_DOUBLE_EQ(h, waypoint_m) << name;
  }
  EXPECT_EQ(flown_m, (std::set<double>{60.0, 70.0, 80.0}));
}

// With sorties the map path is what the drone flies: each sortie from home to its resume point
// and back home from its cut point (the uncut flight left those legs out: home at its two ends
// only).
TEST(PlanCli, MapsDrawEverySortiesLegsHomeAndBack) {
  const std::string out = fresh_dir("maps-sorties");
  const CliRun run = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 40 --sorties auto "
      "--endurance 420 -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  const std::size_t sorties = s["drones"][0]["sorties"].size();
  ASSERT_GT(sorties, 2u);
  const double home_lat = s["home"]["lat_deg"], home_lon = s["home"]["lon_deg"];
  const json g = json::parse(read_text(out + "/mission.geojson"));
  std::size_t at_home = 0, paths = 0, points = 0;
  for (const json& f : g["features"]) {
    if (f["properties"]["role"] != "path") continue;
    ++paths;
    points = f["geometry"]["coordinates"].size();
    for (const json& p : f["geometry"]["coordinates"])
      at_home += std::abs(p[1].get<double>() - home_lat) < 1e-7 &&
                 std::abs(p[0].get<double>() - home_lon) < 1e-7;
  }
  EXPECT_EQ(paths, 1u);
  EXPECT_EQ(at_home, sorties + 1);  // out and back, the landings and take-offs between counted once
  const std::string kml = read_text(out + "/mission.kml");
  EXPECT_EQ(kml_path_heights(kml, "Drone 1 path").size(), points);  // the same path
}

}  // namespace
}  // namespace swath::test
