// swath plan on other inputs than GeoJSON in metres: a shapefile in the Swiss grid, ground from
// a DEM (metres and feet), and swath batch over a district's areas, checked from the files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cli_runner.hpp"
#include "swath/base/number_text.hpp"

namespace swath::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// Every number of a JSON document by its path.
void numbers(const nlohmann::json& j, const std::string& path, std::map<std::string, double>& out) {
  if (j.is_object())
    for (const auto& [k, v] : j.items()) numbers(v, path + "." + k, out);
  else if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i)
      numbers(j[i], path + "[" + std::to_string(i) + "]", out);
  else if (j.is_number())
    out[path] = j.get<double>();
}

TEST(PlanCli, AShapefileInTheSwissGridPlansAsItsGeoJson) {
  const std::string dir = fresh_dir("plan-ogr");
  fs::create_directories(dir);
  const std::string shp = dir + "/meadow-2056.shp";
  ASSERT_EQ(run_program("ogr2ogr", "-f 'ESRI Shapefile' -t_srs EPSG:2056 " + shp +
                                       " share/fields/meadow.geojson")
                .exit_code,
            0);
  const std::string args = " --camera sony-ilce-qx1 --altitude 60 -o ";
  ASSERT_EQ(run_swath("plan share/fields/meadow.geojson" + args + dir + "/geojson").exit_code, 0);
  const CliRun run = run_swath("plan " + shp + args + dir + "/shp");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::map<std::string, double> a, b;
  numbers(nlohmann::json::parse(read_text(dir + "/geojson/summary.json")), "", a);
  numbers(nlohmann::json::parse(read_text(dir + "/shp/summary.json")), "", b);
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [key, value] : a) {
    // The home is the field's first vertex: back from the Swiss grid within 1e-7 degrees.
    const double tolerance =
        key.find("_deg") != std::string::npos ? 1e-7 : 1e-6 * std::max(1.0, std::abs(value));
    EXPECT_NEAR(b.at(key), value, tolerance) << key;
  }
  // Before GDAL, the same file as GeoJSON in EPSG:2056 read "latitude 1248000 is beyond ±90".
  const std::string swiss = dir + "/meadow-2056.geojson";
  ASSERT_EQ(run_program("ogr2ogr", "-f GeoJSON -lco RFC7946=NO -t_srs EPSG:2056 " + swiss +
                                       " share/fields/meadow.geojson")
                .exit_code,
            0);
  const CliRun c = run_swath("classify " + swiss);
  EXPECT_EQ(c.exit_code, 0) << c.err;
  EXPECT_NE(c.out.find("100694.3"), std::string::npos) << c.out;
}

// An ESRI ASCII grid in longitude/latitude, read here independently of GDAL, bilinear between
// cell centres as docs/swath-plan.md defines the DEM's surface.
struct AsciiGrid {
  int cols = 0, rows = 0;
  double x0 = 0, y0 = 0, cell = 0;
  std::vector<double> z;
  explicit AsciiGrid(const std::string& path) {
    std::istringstream in(read_text(path));
    std::string key;
    double nodata = 0;
    in >> key >> cols >> key >> rows >> key >> x0 >> key >> y0 >> key >> cell >> key >> nodata;
    z.resize(static_cast<std::size_t>(cols * rows));
    for (double& v : z) in >> v;
  }
  double at(double lat, double lon) const {
    const double u = (lon - x0) / cell - 0.5, v = (y0 + rows * cell - lat) / cell - 0.5;
    const int i = static_cast<int>(std::floor(u)), j = static_cast<int>(std::floor(v));
    auto px = [&](int a, int b) {
      return z[static_cast<std::size_t>(std::clamp(b, 0, rows - 1) * cols +
                                        std::clamp(a, 0, cols - 1))];
    };
    const double fu = u - i, fv = v - j;
    return (1 - fv) * ((1 - fu) * px(i, j) + fu * px(i + 1, j)) +
           fv * ((1 - fu) * px(i, j + 1) + fu * px(i + 1, j + 1));
  }
};

TEST(PlanCli, OverTheMeadowHillEveryWaypointIsSixtyMetresAboveTheGround) {
  const std::string out = fresh_dir("plan-terrain");
  const CliRun run = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 --terrain "
      "share/dems/meadow-hill.asc --altitude-frame amsl --litchi -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const AsciiGrid dem(source_path("share/dems/meadow-hill.asc"));
  const json plan = json::parse(read_text(out + "/drone-1.plan"));
  EXPECT_EQ(plan["mission"]["globalPlanAltitudeMode"], 2);
  const json home = plan["mission"]["plannedHomePosition"];
  const double home_ground = dem.at(home[0], home[1]);
  EXPECT_NEAR(home[2].get<double>(), home_ground, 0.01);
  int waypoints = 0;
  for (const json& item : plan["mission"]["items"]) {
    if (item["command"] != 16) continue;
    ++waypoints;
    EXPECT_EQ(item["frame"], 0);  // MAV_FRAME_GLOBAL
    EXPECT_EQ(item["AltitudeMode"], 2);
    const double lat = item["params"][4], lon = item["params"][5];
    EXPECT_NEAR(item["Altitude"].get<double>() - dem.at(lat, lon), 60.0, 0.01);
    EXPECT_EQ(item["Altitude"], item["params"][6]);
  }
  const json t = json::parse(read_text(out + "/summary.json"))["terrain"];
  EXPECT_GT(t["waypoints_added"].get<int>(), 5);
  EXPECT_EQ(waypoints, 11 * 2 + t["waypoints_added"].get<int>());  // the lines' ends, and those
  EXPECT_GE(t["agl_min_m"].get<double>(), 58.0);
  EXPECT_LE(t["agl_max_m"].get<double>(), 62.0);
  EXPECT_LT(t["ground_min_m"].get<double>(), t["ground_max_m"].get<double>() - 30);
  // Litchi flies above the take-off point: the same points, less the home's ground.
  std::istringstream litchi(read_text(out + "/drone-1-litchi.csv"));
  std::string row;
  std::getline(litchi, row);
  int rows = 0;
  while (std::getline(litchi, row)) {
    std::istringstream cells(row);
    std::string lat, lon, alt;
    std::getline(cells, lat, ',');
    std::getline(cells, lon, ',');
    std::getline(cells, alt, ',');
    ++rows;
    EXPECT_NEAR(std::stod(alt) + home_ground - dem.at(std::stod(lat), std::stod(lon)), 60.0, 0.01);
  }
  EXPECT_EQ(rows, waypoints);
}

// In the terrain frame the .plan's heights are above the ground under each waypoint, the Litchi
// and DJI files' above the take-off point: swath's own check compared the two without the
// ground and refused its own files ("flies at 59.69 m above home, the .plan's at 60.00 m").
TEST(PlanCli, TheTerrainFrameAgreesWithItsLitchiAndDjiTwinsOverTheGround) {
  const std::string out = fresh_dir("plan-terrain-frame");
  const std::string dem = "share/dems/meadow-hill.asc";
  const CliRun run =
      run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 --terrain " +
                dem + " --altitude-frame terrain --litchi --dji -o " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const AsciiGrid grid(source_path(dem));
  const json home = json::parse(read_text(out + "/drone-1.plan"))["mission"]["plannedHomePosition"];
  const double home_ground = grid.at(home[0], home[1]);
  const auto rows = csv_rows(read_text(out + "/drone-1-litchi.csv"));
  ASSERT_GT(rows.size(), 20u);
  double least_m = 1e9, most_m = -1e9;  // the ground above home under the rows
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const double ground_m = grid.at(std::stod(rows[r][0]), std::stod(rows[r][1])) - home_ground;
    EXPECT_NEAR(std::stod(rows[r][2]) - ground_m, 60.0, 0.01) << "row " << r;
    least_m = std::min(least_m, ground_m);
    most_m = std::max(most_m, ground_m);
  }
  EXPECT_GT(most_m - least_m, 20.0);  // a hill: heights above home and above ground differ
  const CliRun verify = run_swath("verify " + out + " --terrain " + dem);
  EXPECT_EQ(verify.exit_code, 0) << verify.out;
  EXPECT_NE(verify.out.find("3 of 3 twin files"), std::string::npos) << verify.out;
  // Without the DEM the heights cannot be compared, and the report says so.
  const CliRun flat = run_swath("verify " + out);
  EXPECT_EQ(flat.exit_code, 0) << flat.out;
  EXPECT_NE(flat.out.find("heights in the terrain frame not compared: no DEM"), std::string::npos)
      << flat.out;
  // A Litchi row 5 cm off the ground-following height is a disagreement over the DEM.
  std::string csv = read_text(out + "/drone-1-litchi.csv");
  const std::size_t row_2 = csv.find('\n', csv.find('\n') + 1) + 1;
  const std::size_t alt = csv.find(',', csv.find(',', row_2) + 1) + 1;
  const double moved_m = std::stod(csv.substr(alt)) + 0.05;
  csv.replace(alt, csv.find(',', alt) - alt, base::fixed_text(moved_m, 3));
  std::ofstream(out + "/drone-1-litchi.csv") << csv;
  const CliRun moved = run_swath("verify " + out + " --terrain " + dem);
  EXPECT_EQ(moved.exit_code, 4) << moved.out;
  EXPECT_NE(moved.out.find("VIOLATION agreement: " + out + "/drone-1-litchi.csv differs from " +
                           out + "/drone-1.plan: waypoint 2 flies at"),
            std::string::npos)
      << moved.out;
}

// A 40 x 25 ESRI ASCII grid of 0.0001 deg pixels from lon 8.539, lat 47.396, each pixel's height
// `height_m`(column, row from the north).
std::string grid_dem(const std::function<int(int, int)>& height_m) {
  std::ostringstream out;
  out << "ncols 40\nnrows 25\nxllcorner 8.539\nyllcorner 47.396\ncellsize 0.0001\n"
         "NODATA_value -9999\n";
  for (int row = 0; row < 25; ++row) {
    for (int col = 0; col < 40; ++col) out << (col ? " " : "") << height_m(col, row);
    out << '\n';
  }
  return out.str();
}

// A ground of 400 m with a 100 m cliff between two columns of pixel centres (lon 8.54095 and
// 8.54105) and a 40 m one-pixel spike east of it (centre 47.39735, 8.54155).
std::string cliff_and_spike_dem() {
  return grid_dem([](int col, int row) {
    const bool spike = col == 25 && row == 11;
    return (col >= 20 ? 500 : 400) + (spike ? 40 : 0);
  });
}

// Every straight leg between two waypoints of a .plan in the relative frame, and its return to
// launch (straight home at the last waypoint's height), measured against the DEM every 5 cm: the
// least height above the ground.
double least_height_between_waypoints(const json& plan, const AsciiGrid& dem) {
  const json home = plan["mission"]["plannedHomePosition"];
  const double home_ground = dem.at(home[0], home[1]);
  double least_m = 1e9;
  const auto leg = [&](double lat0, double lon0, double z0, double lat1, double lon1, double z1) {
    const double length_m =
        std::hypot((lat1 - lat0) * 111'320.0, (lon1 - lon0) * 111'320.0 * std::cos(0.8272));
    const int n = std::max(1, static_cast<int>(std::ceil(length_m / 0.05)));
    for (int k = 0; k <= n; ++k) {
      const double t = static_cast<double>(k) / n;
      const double ground = dem.at(lat0 + t * (lat1 - lat0), lon0 + t * (lon1 - lon0));
      least_m = std::min(least_m, home_ground + z0 + t * (z1 - z0) - ground);
    }
  };
  const json* prev = nullptr;
  for (const json& item : plan["mission"]["items"]) {
    const json& p = item["params"];
    if (prev && item["command"] == 16)
      leg((*prev)["params"][4], (*prev)["params"][5], (*prev)["params"][6], p[4], p[5], p[6]);
    if (prev && item["command"] == 20)
      leg((*prev)["params"][4], (*prev)["params"][5], (*prev)["params"][6], home[0], home[1],
          (*prev)["params"][6]);
    if (item["command"] == 16) prev = &item;
  }
  return least_m;
}

// A field (from `field_west_lon_deg` to 8.5420 E, 47.3970 to 47.3976 N) planned at 12 m, lines
// east-west, from a home west of it (47.3973, 8.5395) following the ground of `dem_text`: in the
// fresh directory `name`, the DEM as dem.asc and the plan in out/.
struct TerrainCase {
  std::string dir;
  CliRun plan;
  std::string dem() const { return dir + "/dem.asc"; }
  json drone_plan() const { return json::parse(read_text(dir + "/out/drone-1.plan")); }
  CliRun verify() const { return run_swath("verify " + dir + "/out --terrain " + dem()); }
};

TerrainCase terrain_case(const std::string& name, const std::string& dem_text,
                         double field_west_lon_deg = 8.5400) {
  TerrainCase c{fresh_dir(name), {}};
  fs::create_directories(c.dir);
  std::ofstream(c.dem()) << dem_text;
  const std::string west = base::fixed_text(field_west_lon_deg, 4);
  std::ofstream(c.dir + "/field.geojson")
      << R"({"type": "Polygon", "coordinates": [[[)" << west << R"(, 47.3970], [8.5420, 47.3970], )"
      << R"([8.5420, 47.3976], [)" << west << R"(, 47.3976], [)" << west << R"(, 47.3970]]]})";
  c.plan = run_swath("plan " + c.dir +
                     "/field.geojson --camera sony-ilce-qx1 --altitude 12 --angle 90 "
                     "--home 47.3973,8.5395 --terrain " +
                     c.dem() + " -o " + c.dir + "/out");
  return c;
}

// Terrain following over a cliff and a spike: no straight leg between the waypoints passes lower
// than the height asked less the tolerance (10 m of 12, the default 2 m), measured here between
// the waypoints too; summary and verify report the same. Sampled every half pixel, the profile
// missed the cliff's top edge and a leg 11 m long crossed it 3 m inside the ground.
TEST(PlanCli, TerrainFollowingNeverDipsBelowTheToleranceOverACliffOrASpike) {
  const TerrainCase c = terrain_case("plan-terrain-cliff", cliff_and_spike_dem());
  ASSERT_EQ(c.plan.exit_code, 0) << c.plan.err;
  const double least_m = least_height_between_waypoints(c.drone_plan(), AsciiGrid(c.dem()));
  EXPECT_GE(least_m, 10.0 - 0.01);
  const json t = json::parse(read_text(c.dir + "/out/summary.json"))["terrain"];
  EXPECT_EQ(t["ground_min_m"].get<double>(), 400.0);
  EXPECT_GT(t["ground_max_m"].get<double>(), 530.0);  // a line over the spike, near its top
  EXPECT_GE(t["agl_min_m"].get<double>(), 10.0 - 0.01);
  EXPECT_LE(t["agl_min_m"].get<double>(), least_m + 0.01);  // the summary's least is the true one
  EXPECT_NE(c.plan.out.find(", " + std::to_string(t["waypoints_added"].get<int>()) +
                            " waypoints added, relative frame\n"),
            std::string::npos)
      << c.plan.out;
  const CliRun verify = c.verify();
  EXPECT_EQ(verify.exit_code, 0) << verify.out;
}

// The way home over terrain: a 30 m wall one pixel wide (centre lon 8.53985) between home and the
// field. ArduPilot's RTL flies straight home at the last waypoint's height, 12 m above the field,
// and went through the wall (the plan's check refused it, 18 m into the ground); the way home is
// now waypoints over the ground ending above home, then the RTL.
TEST(PlanCli, TheWayHomeFollowsTheGroundOverAWall) {
  const TerrainCase c = terrain_case(
      "plan-terrain-wall", grid_dem([](int col, int) { return col == 8 ? 430 : 400; }), 8.5405);
  ASSERT_EQ(c.plan.exit_code, 0) << c.plan.err;
  const json plan = c.drone_plan();
  EXPECT_GE(least_height_between_waypoints(plan, AsciiGrid(c.dem())), 10.0 - 0.01);
  const json& items = plan["mission"]["items"];
  ASSERT_EQ(items.back()["command"], 20);
  const json* last = nullptr;  // the last waypoint: above home, at the height asked
  for (const json& item : items)
    if (item["command"] == 16) last = &item;
  ASSERT_NE(last, nullptr);
  EXPECT_NEAR((*last)["params"][4].get<double>(), 47.3973, 1e-7);
  EXPECT_NEAR((*last)["params"][5].get<double>(), 8.5395, 1e-7);
  EXPECT_NEAR((*last)["params"][6].get<double>(), 12.0, 0.001);
  const CliRun verify = c.verify();
  EXPECT_EQ(verify.exit_code, 0) << verify.out;
}

// A QGroundControl .plan for ArduCopter without fences or rally points: `home` [lat, lon, alt],
// `altitude_mode` its globalPlanAltitudeMode (1 above home, 2 above mean sea level), `items`.
json qgc_plan(const json& home, int altitude_mode, const json& items) {
  return {{"fileType", "Plan"},
          {"groundStation", "QGroundControl"},
          {"version", 1},
          {"geoFence", {{"circles", json::array()}, {"polygons", json::array()}, {"version", 2}}},
          {"rallyPoints", {{"points", json::array()}, {"version", 2}}},
          {"mission",
           {{"cruiseSpeed", 5},
            {"firmwareType", 3},
            {"globalPlanAltitudeMode", altitude_mode},
            {"hoverSpeed", 5},
            {"plannedHomePosition", home},
            {"vehicleType", 2},
            {"version", 2},
            {"items", items}}}};
}

// Over a plane sloping up to the east, 2 m a pixel, the legs follow the ground as they are: only
// the way home gains a waypoint, above home, and the summary says so in the singular.
TEST(PlanCli, OneWaypointAddedIsSaidInTheSingular) {
  const TerrainCase c =
      terrain_case("plan-terrain-slope", grid_dem([](int col, int) { return 400 + 2 * col; }));
  ASSERT_EQ(c.plan.exit_code, 0) << c.plan.err;
  const json t = json::parse(read_text(c.dir + "/out/summary.json"))["terrain"];
  EXPECT_EQ(t["waypoints_added"], 1);
  EXPECT_NE(c.plan.out.find(" m flown, GSD 0.319 to 0.319 cm/px), 1 waypoint added, relative "
                            "frame\n"),
            std::string::npos)
      << c.plan.out;
}

// A hand-made leg across the cliff, 12 m above the ground at both ends (1.5 m beyond the pixel
// centres the cliff lies between), passes 2.3 m inside the ground at the cliff's top edge: verify
// --terrain names it. Sampled every half pixel (0, 5.25, 10.5 m) it was 12 m high everywhere.
TEST(VerifyCli, ALegIntoTheGroundBetweenTheDemsSamplesIsCaught) {
  const std::string dir = fresh_dir("verify-terrain-cliff");
  fs::create_directories(dir);
  std::ofstream(dir + "/cliff.asc") << cliff_and_spike_dem();
  const double lat = 47.3973, m_per_lon_deg = 111'320.0 * std::cos(lat * M_PI / 180);
  const double west = 8.54095 - 1.5 / m_per_lon_deg, east = 8.54105 + 1.5 / m_per_lon_deg;
  const json plan =
      qgc_plan({lat, 8.5395, 400.0}, 1,
               {qgc_item(22, 1, lat, 8.5395, 12), qgc_item(16, 2, lat, west, 12),
                qgc_item(16, 3, lat, east, 112), qgc_item(16, 4, lat + 0.0003, east, 112),
                qgc_item(16, 5, lat + 0.0003, west, 12), qgc_item(21, 6, lat, 8.5395, 0)});
  std::ofstream(dir + "/cliff.plan") << plan.dump();
  const CliRun run = run_swath("verify " + dir + "/cliff.plan --terrain " + dir + "/cliff.asc");
  EXPECT_EQ(run.exit_code, 4) << run.out;
  const std::string named = "VIOLATION ground: " + dir + "/cliff.plan: item 3 goes ";
  const std::size_t at = run.out.find(named);
  ASSERT_NE(at, std::string::npos) << run.out;
  EXPECT_NEAR(std::stod(run.out.substr(at + named.size())), 2.3, 0.1) << run.out;
  EXPECT_NE(run.out.find("at 47.3973000, 8.5410500 (lat, lon)"), std::string::npos) << run.out;
}

// A .plan of waypoints above mean sea level (frame 0) over a flat 400 m DEM: home altitude
// `home_m` in the file, every leg at `legs_m`.
json amsl_plan(double home_m, double legs_m) {
  const double lat = 47.3973;
  const int amsl = 0;  // MAV_FRAME_GLOBAL
  return qgc_plan(
      {lat, 8.5395, home_m}, 2,
      {qgc_item(22, 1, lat, 8.5395, legs_m, amsl), qgc_item(16, 2, lat, 8.5405, legs_m, amsl),
       qgc_item(16, 3, lat + 0.0003, 8.5405, legs_m, amsl), qgc_item(21, 4, lat, 8.5395, 0, amsl)});
}

// With a DEM, altitudes above sea level are measured against the DEM's ground, not against the
// file's home altitude: legs 20 m under the DEM behind a home altitude 40 m low passed ("lowest
// 20.0 m above the ground"), and right legs behind QGC's home altitude 0 flew "420 m above the
// ground" into the ceiling.
TEST(VerifyCli, AltitudesAboveSeaLevelAreMeasuredAgainstTheDemWhateverTheHomeAltitude) {
  const std::string dir = fresh_dir("verify-terrain-amsl");
  fs::create_directories(dir);
  std::ofstream(dir + "/flat.asc") << grid_dem([](int, int) { return 400; });
  std::ofstream(dir + "/under.plan") << amsl_plan(360, 380).dump();
  const CliRun under = run_swath("verify " + dir + "/under.plan --terrain " + dir + "/flat.asc");
  EXPECT_EQ(under.exit_code, 4) << under.out;
  const std::string named = "VIOLATION ground: " + dir + "/under.plan: item 3 goes ";
  const std::size_t at = under.out.find(named);
  ASSERT_NE(at, std::string::npos) << under.out;
  EXPECT_NEAR(std::stod(under.out.substr(at + named.size())), 20.0, 0.05) << under.out;
  EXPECT_NE(under.out.find("the home altitude 360.0 m differs from the DEM's ground at home, "
                           "400.0 m"),
            std::string::npos)
      << under.out;
  std::ofstream(dir + "/home0.plan") << amsl_plan(0, 420).dump();
  const CliRun home0 = run_swath("verify " + dir + "/home0.plan --terrain " + dir + "/flat.asc");
  EXPECT_EQ(home0.exit_code, 0) << home0.out;
  EXPECT_NE(home0.out.find("lowest 20.0 m above the ground"), std::string::npos) << home0.out;
  EXPECT_NE(home0.out.find("the home altitude 0.0 m differs"), std::string::npos) << home0.out;
}

// Terrain following lets legs down to --altitude less --terrain-tolerance above the ground: below
// the 5 m the plan's check demands, the option is refused before anything is planned (20 m less
// 30 m planned legs into the ground, then the check refused "item 25" naming no option).
TEST(PlanCli, ATerrainToleranceReachingBelowTheLeastHeightIsRefused) {
  const std::string dir = fresh_dir("plan-terrain-tolerance");
  fs::create_directories(dir);
  std::ofstream(dir + "/flat.asc") << grid_dem([](int, int) { return 400; });
  std::ofstream(dir + "/field.geojson")
      << R"({"type": "Polygon", "coordinates": [[[8.5405, 47.3970], [8.5420, 47.3970], )"
         R"([8.5420, 47.3976], [8.5405, 47.3976], [8.5405, 47.3970]]]})";
  const std::string args = "plan " + dir + "/field.geojson --camera sony-ilce-qx1 --altitude 20 " +
                           "--home 47.3973,8.5395 --terrain " + dir + "/flat.asc -o " + dir;
  const CliRun wide = run_swath(args + "/wide --terrain-tolerance 30");
  EXPECT_EQ(wide.exit_code, 2) << wide.err;
  EXPECT_NE(wide.err.find("--terrain-tolerance 30.0 m at an altitude of 20.0 m (--altitude) lets "
                          "legs pass -10.0 m above the ground, below the least 5.0 m: give at "
                          "most --terrain-tolerance 15.0 or a higher --altitude"),
            std::string::npos)
      << wide.err;
  EXPECT_FALSE(fs::exists(dir + "/wide"));
  EXPECT_EQ(run_swath(args + "/edge --terrain-tolerance 15").exit_code, 0);
}

// Litchi and DJI Pilot 2 take waypoints down to 200 m below the take-off point: a home on a
// 700 m plateau over a field at 400 m puts the lines 250 m below it at 50 m, refused (written).
TEST(PlanCli, LitchiAndDjiRefuseWaypointsMoreThan200MetresBelowTheTakeOff) {
  const std::string dir = fresh_dir("plan-terrain-deep");
  fs::create_directories(dir);
  std::ofstream(dir + "/deep.asc") << grid_dem([](int col, int) { return col < 5 ? 700 : 400; });
  std::ofstream(dir + "/field.geojson")
      << R"({"type": "Polygon", "coordinates": [[[8.5405, 47.3970], [8.5420, 47.3970], )"
         R"([8.5420, 47.3976], [8.5405, 47.3976], [8.5405, 47.3970]]]})";
  const std::string args = "plan " + dir + "/field.geojson --camera dji-mavic-3e --altitude 50 " +
                           "--home 47.3973,8.5392 --terrain " + dir + "/deep.asc -o " + dir;
  for (const auto& [flag, app] :
       {std::pair{"--litchi", "Litchi's"}, std::pair{"--dji", "DJI Pilot 2's"}}) {
    const CliRun run = run_swath(args + "/out " + flag);
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_NE(run.err.find(std::string(flag) + ": the altitude -250.0 m is below " + app +
                           " lowest waypoint, 200 m below the take-off point"),
              std::string::npos)
        << run.err;
    EXPECT_FALSE(fs::exists(dir + "/out"));
  }
  const CliRun plain = run_swath(args + "/plain");
  EXPECT_EQ(plain.exit_code, 0) << plain.err;
}

}  // namespace
}  // namespace swath::test

namespace swath::test {
namespace {

// Twelve fields near Zurich, the sixth a bow tie that `swath plan` refuses.
std::string district_geojson() {
  std::string out = "{\"type\": \"FeatureCollection\", \"features\": [\n";
  for (int i = 0; i < 12; ++i) {
    const double lon = 8.40 + 0.01 * (i % 4), lat = 47.30 + 0.008 * (i / 4);
    const double w = 0.0015 + 0.0002 * i, h = 0.001 + 0.0001 * (i % 3);
    std::vector<std::pair<double, double>> ring{
        {lon, lat}, {lon + w, lat}, {lon + w, lat + h}, {lon, lat + h}};
    if (i == 5) std::swap(ring[1], ring[2]);  // crosses itself
    std::string coords;
    for (const auto& [x, y] : ring)
      coords += "[" + base::shortest_text(x) + ", " + base::shortest_text(y) + "], ";
    coords +=
        "[" + base::shortest_text(ring[0].first) + ", " + base::shortest_text(ring[0].second) + "]";
    out += std::string(i ? ",\n" : "") +
           "{\"type\": \"Feature\", \"properties\": {\"name\": \"plot " + std::to_string(i) +
           "\"}, \"geometry\": {\"type\": \"Polygon\", \"coordinates\": [[" + coords + "]]}}";
  }
  return out + "\n]}\n";
}

TEST(BatchCli, EveryAreaPlannedAsAloneTheSameBytesForAnyJobsAndGnuParallel) {
  const std::string dir = fresh_dir("batch");
  fs::create_directories(dir);
  const std::string areas = dir + "/district.geojson";
  std::ofstream(areas) << district_geojson();
  const std::string opts = " --camera sony-ilce-qx1 --altitude 60";
  const CliRun one = run_swath("batch " + areas + " -o " + dir + "/one --jobs 1" + opts);
  EXPECT_EQ(one.exit_code, 3) << one.err;  // one area refused
  EXPECT_NE(one.out.find("11 of 12 areas planned"), std::string::npos) << one.out;
  ASSERT_EQ(run_swath("batch " + areas + " -o " + dir + "/two --jobs 2" + opts).exit_code, 3);
  const auto a = directory_files(dir + "/one"), b = directory_files(dir + "/two");
  EXPECT_EQ(a.size(), b.size());
  for (const auto& [path, bytes] : a) EXPECT_EQ(b.count(path) ? b.at(path) : "", bytes) << path;
  // batch.csv: each planned row is what `swath plan --feature i` alone gives.
  std::istringstream csv(a.at("batch.csv"));
  std::string line;
  std::getline(csv, line);
  int rows = 0, refused = 0;
  while (std::getline(csv, line)) {
    ++rows;
    if (line.find(",refused,") != std::string::npos) {
      ++refused;
      EXPECT_NE(line.find("plot 5"), std::string::npos) << line;
      EXPECT_NE(line.find("crosses itself"), std::string::npos) << line;
      continue;
    }
    if (rows % 4 != 1) continue;  // three of the planned ones, run alone
    const std::string index = std::to_string(rows - 1);
    const std::string alone = dir + "/alone-" + index;
    ASSERT_EQ(run_swath("plan " + areas + " --feature " + index + opts + " -o " + alone).exit_code,
              0);
    const std::string sub = "plot_" + index;
    EXPECT_EQ(read_text(alone + "/summary.json"), a.at(sub + "/summary.json")) << sub;
    const auto s = nlohmann::json::parse(read_text(alone + "/summary.json"));
    EXPECT_NE(line.find(base::fixed_text(s["drones"][0]["path_length_m"].get<double>(), 3)),
              std::string::npos)
        << line;
  }
  EXPECT_EQ(rows, 12);
  EXPECT_EQ(refused, 1);
  // --emit-jobs prints the command lines; GNU parallel runs them to the same files.
  const CliRun jobs = run_swath("batch " + areas + " -o " + dir + "/par --emit-jobs" + opts);
  ASSERT_EQ(jobs.exit_code, 0);
  EXPECT_EQ(jobs.err, "");
  // The batch's own --timeout-s does not reach them: the same lines, and a warning saying so.
  const CliRun timed =
      run_swath("batch " + areas + " -o " + dir + "/par --emit-jobs --timeout-s 5" + opts);
  EXPECT_EQ(timed.exit_code, 0);
  EXPECT_EQ(timed.out, jobs.out);
  EXPECT_NE(timed.err.find("warning: --timeout-s does not reach the command lines"),
            std::string::npos)
      << timed.err;
  std::ofstream(dir + "/jobs.txt") << jobs.out;
  const CliRun par = run_program("parallel", "-j2 --will-cite -a " + dir + "/jobs.txt");
  EXPECT_EQ(par.exit_code, 1) << par.err;  // parallel's exit code: how many jobs failed
  for (const auto& [path, bytes] : directory_files(dir + "/par"))
    EXPECT_EQ(a.count(path) ? a.at(path) : "", bytes) << path;
  std::size_t planned_files = 0;  // all but batch.csv, batch.geojson and the batch's manifest
  for (const auto& [path, bytes] : a) planned_files += path.find('/') != std::string::npos;
  EXPECT_EQ(directory_files(dir + "/par").size(), planned_files);
}

// --dem-units: the bundled hill written again in international feet and in US survey feet (each
// height divided by the exact factor, printed to 12 digits) plans to the same altitudes as the
// metres it came from: every .plan item within 1 mm, as written (AMSL frame: the DEM's heights
// themselves reach the file; written to the millimetre, so one rounding apart at most).
std::vector<double> plan_altitudes(const std::string& dir) {
  std::vector<double> out;
  const json plan = json::parse(read_text(dir + "/drone-1.plan"));
  out.push_back(plan["mission"]["plannedHomePosition"][2].get<double>());
  for (const json& item : plan["mission"]["items"])
    if (item["command"] == 16) out.push_back(item["Altitude"].get<double>());
  return out;
}

TEST(PlanCli, TheSameGroundInFeetPlansTheSameAltitudesAsInMetres) {
  const std::string dir = fresh_dir("dem-units");
  std::filesystem::create_directories(dir);
  const std::string metres = read_text(source_path("share/dems/meadow-hill.asc"));
  auto converted = [&](const std::string& name, double metres_per_unit) {
    std::istringstream in(metres);
    std::ofstream f(dir + "/" + name);
    std::string line;
    for (int header = 0; header < 6 && std::getline(in, line); ++header) f << line << '\n';
    while (std::getline(in, line)) {
      std::istringstream cells(line);
      const char* sep = "";
      for (double h; cells >> h; sep = " ") {
        char text[32];
        std::snprintf(text, sizeof text, "%.12g", h == -9999 ? h : h / metres_per_unit);
        f << sep << text;
      }
      f << '\n';
    }
    return dir + "/" + name;
  };
  const std::string ft = converted("hill-ft.asc", 0.3048);
  const std::string us_ft = converted("hill-us-ft.asc", 1200.0 / 3937.0);
  const std::string plan =
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 "
      "--altitude-frame amsl --terrain ";
  ASSERT_EQ(run_swath(plan + "share/dems/meadow-hill.asc -o " + dir + "/m").exit_code, 0);
  ASSERT_EQ(run_swath(plan + ft + " --dem-units ft -o " + dir + "/ft").exit_code, 0);
  ASSERT_EQ(run_swath(plan + us_ft + " --dem-units us-ft -o " + dir + "/us-ft").exit_code, 0);
  const std::vector<double> m = plan_altitudes(dir + "/m");
  ASSERT_GT(m.size(), 20u);
  EXPECT_GT(m[0], 300.0);  // above sea level, the hill's ground in it
  for (const std::string unit : {"ft", "us-ft"}) {
    const std::vector<double> other = plan_altitudes(dir + "/" + unit);
    ASSERT_EQ(other.size(), m.size()) << unit;
    for (std::size_t k = 0; k < m.size(); ++k)
      EXPECT_NEAR(other[k], m[k], 0.001 + 1e-9) << unit << k;
  }
  // Read as metres, the feet are another ground: the check can tell them apart.
  ASSERT_EQ(run_swath(plan + ft + " -o " + dir + "/ft-as-m").exit_code, 0);
  EXPECT_GT(plan_altitudes(dir + "/ft-as-m")[0], m[0] + 100.0);
}

}  // namespace
}  // namespace swath::test
