// The mission readers (issue 45) against swath's own writers (a real meadow plan, round trip of
// its .plan, .waypoints, Litchi CSV and DJI KMZ),
// a hand-written QGroundControl-style .plan, altitude frames, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "meadow_survey.hpp"
#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/energy/budget.hpp"
#include "swath/energy/sim_config.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/missions/mission.hpp"
#include "swath/planning/survey_files.hpp"

namespace swath {
namespace {

std::string source(const std::string& relative) {
  return std::string(SWATH_SOURCE_DIR) + "/" + relative;
}

std::string fixture(const std::string& name) {
  return base::read_text_file(source("tests/fixtures/verify/" + name), "fixture");
}

// Every NAV_WAYPOINT of the plan's own mission, in WGS84, against the readers' items of each
// file swath writes for it: the same points in order, at the same height above home.
TEST(MissionReaders, ReadBackSwathsOwnFilesOfTheMeadow) {
  planning::SurveyRequest r = test::meadow_request(60);
  r.home = geometry::GeoPoint{47.3965, 8.5405, 0};
  const planning::SurveyPlan plan = planning::plan_survey(r);
  const auto files = planning::survey_files(plan, {true, true, true, false});
  const planning::DronePlan& drone = plan.drones.at(0);
  std::vector<geometry::GeoPoint> planned;
  for (const planning::MissionItem& item : drone.mission.items)
    if (item.kind == planning::ItemKind::waypoint)
      planned.push_back(plan.request.field.frame->to_geo(item.position));
  ASSERT_GT(planned.size(), 10u);
  int read = 0;
  for (const auto& [name, text] : files) {
    if (name != "drone-1.plan" && name != "drone-1.waypoints" && name != "drone-1-litchi.csv" &&
        name != "drone-1.kmz")
      continue;
    ++read;
    const missions::Mission m = missions::parse_mission(text, name);
    std::vector<const missions::Item*> waypoints;
    for (const missions::Item& item : m.items)
      if (item.command == 16) waypoints.push_back(&item);
    // Litchi and DJI add their landing point at home as a last waypoint.
    ASSERT_GE(waypoints.size(), planned.size()) << name;
    for (std::size_t k = 0; k < planned.size(); ++k) {
      EXPECT_LT(geometry::geodesic_distance_m(waypoints[k]->position, planned[k]), 1e-3)
          << name << " waypoint " << k;
      EXPECT_NEAR(missions::above_home_m(*waypoints[k], missions::home_amsl_m(m)), 60.0, 1e-3)
          << name << " waypoint " << k;
    }
    if (name == "drone-1.plan") {
      EXPECT_EQ(m.inclusion_fences.size(), plan.fence.size());
      EXPECT_NEAR(m.cruise_speed_m_s, drone.speed_m_s, 1e-3);
    }
  }
  EXPECT_EQ(read, 4);
}

TEST(MissionReaders, ReadsAQgcStylePlanWithItsFencesAndRally) {
  const missions::Mission m = missions::parse_mission(fixture("qgc-style.plan"), "qgc-style.plan");
  EXPECT_EQ(m.format, "QGC plan");
  EXPECT_DOUBLE_EQ(m.home.lat_deg, 47.39685);
  EXPECT_DOUBLE_EQ(m.home_amsl_m, 488.0);
  ASSERT_EQ(m.items.size(), 11u);
  EXPECT_EQ(m.items[0].command, 22);
  EXPECT_EQ(m.items[2].altitude_frame, missions::AltitudeFrame::relative);
  EXPECT_DOUBLE_EQ(m.items[2].altitude_m, 40.0);
  EXPECT_TRUE(std::isnan(m.items[2].params[3]));  // QGC writes unused params as null
  EXPECT_EQ(m.items[3].command, 206);
  EXPECT_DOUBLE_EQ(m.items[3].params[0], 15.0);
  EXPECT_EQ(m.items[2].place, "qgc-style.plan: item 3");
  EXPECT_EQ(m.inclusion_fences.size(), 1u);
  EXPECT_EQ(m.rally_points.size(), 1u);
  EXPECT_DOUBLE_EQ(m.cruise_speed_m_s, 5.0);  // a multirotor's hoverSpeed
}

TEST(MissionReaders, AmslAltitudesAreReadAboveHome) {
  const missions::Mission rel = missions::parse_mission(fixture("qgc-style.plan"), "rel.plan");
  const missions::Mission amsl =
      missions::parse_mission(fixture("qgc-style-amsl.plan"), "amsl.plan");
  ASSERT_EQ(rel.items.size(), amsl.items.size());
  for (std::size_t k = 0; k < rel.items.size(); ++k) {
    if (!missions::is_navigation(rel.items[k].command)) continue;
    EXPECT_EQ(amsl.items[k].altitude_frame, missions::AltitudeFrame::amsl);
    EXPECT_DOUBLE_EQ(missions::above_home_m(amsl.items[k], missions::home_amsl_m(amsl)),
                     missions::above_home_m(rel.items[k], missions::home_amsl_m(rel)));
  }
}

// The issue: an AMSL .plan read as heights above home climbed 488 m more. Budgeted through the
// same reader, the AMSL file and its relative twin fly the same time and energy.
TEST(MissionReaders, AnAmslPlanBudgetsAsItsRelativeTwin) {
  const energy::DroneProfile drone =
      energy::read_drone_profile(source("share/drones/quad-5ah.yaml"));
  const auto rel = energy::parse_waypoint_missions(fixture("qgc-style.plan"), "rel.plan");
  const auto amsl = energy::parse_waypoint_missions(fixture("qgc-style-amsl.plan"), "amsl.plan");
  const energy::DroneBudget a = energy::budget(rel.at(0), drone);
  const energy::DroneBudget b = energy::budget(amsl.at(0), drone);
  EXPECT_GT(a.flight_time_s, 60.0);
  EXPECT_NEAR(a.flight_time_s, b.flight_time_s, 1e-9);
  EXPECT_NEAR(a.energy_j, b.energy_j, 1e-6);
  // Closed form of the climb: 40 m at 3 m/s, the profile's climb speed, is in both.
  EXPECT_NEAR(b.timeline.at(1).altitude_m, 40.0, 1e-9);
}

TEST(MissionReaders, WplFramesGlobalAndRelativeAgree) {
  const std::string rows =
      "QGC WPL 110\n"
      "0\t1\t0\t16\t0\t0\t0\t0\t47.0\t8.0\t500\t1\n"
      "1\t0\t3\t16\t0\t0\t0\t0\t47.001\t8.0\t30\t1\n"
      "2\t0\t0\t16\t0\t0\t0\t0\t47.002\t8.0\t530\t1\n";
  const missions::Mission m = missions::parse_mission(rows, "m.waypoints");
  ASSERT_EQ(m.items.size(), 2u);
  EXPECT_EQ(m.items[1].place, "m.waypoints: item 2 (line 4)");
  EXPECT_DOUBLE_EQ(missions::above_home_m(m.items[0], missions::home_amsl_m(m)), 30.0);
  EXPECT_DOUBLE_EQ(missions::above_home_m(m.items[1], missions::home_amsl_m(m)), 30.0);
}

TEST(MissionReaders, BadFilesNameTheFileAndThePlace) {
  auto message = [](const std::string& text, const std::string& name) {
    try {
      missions::parse_mission(text, name);
    } catch (const base::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(
      message("QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t47\t8\t0\t1\n1\t0\t3\t16\t0\t0\n",
              "a.waypoints"),
      "a.waypoints: line 3: a WPL row has 12 fields (index, current, frame, command, 4 params, "
      "latitude, longitude, altitude, autocontinue); found 6");
  EXPECT_EQ(message("QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t47\t8\t0\t1\n"
                    "1\t0\t7\t16\t0\t0\t0\t0\t47\t8\t30\t1\n",
                    "b.waypoints"),
            "b.waypoints: item 1 (line 3): frame 7 is not a position frame (0 AMSL, 3 relative "
            "to home, 10 terrain)");
  std::string plan = fixture("qgc-style.plan");
  plan.replace(plan.find("\"type\": \"SimpleItem\""), 20, "\"type\": \"Other\"");
  EXPECT_EQ(message(plan, "c.plan"), "c.plan: item 1: 'type' must be SimpleItem or ComplexItem");
  const std::string survey =
      R"({"fileType": "Plan", "mission": {"plannedHomePosition": [47, 8, 0], "items": [)"
      R"({"type": "ComplexItem", "complexItemType": "StructureScan"}]}})";
  EXPECT_NE(message(survey, "d.plan").find("d.plan: item 1: the complex item 'StructureScan'"),
            std::string::npos);
  EXPECT_EQ(message("latitude,longitude,altitude(m),altitudemode,speed(m/s),photo_timeinterval,"
                    "photo_distinterval\n47,8,x,0,5,-1,-1\n",
                    "e.csv"),
            "e.csv: line 2: altitude(m) 'x' is not a number");
}

// What Windows editors and other apps write is read as the file it is: a byte order mark before
// a WPL file or a Litchi CSV, "QGC WPL 120", Litchi's columns in another order or in feet and
// miles per hour; a file of none of the formats is refused naming the ones expected.
TEST(MissionReaders, ByteOrderMarksReorderedColumnsAndImperialUnitsAreRead) {
  const std::string bom = "\xEF\xBB\xBF";
  const std::string wpl =
      "QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t47\t8\t500\t1\n"
      "1\t0\t3\t16\t0\t0\t0\t0\t47.001\t8.002\t40\t1\n";
  for (const std::string& text : {bom + wpl, "QGC WPL 120" + wpl.substr(11)}) {
    const missions::Mission m = missions::parse_mission(text, "w.waypoints");
    ASSERT_EQ(m.items.size(), 1u);
    EXPECT_DOUBLE_EQ(m.items[0].position.lon_deg, 8.002);
    EXPECT_DOUBLE_EQ(m.items[0].altitude_m, 40.0);
  }
  const std::vector<std::string> litchi = {
      "latitude,longitude,altitude(m),altitudemode,speed(m/s),photo_distinterval,"
      "photo_timeinterval\n47,8,40,0,5,-1,-1\n47.001,8.002,40,0,5,-1,-1\n",
      bom +
          "latitude,longitude,altitude(m),altitudemode,speed(m/s),photo_distinterval,"
          "photo_timeinterval\n47,8,40,0,5,-1,-1\n47.001,8.002,40,0,5,-1,-1\n",
      "photo_timeinterval,photo_distinterval,speed(m/s),altitudemode,altitude(m),longitude,"
      "latitude\n-1,-1,5,0,40,8,47\n-1,-1,5,0,40,8.002,47.001\n",
      "latitude,longitude,altitude(ft),altitudemode,speed(mph),photo_distinterval,"
      "photo_timeinterval\n47,8,131.2335958,0,11.1846814,-1,-1\n"
      "47.001,8.002,131.2335958,0,11.1846814,-1,-1\n"};
  for (const std::string& text : litchi) {
    SCOPED_TRACE(text.substr(0, 40));
    const missions::Mission m = missions::parse_mission(text, "l-litchi.csv");
    ASSERT_EQ(m.items.size(), 3u);  // the speed, two waypoints
    EXPECT_NEAR(m.items[0].params[1], 5.0, 1e-6);
    EXPECT_DOUBLE_EQ(m.items[2].position.lon_deg, 8.002);
    EXPECT_NEAR(m.items[2].altitude_m, 40.0, 1e-6);
  }
  auto message = [](const std::string& text, const std::string& name) {
    try {
      missions::parse_mission(text, name);
    } catch (const base::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("hello", "k.kmz"),
            "k.kmz: not a zip archive, which a DJI KMZ is (wpmz/waylines.wpml in it)");
  EXPECT_EQ(message(bom + "lat,lon\n47,8\n", "a.csv"),
            "a.csv: neither a QGC plan (a JSON object), a QGC WPL 110 file ('QGC WPL 110' on line "
            "1), a Litchi CSV (a header naming latitude, longitude, altitude(m) columns) nor a DJI "
            "KMZ (a zip archive)");
  EXPECT_EQ(message("latitude,longitude,altitude(yd),altitudemode,speed(m/s),photo_distinterval,"
                    "photo_timeinterval\n47,8,40,0,5,-1,-1\n",
                    "y.csv"),
            "y.csv: line 1: the Litchi header has no column 'altitude(m)' or 'altitude(ft)'");
}

// The places a WPL file's, a fence file's and a .plan's refused numbers and positions are named by
// (composed only when refused): the line of the row, the item, the param.
TEST(MissionReaders, RefusedPositionsAndNumbersNameTheirPlace) {
  auto message = [](const std::string& text, const std::string& name) {
    try {
      missions::parse_mission(text, name);
    } catch (const base::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  auto fence_message = [](const std::string& text) {
    missions::Mission m;
    try {
      missions::add_wpl_fences(m, text, "fence.waypoints");
    } catch (const base::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string home = "QGC WPL 110\n\n0\t1\t0\t16\t0\t0\t0\t0\t47\t8\t0\t1\n";
  EXPECT_EQ(message("QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t91\t8\t0\t1\n", "a.waypoints"),
            "a.waypoints: line 2: latitude/longitude out of range (91, 8)");
  EXPECT_EQ(message(home + "1\t0\t3\t16\t0\t0\t0\t0\t47\t-181\t30\t1\n", "b.waypoints"),
            "b.waypoints: item 1 (line 4): latitude/longitude out of range (47, -181)");
  EXPECT_EQ(fence_message("QGC WPL 110\n5001\t0\t3\t5001\t3\t0\t0\t0\t47\t8\t0\t1\n"
                          "\n5001\t0\t3\t5001\t3\t0\t0\t0\t95\t8\t0\t1\n"),
            "fence.waypoints: line 4: latitude/longitude out of range (95, 8)");
  EXPECT_EQ(fence_message("QGC WPL 110\n\n\n5001\t0\t3\t5001\t2\t0\t0\t0\t47\t8\t0\t1\n"),
            "fence.waypoints: line 4: a fence polygon has at least 3 vertices");
  EXPECT_EQ(fence_message("QGC WPL 110\n5100\t0\t3\t5100\t0\t0\t0\t0\t47\t8\t0\t1\n"
                          "16\t0\t3\t16\t0\t0\t0\t0\t47\t8\t0\t1\n"),
            "fence.waypoints: line 3: command 16 is no fence vertex, fence circle or rally point");
  // A fence circle of no radius, or a negative or missing one, is refused naming it and the key.
  const std::string fence_head =
      R"({"fileType": "Plan", "mission": {"plannedHomePosition": [47, 8, 0], "items": []}, )"
      R"("geoFence": {"circles": [{"inclusion": false, "circle": {"center": [47.5, 8.25])";
  EXPECT_EQ(message(fence_head + R"(, "radius": -5}}]}})", "n.plan"),
            "n.plan: geoFence circle 1 at 47.5, 8.25: radius -5 m must be above 0");
  EXPECT_EQ(message(fence_head + R"(, "radius": 0}}]}})", "z.plan"),
            "z.plan: geoFence circle 1 at 47.5, 8.25: radius 0 m must be above 0");
  EXPECT_EQ(message(fence_head + R"(}}]}})", "m.plan"),
            "m.plan: geoFence circle 1: radius must be a number");
  EXPECT_EQ(fence_message("QGC WPL 110\n5004\t0\t3\t5004\t-3\t0\t0\t0\t47\t8\t0\t1\n"),
            "fence.waypoints: line 2: fence circle at 47, 8: radius -3 m must be above 0");
  const std::string plan_head =
      R"({"fileType": "Plan", "mission": {"plannedHomePosition": [47, 8, 0], "items": [)"
      R"({"type": "SimpleItem", "command": 16, "frame": 3, "params": [0, 0, 0, null, 47, )";
  EXPECT_EQ(message(plan_head + R"("8", 30]}]}})", "c.plan"),
            "c.plan: item 1: params[5] must be a number");
  EXPECT_EQ(message(plan_head + R"(8, 30]}]}, "geoFence": {"polygons": [{"inclusion": true, )"
                                R"("polygon": [[47, 8], [47, 9], [47, true]]}]}})",
                    "d.plan"),
            "d.plan: geoFence polygon 1 longitude must be a number");
}

}  // namespace
}  // namespace swath
