// `swath verify` on real `swath plan` output and on planted violations, and `swath plan`'s own
// check of the files it is about to write (issue 45).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

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
