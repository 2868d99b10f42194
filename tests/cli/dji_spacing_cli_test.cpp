// swath plan --litchi --dji and DJI's waypoint spacing: DJI's waypoint missions (which Litchi
// flies on) take adjacent waypoints only 0.5 m to 2,000 m apart in three dimensions
// (DJIMutableWaypointMission addWaypoint). The written Litchi CSVs and the KMZs' waylines.wpml are
// read back here (libzip, pugixml) and every adjacent pair measured with this file's own distance;
// the cases are those that broke it: 3.2 km lines, slow-downs beside a zone, sorties cut beside a
// waypoint. Also several drones whose first leg is slowed (the DJI and Litchi flights flew out
// from home at the slow speed, minutes late, into the next drone's launch).
#include <gtest/gtest.h>
#include <pugixml.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../support/zip_entries.hpp"
#include "cli_runner.hpp"

namespace swath::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

struct Position {
  double lat_deg, lon_deg, alt_m;
};

// Distance in three dimensions, metres: the horizontal one in east and north metres about a's
// latitude by WGS84's radii of curvature there (under a millimetre off over 2 km), and the height.
double apart_m(const Position& a, const Position& b) {
  const double rad = M_PI / 180, e2 = 6.69437999014e-3, s = std::sin(a.lat_deg * rad);
  const double w = 1 - e2 * s * s;
  const double north_m_per_deg = 6378137.0 * (1 - e2) / std::pow(w, 1.5) * rad;
  const double east_m_per_deg = 6378137.0 / std::sqrt(w) * std::cos(a.lat_deg * rad) * rad;
  return std::hypot((b.lat_deg - a.lat_deg) * north_m_per_deg,
                    (b.lon_deg - a.lon_deg) * east_m_per_deg, b.alt_m - a.alt_m);
}

std::vector<Position> litchi_positions(const std::string& path) {
  const auto rows = csv_rows(read_text(path));
  std::map<std::string, std::size_t> column;
  for (std::size_t k = 0; k < rows.at(0).size(); ++k) column[rows[0][k]] = k;
  std::vector<Position> out;
  for (std::size_t r = 1; r < rows.size(); ++r)
    out.push_back({std::stod(rows[r].at(column.at("latitude"))),
                   std::stod(rows[r].at(column.at("longitude"))),
                   std::stod(rows[r].at(column.at("altitude(m)")))});
  return out;
}

std::string unzipped(const std::string& path, const char* entry) {
  const auto entries = zip_entries(read_text(path));
  const bool found = entries && entries->count(entry) == 1;
  EXPECT_TRUE(found) << path << " has no " << entry;
  return found ? entries->at(entry) : "";
}

std::vector<Position> kmz_positions(const std::string& path) {
  pugi::xml_document doc;
  const std::string wpml = unzipped(path, "wpmz/waylines.wpml");
  EXPECT_TRUE(doc.load_string(wpml.c_str())) << path;
  std::vector<Position> out;
  for (const auto& p : doc.child("kml").child("Document").child("Folder").children("Placemark")) {
    double lon = 0, lat = 0;
    EXPECT_EQ(std::sscanf(p.child("Point").child("coordinates").text().as_string(), "%lf,%lf", &lon,
                          &lat),
              2);
    out.push_back({lat, lon, p.child("wpml:executeHeight").text().as_double()});
  }
  return out;
}

std::vector<Position> plan_waypoints(const std::string& path) {
  std::vector<Position> out;
  const json plan = json::parse(read_text(path));
  for (const json& item : plan["mission"]["items"])
    if (item["command"] == 16)
      out.push_back({item["params"][4].get<double>(), item["params"][5].get<double>(),
                     item["params"][6].get<double>()});
  return out;
}

// Adjacent pairs outside [lo, hi] m, and the count of pairs.
struct Spacing {
  std::size_t pairs = 0, outside = 0;
  double least_m = 1e18, most_m = 0;
};

void measure(const std::vector<Position>& p, double lo_m, double hi_m, Spacing& s) {
  for (std::size_t k = 0; k + 1 < p.size(); ++k) {
    const double d = apart_m(p[k], p[k + 1]);
    ++s.pairs;
    s.outside += d < lo_m || d > hi_m;
    s.least_m = std::min(s.least_m, d);
    s.most_m = std::max(s.most_m, d);
  }
}

// Plans (the plan's own check on: exit 0) and measures every Litchi CSV and KMZ written, and the
// .plan files' waypoints on their own.
struct Planned {
  Spacing exports, plans;
  std::string out;
};

Planned plan_and_measure(const std::string& name, const std::string& args) {
  Planned p;
  p.out = fresh_dir("dji-spacing-" + name);
  const CliRun run = run_swath("plan " + args + " --litchi --dji -o " + p.out);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  if (!fs::is_directory(p.out)) return p;
  for (const auto& entry : fs::directory_iterator(p.out)) {
    const std::string path = entry.path().string(), ext = entry.path().extension().string();
    if (ext == ".csv" && path.find("-litchi") != std::string::npos)
      measure(litchi_positions(path), 0.5, 2000.0, p.exports);
    else if (ext == ".kmz")
      measure(kmz_positions(path), 0.5, 2000.0, p.exports);
    else if (ext == ".plan")
      measure(plan_waypoints(path), 0.5, 1e18, p.plans);
  }
  const CliRun verified = run_swath("verify " + p.out);
  EXPECT_EQ(verified.exit_code, 0) << verified.out;
  return p;
}

std::string write_area(const std::string& name, const std::string& polygon) {
  const std::string dir = fresh_dir("dji-spacing-in-" + name);
  fs::create_directories(dir);
  std::ofstream(dir + "/area.geojson")
      << R"({"type":"Polygon","coordinates":[[)" << polygon << "]]}";
  return dir + "/area.geojson";
}

// 3.2 km lines at 50 N: each written as two legs of 1.6 km, photos on both.
TEST(PlanCli, DjiAndLitchiLegsLongerThan2000MetresAreSplit) {
  const std::string area =
      write_area("long", "[10.0,50.0],[10.045,50.0],[10.045,50.006],[10.0,50.006],[10.0,50.0]");
  const Planned p = plan_and_measure(
      "long", area + " --camera dji-mavic-3e --altitude 120 --speed 10 --angle 90");
  EXPECT_GT(p.plans.most_m, 3000.0) << "the .plan flies legs over 2 km";
  EXPECT_GT(p.exports.pairs, 0u);
  EXPECT_EQ(p.exports.outside, 0u) << "longest " << p.exports.most_m << " m";
  // The rows that split a line keep its photos by distance going.
  const auto rows = csv_rows(read_text(p.out + "/drone-1-litchi.csv"));
  std::size_t photo_rows = 0;
  for (std::size_t r = 1; r < rows.size(); ++r) photo_rows += rows[r].back() != "-1";
  const std::size_t lines = 11;
  EXPECT_EQ(photo_rows, 2 * lines) << "each line flown as two photographing legs";
}

// Slow-downs before stops beside the pond: their points half a metre from the stop (0.499 m on
// the ellipsoid) and a line's end 5 cm from the next line's start are merged.
TEST(PlanCli, DjiAndLitchiPointsCloserThanHalfAMetreAreMerged) {
  const Planned p = plan_and_measure(
      "pond", source_path("share/fields/meadow.geojson") +
                  " --camera dji-mavic-3e --altitude 60 --speed 12 --turnaround 30 --exclude " +
                  source_path("share/zones/meadow-pond.geojson"));
  EXPECT_LT(p.plans.least_m, 0.5) << "the .plan has such points (ArduPilot's speed changes)";
  EXPECT_GT(p.exports.pairs, 0u);
  EXPECT_EQ(p.exports.outside, 0u) << "closest " << p.exports.least_m << " m";
}

// 69 sorties: cut by a bisection to the millimetre, two landed 0.4 mm before and 0.17 m after a
// waypoint, which every file of those sorties then held twice, so close.
TEST(PlanCli, SortiesAreNotCutBesideAWaypoint) {
  const std::string area =
      write_area("sorties",
                 "[10.000509377685518,45.818609892190686],[10.000052260775703,45.81925797479055],"
                 "[9.999157733186536,45.81958670864697],[9.99799664796953,45.8193473600595],"
                 "[9.997505678744687,45.81843520587916],[9.998107377903807,45.81781443895332],"
                 "[9.998925955957162,45.817551513827894],[10.000061636943116,45.818057182507744],"
                 "[10.000509377685518,45.818609892190686]");
  const Planned p = plan_and_measure("sorties", area +
                                                    " --camera micasense-rededge --altitude 5 "
                                                    "--speed 5 --sorties auto --endurance 300 "
                                                    "--crosshatch");
  EXPECT_TRUE(fs::exists(p.out + "/drone-1-60.plan")) << "the sorties";
  EXPECT_EQ(p.plans.outside, 0u) << "closest .plan waypoints " << p.plans.least_m << " m";
  EXPECT_EQ(p.exports.outside, 0u) << "closest " << p.exports.least_m << " m";
}

// Three drones from a home beside a small field, the first's first leg slowed for a stop beside
// the zone: its DJI and Litchi flights flew all the way out from home at 0.2 m/s, 1.7 min longer
// than its .plan, and met the second drone taking off. They now rise above home and fly out at
// the drone's speed, as the .plan does: the plan's own check and swath verify pass.
TEST(PlanCli, DjiAndLitchiFlightsOfSeveralDronesKeepTheirPlansTimes) {
  const std::string dir = fresh_dir("dji-spacing-in-drones");
  fs::create_directories(dir);
  std::ofstream(dir + "/area.geojson")
      << R"({"type":"Polygon","coordinates":[[[148.35161908445284,65.67090103000959],)"
      << R"([148.35141553023803,65.67093514075897],[148.35118474927083,65.67099605281891],)"
      << R"([148.35115992938125,65.67089412298222],[148.351225296226,65.67076663737956],)"
      << R"([148.35144239763727,65.67082022904117],[148.35161908445284,65.67090103000959]]]})";
  std::ofstream(dir + "/zone.geojson")
      << R"({"type":"Polygon","coordinates":[[[148.35130328479534,65.67089474719418],)"
      << R"([148.35128120009549,65.67090510054051],[148.35124487093714,65.67089936220117],)"
      << R"([148.35124884024773,65.67088501217327],[148.35128212709273,65.67088145660979],)"
      << R"([148.35130328479534,65.67089474719418]]]})";
  const Planned p = plan_and_measure(
      "drones", dir + "/area.geojson --camera dji-phantom-4-pro --altitude 60 --speed 3 " +
                    "--exclude " + dir + "/zone.geojson --drones 3 --home 65.6707448,148.3518294");
  EXPECT_TRUE(fs::exists(p.out + "/drone-3.kmz"));
  EXPECT_EQ(p.exports.outside, 0u) << "closest " << p.exports.least_m << " m";
  // The first drone's DJI flight starts above home, at the .plan's take-off altitude.
  const std::vector<Position> kmz = kmz_positions(p.out + "/drone-1.kmz");
  ASSERT_FALSE(kmz.empty());
  EXPECT_LT(apart_m(kmz.front(), {65.6707448, 148.3518294, 60.0}), 0.01);
}

}  // namespace
}  // namespace swath::test
