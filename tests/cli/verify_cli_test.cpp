// `swath verify` on real `swath plan` output and on planted violations, and `swath plan`'s own
// check of the files it is about to write (issue 45).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "cli_runner.hpp"

namespace swath::test {
namespace {

using nlohmann::json;

const std::string kMeadow = "share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60";

void write(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

TEST(VerifyCli, PassesTheFilesOfARealPlanAndTheirTwins) {
  const std::string dir = fresh_dir("swath-verify-clean");
  const CliRun plan = run_swath("plan " + kMeadow + " --litchi --dji -o " + dir + "/out");
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  const CliRun run = run_swath("verify " + dir + "/out --area share/fields/meadow.geojson --json");
  EXPECT_EQ(run.exit_code, 0) << run.out;
  const json j = json::parse(run.out);
  EXPECT_TRUE(j["ok"].get<bool>());
  for (const json& c : j["checks"]) {
    if (c["check"] == "agreement") {  // none of the three twins differs
      EXPECT_EQ(c["value"], 0) << c["text"];
      EXPECT_NE(c["text"].get<std::string>().find("3 of 3 twin files"), std::string::npos);
    }
    if (c["check"] == "ceiling") EXPECT_DOUBLE_EQ(c["value"].get<double>(), 60.0);
    if (c["check"] == "ground") EXPECT_FALSE(c["ran"].get<bool>());  // no DEM: said so
  }
}

TEST(VerifyCli, CatchesATwinThatDiffersFromItsPlan) {
  const std::string dir = fresh_dir("swath-verify-twin");
  ASSERT_EQ(run_swath("plan " + kMeadow + " -o " + dir).exit_code, 0);
  std::string wpl = read_text(dir + "/drone-1.waypoints");
  const std::size_t at = wpl.rfind("\t60.000000\t1\n");  // the last waypoint's altitude
  ASSERT_NE(at, std::string::npos);
  wpl.replace(at, 12, "\t65.000000\t1");
  write(dir + "/drone-1.waypoints", wpl);
  const CliRun run = run_swath("verify " + dir);
  EXPECT_EQ(run.exit_code, 4);
  EXPECT_NE(run.out.find("VIOLATION agreement: " + dir + "/drone-1.waypoints differs from " + dir +
                         "/drone-1.plan"),
            std::string::npos)
      << run.out;
}

// A Litchi twin may add one last row: its landing at home. A row added anywhere else (here 5 km
// off at 400 m) is a disagreement, besides what flying it breaks.
TEST(VerifyCli, ALitchiTwinsExtraRowMustBeItsLandingAtHome) {
  const std::string dir = fresh_dir("swath-verify-litchi-row");
  ASSERT_EQ(run_swath("plan " + kMeadow + " --litchi -o " + dir).exit_code, 0);
  ASSERT_EQ(run_swath("verify " + dir).exit_code, 0);
  std::string csv = read_text(dir + "/drone-1-litchi.csv");
  const std::string last = csv.substr(csv.rfind('\n', csv.size() - 2) + 1);
  std::vector<std::string> cells;
  std::stringstream cut(last.substr(0, last.size() - 1));
  for (std::string cell; std::getline(cut, cell, ',');) cells.push_back(cell);
  ASSERT_GT(cells.size(), 3u);
  cells[0] = std::to_string(std::stod(cells[0]) + 0.045);  // 5 km north
  cells[2] = "400";
  std::string row;
  for (const std::string& cell : cells) row += (row.empty() ? "" : ",") + cell;
  write(dir + "/drone-1-litchi.csv", csv + row + "\n");
  const CliRun run = run_swath("verify " + dir);
  EXPECT_EQ(run.exit_code, 4) << run.out;
  EXPECT_NE(run.out.find("VIOLATION agreement: " + dir + "/drone-1-litchi.csv differs from "),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("m from its home (only a landing at home may be added)"),
            std::string::npos)
      << run.out;
}

// A square zone of 2 * half_deg a side around (lat, lon), as GeoJSON.
std::string square_zone(double lat, double lon, double half_deg) {
  auto corner = [](double x, double y) {
    return "[" + std::to_string(x) + ", " + std::to_string(y) + "]";
  };
  return "{\"type\": \"Polygon\", \"coordinates\": [[" + corner(lon - half_deg, lat - half_deg) +
         ", " + corner(lon + half_deg, lat - half_deg) + ", " +
         corner(lon + half_deg, lat + half_deg) + ", " + corner(lon - half_deg, lat + half_deg) +
         ", " + corner(lon - half_deg, lat - half_deg) + "]]}";
}

std::string csv_text(const std::vector<std::vector<std::string>>& rows) {
  std::string out;
  for (const auto& row : rows) {
    std::string line;
    for (const std::string& cell : row) line += (line.empty() ? "" : ",") + cell;
    out += line + "\n";
  }
  return out;
}

// The (check, place) pairs of a --json report's violations whose place names `file`.
std::vector<std::string> checks_failed_by(const json& report, const std::string& file) {
  std::vector<std::string> out;
  for (const json& v : report["violations"])
    if (v["place"].get<std::string>().rfind(file, 0) == 0) out.push_back(v["check"]);
  return out;
}

bool has(const std::vector<std::string>& checks, const std::string& check) {
  return std::find(checks.begin(), checks.end(), check) != checks.end();
}

// The pilot may load a .plan's Litchi or Mission Planner twin instead of it: each twin is flown
// and checked on its own (zones, fence, ceiling), not only compared with its .plan. A Litchi row
// moved 1 km north into a zone at 150 m and a .waypoints item raised to 150 m passed as mere
// disagreements, the figures those of the .plan alone.
TEST(VerifyCli, EveryTwinIsFlownAndCheckedOnItsOwn) {
  const std::string dir = fresh_dir("swath-verify-twins-flown");
  ASSERT_EQ(run_swath("plan " + kMeadow + " --litchi -o " + dir + "/out").exit_code, 0);
  const std::string out = dir + "/out";
  auto rows = csv_rows(read_text(out + "/drone-1-litchi.csv"));
  ASSERT_GT(rows.size(), 4u);
  ASSERT_EQ(rows[0][2], "altitude(m)");
  const double lat = std::stod(rows[3][0]) + 0.01, lon = std::stod(rows[3][1]);
  rows[3][0] = std::to_string(lat);
  rows[3][2] = "150";
  write(out + "/drone-1-litchi.csv", csv_text(rows));
  write(dir + "/zone.geojson", square_zone(lat, lon, 0.0005));
  std::string wpl = read_text(out + "/drone-1.waypoints");
  const std::size_t at = wpl.rfind("\t60.000000\t1\n");  // the last waypoint's altitude
  ASSERT_NE(at, std::string::npos);
  wpl.replace(at, 12, "\t150.000000\t1");
  write(out + "/drone-1.waypoints", wpl);

  const CliRun run = run_swath("verify " + out + " --exclude " + dir + "/zone.geojson --json");
  EXPECT_EQ(run.exit_code, 4) << run.out;
  const json j = json::parse(run.out);
  const auto litchi = checks_failed_by(j, out + "/drone-1-litchi.csv");
  EXPECT_TRUE(has(litchi, "no-fly zone")) << run.out;
  EXPECT_TRUE(has(litchi, "ceiling")) << run.out;
  EXPECT_TRUE(has(checks_failed_by(j, out + "/drone-1.waypoints"), "ceiling")) << run.out;
  EXPECT_TRUE(checks_failed_by(j, out + "/drone-1.plan").empty()) << run.out;
  for (const json& c : j["checks"]) {  // the figures count the twins' flights
    if (c["check"] == "ceiling") EXPECT_DOUBLE_EQ(c["value"].get<double>(), 150.0);
    if (c["check"] == "zones") EXPECT_DOUBLE_EQ(c["value"].get<double>(), 0.0);
  }
}

TEST(VerifyCli, CatchesAWaypointMovedIntoAZoneOfTheQgcStyleFixture) {
  // zone.geojson lies around the fixture's third waypoint (47.3973, 8.5445), item 7.
  const CliRun clean = run_swath("verify tests/fixtures/verify/qgc-style.plan");
  EXPECT_EQ(clean.exit_code, 0) << clean.out;
  const CliRun run = run_swath(
      "verify tests/fixtures/verify/qgc-style.plan --exclude tests/fixtures/verify/zone.geojson");
  EXPECT_EQ(run.exit_code, 4);
  EXPECT_NE(run.out.find("VIOLATION no-fly zone: tests/fixtures/verify/qgc-style.plan: item 7 "
                         "enters tests/fixtures/verify/zone.geojson"),
            std::string::npos)
      << run.out;
}

const std::string kVineyardLitchi =
    "plan share/fields/vineyard.kml --camera dji-phantom-4-pro --altitude 60 --home "
    "46.2276,7.5917 --waypoint-spacing 20 --litchi";

// A square zone of 6.7 m around the point 15 % of the way from home to the first row of `part`
// (a Litchi CSV): on the straight flight from home to that part's start.
std::string zone_towards(const std::string& part) {
  const auto rows = csv_rows(read_text(part));
  const double home_lat = 46.2276, home_lon = 7.5917, d = 0.00003;
  const double lat = home_lat + 0.15 * (std::stod(rows.at(1).at(0)) - home_lat);
  const double lon = home_lon + 0.15 * (std::stod(rows.at(1).at(1)) - home_lon);
  auto corner = [](double x, double y) {
    return "[" + std::to_string(x) + ", " + std::to_string(y) + "]";
  };
  return "{\"type\": \"Polygon\", \"coordinates\": [[" + corner(lon - d, lat - d) + ", " +
         corner(lon + d, lat - d) + ", " + corner(lon + d, lat + d) + ", " +
         corner(lon - d, lat + d) + ", " + corner(lon - d, lat - d) + "]]}";
}

// Above 99 waypoints a flight's Litchi file is cut into NAME-litchi-1.csv, -2, ...: each part is
// a Litchi mission of its own, flown from home to its first row and back home (RTH) in turn.
// swath verify skipped them in a directory and refused one given alone.
TEST(VerifyCli, SplitLitchiPartsAreFlownFromTheirPlansHomeAndJoinedAgainstIt) {
  const std::string dir = fresh_dir("swath-verify-litchi-parts");
  const CliRun plan = run_swath(kVineyardLitchi + " -o " + dir);
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  ASSERT_TRUE(std::filesystem::exists(dir + "/drone-1-litchi-3.csv"));
  const CliRun run = run_swath("verify " + dir + " --json");
  EXPECT_EQ(run.exit_code, 0) << run.out;
  const json j = json::parse(run.out);
  for (int k = 1; k <= 3; ++k) {
    const std::string part = dir + "/drone-1-litchi-" + std::to_string(k) + ".csv";
    EXPECT_EQ(std::count(j["files"].begin(), j["files"].end(), part), 1) << part;
  }
  const json plan_only = json::parse(run_swath("verify " + dir + "/drone-1.plan --json").out);
  for (const json& c : j["checks"]) {
    if (c["check"] == "agreement") EXPECT_EQ(c["text"].get<std::string>().rfind("2 of 2", 0), 0);
    if (c["check"] == "photos")
      EXPECT_EQ(c["value"], plan_only["checks"][4]["value"]);            // not again
    if (c["check"] == "separation") EXPECT_FALSE(c["ran"].get<bool>());  // one drone
    if (c["check"] == "flight")  // the later parts fly after the earlier ones landed
      EXPECT_NE(c["text"].get<std::string>().find("drone-1-litchi-3.csv"), std::string::npos);
  }
  // The straight flight home to part 3's start crosses a zone the .plan keeps clear of.
  write(dir + "/zone.geojson", zone_towards(dir + "/drone-1-litchi-3.csv"));
  const std::string zone = " --exclude " + dir + "/zone.geojson";
  EXPECT_EQ(run_swath("verify " + dir + "/drone-1.plan" + zone).exit_code, 0);
  const CliRun crossed = run_swath("verify " + dir + zone);
  EXPECT_EQ(crossed.exit_code, 4);
  EXPECT_NE(crossed.out.find("VIOLATION no-fly zone: " + dir +
                             "/drone-1-litchi-3.csv: line 2 enters " + dir + "/zone.geojson"),
            std::string::npos)
      << crossed.out;
  // A part alone is a mission too.
  const CliRun alone = run_swath("verify " + dir + "/drone-1-litchi-2.csv");
  EXPECT_EQ(alone.exit_code, 0) << alone.err;
  EXPECT_EQ(alone.out.rfind("swath verify: 1 file(s): " + dir + "/drone-1-litchi-2.csv\n", 0), 0)
      << alone.out;
  // The parts joined fly the .plan's waypoints: part 2 without its 50th row does not.
  std::istringstream in(read_text(dir + "/drone-1-litchi-2.csv"));
  std::string line, cut;
  for (int n = 0; std::getline(in, line); ++n)
    if (n != 50) cut += line + "\n";
  write(dir + "/drone-1-litchi-2.csv", cut);
  const CliRun differs = run_swath("verify " + dir);
  EXPECT_EQ(differs.exit_code, 4);
  EXPECT_NE(differs.out.find("VIOLATION agreement: " + dir + "/drone-1-litchi-2.csv differs from " +
                             dir + "/drone-1.plan: waypoint 50 (the .plan's 148) lies "),
            std::string::npos)
      << differs.out;
}

// A second drone (a QGC WPL file saved as intruder.plan) hovering at 60 m over the point 15 % of
// the way from home to part 3's first row, the way part 2 flies home and part 3 flies out, which
// the .plan never flies: against the .plan it keeps its distance, against the Litchi parts, flown
// in turn from the .plan's launch as its drone would fly them, it does not. The twins were never
// checked for separation (the parts were 'instead' of the .plan and skipped).
TEST(VerifyCli, ASplitLitchiPartsWayHomeIsCheckedAgainstTheOtherDrones) {
  const std::string dir = fresh_dir("swath-verify-litchi-separation");
  ASSERT_EQ(run_swath(kVineyardLitchi + " -o " + dir + "/out").exit_code, 0);
  const std::string out = dir + "/out";
  const auto rows = csv_rows(read_text(out + "/drone-1-litchi-3.csv"));
  ASSERT_EQ(rows.at(0).at(2), "altitude(m)");
  const double home_lat = 46.2276, home_lon = 7.5917;
  const double lat = home_lat + 0.15 * (std::stod(rows.at(1).at(0)) - home_lat);
  const double lon = home_lon + 0.15 * (std::stod(rows.at(1).at(1)) - home_lon);
  const std::string at = std::to_string(lat) + "\t" + std::to_string(lon);
  write(dir + "/intruder.plan", "QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t" + at + "\t0\t1\n" +
                                    "1\t0\t3\t22\t0\t0\t0\t0\t" + at + "\t60\t1\n" +
                                    "2\t0\t3\t16\t3000\t0\t0\t0\t" + at + "\t60\t1\n" +
                                    "3\t0\t3\t21\t0\t0\t0\t0\t" + at + "\t0\t1\n");
  // The .plan alone beside it: never within the 10 m.
  const CliRun apart =
      run_swath("verify " + out + "/drone-1.plan " + dir + "/intruder.plan --json");
  EXPECT_EQ(apart.exit_code, 0) << apart.out;
  // With its Litchi parts: part 2's way home (or part 3's way out) flies through it.
  std::filesystem::rename(dir + "/intruder.plan", out + "/intruder.plan");
  const CliRun run = run_swath("verify " + out + " --json");
  EXPECT_EQ(run.exit_code, 4) << run.out;
  const json j = json::parse(run.out);
  ASSERT_FALSE(j["violations"].empty()) << run.out;
  for (const json& v : j["violations"]) {
    EXPECT_EQ(v["check"], "separation") << v.dump();
    const std::string text = v["text"].get<std::string>();
    EXPECT_NE(text.find(out + "/intruder.plan and " + out + "/drone-1-litchi-"), std::string::npos)
        << text;
    EXPECT_EQ(text.find("drone-1.plan"), std::string::npos) << text;
  }
  for (const json& c : j["checks"])
    if (c["check"] == "separation") EXPECT_LT(c["value"].get<double>(), 10.0) << c.dump();
}

// The vineyard pair from one home, each flight split into Litchi parts: alpha's part 1 comes home
// and its part 2 leaves as bravo, launched 400 s after alpha's .plan by the plan's stagger, takes
// off there (the layers and the stagger are set on the .plans, which fly no such trips). swath
// plan's own check flies the parts in turn against the other drone and refuses the plan, exit 2,
// nothing written; without --litchi it is written. (It was written, and flown so, two drones on one
// pad.)
TEST(VerifyCli, PlanRefusesLitchiPartsWhoseWaysHomeMeetAnotherDrone) {
  if (const char* env = std::getenv("SWATH_PLAN_VERIFY"); env && std::string(env) == "0")
    GTEST_SKIP() << "SWATH_PLAN_VERIFY=0 turns swath plan's check off";
  const std::string dir = fresh_dir("swath-verify-litchi-pair");
  const std::string pair =
      "plan share/fields/vineyard.kml --camera sony-ilce-qx1 --altitude 60 --fleet "
      "share/fleets/vineyard-pair.yaml --division region --waypoint-spacing 10 -o ";
  ASSERT_EQ(run_swath(pair + dir + "/plans").exit_code, 0);
  const CliRun run = run_swath(pair + dir + "/litchi --litchi");
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/litchi"));
  const std::regex met(
      R"(swath plan: the plan's files fail the preflight check \(separation\): )"
      R"((\S+) and (\S+) come within ([0-9.]+) m of each other at t = ([0-9.]+) s)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(run.err, m, met)) << run.err;
  const std::string a = m[1], b = m[2];
  EXPECT_TRUE(a.find("-litchi-") != std::string::npos || b.find("-litchi-") != std::string::npos)
      << run.err;
  EXPECT_NE(a.substr(0, 5), b.substr(0, 5)) << "two drones: " << run.err;
  EXPECT_LT(std::stod(m[3]), 10.0);
  EXPECT_NE(run.err.find("leave out --litchi"), std::string::npos) << run.err;
}

// A zone across the straight way out to part 3 of a plan made without it: planned with the zone,
// the parts are cut where Litchi's straight ways home and back keep clear of it
// (docs/swath-plan.md), so the plan passes its own check, which flies every part from home and
// back, and so does verify.
TEST(VerifyCli, PlanCutsItsLitchiPartsWhereTheirWaysHomeKeepClear) {
  if (const char* env = std::getenv("SWATH_PLAN_VERIFY"); env && std::string(env) == "0")
    GTEST_SKIP() << "SWATH_PLAN_VERIFY=0 turns swath plan's check off";
  const std::string dir = fresh_dir("swath-verify-litchi-plan");
  ASSERT_EQ(run_swath(kVineyardLitchi + " -o " + dir + "/clean").exit_code, 0);
  write(dir + "/zone.geojson", zone_towards(dir + "/clean/drone-1-litchi-3.csv"));
  const std::string zone = " --exclude " + dir + "/zone.geojson";
  EXPECT_EQ(run_swath("verify " + dir + "/clean" + zone).exit_code, 4);
  const CliRun planned = run_swath(kVineyardLitchi + zone + " -o " + dir + "/out");
  ASSERT_EQ(planned.exit_code, 0) << planned.err;
  EXPECT_NE(read_text(dir + "/out/drone-1-litchi-2.csv"),
            read_text(dir + "/clean/drone-1-litchi-2.csv"))
      << "part 2 ends elsewhere";
  const CliRun checked = run_swath("verify " + dir + "/out" + zone);
  EXPECT_EQ(checked.exit_code, 0) << checked.out;
}

// swath verify reads zone files as swath plan does: a zone file with a line beside its polygon,
// or a zone that crosses itself, is bad input (exit 2) naming the feature or the crossing; the
// zone was checked without the line, the bow-tie by an inside no one agreed on.
TEST(VerifyCli, ZoneFilesWithALineOrACrossingAreRefused) {
  const std::string dir = fresh_dir("swath-verify-zones");
  std::filesystem::create_directories(dir);
  const std::string zone =
      R"({"type":"Feature","properties":{"name":"pond"},"geometry":{"type":"Polygon",)"
      R"("coordinates":[[[8.5444,47.3972],[8.5446,47.3972],[8.5446,47.3974],[8.5444,47.3974],)"
      R"([8.5444,47.3972]]]}})";
  write(dir + "/line.geojson",
        R"({"type":"FeatureCollection","features":[)" + zone +
            R"(,{"type":"Feature","properties":{"name":"wire"},"geometry":{"type":"LineString",)"
            R"("coordinates":[[8.544,47.397],[8.545,47.398]]}}]})");
  write(dir + "/bowtie.geojson",
        R"({"type":"Polygon","coordinates":[[[8.5444,47.3972],[8.5446,47.3974],[8.5446,47.3972],)"
        R"([8.5444,47.3974],[8.5444,47.3972]]]})");
  const std::string plan = "verify tests/fixtures/verify/qgc-style.plan --exclude ";
  const CliRun line = run_swath(plan + dir + "/line.geojson");
  EXPECT_EQ(line.exit_code, 2) << line.out;
  EXPECT_NE(line.err.find(dir + "/line.geojson: feature 1 (\"wire\") is a LineString starting at "
                                "47.397, 8.544 (lat, lon); a no-fly zone must be a polygon"),
            std::string::npos)
      << line.err;
  const CliRun bowtie = run_swath(plan + dir + "/bowtie.geojson");
  EXPECT_EQ(bowtie.exit_code, 2) << bowtie.out;
  EXPECT_NE(bowtie.err.find(dir + "/bowtie.geojson: the no-fly zone crosses itself at 47.3973, "
                                  "8.5445 (lat, lon)"),
            std::string::npos)
      << bowtie.err;
  EXPECT_EQ(line.out + bowtie.out, "");
}

// A square `half_m` metres either side of (lat, lon), as a QGC geoFence polygon's points.
json square_about(double lat_deg, double lon_deg, double half_m) {
  const double dlat = half_m / 111'195.0, dlon = dlat / std::cos(lat_deg * M_PI / 180);
  return json::array({json::array({lat_deg - dlat, lon_deg - dlon}),
                      json::array({lat_deg - dlat, lon_deg + dlon}),
                      json::array({lat_deg + dlat, lon_deg + dlon}),
                      json::array({lat_deg + dlat, lon_deg - dlon})});
}

TEST(VerifyCli, ASecondInclusionFenceOverPartOfTheFlightIsBreachedUnlessAUnion) {
  const std::string dir = fresh_dir("swath-verify-two-fences");
  ASSERT_EQ(run_swath("plan " + kMeadow + " -o " + dir).exit_code, 0);
  // The plan's own fence holds the flight; a second inclusion fence, 30 m either side of home,
  // holds only the start: ArduPilot (by default) and PX4 breach outside either.
  json plan = json::parse(read_text(dir + "/drone-1.plan"));
  const double lat = plan["mission"]["plannedHomePosition"][0];
  const double lon = plan["mission"]["plannedHomePosition"][1];
  plan["geoFence"]["polygons"].push_back(
      {{"inclusion", true}, {"polygon", square_about(lat, lon, 30)}, {"version", 1}});
  write(dir + "/two.plan", plan.dump());
  const CliRun run = run_swath("verify " + dir + "/two.plan --json");
  EXPECT_EQ(run.exit_code, 4) << run.out;
  int outside = 0;
  const json report = json::parse(run.out);
  for (const json& v : report["violations"]) {
    ASSERT_EQ(v["check"], "fence") << v["text"];
    EXPECT_NE(
        v["text"].get<std::string>().find("m outside " + dir + "/two.plan's inclusion fence 2"),
        std::string::npos)
        << v["text"];
    // Where it is outside: beyond the square, by the amount said (to the metres of a degree).
    const double north_m = (v["lat_deg"].get<double>() - lat) * 111'195.0;
    const double east_m =
        (v["lon_deg"].get<double>() - lon) * 111'195.0 * std::cos(lat * M_PI / 180);
    const double beyond_m = std::max(std::abs(north_m), std::abs(east_m)) - 30;
    EXPECT_GT(beyond_m, 0) << v["text"];
    if (std::abs(north_m) < 30 || std::abs(east_m) < 30)  // off a side, not a corner
      EXPECT_NEAR(beyond_m, v["amount"].get<double>(), 0.05) << v["text"];
    ++outside;
  }
  EXPECT_GT(outside, 0);
  // FENCE_OPTIONS' union (--fence-union): inside the plan's own fence is enough for ArduPilot.
  const CliRun any_one = run_swath("verify " + dir + "/two.plan --fence-union");
  EXPECT_EQ(any_one.exit_code, 0) << any_one.out;
  // PX4 has no union.
  plan["mission"]["firmwareType"] = 12;
  write(dir + "/px4.plan", plan.dump());
  EXPECT_EQ(run_swath("verify " + dir + "/px4.plan --fence-union").exit_code, 4);
}

// An ArduPilot plan of two waypoints ending in RTL, its rally point 89 m south of the last one
// (home 130 m west-south-west of it), with `firmware` its firmwareType.
std::string rally_plan(int firmware, double rally_lat_deg) {
  const auto item = [](int command, int id, double lat, double lon) {
    return qgc_item(command, id, lat, lon, 40);
  };
  const json plan = {
      {"fileType", "Plan"},
      {"groundStation", "QGroundControl"},
      {"version", 1},
      {"geoFence", {{"circles", json::array()}, {"polygons", json::array()}, {"version", 2}}},
      {"rallyPoints", {{"points", {{rally_lat_deg, 8.5445, 20}}}, {"version", 2}}},
      {"mission",
       {{"cruiseSpeed", 15},
        {"firmwareType", firmware},
        {"globalPlanAltitudeMode", 1},
        {"hoverSpeed", 5},
        {"plannedHomePosition", {47.39685, 8.5428, 488.0}},
        {"vehicleType", 2},
        {"version", 2},
        {"items",
         {item(22, 1, 47.39685, 8.5428), item(16, 2, 47.3975, 8.543), item(16, 3, 47.3975, 8.5445),
          item(20, 4, 0, 0)}}}}};
  return plan.dump();
}

TEST(VerifyCli, ArduPilotsRtlFliesToTheNearestRallyPointWithinItsLimit) {
  const std::string dir = fresh_dir("swath-verify-rally");
  std::filesystem::create_directories(dir);
  // A 7.5 m zone on the way from the last waypoint to the rally point, 30 m north of it.
  write(dir + "/zone.geojson",
        R"({"type": "Polygon", "coordinates": [[[8.54445, 47.39705], [8.54455, 47.39705], )"
        R"([8.54455, 47.39715], [8.54445, 47.39715], [8.54445, 47.39705]]]})");
  write(dir + "/rally.plan", rally_plan(3, 47.3967));
  const CliRun run =
      run_swath("verify " + dir + "/rally.plan --exclude " + dir + "/zone.geojson --json");
  EXPECT_EQ(run.exit_code, 4) << run.out;
  const json report = json::parse(run.out);
  ASSERT_FALSE(report["violations"].empty()) << run.out;
  for (const json& v : report["violations"]) {
    EXPECT_EQ(v["check"], "no-fly zone") << v["text"];
    // The RTL item's leg to the rally point, entering the zone's south side.
    EXPECT_NE(
        v["text"].get<std::string>().find("rally.plan: item 4 enters " + dir + "/zone.geojson"),
        std::string::npos)
        << v["text"];
    EXPECT_NEAR(v["lon_deg"].get<double>(), 8.5445, 1e-6) << v["text"];
    EXPECT_LT(v["lat_deg"].get<double>(), 47.39715) << v["text"];
  }
  // A rally point beyond RALLY_LIMIT_KM (0.3 km from the vehicle): home.
  write(dir + "/far.plan", rally_plan(3, 47.3945));
  EXPECT_EQ(run_swath("verify " + dir + "/far.plan --exclude " + dir + "/zone.geojson").exit_code,
            0);
  // Home nearer than the rally point (RALLY_INCL_HOME): home.
  write(dir + "/nearer.plan", rally_plan(3, 47.3960));
  EXPECT_EQ(
      run_swath("verify " + dir + "/nearer.plan --exclude " + dir + "/zone.geojson").exit_code, 0);
}

// summary.json's drones[].sorties[].launch_offset_s launches a sortie then (after the one before
// it has landed): the upper drone's second sortie moved to when the lower drone launches one at
// their shared home climbs with it.
TEST(VerifyCli, ASortieLaunchesAtItsOwnLaunchOffset) {
  const std::string dir = fresh_dir("swath-verify-sortie-launch");
  const CliRun plan = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 40 --sorties auto "
      "--endurance 420 --drones 2 -o " +
      dir);
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  ASSERT_EQ(run_swath("verify " + dir).exit_code, 0);
  json summary = json::parse(read_text(dir + "/summary.json"));
  json& upper = summary["drones"][1]["sorties"];
  const double landed_s =
      upper[0]["launch_offset_s"].get<double>() + 1.1 * upper[0]["flight_time_s"].get<double>();
  double together_s = -1;  // a later launch of the lower drone's, after the upper's first landed
  for (const json& lower : summary["drones"][0]["sorties"])
    if (together_s < 0 && lower["launch_offset_s"].get<double>() >= landed_s)
      together_s = lower["launch_offset_s"].get<double>();
  ASSERT_GE(together_s, 0) << summary.dump();
  upper[1]["launch_offset_s"] = together_s;
  write(dir + "/summary.json", summary.dump(1));
  const CliRun run = run_swath("verify " + dir + " --json");
  EXPECT_EQ(run.exit_code, 4) << run.out;
  const json report = json::parse(run.out);
  ASSERT_FALSE(report["violations"].empty()) << run.out;
  const json& v = report["violations"][0];
  EXPECT_EQ(v["check"], "separation");
  EXPECT_NE(v["text"].get<std::string>().find("drone-2-2.plan"), std::string::npos) << v["text"];
}

// PX4's RTL climbs to RTL_RETURN_ALT, 60 m by default; ArduCopter's to RTL_ALT, 15 m.
TEST(VerifyCli, APx4FilesReturnClimbsToPx4sReturnAltitude) {
  const std::string dir = fresh_dir("swath-verify-px4-rtl");
  std::filesystem::create_directories(dir);
  write(dir + "/px4.plan", rally_plan(12, 47.3967));
  const CliRun px4 = run_swath("verify " + dir + "/px4.plan --ceiling 50 --json");
  EXPECT_EQ(px4.exit_code, 4) << px4.out;
  const json report = json::parse(px4.out);
  ASSERT_EQ(report["violations"].size(), 1u) << px4.out;
  const json& v = report["violations"][0];
  EXPECT_EQ(v["check"], "ceiling") << v["text"];
  EXPECT_NEAR(v["amount"].get<double>(), 10.0, 1e-6) << v["text"];  // 60 m against 50 m
  EXPECT_NE(v["text"].get<std::string>().find("px4.plan: item 4"), std::string::npos) << v["text"];
  write(dir + "/ardupilot.plan", rally_plan(3, 47.3967));
  EXPECT_EQ(run_swath("verify " + dir + "/ardupilot.plan --ceiling 50").exit_code, 0);
}

// Four 16-gons of 8 m radius inside the meadow: with the area's fence, more than ArduPilot stores.
std::string sixteen_gon_zones() {
  json features = json::array();
  for (const auto& [lon, lat] : {std::pair{8.5415, 47.3980}, std::pair{8.5430, 47.3980},
                                 std::pair{8.5415, 47.3990}, std::pair{8.5430, 47.3990}}) {
    json ring = json::array();
    for (int k = 0; k <= 16; ++k) {
      const double a = 2 * M_PI * (k % 16) / 16;
      ring.push_back({lon + 8 * std::cos(a) / (111'195.0 * std::cos(lat * M_PI / 180)),
                      lat + 8 * std::sin(a) / 111'195.0});
    }
    features.push_back({{"type", "Feature"},
                        {"properties", json::object()},
                        {"geometry", {{"type", "Polygon"}, {"coordinates", {ring}}}}});
  }
  return json{{"type", "FeatureCollection"}, {"features", features}}.dump();
}

TEST(VerifyCli, AFenceTheAutopilotCannotStoreIsAWarningOfPlanAndVerify) {
  const std::string dir = fresh_dir("swath-verify-fence-storage");
  std::filesystem::create_directories(dir);
  write(dir + "/zones.geojson", sixteen_gon_zones());
  const CliRun plan =
      run_swath("plan " + kMeadow + " --exclude " + dir + "/zones.geojson -o " + dir + "/out");
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  // The counts said are the .plan's fence as written, in ArduPilot's bytes.
  const std::regex said(
      "swath plan: warning: the fence has (\\d+) points in (\\d+) polygons: (\\d+) bytes of "
      "ArduPilot's fence storage, more than the 560 bytes ArduCopter keeps");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(plan.err, m, said)) << plan.err;
  std::size_t points = 0, polygons = 0;
  const json written = json::parse(read_text(dir + "/out/drone-1.plan"));
  for (const json& p : written["geoFence"]["polygons"]) points += p["polygon"].size(), ++polygons;
  EXPECT_EQ(std::stoul(m[1]), points);
  EXPECT_EQ(std::stoul(m[2]), polygons);
  EXPECT_EQ(std::stoul(m[3]), 4 + 2 * polygons + 8 * points);
  EXPECT_GT(std::stoul(m[3]), 560u);
  // swath verify says the same as a warning: the checks hold, exit 0.
  const CliRun run = run_swath("verify " + dir + "/out --json");
  EXPECT_EQ(run.exit_code, 0) << run.out;
  const json j = json::parse(run.out);
  EXPECT_TRUE(j["ok"].get<bool>());
  ASSERT_EQ(j["warnings"].size(), 1u) << run.out;
  const std::string prefix = "swath plan: warning: ";
  const std::size_t from = plan.err.find(prefix + "the fence has");
  const std::string sentence =
      plan.err.substr(from + prefix.size(), plan.err.find('\n', from) - from - prefix.size());
  EXPECT_EQ(j["warnings"][0], dir + "/out/drone-1.plan: " + sentence);
  // PX4 takes 64 fence items in all: the same fence is too many for it.
  const CliRun px4 = run_swath("plan " + kMeadow + " --firmware px4 --exclude " + dir +
                               "/zones.geojson -o " + dir + "/px4");
  EXPECT_EQ(px4.exit_code, 0) << px4.err;
  EXPECT_EQ(px4.err.find("fence storage"), std::string::npos) << px4.err;
  EXPECT_NE(px4.err.find("swath plan: warning: the fence has " + std::to_string(points) +
                         " points in " + std::to_string(polygons) + " polygons: " +
                         std::to_string(points) + " fence items, more than the 64 PX4 takes"),
            std::string::npos)
      << px4.err;
  const json px4_report = json::parse(run_swath("verify " + dir + "/px4 --json").out);
  ASSERT_EQ(px4_report["warnings"].size(), 1u);
  EXPECT_NE(px4_report["warnings"][0].get<std::string>().find(" fence items, more than the 64"),
            std::string::npos);
}

TEST(VerifyCli, BadInputIsOneSentenceAndExitTwo) {
  const std::string dir = fresh_dir("swath-verify-bad");
  std::filesystem::create_directories(dir);
  write(dir + "/a.waypoints", "QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t47\t8\t0\t1\n1\t0\t3\t16\n");
  const CliRun run = run_swath("verify " + dir + "/a.waypoints");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(
      run.err.find(dir + "/a.waypoints: line 3: a WPL row has 12 fields (index, current, frame, "
                         "command, 4 params, latitude, longitude, altitude, "
                         "autocontinue); found 4"),
      std::string::npos)
      << run.err;
  EXPECT_EQ(run.out, "");
}

TEST(VerifyCli, PlanRefusesAnAltitudeAboveTheCeilingUnlessRaised) {
  if (const char* env = std::getenv("SWATH_PLAN_VERIFY"); env && std::string(env) == "0")
    GTEST_SKIP() << "SWATH_PLAN_VERIFY=0 turns swath plan's check off";
  const std::string dir = fresh_dir("swath-verify-ceiling");
  const CliRun refused = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 150 -o " + dir + "/out");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("(ceiling): drone-1.plan: item 1 flies at 150.0 m above home, 30.0 "
                             "m above the 120.0 m ceiling"),
            std::string::npos)
      << refused.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
  const CliRun allowed = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 150 --ceiling 150 -o " +
      dir + "/out");
  EXPECT_EQ(allowed.exit_code, 0) << allowed.err;
}

}  // namespace
}  // namespace swath::test

namespace swath::test {
namespace {

// A fence across the ±180° meridian, as swath plan wrote it for a 213 m square from 179.999 to
// -179.999 (tests/fixtures/verify/antimeridian-fence.plan): ArduPilot and PX4 compare a fence's
// edges in raw longitude, where this one is the rest of its latitude band, home and every
// waypoint outside it; the check, measuring in a frame that wraps longitude, passed it. Refused
// as an inclusion fence, and as an exclusion fence (the same ring marked so).
TEST(VerifyCli, RefusesAFenceAcrossTheAntimeridian) {
  const std::string fixture = "tests/fixtures/verify/antimeridian-fence.plan";
  const CliRun run = run_swath("verify " + fixture);
  EXPECT_EQ(run.exit_code, 4) << run.out << run.err;
  EXPECT_NE(
      run.out.find("VIOLATION fence: " + fixture +
                   "'s inclusion fence crosses the ±180° meridian (its edge from -17.0003447, "
                   "179.9990000 to -17.0003447, -179.9990000, lat, lon)"),
      std::string::npos)
      << run.out;
  const std::string dir = fresh_dir("swath-verify-antimeridian");
  std::filesystem::create_directories(dir);
  json plan = json::parse(read_text(source_path(fixture)));
  plan["geoFence"]["polygons"][0]["inclusion"] = false;
  write(dir + "/drone-1.plan", plan.dump());
  const CliRun exclusion = run_swath("verify " + dir + "/drone-1.plan");
  EXPECT_EQ(exclusion.exit_code, 4) << exclusion.out << exclusion.err;
  EXPECT_NE(exclusion.out.find("VIOLATION no-fly zone: " + dir +
                               "/drone-1.plan's exclusion fence 1 crosses the ±180° meridian"),
            std::string::npos)
      << exclusion.out;
}

}  // namespace
}  // namespace swath::test
