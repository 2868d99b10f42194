// `swath plan` and `swath cameras` as a user runs them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
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

const std::vector<std::string> kFiles{"mission.geojson",   "summary.json",  "drone-1.plan",
                                      "drone-1.waypoints", "waypoints.csv", "mission.kml",
                                      "photos.geojson",    "photos.csv"};

std::size_t entries(const std::string& dir) {
  std::error_code ec;
  std::size_t n = 0;
  // swath's own manifest of the set (.swath-plan.files) is not one of the files.
  for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator(); ++it)
    n += it->path().filename().string().rfind(".swath-", 0) != 0;
  return n;
}

TEST(PlanCli, MeadowWritesEveryFileAndReportsFullCoverage) {
  const std::string out = fresh_dir("meadow");
  const CliRun run =
      run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 80 -o " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");
  EXPECT_EQ(entries(out), kFiles.size()) << "exactly the eight files, no temporaries";
  for (const std::string& f : kFiles) EXPECT_FALSE(read_text(out + "/" + f).empty()) << f;
  const json s = json::parse(read_text(out + "/summary.json"));
  EXPECT_EQ(s["area"]["type"], "convex");
  EXPECT_DOUBLE_EQ(s["camera"]["altitude_m"].get<double>(), 80.0);
  EXPECT_NEAR(s["camera"]["line_spacing_m"].get<double>(), 23.2 * 80 / 16 * 0.3, 1e-4);
  EXPECT_GE(s["coverage"]["covered_fraction"].get<double>(), 0.9999);
  EXPECT_EQ(s["drones"].size(), 1u);
  EXPECT_NE(run.out.find("coverage   100.000 % of the area"), std::string::npos) << run.out;
}

TEST(PlanCli, SameInputSameBytes) {
  const std::string a = fresh_dir("same-a"), b = fresh_dir("same-b");
  const std::string args =
      " share/fields/vineyard.kml --camera dji-phantom-4-pro --gsd 2 --home 46.2275,7.5915 -o ";
  ASSERT_EQ(run_swath("plan" + args + a).exit_code, 0);
  ASSERT_EQ(run_swath("plan" + args + b).exit_code, 0);
  for (const std::string& f : kFiles)
    EXPECT_EQ(read_text(a + "/" + f), read_text(b + "/" + f)) << f;
}

TEST(PlanCli, FixedAngleHomeAndFirmwareReachTheFiles) {
  const std::string out = fresh_dir("options");
  const CliRun run = run_swath(
      "plan share/fields/meadow.geojson --camera sony-a6000-16mm --altitude 60 --angle 0 --home "
      "47.3965,8.5405 "
      "--firmware px4 --vehicle fixedwing --speed 14 --turnaround 20 -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  EXPECT_NEAR(s["sweep"]["bearing_deg"].get<double>(), 0.0, 1e-9);
  EXPECT_EQ(s["sweep"]["angle_search"], "fixed");
  EXPECT_NEAR(s["home"]["lat_deg"].get<double>(), 47.3965, 1e-9);
  EXPECT_DOUBLE_EQ(s["drones"][0]["speed_m_s"].get<double>(), 14.0);
  const json plan = json::parse(read_text(out + "/drone-1.plan"));
  EXPECT_EQ(plan["mission"]["firmwareType"], 12);
  EXPECT_EQ(plan["mission"]["vehicleType"], 1);
  // Fixed-wing: airspeed (param1 0) at the drone's speed, and gimbal per PX4 (command 1000).
  const json& items = plan["mission"]["items"];
  EXPECT_EQ(items[1]["command"], 178);
  EXPECT_EQ(items[1]["params"][0], 0);
  EXPECT_DOUBLE_EQ(items[1]["params"][1].get<double>(), 14.0);
  EXPECT_EQ(items[2]["command"], 1000);
  // North-south lines: the two waypoints of the first line share a longitude.
  EXPECT_EQ(items[3]["command"], 16);
  EXPECT_EQ(items[5]["command"], 16);
  EXPECT_NEAR(items[3]["params"][5].get<double>(), items[5]["params"][5].get<double>(), 1e-6);
}

TEST(PlanCli, DetectionModeReportsTheAltitudeRange) {
  const std::string out = fresh_dir("detection");
  const CliRun run = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --mode detection --pattern 1x1 "
      "--min-pixels 30 --overlap 0.5 -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  const double h_max = 1.0 * 5456 / (2 * 30 * (23.2 / 32));
  EXPECT_NEAR(s["camera"]["h_max_m"].get<double>(), h_max, 1e-3);
  EXPECT_NEAR(s["camera"]["h_min_m"].get<double>(), h_max / 2, 1e-3);
  EXPECT_NEAR(s["camera"]["altitude_m"].get<double>(), h_max * 0.75, 1e-3);
  EXPECT_EQ(s["camera"]["mode"], "detection");
}

TEST(PlanCli, ConfigFileHoldsTheOptionsAndFlagsOverrideIt) {
  const std::string dir = fresh_dir("config");
  fs::create_directories(dir);
  std::ofstream(dir + "/mission.yaml")
      << "field: share/fields/meadow.geojson\ncamera: sony-ilce-qx1\naltitude: 80\n"
         "side-overlap: 0.6\nline-placement: paper\noutput: " +
             dir + "/out\n";
  const CliRun run = run_swath("plan --config " + dir + "/mission.yaml --altitude 50");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(dir + "/out/summary.json"));
  EXPECT_DOUBLE_EQ(s["camera"]["altitude_m"].get<double>(), 50.0);  // the flag wins
  EXPECT_NEAR(s["camera"]["line_spacing_m"].get<double>(), 23.2 * 50 / 16 * 0.4,
              1e-4);  // from the file
  EXPECT_EQ(s["sweep"]["line_placement"], "paper");

  std::ofstream(dir + "/bad.yaml") << "camera: sony-ilce-qx1\nzoom: 3\n";
  const CliRun bad = run_swath("plan --config " + dir + "/bad.yaml");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad.yaml: line 2: unknown key 'zoom'"), std::string::npos) << bad.err;
}

TEST(PlanCli, LocalAreaNeedsAnOrigin) {
  const std::string out = fresh_dir("local");
  const CliRun no_origin = run_swath(
      "plan share/fields/yard-local.csv --local --camera sony-ilce-qx1 --altitude 40 -o " + out);
  EXPECT_EQ(no_origin.exit_code, 2);
  EXPECT_NE(no_origin.err.find("needs --origin LAT,LON"), std::string::npos) << no_origin.err;
  EXPECT_FALSE(fs::exists(out));
  const CliRun run = run_swath(
      "plan share/fields/yard-local.csv --local --origin 52.0,-1.0 --camera sony-ilce-qx1 "
      "--altitude 40 -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  EXPECT_NEAR(s["area"]["area_m2"].get<double>(), 11400.0, 1e-6);
}

TEST(PlanCli, WarnsWhenTheCameraCannotTriggerThatFast) {
  const std::string out = fresh_dir("fast");
  const CliRun run = run_swath(
      "plan share/fields/meadow.geojson --camera dji-phantom-4-pro --altitude 40 --speed 15 -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("swath plan: warning: at 15.0 m/s the camera must trigger every"),
            std::string::npos)
      << run.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  EXPECT_EQ(s["warnings"].size(), 1u);
}

TEST(PlanCli, ConcaveAreaIsSplitByDefaultAndNeverFliesOutside) {
  const std::string split_dir = fresh_dir("split"), hull_dir = fresh_dir("hull");
  const std::string args =
      " share/fields/vineyard.kml --camera dji-phantom-4-pro --altitude 60 --home 46.2276,7.5917 "
      "-o ";
  ASSERT_EQ(run_swath("plan" + args + split_dir).exit_code, 0);
  ASSERT_EQ(run_swath("plan" + args + hull_dir + " --concave hull").exit_code, 0);
  const json split = json::parse(read_text(split_dir + "/summary.json"));
  const json hull = json::parse(read_text(hull_dir + "/summary.json"));
  EXPECT_EQ(split["area"]["handling"], "split");
  EXPECT_GE(split["area"]["cells"].get<int>(), 2);
  EXPECT_EQ(split["coverage"]["line_length_outside_m"].get<double>(), 0.0);
  EXPECT_EQ(split["coverage"]["transit_outside_m"].get<double>(), 0.0);
  EXPECT_GE(split["coverage"]["covered_fraction"].get<double>(), 0.999);
  EXPECT_EQ(split["sweep"]["angle_search"], "shortest-path");
  EXPECT_EQ(hull["area"]["handling"], "hull");
  EXPECT_GT(hull["coverage"]["line_length_outside_m"].get<double>(),
            100.0);  // over the pond and the notch
  EXPECT_LT(split["drones"][0]["path_length_m"].get<double>(),
            hull["drones"][0]["path_length_m"].get<double>());
  // The cells are in the GeoJSON.
  int cells = 0;
  const json geojson = json::parse(read_text(split_dir + "/mission.geojson"));
  for (const json& f : geojson["features"]) cells += f["properties"]["role"] == "cell";
  EXPECT_EQ(cells, split["area"]["cells"].get<int>());
}

// --split-cells: runs from the lanes by default on the vineyard, shorter than the cells alone,
// and what made the plan in the summary; --outside-margin is reported as asked.
TEST(PlanCli, SplitCellsAndOutsideMarginReachThePlan) {
  const std::string runs = fresh_dir("split-runs"), cells = fresh_dir("split-cells");
  const std::string plan =
      "plan share/fields/vineyard.kml --camera dji-phantom-4-pro --altitude 60 --home "
      "46.2276,7.5917 ";
  ASSERT_EQ(run_swath(plan + "--outside-margin 0 -o " + runs).exit_code, 0);
  ASSERT_EQ(run_swath(plan + "--split-cells boustrophedon -o " + cells).exit_code, 0);
  const json r = json::parse(read_text(runs + "/summary.json"));
  const json c = json::parse(read_text(cells + "/summary.json"));
  EXPECT_EQ(r["area"]["cells_from"], "lanes");
  EXPECT_EQ(c["area"]["cells_from"], "polygon");
  EXPECT_EQ(r["flight"]["outside_margin_m"].get<double>(), 0.0);
  EXPECT_LT(r["drones"][0]["path_length_m"].get<double>(),
            c["drones"][0]["path_length_m"].get<double>());
  EXPECT_GE(r["coverage"]["covered_fraction"].get<double>(), 0.999);
  EXPECT_EQ(r["coverage"]["line_length_outside_m"].get<double>(), 0.0);
}

// Zones across the boundary and overlapping each other (issue 18): the area less their union,
// planned with a warning; no line enters a zone, and the area is the meadow less the zones' parts
// inside it (the oracle: the meadow's area less each zone's sampled share inside the meadow).
TEST(PlanCli, RepairPlansTheAreasACrossingRingEncloses) {
  const std::string out = fresh_dir("repair");
  const CliRun run = run_swath(
      "plan share/fields/bowtie.geojson --camera sony-ilce-qx1 --altitude 50 --repair -o " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find(
                "swath plan: warning: repaired: the outer ring crosses itself at 48.13825, 11.577"),
            std::string::npos)
      << run.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  EXPECT_EQ(s["area"]["repaired_pieces"], 2);
  // Two triangles of the bowtie: half its bounding box (4 x 0.004 x 0.0025 degrees at 48.14 N).
  const double box = 0.004 * 111320 * std::cos(48.13825 * 3.14159265358979 / 180) * 0.0025 * 111200;
  EXPECT_NEAR(s["area"]["area_m2"].get<double>(), box / 2, 0.01 * box);
  EXPECT_GE(s["coverage"]["covered_fraction"].get<double>(), 0.999);
  EXPECT_EQ(s["coverage"]["line_length_outside_m"].get<double>(), 0.0);
  const json g = json::parse(read_text(out + "/mission.geojson"));
  int areas = 0;
  for (const json& f : g["features"]) areas += f["properties"]["role"] == "area";
  EXPECT_EQ(areas, 2);
}

// A ring that touches itself at a vertex (two notches meeting at one point) repairs into two
// pieces that share that point; their decomposition ended in "bad merge" (exit 1). They are now
// planned a millimetre apart.
TEST(PlanCli, RepairPlansPiecesThatTouchAtAPoint) {
  for (const std::string cells : {"best", "boustrophedon"}) {
    const std::string out = fresh_dir("touching-" + cells);
    const CliRun run = run_swath(
        "plan tests/fixtures/self-touching.geojson --camera sony-ilce-qx1 --altitude 40 "
        "--repair --split-cells " +
        cells + " -o " + out);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const json s = json::parse(read_text(out + "/summary.json"));
    EXPECT_EQ(s["area"]["repaired_pieces"], 2);
    EXPECT_GE(s["coverage"]["covered_fraction"].get<double>(), 0.999) << cells;
    EXPECT_EQ(s["coverage"]["line_length_outside_m"].get<double>(), 0.0) << cells;
  }
}

// A strip a few metres wide round a hole that fills the field: the lines cannot reach all of it,
// and the plan says so (it said nothing at 94 %).
TEST(PlanCli, CoverageBelowThePromiseIsWarnedAbout) {
  const std::string out = fresh_dir("thin-ring");
  const CliRun run = run_swath(
      "plan tests/fixtures/thin-ring-round-a-hole.geojson --camera sony-ilce-qx1 "
      "--altitude 60 --clearance 0 -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  const double covered = s["coverage"]["covered_fraction"].get<double>();
  ASSERT_LT(covered, 0.999);
  char percent[32];
  std::snprintf(percent, sizeof percent, "the photos cover %.2f %% of the area", 100 * covered);
  EXPECT_NE(run.err.find(std::string("swath plan: warning: ") + percent), std::string::npos)
      << run.err;
  bool in_summary = false;
  for (const json& w : s["warnings"])
    in_summary |= w.get<std::string>().find(percent) != std::string::npos;
  EXPECT_TRUE(in_summary) << s["warnings"].dump();
  // The bundled meadow is covered whole: no such warning.
  const std::string meadow = fresh_dir("meadow-covered");
  const CliRun whole = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 -o " + meadow);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(whole.err.find("the photos cover"), std::string::npos) << whole.err;
}

// A 100 m square zone along part of a 300 x 200 m field's west edge: the edge lies on a meridian,
// which the local plane bends by micrometres, and the cut left 153 m² of the zone's 10,000 out
// of the area (coverage then read 92.4 %).
TEST(PlanCli, AZoneAlongTheBoundaryIsCutOutWhole) {
  const std::string out = fresh_dir("zone-on-edge");
  const CliRun run = run_swath(
      "plan tests/fixtures/edge-field.geojson --exclude tests/fixtures/zone-on-edge.geojson "
      "--camera sony-ilce-qx1 --altitude 60 -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  // 0.00324686 x 0.001796622 degrees less 0.001082287 x 0.000898311 at 33.899 S.
  const double m_lon = 111320 * std::cos(33.899 * 3.14159265358979 / 180), m_lat = 110900;
  const double expected = (0.00324686 * 0.001796622 - 0.001082287 * 0.000898311) * m_lon * m_lat;
  EXPECT_NEAR(s["area"]["area_m2"].get<double>(), expected, 0.005 * expected);
  EXPECT_GE(s["coverage"]["covered_fraction"].get<double>(), 0.999);
  EXPECT_EQ(run.err.find("the photos cover"), std::string::npos) << run.err;
}

TEST(PlanCli, ThreeDronesByPathAndByRegion) {
  for (const std::string division : {"path", "region"}) {
    const std::string out = fresh_dir("fleet-" + division);
    const CliRun run = run_swath(
        "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 --fleet "
        "share/fleets/three-quads.yaml --division " +
        division + " -o " + out);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const json s = json::parse(read_text(out + "/summary.json"));
    ASSERT_EQ(s["drones"].size(), 3u);
    EXPECT_EQ(s["division"]["mode"], division);
    EXPECT_EQ(s["drones"][2]["name"], "charlie");
    EXPECT_DOUBLE_EQ(s["drones"][2]["speed_m_s"].get<double>(), 8.0);
    EXPECT_GE(s["coverage"]["covered_fraction"].get<double>(), 0.9999);
    // docs/swath-plan.md: files after the drones' names, each with its own speed and home.
    const json fleet_home = s["home"];
    for (int i = 0; i < 3; ++i) {
      const std::string name = s["drones"][i]["name"];
      EXPECT_EQ(s["drones"][i]["file"], name);
      const json plan = json::parse(read_text(out + "/" + name + ".plan"));
      const json& items = plan["mission"]["items"];
      EXPECT_EQ(items.front()["command"], 22);
      EXPECT_EQ(items.back()["command"], 20);
      EXPECT_EQ(items[1]["command"], 178);
      const double speed = s["drones"][i]["speed_m_s"];
      EXPECT_DOUBLE_EQ(items[1]["params"][1].get<double>(), speed) << name;
      EXPECT_DOUBLE_EQ(plan["mission"]["cruiseSpeed"].get<double>(), speed) << name;
      EXPECT_DOUBLE_EQ(plan["mission"]["hoverSpeed"].get<double>(), speed) << name;
      const json& home = s["drones"][i]["home"];
      EXPECT_DOUBLE_EQ(plan["mission"]["plannedHomePosition"][0].get<double>(),
                       home["lat_deg"].get<double>());
      EXPECT_DOUBLE_EQ(plan["mission"]["plannedHomePosition"][1].get<double>(),
                       home["lon_deg"].get<double>());
      std::ifstream wpl(out + "/" + name + ".waypoints");
      std::string header, row0;
      std::getline(wpl, header);
      std::getline(wpl, row0);
      EXPECT_NE(row0.find(base::fixed_text(home["lat_deg"].get<double>(), 9)), std::string::npos)
          << "row 0 of the .waypoints is the drone's own home: " << row0;
      EXPECT_FALSE(fs::exists(out + "/drone-" + std::to_string(i + 1) + ".plan"));
    }
    // Charlie takes off from its own home, not the fleet's.
    const json plan3 = json::parse(read_text(out + "/charlie.plan"));
    EXPECT_NEAR(plan3["mission"]["items"][0]["params"][4].get<double>(), 47.3982, 1e-7);
    EXPECT_NE(s["drones"][2]["home"], fleet_home);
    int regions = 0;
    const json g = json::parse(read_text(out + "/mission.geojson"));
    for (const json& f : g["features"]) regions += f["properties"]["role"] == "region";
    EXPECT_EQ(regions > 0, division == "region");
  }
}

TEST(PlanCli, ShortFleetIsRefusedUnlessPartialIsAllowed) {
  const std::string out = fresh_dir("short");
  const std::string args =
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 40 --fleet "
      "share/fleets/short-range.yaml -o " +
      out;
  const CliRun refused = run_swath(args);
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("the fleet cannot fly the whole survey:"), std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("m of path and"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(out));
  const CliRun partial = run_swath(args + " --allow-partial");
  ASSERT_EQ(partial.exit_code, 0) << partial.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  EXPECT_GT(s["division"]["unflown_path_m"].get<double>(), 0.0);
  EXPECT_LT(s["coverage"]["covered_fraction"].get<double>(), 1.0);
  // Each drone flies exactly its range (budget plus home cost, straight legs), no more.
  for (const json& d : s["drones"])
    EXPECT_LE(d["path_length_m"].get<double>(), 0.5 * 600 * 5 + 1e-3);
}

TEST(PlanCli, LitchiAndDjiExportsJoinTheSetAndLeaveWithIt) {
  const std::string out = fresh_dir("exports");
  const std::string base =
      "plan share/fields/meadow.geojson --camera dji-mavic-3e --altitude 60 -o " + out;
  const CliRun run = run_swath(base + " --litchi --dji");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");
  EXPECT_EQ(entries(out), kFiles.size() + 2);
  const std::string kmz = read_text(out + "/drone-1.kmz");
  EXPECT_EQ(kmz.substr(0, 4), std::string("PK\x03\x04", 4)) << "a zip archive";
  EXPECT_NE(kmz.find("wpmz/waylines.wpml"), std::string::npos);
  const std::string csv = read_text(out + "/drone-1-litchi.csv");
  EXPECT_EQ(csv.rfind("latitude,longitude,altitude(m),heading(deg),", 0), 0u);
  const json s = json::parse(read_text(out + "/summary.json"));
  std::set<std::string> listed;
  for (const json& f : s["files"]) listed.insert(f.get<std::string>());
  EXPECT_TRUE(listed.count("drone-1-litchi.csv") && listed.count("drone-1.kmz"));
  // Planned again without them, the set's manifest removes the exports it no longer writes.
  ASSERT_EQ(run_swath(base).exit_code, 0);
  EXPECT_FALSE(fs::exists(out + "/drone-1.kmz"));
  EXPECT_FALSE(fs::exists(out + "/drone-1-litchi.csv"));
  EXPECT_EQ(entries(out), kFiles.size());
}

struct BadPlan {
  std::string name, args, fragment;
  friend void PrintTo(const BadPlan& b, std::ostream* os) { *os << "swath plan " << b.args; }
};

class PlanBadInput : public ::testing::TestWithParam<BadPlan> {};

TEST_P(PlanBadInput, ExitsTwoAndWritesNothing) {
  const std::string out = fresh_dir("bad-" + GetParam().name);
  const CliRun run = run_swath("plan " + GetParam().args + " -o " + out);
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find(GetParam().fragment), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << "one line: " << run.err;
  EXPECT_EQ(entries(out), 0u) << "no output on bad input";
}

INSTANTIATE_TEST_SUITE_P(
    Catalogue, PlanBadInput,
    ::testing::Values(
        BadPlan{"crossing", "share/fields/bowtie.geojson --camera sony-ilce-qx1 --altitude 50",
                "bowtie.geojson: the area crosses itself at 48.13825"},
        BadPlan{"reject",
                "share/fields/orchard.csv --camera sony-ilce-qx1 --altitude 50 --concave reject",
                "orchard.csv: the area is not convex (2 reflex vertices) and the plan refuses "
                "concave areas; use --concave hull"},
        BadPlan{"no_altitude", "share/fields/meadow.geojson --camera sony-ilce-qx1",
                "needs --altitude M or --gsd CM"},
        BadPlan{"unknown_camera", "share/fields/meadow.geojson --camera sony-a9 --altitude 50",
                "did you mean sony-"},
        BadPlan{"overlap",
                "share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 50 --side-overlap 1",
                "--side-overlap 1 is outside the range swath accepts, 0 to 0.99"},
        BadPlan{"negative_altitude",
                "share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude -3",
                "--altitude -3 m is outside the range swath accepts"},
        BadPlan{"zero_speed",
                "share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 50 --speed 0",
                "--speed 0 m/s is outside the range swath accepts"},
        BadPlan{"home",
                "share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 50 --home 95,8",
                "--home '95,8': latitude must be within"},
        BadPlan{"bad_field", "tests/fixtures/latitude.csv --camera sony-ilce-qx1 --altitude 50",
                "latitude 91"},
        BadPlan{"bad_start",
                "share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 50 --start middle",
                "--start"},
        BadPlan{"zone_over_area",
                "share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 50 --exclude "
                "tests/fixtures/zone-over-area.geojson",
                "meadow.geojson: the no-fly zones cover the whole area"},
        BadPlan{"fleet_zero_capability",
                "share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 50 --fleet "
                "tests/fixtures/fleet-zero-capability.yaml",
                "fleet-zero-capability.yaml: drone 1 (zero): capability 0"},
        BadPlan{"fleet_no_drones",
                "share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 50 --fleet "
                "tests/fixtures/fleet-no-drones.yaml",
                "'drones' must list at least one drone"},
        BadPlan{"fleet_home_unreachable",
                "share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 50 --fleet "
                "tests/fixtures/fleet-home-unreachable.yaml",
                "drone weak: flying to the farthest point of the survey and back"},
        BadPlan{"region_beyond_charge",
                "share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 40 --fleet "
                "share/fleets/short-range.yaml "
                "--division region",
                "drone tiny-1's flight takes 12 min 13 s, longer than the 4 min 00 s its battery "
                "gives less the 20 % reserve (battery_level 0.5 x endurance_s 600 in "
                "share/fleets/short-range.yaml, --reserve 0.2); add drones or battery, cut the "
                "flights into sorties with --sorties auto, or fly higher with a larger --altitude "
                "(fewer lines)"},
        BadPlan{"zero_drones",
                "share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 50 --drones 0",
                "--drones 0 drones is outside the range swath accepts, 1 to 100"},
        BadPlan{"detection_needs_pattern",
                "share/fields/meadow.geojson --camera sony-ilce-qx1 --mode detection",
                "detection mode needs --pattern"}),
    [](const ::testing::TestParamInfo<BadPlan>& param_info) { return param_info.param.name; });

TEST(CamerasCli, ListsTheDatabase) {
  const CliRun run = run_swath("cameras --json");
  ASSERT_EQ(run.exit_code, 0);
  const json list = json::parse(run.out);
  ASSERT_GE(list.size(), 12u);
  bool qx1 = false;
  for (const json& c : list)
    if (c["id"] == "sony-ilce-qx1") {
      qx1 = true;
      EXPECT_DOUBLE_EQ(c["sensor_width_mm"].get<double>(), 23.2);
      EXPECT_EQ(c["image_width_px"], 5456);
    }
  EXPECT_TRUE(qx1);
  const CliRun table = run_swath("cameras");
  EXPECT_NE(table.out.find("sony-ilce-qx1          Sony ILCE-QX1"), std::string::npos) << table.out;
}

// A directory whose one file is not an area: that file is its own refused row (its `swath plan`
// message, exit 2) and the others are planned (the whole batch was refused, nothing planned).
TEST(BatchCli, ABadFileOfADirectoryIsItsOwnRow) {
  const std::string dir = fresh_dir("batch-dir");
  fs::create_directories(dir + "/areas");
  fs::copy_file(source_path("share/fields/meadow.geojson"), dir + "/areas/meadow.geojson");
  std::ofstream(dir + "/areas/junk.geojson") << "&not json\n";
  const CliRun run = run_swath("batch " + dir + "/areas -o " + dir +
                               "/out --camera sony-ilce-qx1 " + "--altitude 60");
  EXPECT_EQ(run.exit_code, 3) << run.err;
  const std::string csv = read_text(dir + "/out/batch.csv");
  std::istringstream rows(csv);
  std::string line;
  std::getline(rows, line);
  std::vector<std::string> lines;
  while (std::getline(rows, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), 2u) << csv;
  EXPECT_EQ(lines[0].rfind("junk,", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find(",refused,2,"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find("invalid JSON"), std::string::npos) << lines[0];
  EXPECT_EQ(lines[1].rfind("meadow,", 0), 0u) << lines[1];
  EXPECT_NE(lines[1].find(",planned,0,"), std::string::npos) << lines[1];
  const auto s = nlohmann::json::parse(read_text(dir + "/out/meadow/summary.json"));
  EXPECT_GE(s["coverage"]["covered_fraction"].get<double>(), 0.999);
  // A bad file given alone is refused as before.
  EXPECT_EQ(run_swath("batch " + dir + "/areas/junk.geojson -o " + dir +
                      "/alone --camera "
                      "sony-ilce-qx1 --altitude 60")
                .exit_code,
            2);
  EXPECT_FALSE(fs::exists(dir + "/alone"));
}

// The tester's file of one MultiPolygon of 3 parts: the batch said "no layer holds an area". Now
// one row per part ("<name>, part K"), each planned as the part alone would be (the oracle: each
// part written as its own Polygon and planned), then the file's next feature.
TEST(BatchCli, AMultiPolygonIsOneRowPerPart) {
  const std::string dir = fresh_dir("batch-multi");
  fs::create_directories(dir);
  const std::vector<std::string> parts{
      "[[15.6,78.2],[15.613178413,78.2],[15.613178413,78.201796622],[15.6,78.201796622],[15.6,"
      "78.2]]",
      "[[15.621964022,78.2],[15.630749631,78.2],[15.630749631,78.201796622],[15.621964022,78."
      "201796622],[15.621964022,78.2]]",
      "[[15.6,78.203593245],[15.608785609,78.203593245],[15.608785609,78.204940711],[15.6,78."
      "204940711],[15.6,78.203593245]]"};
  const std::string field = dir + "/fields.geojson";
  std::ofstream(field) << R"({"type":"FeatureCollection","features":[{"type":"Feature",)"
                       << R"("properties":{"name":"x"},"geometry":{"type":"MultiPolygon",)"
                       << R"("coordinates":[[)" << parts[0] << "],[" << parts[1] << "],["
                       << parts[2] << R"(]]}},{"type":"Feature","properties":{"name":"y"},)"
                       << R"("geometry":{"type":"Polygon","coordinates":[)" << parts[1]
                       << "]}}]}\n";
  const CliRun run =
      run_swath("batch " + field + " -o " + dir + "/out --camera sony-ilce-qx1 --altitude 60");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json areas = json::parse(read_text(dir + "/out/batch.geojson"))["features"];
  ASSERT_EQ(areas.size(), 4u);
  const std::vector<std::string> names{"x, part 0", "x, part 1", "x, part 2", "y"};
  for (std::size_t k = 0; k < 4; ++k) {
    const json& p = areas[k]["properties"];
    EXPECT_EQ(p["area"], names[k]);
    EXPECT_EQ(p["index"], k);
    EXPECT_EQ(p["status"], "planned");
    const std::string alone = dir + "/part-" + std::to_string(k);
    std::ofstream(alone + ".geojson")
        << R"({"type":"Polygon","coordinates":[)" << parts[k < 3 ? k : 1] << "]}\n";
    ASSERT_EQ(
        run_swath("plan " + alone + ".geojson --camera sony-ilce-qx1 --altitude 60 -o " + alone)
            .exit_code,
        0);
    const json s = json::parse(read_text(alone + "/summary.json"));
    EXPECT_NEAR(p["area_m2"].get<double>(), s["area"]["area_m2"].get<double>(), 1e-3) << names[k];
    EXPECT_EQ(p["photos"].get<double>(), s["drones"][0]["photos"].get<double>()) << names[k];
  }
  // `swath plan` of the file alone still refuses the MultiPolygon, and says what to do.
  std::ofstream(dir + "/multi.geojson")
      << R"({"type":"MultiPolygon","coordinates":[[)" << parts[0] << "],[" << parts[1] << "]]}\n";
  const CliRun plan = run_swath(
      "plan " + dir + "/multi.geojson --camera sony-ilce-qx1 --altitude 60 -o " + dir + "/multi");
  EXPECT_EQ(plan.exit_code, 2);
  EXPECT_NE(plan.err.find("the MultiPolygon has 2 parts; swath plans one connected area: swath "
                          "batch plans each part, --feature INDEX one of them"),
            std::string::npos)
      << plan.err;
}

}  // namespace
}  // namespace swath::test

namespace swath::test {
namespace {

// A field across the antimeridian: its inclusion fence, with edges from 179.99x to -179.99x,
// is read by ArduPilot and PX4 in raw longitude as the rest of its latitude band, home and every
// waypoint outside it; no autopilot fence can hold it (longitudes beyond ±180 are invalid). Refused
// before anything is written, naming the edge.
TEST(PlanCli, AFieldAcrossTheAntimeridianIsRefused) {
  const std::string out = fresh_dir("antimeridian") + "/out";
  const CliRun run = run_swath(
      "plan tests/fixtures/antimeridian.geojson --camera sony-ilce-qx1 --altitude 100 -o " + out);
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("tests/fixtures/antimeridian.geojson: the area crosses the ±180° "
                         "meridian (its edge from -16.5000000, 179.9900000 to -16.5000000, "
                         "-179.9900000, lat, lon), where ArduPilot's and PX4's fences, compared in "
                         "raw longitude, cannot hold it"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// An area short of the meridian whose fence, grown by the margin, would reach across it: refused
// naming the fence; with a margin that stays short of it the plan is written, every fence vertex
// and waypoint on the east side (positive longitude), as the autopilot compares them.
TEST(PlanCli, AFenceReachingAcrossTheAntimeridianIsRefused) {
  const std::string dir = fresh_dir("antimeridian-fence");
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/area.geojson")
      << R"({"type":"Polygon","coordinates":[[[179.9990,-17.0],[179.9998,-17.0],)"
      << R"([179.9998,-16.9992],[179.9990,-16.9992],[179.9990,-17.0]]]})";
  const std::string plan = "plan " + dir + "/area.geojson --camera dji-mavic-3e --altitude 40 ";
  const CliRun refused = run_swath(plan + "-o " + dir + "/out");
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_NE(refused.err.find("the inclusion fence (the area grown by the "), std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("crosses the ±180° meridian"), std::string::npos) << refused.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
  const CliRun written = run_swath(plan + "--fence-margin 5 -o " + dir + "/out");
  ASSERT_EQ(written.exit_code, 0) << written.err;
  const nlohmann::json j = nlohmann::json::parse(read_text(dir + "/out/drone-1.plan"));
  int vertices = 0;
  for (const auto& v : j["geoFence"]["polygons"][0]["polygon"]) {
    EXPECT_GT(v[1].get<double>(), 179.99) << v;
    ++vertices;
  }
  EXPECT_GE(vertices, 4);
  for (const auto& item : j["mission"]["items"])
    if (item["command"] == 16) EXPECT_GT(item["params"][5].get<double>(), 179.99) << item;
}

}  // namespace
}  // namespace swath::test
