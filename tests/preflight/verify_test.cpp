// The preflight check (issue 45): the flown path's timing against closed forms, each check caught
// on a planted violation and silent on the clean mission, distances against brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "../../missions/src/zip_archive.hpp"
#include "../../preflight/src/checks.hpp"
#include "local_field.hpp"
#include "meadow_survey.hpp"
#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/energy/sim_config.hpp"
#include "swath/geometry/autopilot_track.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/missions/fence_storage.hpp"
#include "swath/missions/mission.hpp"
#include "swath/planning/survey_files.hpp"
#include "swath/preflight/verify.hpp"

namespace swath::preflight {
namespace {

const geometry::GeoPoint kOrigin{47.0, 8.0, 0.0};

struct Row {
  int command;
  double x = 0, y = 0, alt_m = 0, p1 = 0, p2 = 0, p3 = 0;
};

// A WPL 110 file of rows placed in local metres around kOrigin, home at `home`.
std::string wpl(const std::vector<Row>& rows, geometry::Point2 home = {0, 0}) {
  const geometry::LocalFrame frame(kOrigin);
  const geometry::GeoPoint h = frame.to_geo(home);
  std::string out = "QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t" + base::fixed_text(h.lat_deg, 9) +
                    "\t" + base::fixed_text(h.lon_deg, 9) + "\t0\t1\n";
  int index = 1;
  for (const Row& r : rows) {
    const bool nav = missions::is_navigation(r.command);
    const geometry::GeoPoint g = nav ? frame.to_geo({r.x, r.y}) : geometry::GeoPoint{0, 0, 0};
    out += std::to_string(index++) + "\t0\t" + (nav ? "3" : "2") + "\t" +
           std::to_string(r.command) + "\t" + base::fixed_text(r.p1, 3) + "\t" +
           base::fixed_text(r.p2, 3) + "\t" + base::fixed_text(r.p3, 3) + "\t0\t" +
           base::fixed_text(g.lat_deg, 9) + "\t" + base::fixed_text(g.lon_deg, 9) + "\t" +
           base::fixed_text(r.alt_m, 3) + "\t1\n";
  }
  return out;
}

DroneFile drone(const std::vector<Row>& rows, const std::string& name, double launch_s = 0,
                geometry::Point2 home = {0, 0}) {
  return {missions::parse_mission(wpl(rows, home), name), launch_s, ""};
}

std::vector<geometry::GeoPoint> square(double x0, double y0, double x1, double y1) {
  const geometry::LocalFrame frame(kOrigin);
  return {frame.to_geo({x0, y0}), frame.to_geo({x1, y0}), frame.to_geo({x1, y1}),
          frame.to_geo({x0, y1})};
}

// Take off to 20 m, a line east with the camera on from (0, 20) to (100, 20), camera off, RTL.
std::vector<Row> survey_rows() {
  return {{22, 0, 0, 20},    {16, 0, 20, 20},   {206, 0, 0, 0, 10},
          {16, 100, 20, 20}, {206, 0, 0, 0, 0}, {20}};
}

const Violation* find(const Report& r, const std::string& check) {
  for (const Violation& v : r.violations)
    if (v.check == check) return &v;
  return nullptr;
}

TEST(FlownPath, TimesLegsWithStopsAsClosedForms) {
  // Climb 20 m at 2.5 m/s (8 s); 100 m east at 5 m/s stopping at both ends (100/5 + 2 * 5/5 =
  // 22 s); RTL: 20 m is above RTL_ALT's 15 m (no climb), 100 m back (22 s), 20 m down at 1.5 m/s.
  const DroneFile d = drone({{22, 0, 0, 20}, {16, 100, 0, 20}, {20}}, "a.waypoints");
  const FlownPath p = fly(d.mission, geometry::LocalFrame(kOrigin), FlightModel{});
  EXPECT_NEAR(p.duration_s, 8 + 22 + 22 + 20 / 1.5, 1e-4);  // positions written to 0.1 mm
  // Stops where it turns back and at home: each overrun is v^2 / 2a = 5 m along the leg.
  ASSERT_EQ(p.overruns.size(), 2u);
  EXPECT_NEAR(p.overruns[0].to.x, 105.0, 1e-3);
  EXPECT_NEAR(p.overruns[1].to.x, -5.0, 1e-3);
  EXPECT_DOUBLE_EQ(missions::stopping_distance_m(5.0), 5.0);
}

TEST(FlownPath, ShortLegsNeverReachCruiseAndGentleCornersDoNotStop) {
  // 4 m between stops at a = 2.5: 2 sqrt(L / a) = 2.53 s (cruise speed 5 m/s is never reached).
  const DroneFile d = drone({{22, 0, 0, 10}, {16, 4, 0, 10}, {16, 104, 10, 10}, {20}}, "b");
  const FlownPath p = fly(d.mission, geometry::LocalFrame(kOrigin), FlightModel{});
  ASSERT_GE(p.legs.size(), 3u);
  const Leg& short_leg = p.legs[1];
  // The corner at (4, 0) turns by 5.7 degrees: no stop there, so this leg stops at its start only.
  EXPECT_FALSE(short_leg.stops_at_end);
  EXPECT_NEAR(short_leg.t_end_s - short_leg.t_start_s, std::sqrt(2 * 4 / 2.5), 1e-4);
}

// A stop approached slowly: cruise at 5 m/s to x = 100 - d, DO_CHANGE_SPEED 0.2 m/s there, the
// stop at x = 100 (the way home turns back). Braking at 2.5 m/s² from 5 m/s over d leaves
// v² = 25 - 5 d (never below 0.04), and the overrun v² / 5 = 5 - d m (at least 8 mm): a cut
// 0.5 m before the stop still runs 4.5 m past it.
FlownPath slow_approach(double d) {
  const DroneFile f = drone(
      {{22, 0, 0, 20}, {16, 100 - d, 0, 20}, {178, 0, 0, 0, 1, 0.2}, {16, 100, 0, 20}, {20}}, "s");
  return fly(f.mission, geometry::LocalFrame(kOrigin), FlightModel{});
}

TEST(FlownPath, ASpeedCutBeforeAStopBrakesAtTheDecelerationFromTheSpeedBefore) {
  for (const double d : {0.5, 1.0, 2.5, 4.0, 4.9, 5.0, 8.0}) {
    SCOPED_TRACE(d);
    const FlownPath p = slow_approach(d);
    ASSERT_EQ(p.overruns.size(), 2u);  // at x = 100 and at home
    const double expected_m = std::max(5.0 - d, 0.2 * 0.2 / 5);
    EXPECT_NEAR(p.overruns[0].to.x - p.overruns[0].from.x, expected_m, 1e-3);
    // The way home is flown at the slow speed from its start (at rest after the stop).
    EXPECT_NEAR(p.overruns[1].from.x - p.overruns[1].to.x, 0.2 * 0.2 / 5, 1e-6);
  }
}

TEST(Verify, ASlowApproachBegunTooLateReachesAZone) {
  CheckOptions o;
  o.clearance_m = 0;
  o.zones = {{"wall", square(102, -20, 110, 20)}};
  const Report late = verify(
      {drone({{22, 0, 0, 20}, {16, 99.5, 0, 20}, {178, 0, 0, 0, 1, 0.2}, {16, 100, 0, 20}, {20}},
             "late.waypoints")},
      o);
  const Violation* v = find(late, "no-fly zone");
  ASSERT_NE(v, nullptr) << report_text(late);
  EXPECT_NE(v->place.find("stopping margin"), std::string::npos);
  // Begun 4 m before, it brakes to 2.24 m/s and runs 1 m on: short of the wall at 102.
  const Report early = verify(
      {drone({{22, 0, 0, 20}, {16, 96, 0, 20}, {178, 0, 0, 0, 1, 0.2}, {16, 100, 0, 20}, {20}},
             "early.waypoints")},
      o);
  EXPECT_EQ(find(early, "no-fly zone"), nullptr) << report_text(early);
}

// Photos every 10 m from the line's start (206's param3: one at once) along a 105 m line written
// as two legs: 1 + floor(105 / 10) = 11 photos wherever the split, as the camera triggers on the
// distance flown since the last photo (counted leg by leg anew, the second leg's start would be
// counted again: 12 photos).
TEST(Verify, PhotosAreCountedAlongALineSplitIntoLegs) {
  for (const double split_x : {45.0, 50.0, 55.0, 99.0}) {
    SCOPED_TRACE(split_x);
    const Report r = verify({drone({{22, 0, 0, 20},
                                    {16, 0, 20, 20},
                                    {206, 0, 0, 0, 10, 0, 1},
                                    {16, split_x, 20, 20},
                                    {16, 105, 20, 20},
                                    {206, 0, 0, 0, 0},
                                    {20}},
                                   "p.waypoints")},
                            {});
    const auto f = std::find_if(r.figures.begin(), r.figures.end(),
                                [](const Figure& g) { return g.check == "photos"; });
    ASSERT_NE(f, r.figures.end());
    EXPECT_EQ(*f->value, 11.0) << report_text(r);
  }
}

TEST(Verify, CleanMissionPassesEveryCheck) {
  CheckOptions o;
  o.zones = {{"pond", square(40, 40, 60, 60)}};  // 20 m north of the line
  const Report r = verify({drone(survey_rows(), "a.waypoints")}, o);
  EXPECT_TRUE(r.ok()) << report_text(r);
  // The least clearance is the line's 20 m to the pond (closed form).
  for (const Figure& f : r.figures)
    if (f.check == "zones") EXPECT_NEAR(*f.value, 20.0, 1e-3);
}

TEST(Verify, AWaypointMovedIntoAZone) {
  std::vector<Row> rows = survey_rows();
  rows[3].x = 50, rows[3].y = 50;  // the line's end inside the pond
  CheckOptions o;
  o.zones = {{"pond", square(40, 40, 60, 60)}};
  const Report r = verify({drone(rows, "a.waypoints")}, o);
  const Violation* v = find(r, "no-fly zone");
  ASSERT_NE(v, nullptr) << report_text(r);
  EXPECT_NE(v->place.find("a.waypoints: item"), std::string::npos);
  EXPECT_NEAR(v->amount, 5.0, 1e-3);  // inside it: 0 m of the 5 m asked
}

TEST(Verify, TheStoppingMarginAloneReachesAZone) {
  // The line ends 3 m short of a wall; the 5 m stop overrun enters it.
  CheckOptions o;
  o.clearance_m = 0;
  o.zones = {{"wall", square(103, 0, 110, 40)}};
  const Report r = verify({drone(survey_rows(), "a.waypoints")}, o);
  const Violation* v = find(r, "no-fly zone");
  ASSERT_NE(v, nullptr);
  EXPECT_NE(v->place.find("stopping margin"), std::string::npos);
}

TEST(Verify, AFenceShrunkOffTheHome) {
  missions::Mission m = missions::parse_mission(wpl(survey_rows()), "a.waypoints");
  m.inclusion_fences = {square(-20, -20, 120, 40)};
  EXPECT_TRUE(verify({{m, 0, ""}}, {}).ok());
  m.inclusion_fences = {square(-20, 10, 120, 40)};  // the home (0, 0) 10 m outside
  const Report r = verify({{m, 0, ""}}, {});
  bool home = false;
  for (const Violation& v : r.violations)
    if (v.check == "fence" && v.place == "a.waypoints: home") {
      home = true;
      EXPECT_NEAR(v.amount, 10.0, 1e-3);
    }
  EXPECT_TRUE(home) << report_text(r);
}

// The fence violation of the largest amount (the place farthest outside), or none.
const Violation* farthest_outside(const Report& r) {
  const Violation* worst = nullptr;
  for (const Violation& v : r.violations)
    if (v.check == "fence" && (!worst || v.amount > worst->amount)) worst = &v;
  return worst;
}

TEST(Verify, EveryInclusionFenceMustHoldNotJustOne) {
  // The flight (home (0, 0), the line (0, 20)-(100, 20), its 5 m stopping margin to (105, 20))
  // lies inside fence 1; fence 2 ends at x = 60. ArduPilot (by default) and PX4 breach outside
  // any one inclusion fence: the margin's end is 45 m outside fence 2.
  missions::Mission m = missions::parse_mission(wpl(survey_rows()), "a.waypoints");
  m.inclusion_fences = {square(-20, -20, 120, 40), square(-20, -20, 60, 40)};
  const Report r = verify({{m, 0, ""}}, {});
  const Violation* v = farthest_outside(r);
  ASSERT_NE(v, nullptr) << report_text(r);
  EXPECT_NEAR(v->amount, 45.0, 1e-3);
  EXPECT_NE(v->text.find("m outside a.waypoints's inclusion fence 2"), std::string::npos)
      << v->text;
  ASSERT_TRUE(v->at.has_value());
  EXPECT_NEAR(geometry::LocalFrame(kOrigin).to_local(*v->at).x, 105.0, 0.01);
  // ArduPilot's FENCE_OPTIONS union: inside fence 1 is enough.
  CheckOptions any_one;
  any_one.fence_union = true;
  EXPECT_TRUE(verify({{m, 0, ""}}, any_one).ok()) << report_text(verify({{m, 0, ""}}, any_one));
  // PX4 has no union: its file fails even so.
  m.autopilot = missions::Autopilot::px4;
  EXPECT_NEAR(farthest_outside(verify({{m, 0, ""}}, any_one))->amount, 45.0, 1e-3);
}

TEST(Verify, AnInclusionCircleBesideAPolygonMustHoldToo) {
  // A 60 m circle about home: the stopping margin's end (105, 20) is hypot(105, 20) - 60 outside.
  missions::Mission m = missions::parse_mission(wpl(survey_rows()), "a.waypoints");
  m.inclusion_fences = {square(-20, -20, 120, 40)};
  m.inclusion_circles = {{kOrigin, 60.0}};
  const Report r = verify({{m, 0, ""}}, {});
  const Violation* v = farthest_outside(r);
  ASSERT_NE(v, nullptr) << report_text(r);
  EXPECT_NEAR(v->amount, std::hypot(105.0, 20.0) - 60.0, 1e-3);
  EXPECT_NE(v->text.find("m outside a.waypoints's inclusion circle 1"), std::string::npos)
      << v->text;
}

// A DJI KMZ of waylines (Folders) of points in local metres around kOrigin, each point 40 m above
// the take-off point at `speed` m/s, its missionConfig climbing to `take_off_m` first and
// returning home at `rth_m` (finishAction goHome).
std::string kmz(const std::vector<std::vector<geometry::Point2>>& waylines, double take_off_m,
                double rth_m, const std::string& speed = "5") {
  const geometry::LocalFrame frame(kOrigin);
  std::string xml =
      R"(<?xml version="1.0" encoding="UTF-8"?><kml xmlns="http://www.opengis.net/kml/2.2" )"
      R"(xmlns:wpml="http://www.dji.com/wpmz/1.0.2"><Document><wpml:missionConfig>)"
      "<wpml:finishAction>goHome</wpml:finishAction><wpml:takeOffSecurityHeight>" +
      base::shortest_text(take_off_m) + "</wpml:takeOffSecurityHeight><wpml:globalRTHHeight>" +
      base::shortest_text(rth_m) + "</wpml:globalRTHHeight></wpml:missionConfig>";
  for (const auto& wayline : waylines) {
    xml += "<Folder><wpml:executeHeightMode>relativeToStartPoint</wpml:executeHeightMode>";
    for (const geometry::Point2& p : wayline) {
      const geometry::GeoPoint g = frame.to_geo(p);
      xml += "<Placemark><Point><coordinates>" + base::fixed_text(g.lon_deg, 9) + "," +
             base::fixed_text(g.lat_deg, 9) +
             "</coordinates></Point><wpml:executeHeight>40</wpml:executeHeight>"
             "<wpml:waypointSpeed>" +
             speed + "</wpml:waypointSpeed></Placemark>";
    }
    xml += "</Folder>";
  }
  return missions::zip_archive({{"wpmz/waylines.wpml", xml + "</Document></kml>"}});
}

DroneFile kmz_drone(const std::string& bytes) {
  return {missions::parse_mission(bytes, "k.kmz"), 0, ""};
}

TEST(Verify, EveryWaylineOfAKmzIsFlownInTurn) {
  // The second wayline (Folder) goes north through a pond the first never comes near.
  CheckOptions o;
  o.zones = {{"pond", square(90, 40, 110, 60)}};
  const std::string two = kmz({{{0, 0}, {100, 0}}, {{100, 0}, {100, 100}}}, 20, 40);
  const Report r = verify({kmz_drone(two)}, o);
  const Violation* v = find(r, "no-fly zone");
  ASSERT_NE(v, nullptr) << report_text(r);
  EXPECT_NE(v->place.find("k.kmz: waylines.wpml: wayline 1: waypoint 1"), std::string::npos)
      << v->place;
  EXPECT_EQ(find(verify({kmz_drone(kmz({{{0, 0}, {100, 0}}}, 20, 40))}, o), "no-fly zone"),
            nullptr);
}

TEST(Verify, AKmzIsFlownNoSlowerThanDjisLeastSpeed) {
  // A stop at (100, 0) 0.15 m short of a wall: at 0.2 m/s it would run 8 mm on, but DJI flies no
  // slower than 1 m/s, which runs 0.2 m on (1 / (2 x 2.5)), into the wall.
  CheckOptions o;
  o.clearance_m = 0;
  o.zones = {{"wall", square(100.15, -10, 120, 10)}};
  const std::vector<std::vector<geometry::Point2>> line = {{{-20, 0}, {100, 0}}};
  for (const char* speed : {"0.2", "1"}) {
    const Report r = verify({kmz_drone(kmz(line, 20, 40, speed))}, o);
    const Violation* v = find(r, "no-fly zone");
    ASSERT_NE(v, nullptr) << speed << " m/s: " << report_text(r);
    EXPECT_NE(v->place.find("stopping margin"), std::string::npos) << v->place;
  }
  // Stopped 0.25 m short, the wall is out of reach at 1 m/s.
  o.zones = {{"wall", square(100.25, -10, 120, 10)}};
  EXPECT_EQ(find(verify({kmz_drone(kmz(line, 20, 40, "0.2"))}, o), "no-fly zone"), nullptr);
}

TEST(Verify, AKmzClimbsToItsTakeOffSecurityHeightAndReturnsAtItsRthHeight) {
  const std::vector<std::vector<geometry::Point2>> line = {{{0, 0}, {100, 0}}};
  EXPECT_EQ(find(verify({kmz_drone(kmz(line, 20, 60))}, {}), "ceiling"), nullptr);
  const Report climb = verify({kmz_drone(kmz(line, 200, 60))}, {});
  const Violation* v = find(climb, "ceiling");
  ASSERT_NE(v, nullptr) << report_text(climb);
  EXPECT_NEAR(v->amount, 80.0, 1e-6);  // 200 m against the 120 m ceiling
  EXPECT_NE(v->place.find("takeOffSecurityHeight"), std::string::npos) << v->place;
  const Report rth = verify({kmz_drone(kmz(line, 20, 200))}, {});
  v = find(rth, "ceiling");
  ASSERT_NE(v, nullptr) << report_text(rth);
  EXPECT_NEAR(v->amount, 80.0, 1e-6);
  EXPECT_NE(v->place.find("finishAction goHome"), std::string::npos) << v->place;
}

// A ring of `n` points on a 200 m circle about (50, 10): it holds the whole survey flight.
std::vector<geometry::GeoPoint> round_fence(int n) {
  const geometry::LocalFrame frame(kOrigin);
  std::vector<geometry::GeoPoint> ring;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    ring.push_back(frame.to_geo({50 + 200 * std::cos(a), 10 + 200 * std::sin(a)}));
  }
  return ring;
}

TEST(FenceStorage, CountsAsArduPilotStoresItAndWarnsPastTheCopterLimit) {
  // A 4-byte header, 2 bytes and 8 per point for each polygon, 13 bytes for each circle.
  EXPECT_EQ(missions::ardupilot_fence_storage({4, 5}, 1).bytes, 4u + 2 * 2 + 9 * 8 + 13);
  missions::Mission m = missions::parse_mission(wpl(survey_rows()), "a.waypoints");
  m.inclusion_fences = {round_fence(69)};  // 4 + 2 + 69 * 8 = 558 bytes: fits 560
  Report r = verify({{m, 0, ""}}, {});
  EXPECT_TRUE(r.ok()) << report_text(r);
  EXPECT_TRUE(r.warnings.empty()) << report_text(r);
  m.inclusion_fences = {round_fence(70)};  // 566 bytes
  r = verify({{m, 0, ""}}, {});
  EXPECT_TRUE(r.ok()) << report_text(r);  // a warning, not a failure
  ASSERT_EQ(r.warnings.size(), 1u) << report_text(r);
  EXPECT_EQ(r.warnings[0].rfind("a.waypoints: the fence has 70 points in 1 polygon: 566 bytes of "
                                "ArduPilot's fence storage, more than the 560 bytes ArduCopter "
                                "keeps",
                                0),
            0u)
      << r.warnings[0];
  EXPECT_NE(report_text(r).find("\n  warning    a.waypoints: the fence has 70 points"),
            std::string::npos);
  // The same polygon again (a fence.waypoints repeating the .plan's) is one upload.
  m.inclusion_fences.push_back(m.inclusion_fences.front());
  EXPECT_EQ(missions::ardupilot_fence_storage(m).bytes, 566u);
}

TEST(FenceStorage, PX4TakesSixtyFourFenceItemsInAll) {
  // Two polygons of 32 points: 64 items, what PX4 takes; one more point is refused.
  const std::vector<geometry::GeoPoint> ring = round_fence(32);
  missions::Mission m = missions::parse_mission(wpl(survey_rows()), "a.waypoints");
  m.autopilot = missions::Autopilot::px4;
  m.inclusion_fences = {ring, round_fence(32)};
  m.inclusion_fences[1].front().lat_deg += 1e-6;  // another polygon, not the first repeated
  EXPECT_TRUE(verify({{m, 0, ""}}, {}).warnings.empty());
  m.inclusion_fences[1].push_back(ring.front());
  const Report r = verify({{m, 0, ""}}, {});
  ASSERT_EQ(r.warnings.size(), 1u) << report_text(r);
  EXPECT_EQ(r.warnings[0].rfind("a.waypoints: the fence has 65 points in 2 polygons: 65 fence "
                                "items, more than the 64 PX4 takes in all",
                                0),
            0u)
      << r.warnings[0];
}

TEST(Verify, ALegAboveTheCeiling) {
  std::vector<Row> rows = survey_rows();
  rows[3].alt_m = 130;
  const Report r = verify({drone(rows, "a.waypoints")}, {});
  const Violation* v = find(r, "ceiling");
  ASSERT_NE(v, nullptr);
  EXPECT_NEAR(v->amount, 10.0, 1e-6);
  // Placed at the leg's highest point: the waypoint flown at 130 m (its file position, to the
  // WPL file's 8 decimals of a degree).
  ASSERT_TRUE(v->at.has_value());
  const geometry::Point2 at = geometry::LocalFrame(kOrigin).to_local(*v->at);
  EXPECT_NEAR(at.x, rows[3].x, 0.01);
  EXPECT_NEAR(at.y, rows[3].y, 0.01);
  CheckOptions higher;
  higher.ceiling_m = 130;
  EXPECT_EQ(find(verify({drone(rows, "a.waypoints")}, higher), "ceiling"), nullptr);
}

// Ground rising 0.5 m per metre east of x = 50 (500 m above sea level west of it): closed form.
class RampGround : public geometry::Ground {
 public:
  std::vector<double> heights_m(const std::vector<geometry::GeoPoint>& points) const override {
    std::vector<double> out;
    for (const geometry::GeoPoint& g : points)
      out.push_back(500.0 + 0.5 * std::max(0.0, frame_.to_local(g).x - 50.0));
    return out;
  }
  double resolution_m() const override { return 1.0; }
  std::string source() const override { return "ramp"; }

 private:
  geometry::LocalFrame frame_{kOrigin};
};

TEST(Verify, WithADemTheGroundRisesUnderTheLine) {
  // The line flies at 20 m above home; at x = 100 the ground is 25 m above home: 5 m under it.
  CheckOptions o;
  o.ground = std::make_shared<RampGround>();
  const Report r = verify({drone(survey_rows(), "a.waypoints")}, o);
  const Violation* v = find(r, "ground");
  ASSERT_NE(v, nullptr) << report_text(r);
  EXPECT_NEAR(v->amount, 5.0 - (20.0 - 25.0), 1e-3);  // 10 m below the least 5 m
  for (const Figure& f : r.figures)
    if (f.check == "ground") EXPECT_NEAR(*f.value, -5.0, 1e-3);
  // Terrain-relative items (frame 10) follow it: 20 m above the ground everywhere.
  std::string text = wpl(survey_rows());
  for (std::size_t at = text.find("\t0\t3\t"); at != std::string::npos;
       at = text.find("\t0\t3\t", at))
    text.replace(at, 5, "\t0\t10\t");
  const Report follow = verify({{missions::parse_mission(text, "t.waypoints"), 0, ""}}, o);
  EXPECT_EQ(find(follow, "ground"), nullptr) << report_text(follow);
}

TEST(Verify, TwoDronesCrossingAtOneHeightAndTime) {
  // a: climb (8 s), north 50 m (12 s), east 100 m: at (50, 50) 11 s in, t = 31 s. b from (50, -30):
  // climb (8 s), north 20 m (6 s), hold 4 s, north 120 m: at (50, 50) 13 s in, t = 31 s. Same 20 m.
  const std::vector<Row> a = {{22, 0, 0, 20}, {16, 0, 50, 20}, {16, 100, 50, 20}, {20}};
  const std::vector<Row> b = {{22, 50, -30, 20}, {16, 50, -10, 20, 4}, {16, 50, 110, 20}, {20}};
  const Report r =
      verify({drone(a, "a.waypoints"), drone(b, "b.waypoints", 0, {50, -30})}, CheckOptions{});
  const Violation* v = find(r, "separation");
  ASSERT_NE(v, nullptr) << report_text(r);
  EXPECT_NEAR(v->amount, 10.0, 1e-3);  // they meet
  EXPECT_NE(v->text.find("t = 31.0 s"), std::string::npos) << v->text;
  // b launched after a has landed: never airborne together, homes 58 m apart.
  const Report later =
      verify({drone(a, "a.waypoints"), drone(b, "b.waypoints", 300, {50, -30})}, CheckOptions{});
  EXPECT_EQ(find(later, "separation"), nullptr) << report_text(later);
}

TEST(Verify, SortiesOfOneDroneFlyInTurn) {
  const std::vector<Row> a = {{22, 0, 0, 20}, {16, 0, 50, 20}, {16, 100, 50, 20}, {20}};
  DroneFile first = drone(a, "d-1.waypoints"), second = drone(a, "d-2.waypoints");
  first.sorties_of = second.sorties_of = "d";
  const Report r = verify({first, second}, CheckOptions{});
  EXPECT_EQ(find(r, "separation"), nullptr) << report_text(r);
  const double t = fly(first.mission, geometry::LocalFrame(kOrigin), {}).duration_s;
  bool said = false;  // the second launches when the first has landed
  for (const Figure& f : r.figures)
    said = said || (f.check == "flight" &&
                    f.text.find("d-2.waypoints " + base::fixed_text(t / 60, 1) + " min from t = " +
                                base::fixed_text(t, 0) + " s") != std::string::npos);
  EXPECT_TRUE(said) << report_text(r);
}

TEST(Verify, SeparationAgreesWithBruteForceInTime) {
  const std::vector<Row> a = {{22, 0, 0, 20}, {16, 0, 50, 20}, {16, 100, 50, 20}, {20}};
  const std::vector<Row> b = {{22, 60, -40, 25}, {16, 60, 10, 25}, {16, 60, 120, 25}, {20}};
  const DroneFile da = drone(a, "a"), db = drone(b, "b", 3.0, {60, -40});
  const geometry::LocalFrame frame(kOrigin);
  const FlownPath pa = fly(da.mission, frame, {}), pb = fly(db.mission, frame, {});
  double brute = 1e9;
  for (double t = 3.0; t <= std::min(pa.duration_s, pb.duration_s + 3.0); t += 1e-3) {
    const Point3 p = position_at(pa, t), q = position_at(pb, t - 3.0);
    brute = std::min(brute, std::hypot(p.x - q.x, p.y - q.y, p.z_m - q.z_m));
  }
  CheckOptions o;
  o.separation_m = 0;
  for (const Figure& f : verify({da, db}, o).figures)
    if (f.check == "separation") EXPECT_NEAR(*f.value, brute, 1e-2);
}

TEST(Verify, ABatteryTooSmall) {
  std::string yaml = base::read_text_file(
      std::string(SWATH_SOURCE_DIR) + "/share/drones/quad-5ah.yaml", "profile");
  CheckOptions o;
  o.drone = energy::parse_drone_profile(yaml, "quad-5ah.yaml");
  EXPECT_EQ(find(verify({drone(survey_rows(), "a")}, o), "energy"), nullptr);
  yaml.replace(yaml.find("capacity_ah: 5"), 14, "capacity_ah: 0.05");
  o.drone = energy::parse_drone_profile(yaml, "tiny.yaml");
  const Report small = verify({drone(survey_rows(), "a")}, o);  // outlives the pointer below
  const Violation* v = find(small, "energy");
  ASSERT_NE(v, nullptr);
  EXPECT_GT(v->amount, 0.0);
}

TEST(Verify, ATriggerLeftOnInTheWayHome) {
  std::vector<Row> rows = survey_rows();
  rows.erase(rows.begin() + 4);  // no 206 0 after the line: photos all the way home
  const Report r = verify({drone(rows, "a.waypoints")}, {});
  const Violation* v = find(r, "photos");
  ASSERT_NE(v, nullptr) << report_text(r);
  EXPECT_NE(v->text.find("the return to launch"), std::string::npos);
  EXPECT_TRUE(verify({drone(survey_rows(), "a.waypoints")}, {}).ok());
}

// The InputError fly() throws for `rows`, or "flown".
std::string refusal(const std::vector<Row>& rows) {
  try {
    fly(drone(rows, "m.waypoints").mission, geometry::LocalFrame(kOrigin), {});
  } catch (const base::InputError& e) {
    return e.what();
  }
  return "flown";
}

// Take off at home, A (0, 100), B (100, 100), C (100, 0), DO_JUMP to A (item 2) `repeats` times,
// RTL: each repeat flies C -> A across the square's diagonal, never flown without the jump.
std::vector<Row> jump_rows(double repeats) {
  return {{22, 0, 0, 20},   {16, 0, 100, 20},           {16, 100, 100, 20},
          {16, 100, 0, 20}, {177, 0, 0, 0, 2, repeats}, {20}};
}

TEST(FlownPath, ADoJumpIsUnrolledItsRepeatCountTimes) {
  const geometry::LocalFrame frame(kOrigin);
  for (const int repeats : {0, 1, 3}) {
    SCOPED_TRACE(repeats);
    const FlownPath p = fly(drone(jump_rows(repeats), "j").mission, frame, {});
    int at_a = 0;
    for (const Leg& l : p.legs) at_a += std::hypot(l.to.x, l.to.y - 100) < 0.01;
    EXPECT_EQ(at_a, 1 + repeats);  // the first pass and one per jump
  }
  CheckOptions o;
  o.zones = {{"diagonal", square(45, 45, 55, 55)}};  // 35 m from every side of the square
  EXPECT_EQ(find(verify({drone(jump_rows(0), "j.waypoints")}, o), "no-fly zone"), nullptr);
  const Report r = verify({drone(jump_rows(1), "j.waypoints")}, o);
  const Violation* v = find(r, "no-fly zone");
  ASSERT_NE(v, nullptr) << report_text(r);
  EXPECT_EQ(v->place, "j.waypoints: item 2 (line 4)");  // the leg to A, after the jump
  EXPECT_EQ(refusal(jump_rows(-1)),
            "m.waypoints: item 5 (line 7): DO_JUMP (177) repeats -1 times (-1: forever); a "
            "flight that never ends cannot be checked");
  std::vector<Row> astray = jump_rows(1);
  astray[4].p1 = 9;
  EXPECT_EQ(refusal(astray),
            "m.waypoints: item 5 (line 7): DO_JUMP (177) goes to item 9, which the file does not "
            "have (1 to 6)");
}

TEST(FlownPath, CommandsItDoesNotModelAreRefusedByNumberAndName) {
  const std::vector<std::pair<int, std::string>> commands = {
      {17, "NAV_LOITER_UNLIM"},  {31, "NAV_LOITER_TO_ALT"}, {82, "NAV_SPLINE_WAYPOINT"},
      {94, "NAV_PAYLOAD_PLACE"}, {179, "DO_SET_HOME"},      {999, "unknown"},
      {31000, "unknown"}};
  for (const auto& [command, name] : commands) {
    EXPECT_EQ(refusal({{22, 0, 0, 20}, {command, 50, 50, 20}, {16, 100, 0, 20}, {20}}),
              "m.waypoints: item 2 (line 4): command " + std::to_string(command) + " (" + name +
                  ") is not modelled by swath verify; its flight cannot be checked");
    EXPECT_FALSE(modelled_command(command));
  }
  // Camera, gimbal and region-of-interest items move nothing: flown past.
  EXPECT_EQ(refusal({{22, 0, 0, 20}, {201, 50, 50, 20}, {205}, {16, 100, 0, 20}, {20}}), "flown");
}

// LOITER_TURNS 2 turns of 30 m (param3 30: clockwise) round (0, 100): the way there passes 25 m
// from a zone the circle crosses; a zone 6 m outside the circle is 6 m away (to 0.1 % of 30 m).
TEST(Verify, LoiterTurnsFliesItsCircle) {
  const std::vector<Row> rows = {{22, 0, 0, 20}, {18, 0, 100, 20, 2, 0, 30}, {20}};
  CheckOptions o;
  o.zones = {{"crossed", square(25, 95, 35, 105)}};
  const Report r = verify({drone(rows, "c.waypoints")}, o);
  const Violation* v = find(r, "no-fly zone");
  ASSERT_NE(v, nullptr) << report_text(r);
  EXPECT_EQ(v->place, "c.waypoints: item 2 (line 4)");
  o.zones = {{"beside", square(36, 95, 40, 105)}};
  const Report beside = verify({drone(rows, "c.waypoints")}, o);
  EXPECT_TRUE(beside.ok()) << report_text(beside);
  for (const Figure& f : beside.figures)
    if (f.check == "zones") EXPECT_NEAR(*f.value, 6.0, 0.03);
  // Two turns at 5 m/s, 4 pi 30 / 5 = 75.4 s, on top of the flight to the edge and back; the
  // stops at the circle's ends add up to 1 s each (less: its first sides are short, and the model
  // times a leg after one that could not reach speed at full speed).
  const geometry::LocalFrame frame(kOrigin);
  const FlownPath p = fly(drone(rows, "c").mission, frame, {});
  const FlownPath straight =
      fly(drone({{22, 0, 0, 20}, {16, 0, 70, 20}, {20}}, "s").mission, frame, {});
  const double circling_s = 4 * std::numbers::pi * 30 / 5;
  EXPECT_GT(p.duration_s - straight.duration_s, circling_s);
  EXPECT_LT(p.duration_s - straight.duration_s, circling_s + 2.1);
  EXPECT_EQ(refusal({{22, 0, 0, 20}, {18, 0, 100, 20, 2, 0, 0}, {20}}),
            "m.waypoints: item 2 (line 4): LOITER_TURNS (18) with radius 0 flies the autopilot's "
            "CIRCLE_RADIUS, which swath verify does not know; give param3");
}

// DO_CHANGE_SPEED's param1 2 and 3 set the climb and descent speeds (ArduCopter's
// ModeAuto::do_change_speed), leaving the horizontal speed as it was.
TEST(FlownPath, ClimbAndDescentSpeedChangesAreVertical) {
  const FlownPath p = fly(
      drone({{178, 0, 0, 0, 2, 1}, {22, 0, 0, 20}, {16, 100, 0, 20}, {178, 0, 0, 0, 3, 0.5}, {20}},
            "v")
          .mission,
      geometry::LocalFrame(kOrigin), {});
  ASSERT_EQ(p.legs.size(), 4u);  // climb, east, home (20 m is above RTL_ALT), descent
  EXPECT_NEAR(p.legs[0].t_end_s - p.legs[0].t_start_s, 20.0, 1e-6);  // 20 m at 1 m/s
  EXPECT_EQ(p.legs[1].speed_m_s, 5.0);
  EXPECT_NEAR(p.legs[1].t_end_s - p.legs[1].t_start_s, 100.0 / 5 + 2 * 5 / 5.0, 1e-4);
  EXPECT_NEAR(p.legs[3].t_end_s - p.legs[3].t_start_s, 40.0, 1e-6);  // 20 m at 0.5 m/s
}

TEST(Verify, BelowHomeWithoutADemIsUnderTheGround) {
  const Report r = verify({drone({{22, 0, 0, 20}, {16, 100, 0, -10}, {20}}, "n.waypoints")}, {});
  const Violation* v = find(r, "ground");
  ASSERT_NE(v, nullptr) << report_text(r);
  EXPECT_NEAR(v->amount, 10.0, 1e-3);
  EXPECT_EQ(v->place, "n.waypoints: item 2 (line 4)");
  EXPECT_TRUE(verify({drone({{22, 0, 0, 20}, {16, 100, 0, 0}, {20}}, "z.waypoints")}, {}).ok());
}

// The energy check flies the flown path: a 20-minute hold costs 20 minutes of hovering.
TEST(Verify, EnergyHoversThroughAHold) {
  CheckOptions o;
  o.drone = energy::parse_drone_profile(
      base::read_text_file(std::string(SWATH_SOURCE_DIR) + "/share/drones/quad-5ah.yaml", "p"),
      "quad-5ah.yaml");
  auto minutes = [&](const std::vector<Row>& rows) {
    const Report r = verify({drone(rows, "h.waypoints")}, o);
    for (const Figure& f : r.figures)
      if (f.check == "energy") return *f.value / 60;
    return -1.0;
  };
  std::vector<Row> held = survey_rows();
  held[3].p1 = 1200;
  EXPECT_NEAR(minutes(held) - minutes(survey_rows()), 20.0, 1e-6);
  held[3].p1 = 0;
  held.insert(held.begin() + 4, Row{93, 0, 0, 0, 1200});  // NAV_DELAY
  EXPECT_NEAR(minutes(held) - minutes(survey_rows()), 20.0, 1e-6);
  // Each DO_JUMP repeat flies C -> A, A -> B and B -> C once more: 341.4 m at 5 m/s.
  const double loop_min = (200 + 100 * std::sqrt(2.0)) / 5 / 60;
  EXPECT_NEAR(minutes(jump_rows(3)) - minutes(jump_rows(0)), 3 * loop_min, 1e-4);
}

// A Mission Planner fence file is one by its rows (fence and rally items only), whatever its
// name; its fence return point (5000) is not flown and passed over.
TEST(VerifyFiles, AFenceFileIsKnownByItsContent) {
  const geometry::LocalFrame frame(kOrigin);
  std::string fence = "QGC WPL 110\n";
  const geometry::GeoPoint ret = frame.to_geo({0, 0});
  fence += "0\t0\t0\t5000\t0\t0\t0\t0\t" + base::fixed_text(ret.lat_deg, 9) + "\t" +
           base::fixed_text(ret.lon_deg, 9) + "\t0\t1\n";
  int row = 1;
  for (const geometry::GeoPoint& g : square(-20, -20, 60, 40))  // the line ends 40 m outside it
    fence += std::to_string(row++) + "\t0\t0\t5001\t4\t0\t0\t0\t" + base::fixed_text(g.lat_deg, 9) +
             "\t" + base::fixed_text(g.lon_deg, 9) + "\t0\t1\n";
  const Report r =
      verify_files({{"d/a.waypoints", wpl(survey_rows())}, {"d/field-fence.waypoints", fence}}, {});
  EXPECT_EQ(r.files, std::vector<std::string>{"d/a.waypoints"});
  const Violation* v = find(r, "fence");
  ASSERT_NE(v, nullptr) << report_text(r);
  EXPECT_NEAR(v->amount, 40.0, 1e-2);
}

// segment_distance against sampling both segments, on random segments (fixed seed).
TEST(Checks, SegmentDistanceAgreesWithSampling) {
  std::mt19937 rng(45);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int trial = 0; trial < 200; ++trial) {
    const geometry::Point2 p{u(rng), u(rng)}, q{u(rng), u(rng)}, a{u(rng), u(rng)},
        b{u(rng), u(rng)};
    double brute = 1e9;
    for (int i = 0; i <= 400; ++i)
      brute = std::min(brute, geometry::distance_to_segment(p + (q - p) * (i / 400.0), a, b));
    const SegmentDistance d = segment_distance(p, q, a, b);
    EXPECT_LE(d.distance_m, brute + 1e-9);
    EXPECT_NEAR(d.distance_m, brute, geometry::distance(p, q) / 400 + 1e-9);  // the sample step
    EXPECT_NEAR(geometry::distance_to_segment(d.at, a, b), d.distance_m, 1e-9);
  }
}

// ring_distance (which measures only the edges whose bounding box comes near enough) against
// measuring every edge, the first nearest kept: the same distance and point, bit for bit, on random
// rings around random segments (fixed seed), at every scale from 1 mm to 2,000 km, on integer grids
// (many equally near edges: the first must win), with points for segments, repeated vertices and
// far-off coordinates.
SegmentDistance every_edge_distance(geometry::Point2 p, geometry::Point2 q,
                                    const geometry::Ring& ring) {
  SegmentDistance best{std::numeric_limits<double>::infinity(), p};
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const SegmentDistance d = segment_distance(p, q, ring[i], ring[(i + 1) % ring.size()]);
    if (d.distance_m < best.distance_m) best = d;
  }
  return best;
}

TEST(Checks, RingDistanceIsEveryEdgesNearest) {
  std::mt19937_64 rng(52);
  std::uniform_real_distribution<double> unit(0, 1);
  int skipped_some = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double scale = std::pow(10.0, -3.0 + 9.3 * unit(rng));
    const bool grid = trial % 4 == 0;
    const geometry::Point2 offset =
        trial % 7 == 0 ? geometry::Point2{3e6 * unit(rng), -5e6 * unit(rng)} : geometry::Point2{};
    auto point = [&] {
      geometry::Point2 v{(unit(rng) - 0.5) * scale, (unit(rng) - 0.5) * scale};
      if (grid) v = {std::round(v.x / scale * 8), std::round(v.y / scale * 8)};
      return v + offset;
    };
    geometry::Ring ring(3 + rng() % 60);
    for (auto& v : ring) v = point();
    if (trial % 5 == 0) ring[rng() % ring.size()] = ring[rng() % ring.size()];
    const geometry::Point2 p = point();
    const geometry::Point2 q = trial % 6 == 0 ? p : point();
    const SegmentDistance fast = ring_distance(p, q, ring);
    const SegmentDistance every = every_edge_distance(p, q, ring);
    ASSERT_EQ(fast.distance_m, every.distance_m) << "trial " << trial;
    ASSERT_EQ(fast.at.x, every.at.x) << "trial " << trial;
    ASSERT_EQ(fast.at.y, every.at.y) << "trial " << trial;
    // Most rings have an edge far beyond the nearest, which the bound leaves out (else this would
    // compare the brute force with itself).
    for (std::size_t i = 0; i < ring.size(); ++i)
      if (segment_distance(p, q, ring[i], ring[(i + 1) % ring.size()]).distance_m >
          2 * every.distance_m + 1) {
        ++skipped_some;
        break;
      }
  }
  EXPECT_GT(skipped_some, 5000);
}

// check_zones (which leaves out a ring zone whose bounding box is too far from a piece to matter,
// and measures ArduPilot's track only where it could matter) against measuring every piece, and
// both its tracks, against every zone: the same least clearance, where, and violations, on random
// flights among random holes, circles and own fences (fixed seed).
void reference_check_zones(const FileContext& f, const std::vector<LocalZone>& zones,
                           double clearance_m, Checked& out) {
  const auto closest = [](geometry::Point2 p, geometry::Point2 a, geometry::Point2 b) {
    const geometry::Point2 d = b - a;
    const double len2 = geometry::dot(d, d);
    if (len2 <= 0) return a;
    const double t = std::clamp(geometry::dot(p - a, d) / len2, 0.0, 1.0);
    return a + d * t;
  };
  using base::fixed_text;
  const geometry::AutopilotTrack track(*f.frame, f.path->home.xy());
  for (const PathPiece& piece : pieces(*f.path))
    for (const LocalZone& zone : zones) {
      const double asked = zone.own_fence ? 0.0 : clearance_m;
      const auto measure = [&](geometry::Point2 p, geometry::Point2 q) -> SegmentDistance {
        if (zone.radius_m <= 0) return zone_distance(p, q, zone.ring);
        const geometry::Point2 c = zone.ring.front();
        const geometry::Point2 at = closest(c, p, q);
        return {std::max(0.0, geometry::distance(at, c) - zone.radius_m), at};
      };
      // The straight leg, then both of ArduPilot's tracks, every time.
      SegmentDistance d = measure(piece.from.xy(), piece.to.xy());
      double bow_seen = 0;
      const double bow = track.bow_m(piece.from.xy(), piece.to.xy());
      if (bow >= geometry::AutopilotTrack::kNegligibleBow_m)
        for (const auto& points : track.tracks(piece.from.xy(), piece.to.xy(),
                                               geometry::AutopilotTrack::pieces_for(bow)))
          for (std::size_t k = 0; k + 1 < points.size(); ++k) {
            const SegmentDistance on = measure(points[k], points[k + 1]);
            if (on.distance_m < d.distance_m) d = on, bow_seen = bow;
          }
      if (d.distance_m < out.least_clearance_m) {
        out.least_clearance_m = d.distance_m;
        out.least_clearance_where = zone.name;
      }
      if (d.distance_m <= 0 || d.distance_m < asked - 1e-3)
        out.violations.push_back(
            {"no-fly zone", piece_name(piece), f.frame->to_geo(d.at), asked - d.distance_m,
             d.distance_m <= 0
                 ? piece_name(piece) + " enters " + zone.name + " (" + fixed_text(asked, 2) +
                       " m clearance asked)" + on_track(bow_seen)
                 : piece_name(piece) + " comes within " + fixed_text(d.distance_m, 2) + " m of " +
                       zone.name + " (" + fixed_text(asked, 2) + " m asked: " +
                       fixed_text(asked - d.distance_m, 2) + " m short)" + on_track(bow_seen)});
    }
}

TEST(Checks, CheckZonesIsEveryPieceAgainstEveryZone) {
  std::mt19937_64 rng(57);
  std::uniform_real_distribution<double> unit(0, 1);
  const geometry::LocalFrame frame(kOrigin);
  int violations = 0, quiet = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const double size_m = std::pow(10.0, 1.0 + 3.0 * unit(rng));
    auto point = [&] { return geometry::Point2{size_m * unit(rng), size_m * unit(rng)}; };
    std::vector<LocalZone> zones;
    for (int z = static_cast<int>(rng() % 12); z > 0; --z) {
      LocalZone zone;
      zone.name = "zone " + std::to_string(z);
      const geometry::Point2 c = point();
      const double r = size_m * 0.1 * unit(rng);
      if (rng() % 5 == 0) {  // a circle
        zone.ring = {c};
        zone.radius_m = r + 0.1;
      } else {
        for (int k = 3 + static_cast<int>(rng() % 20); k > 0; --k) {
          const double a = 2 * M_PI * unit(rng);
          zone.ring.push_back(c + geometry::Point2{std::cos(a), std::sin(a)} * (r * unit(rng)));
        }
      }
      zone.own_fence = rng() % 4 == 0;
      zones.push_back(zone);
    }
    auto point3 = [&] {
      const geometry::Point2 v = point();
      return Point3{v.x, v.y, 50.0};
    };
    FlownPath path;
    path.source = "t.plan";
    path.home = point3();
    Point3 at = path.home;
    for (int k = static_cast<int>(rng() % 40); k > 0; --k) {
      Leg leg;
      leg.from = at;
      leg.to = rng() % 6 == 0 ? at : point3();  // now and then a hold in place
      leg.kind = rng() % 8 == 0 ? LegKind::hold : LegKind::cruise;
      leg.place = "t.plan: item " + std::to_string(k);
      path.legs.push_back(leg);
      at = leg.to;
    }
    if (rng() % 3 == 0) path.overruns.push_back({at, point3(), "t.plan: item 0"});
    const FileContext f{"t.plan", &path, &frame, {}, 0.0};
    const double clearance_m = rng() % 3 == 0 ? 0.0 : size_m * 0.05 * unit(rng);
    Checked fast, every;
    if (rng() % 2) fast.least_clearance_m = every.least_clearance_m = size_m * unit(rng);
    check_zones(f, zones, clearance_m, fast);
    reference_check_zones(f, zones, clearance_m, every);
    ASSERT_EQ(fast.least_clearance_m, every.least_clearance_m) << "trial " << trial;
    ASSERT_EQ(fast.least_clearance_where, every.least_clearance_where) << "trial " << trial;
    ASSERT_EQ(fast.violations.size(), every.violations.size()) << "trial " << trial;
    for (std::size_t k = 0; k < fast.violations.size(); ++k) {
      ASSERT_EQ(fast.violations[k].text, every.violations[k].text) << "trial " << trial;
      ASSERT_EQ(fast.violations[k].amount, every.violations[k].amount) << "trial " << trial;
      ASSERT_EQ(fast.violations[k].at->lat_deg, every.violations[k].at->lat_deg);
      ASSERT_EQ(fast.violations[k].at->lon_deg, every.violations[k].at->lon_deg);
    }
    (every.violations.empty() ? quiet : violations)++;
  }
  EXPECT_GT(violations, 30);  // both outcomes are common
  EXPECT_GT(quiet, 30);
}

TEST(VerifyFiles, ASetWithoutAMissionFileIsBadInput) {
  EXPECT_TRUE(verify_files({{"a.waypoints", wpl(survey_rows())}}, {}).ok());
  EXPECT_THROW(verify_files({{"notes.txt", "x"}}, {}), base::InputError);
}

// ---- Photos: swath verify's count of a written .plan against swath plan's planned photos ----

double verified_photos(const planning::SurveyPlan& plan, const planning::Flight& f) {
  DroneFile d;
  d.mission = missions::parse_mission(planning::qgc_plan(plan, f), f.file_stem + ".plan");
  const Report r = verify({d}, {});
  for (const Figure& g : r.figures)
    if (g.check == "photos" && g.value) return *g.value;
  ADD_FAILURE() << "no photo count for " << f.file_stem;
  return -1;
}

// A star-shaped field of 6 to 15 vertices around (0, 0) of radius 120-300 m, with a pond near
// its middle half the time (slow approaches split lines into several legs), home south-west.
planning::SurveyRequest random_request(std::mt19937& rng) {
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  geometry::Ring outer;
  const int n = 6 + static_cast<int>(rng() % 10);
  const double r_m = uniform(120, 300);
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    outer.push_back(geometry::Point2{std::cos(a), std::sin(a)} * (r_m * uniform(0.6, 1.0)));
  }
  planning::SurveyRequest r = test::meadow_request(uniform(40, 90));
  r.field = test::local_field({outer, {}});
  const geometry::LocalFrame& frame = *r.field.frame;
  if (rng() % 2) {
    const geometry::Point2 c{uniform(-0.2, 0.2) * r_m, uniform(-0.2, 0.2) * r_m};
    const double h = uniform(8, 25);
    r.exclusions.push_back(
        {frame.to_geo(c + geometry::Point2{-h, -h}), frame.to_geo(c + geometry::Point2{h, -h}),
         frame.to_geo(c + geometry::Point2{h, h}), frame.to_geo(c + geometry::Point2{-h, h})});
    r.clearance_m = uniform(3, 10);
  }
  r.speed_m_s = uniform(3, 10);
  r.home = frame.to_geo({-1.3 * r_m, -1.3 * r_m});
  return r;
}

// The camera triggers on the distance flown since its last photo: a line split into several
// legs (slow approaches beside a zone, --waypoint-spacing) is one run of photos. swath verify
// counted each leg's start again: 277 photos on the vineyard where swath plan plans 275.
TEST(VerifyPhotos, AgreeWithSwathPlanOnTheBundledFieldsAndRandomOnes) {
  std::vector<std::pair<std::string, planning::SurveyRequest>> requests;
  requests.push_back({"vineyard", test::vineyard_request()});
  planning::SurveyRequest meadow = test::meadow_request(60);
  meadow.home = geometry::GeoPoint{47.3965, 8.5405, 0};
  requests.push_back({"meadow", meadow});
  meadow.waypoint_spacing_m = 37;
  requests.push_back({"meadow, waypoints every 37 m", meadow});
  std::mt19937 rng(275);
  for (int k = 0; k < 30; ++k)
    requests.push_back({"random " + std::to_string(k), random_request(rng)});
  int split_lines = 0;
  for (const auto& [name, request] : requests) {
    SCOPED_TRACE(name);
    planning::SurveyPlan plan;
    try {
      plan = planning::plan_survey(request);
    } catch (const base::InputError&) {
      continue;  // a random layout swath plan refuses
    }
    for (const planning::Flight& f : planning::flights_of(plan)) {
      EXPECT_EQ(verified_photos(plan, f), static_cast<double>(f.photos->size())) << f.file_stem;
      std::size_t waypoints = 0;
      for (const planning::MissionItem& it : f.mission->items)
        waypoints += it.kind == planning::ItemKind::waypoint;
      split_lines += waypoints > 2 * f.mission->lines.size();
    }
  }
  EXPECT_GT(split_lines, 5);  // the case that differed: lines flown as several legs
}

}  // namespace
}  // namespace swath::preflight
