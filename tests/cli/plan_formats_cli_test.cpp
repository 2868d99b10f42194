// The files swath plan writes for other apps, as those apps read them: DJI WPML speeds within
// DJI's 1 to 15 m/s (the slow-downs beside no-fly zones too) and heights within its 1500 m, and
// the PX4 .waypoints' params "no value" (NaN) where the .plan has null. Asserted on the written
// files parsed back (the KMZ unzipped with libzip, its XML parsed with pugixml).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <pugixml.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../support/zip_entries.hpp"
#include "cli_runner.hpp"

namespace swath::test {
namespace {

using nlohmann::json;

// Every speed a waylines.wpml sets: the wayline's autoFlightSpeed and each waypointSpeed.
std::vector<double> wpml_speeds(const std::string& wpml) {
  pugi::xml_document doc;
  EXPECT_TRUE(doc.load_string(wpml.c_str()));
  std::vector<double> out;
  for (const pugi::xml_node& folder : doc.child("kml").child("Document").children("Folder")) {
    out.push_back(folder.child("wpml:autoFlightSpeed").text().as_double(-1));
    for (const pugi::xml_node& p : folder.children("Placemark"))
      out.push_back(p.child("wpml:waypointSpeed").text().as_double(-1));
  }
  return out;
}

const std::string kMeadowDji = "plan share/fields/meadow.geojson --camera dji-mavic-3e --dji ";

TEST(PlanFormatsCli, DjiSlowDownsBesideZonesAreWithinDjisSpeedsAndPassTheCheck) {
  const std::string out = fresh_dir("formats-dji-zones");
  const CliRun run = run_swath(kMeadowDji +
                               "--altitude 60 --speed 12 --exclude share/zones/meadow-pond.geojson "
                               "--turnaround 30 -o " +
                               out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto entries = zip_entries(read_text(out + "/drone-1.kmz"));
  ASSERT_TRUE(entries);
  ASSERT_EQ(entries->count("wpmz/waylines.wpml"), 1u);
  const std::vector<double> speeds = wpml_speeds(entries->at("wpmz/waylines.wpml"));
  ASSERT_GT(speeds.size(), 10u);
  std::size_t slowed = 0;
  for (double v : speeds) {
    EXPECT_GE(v, 1.0);
    EXPECT_LE(v, 15.0);
    slowed += v < 12.0;
  }
  EXPECT_GT(slowed, 0u) << "the stops beside the pond are approached slowly";
  // The .plan flies the same slow-downs: every DO_CHANGE_SPEED at least 1 m/s.
  const json plan = json::parse(read_text(out + "/drone-1.plan"));
  for (const json& item : plan["mission"]["items"])
    if (item["command"] == 178) EXPECT_GE(item["params"][1].get<double>(), 1.0) << item.dump();
  const CliRun verify = run_swath("verify " + out + " --exclude share/zones/meadow-pond.geojson");
  EXPECT_EQ(verify.exit_code, 0) << verify.out << verify.err;
}

TEST(PlanFormatsCli, DjiRefusesSpeedsAndHeightsDjiDoesNotFly) {
  struct Case {
    std::string args, fragment;
  };
  const std::vector<Case> cases = {
      {"--altitude 60 --speed 20",
       "--dji: drone drone-1 flies at 20.0 m/s, outside DJI's waypoint speeds (1 "
       "to 15 m/s)"},
      {"--altitude 60 --speed 0.5",
       "--dji: drone drone-1 flies at 0.5 m/s, outside DJI's waypoint speeds"},
      {"--altitude 1600 --ceiling 1700",
       "--dji: the altitude 1600.0 m is above DJI Pilot 2's highest, 1500 m above the take-off "
       "point"},
  };
  for (const Case& c : cases) {
    const std::string out = fresh_dir("formats-dji-refused");
    const CliRun run = run_swath(kMeadowDji + c.args + " -o " + out);
    EXPECT_EQ(run.exit_code, 2) << c.args << ": " << run.err;
    EXPECT_NE(run.err.find(c.fragment), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.args << ": nothing written";
  }
  // At DJI's limits the plan is written.
  const std::string out = fresh_dir("formats-dji-limits");
  EXPECT_EQ(run_swath(kMeadowDji + "--altitude 1500 --ceiling 1700 --speed 15 -o " + out).exit_code,
            0);
}

// A WPL row's twelve fields as text.
std::vector<std::vector<std::string>> wpl_fields(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);  // QGC WPL 110
  while (std::getline(lines, line)) {
    std::vector<std::string> fields;
    std::istringstream in(line);
    for (std::string f; std::getline(in, f, '\t');) fields.push_back(f);
    rows.push_back(fields);
  }
  return rows;
}

TEST(PlanFormatsCli, Px4WaypointsSayNoValueWhereThePlanHasNull) {
  const std::string out = fresh_dir("formats-px4");
  const CliRun run = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 --firmware px4 -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json items = json::parse(read_text(out + "/drone-1.plan"))["mission"]["items"];
  const auto rows = wpl_fields(read_text(out + "/drone-1.waypoints"));
  ASSERT_EQ(rows.size(), items.size() + 1) << "the home row, then the .plan's items";
  std::size_t nulls = 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const json& item = items[i];
    const std::vector<std::string>& row = rows[i + 1];
    ASSERT_EQ(row.size(), 12u);
    EXPECT_EQ(std::stoi(row[3]), item["command"].get<int>());
    for (std::size_t k = 0; k < 4; ++k) {
      const json& p = item["params"][k];
      const std::string where = "item " + std::to_string(i + 1) + " param " + std::to_string(k + 1);
      if (p.is_null()) {
        EXPECT_EQ(row[4 + k], "NaN") << where;
        ++nulls;
      } else {
        EXPECT_NEAR(std::stod(row[4 + k]), p.get<double>(), 1e-6) << where;
      }
    }
  }
  EXPECT_GT(nulls, 0u) << "PX4's yaw and gimbal axes are left as they are";
  // swath's own check reads the NaN back as no value: the set passes.
  const CliRun verify = run_swath("verify " + out);
  EXPECT_EQ(verify.exit_code, 0) << verify.out << verify.err;
  // ArduPilot's .waypoints keep 0 there.
  const std::string ardupilot = fresh_dir("formats-ardupilot");
  ASSERT_EQ(run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 -o " +
                      ardupilot)
                .exit_code,
            0);
  EXPECT_EQ(read_text(ardupilot + "/drone-1.waypoints").find("NaN"), std::string::npos);
}

}  // namespace
}  // namespace swath::test
