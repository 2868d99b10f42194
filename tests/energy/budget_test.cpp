#include "swath/energy/budget.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "swath/base/input_error.hpp"
#include "swath/geometry/local_frame.hpp"

namespace swath::energy {
namespace {

using geometry::GeoPoint;
using geometry::LocalFrame;

const GeoPoint kHome{47.0, 8.0, 0.0};

// A QGC plan: take off to 50 m, a 100 m square whose first corner is home, return to launch;
// `hold_s` at the second corner (the waypoint's param1), `delay_s` after it (NAV_DELAY).
std::string square_plan(double speed, double hold_s = 0, double delay_s = 0) {
  const LocalFrame frame(kHome);
  std::string items;
  auto item = [&](int command, double x, double y, double alt, double p1 = 0) {
    const GeoPoint g = frame.to_geo({x, y});
    char buf[400];
    std::snprintf(
        buf, sizeof buf,
        R"({"type": "SimpleItem", "command": %d, "frame": 3, "params": [%.3f, 0, 0, null, %.10f, %.10f, %.3f]},)",
        command, p1, g.lat_deg, g.lon_deg, alt);
    items += buf;
  };
  item(22, 0, 0, 50);
  item(16, 100, 0, 50, hold_s);
  if (delay_s > 0)
    items += R"({"type": "SimpleItem", "command": 93, "frame": 2, "params": [)" +
             std::to_string(delay_s) + R"(, 0, 0, 0, 0, 0, 0]},)";
  item(16, 100, 100, 50);
  item(16, 0, 100, 50);
  items += R"({"type": "SimpleItem", "command": 20, "frame": 2, "params": [0, 0, 0, 0, 0, 0, 0]})";
  char head[300];
  std::snprintf(
      head, sizeof head,
      R"({"fileType": "Plan", "mission": {"vehicleType": 2, "hoverSpeed": %.3f, "plannedHomePosition": [47.0, 8.0, 0], "items": [)",
      speed);
  return std::string(head) + items + "]}}";
}

// The same square as a QGC WPL 110 file: home row 0 at 420 m above the sea (frame 0), a speed
// item, take-off and waypoints relative to home (frame 3) or absolute (frame 0), RTL (frame 2).
std::string square_wpl(double speed) {
  const LocalFrame frame(kHome);
  std::string out = "QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t47.0\t8.0\t420\t1\n";
  int row = 1;
  auto item = [&](int command, int item_frame, double p2, double x, double y, double alt) {
    const GeoPoint g = frame.to_geo({x, y});
    char buf[300];
    std::snprintf(buf, sizeof buf, "%d\t0\t%d\t%d\t0\t%.3f\t0\t0\t%.10f\t%.10f\t%.3f\t1\r\n", row++,
                  item_frame, command, p2, g.lat_deg, g.lon_deg, alt);
    out += buf;
  };
  item(22, 3, 0, 0, 0, 50);
  item(178, 2, speed, 0, 0, 0);
  item(16, 3, 0, 100, 0, 50);
  item(16, 0, 0, 100, 100, 470);  // absolute: 50 m above home
  item(16, 3, 0, 0, 100, 50);
  item(20, 2, 0, 0, 0, 0);
  return out;
}

DroneProfile quad() {
  DroneProfile d;
  d.source = "quad.yaml";
  d.drone.climb_speed_m_s = 2.5;
  d.drone.descent_speed_m_s = 2.0;
  d.power.mechanical = {150.0, 5.0, 0.0, 35.0};  // 150 W at any airspeed
  d.power.climb_w = 200.0;
  d.power.descent_w = 120.0;
  d.power.payload_w = 10.0;
  return d;
}

// By hand: climb 50 m at 2.5 m/s = 20 s at 210 W = 4200 J; 400 m at 5 m/s = 80 s at 160 W =
// 12800 J; descent 50 m at 2 m/s = 25 s at 130 W = 3250 J. Total 125 s, 20250 J.
TEST(Budget, SquareMissionAgainstTheHandSum) {
  const auto missions = parse_waypoint_missions(square_plan(5.0), "square.plan");
  ASSERT_EQ(missions.size(), 1u);
  EXPECT_TRUE(missions[0].returns_home);
  const DroneProfile d = quad();
  const DroneBudget b = budget(missions[0], d);
  EXPECT_NEAR(b.flight_time_s, 125.0, 1e-3);
  EXPECT_NEAR(b.energy_j, 20250.0, 0.5);
  EXPECT_NEAR(b.distance_m, 400.0, 1e-3);
  // SoC segment by segment with eq. 12.
  double soc = soc_after(d.battery, 1.0, 210.0, 20.0);
  soc = soc_after(d.battery, soc, 160.0, 80.0);
  soc = soc_after(d.battery, soc, 130.0, 25.0);
  EXPECT_NEAR(b.landing_soc, soc, 1e-9);
  EXPECT_NEAR(b.reserve_margin, soc - 0.2, 1e-9);
  EXPECT_TRUE(b.can_finish());
  // Take-off, four points (the take-off point, three corners), home, landing.
  ASSERT_EQ(b.timeline.size(), 7u);
  EXPECT_NEAR(b.timeline[2].t_s, 20.0 + 20.0, 1e-3);  // first corner after 100 m
  EXPECT_NEAR(b.timeline[2].position.x, 100.0, 1e-3);
  EXPECT_NEAR(b.timeline[2].geo.lat_deg, kHome.lat_deg, 1e-6);
}

// A hold costs the hover power for its time: 60 s at the corner and a 30 s NAV_DELAY after it,
// 90 s at 150 W (level flight at no airspeed: no wind) + 10 W payload = 14400 J on the hand sum.
TEST(Budget, HoldsAreHoveredForTheirTime) {
  const auto missions = parse_waypoint_missions(square_plan(5.0, 60, 30), "held.plan");
  ASSERT_EQ(missions.size(), 1u);
  ASSERT_EQ(missions[0].holds_s.size(), missions[0].points.size());
  EXPECT_DOUBLE_EQ(missions[0].holds_s[1], 90.0);
  const DroneBudget b = budget(missions[0], quad());
  EXPECT_NEAR(b.flight_time_s, 125.0 + 90.0, 1e-3);
  EXPECT_NEAR(b.energy_j, 20250.0 + 90.0 * 160.0, 0.5);
  // The corner is reached after the climb and 100 m (40 s); the timeline's point leaves it.
  EXPECT_NEAR(b.timeline[2].t_s, 40.0 + 90.0, 1e-3);
}

// A WPL file of the same square gives the same mission and budget as the .plan (the speed from
// its 178 item, absolute altitudes taken above home); its errors name the line.
TEST(Budget, WplFileIsTheSameMissionAsThePlan) {
  const auto plan = parse_waypoint_missions(square_plan(5.0), "square.plan");
  const auto wpl = parse_waypoint_missions(square_wpl(5.0), "square.waypoints");
  ASSERT_EQ(wpl.size(), 1u);
  EXPECT_EQ(wpl[0].drone, "square");
  ASSERT_EQ(wpl[0].points.size(), plan[0].points.size());
  for (std::size_t i = 0; i < plan[0].points.size(); ++i) {
    EXPECT_NEAR(wpl[0].points[i].x, plan[0].points[i].x, 1e-6);
    EXPECT_NEAR(wpl[0].points[i].y, plan[0].points[i].y, 1e-6);
    EXPECT_NEAR(wpl[0].altitudes_m[i], plan[0].altitudes_m[i], 1e-9);
  }
  EXPECT_TRUE(wpl[0].returns_home);
  // Take-off before the speed item: no speed known yet (0); then 5 m/s.
  EXPECT_EQ(wpl[0].speeds_m_s.front(), 0.0);
  EXPECT_EQ(wpl[0].speeds_m_s.back(), 5.0);
  DroneProfile d = quad();
  d.drone.speed_m_s = 5.0;
  EXPECT_NEAR(budget(wpl[0], d).energy_j, budget(plan[0], d).energy_j, 1e-6);
  auto error = [](const std::string& text) {
    try {
      parse_waypoint_missions(text, "m.waypoints");
    } catch (const base::InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error("QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t47\t8\t0\t1\n1\t0\t3\t16\t0\n"),
            "m.waypoints: line 3: a WPL row has 12 fields (index, current, frame, command, 4 "
            "params, latitude, longitude, altitude, autocontinue); found 5");
  EXPECT_EQ(error("QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t47\t8\t0\t1\n"
                  "1\t0\t3\t16\t0\t0\t0\t0\tnorth\t8\t50\t1\n"),
            "m.waypoints: line 3: field 9 'north' is not a number");
  EXPECT_EQ(error("QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t47\t8\t0\t1\n"
                  "1\t0\t7\t16\t0\t0\t0\t0\t47\t8\t50\t1\n"),
            "m.waypoints: item 1 (line 3): frame 7 is not a position frame (0 AMSL, 3 relative to "
            "home, 10 terrain)");
  EXPECT_EQ(error("QGC WPL 110\n"), "m.waypoints: the WPL file has no home row");
}

TEST(Budget, WhereTheReserveIsCrossed) {
  DroneProfile d = quad();
  d.battery.capacity_ah = 0.2;  // the climb takes 0.064 Ah, the square 0.195: reserve on a leg
  const DroneBudget b = budget(parse_waypoint_missions(square_plan(5.0), "s.plan")[0], d);
  ASSERT_TRUE(b.reserve_crossed);
  EXPECT_FALSE(b.can_finish());
  // After the climb, the reserve is reached when the cruise current has drawn the rest.
  const double after_climb = soc_after(d.battery, 1.0, 210.0, 20.0);
  const double s = seconds_to_soc(d.battery, after_climb, 0.2, 160.0);
  ASSERT_LT(s, 80.0);
  EXPECT_NEAR(b.reserve_crossed->t_s, 20.0 + s, 1e-6);
  // Along the square: distance 5 s/m.
  const double along = 5.0 * s;
  const double x = along < 100 ? along : 100, y = along < 100 ? 0 : along - 100;
  EXPECT_NEAR(b.reserve_crossed->position.x, x, 1e-4);  // lat/lon printed to 1e-10 degrees
  EXPECT_NEAR(b.reserve_crossed->position.y, y, 1e-4);
  EXPECT_NEAR(b.reserve_crossed->soc, 0.2, 1e-12);
}

TEST(Budget, GeoJsonPathsAndWind) {
  const LocalFrame frame(kHome);
  std::string coords;
  for (auto [x, y] : {std::pair{0.0, 0.0}, {300.0, 0.0}, {300.0, 50.0}, {0.0, 50.0}, {0.0, 0.0}}) {
    const GeoPoint g = frame.to_geo({x, y});
    char buf[100];
    std::snprintf(buf, sizeof buf, "[%.10f, %.10f],", g.lon_deg, g.lat_deg);
    coords += buf;
  }
  coords.pop_back();
  const std::string geojson =
      R"({"type": "FeatureCollection", "features": [
       {"type": "Feature", "properties": {"role": "path", "drone": 2, "altitude_m": 40, "speed_m_s": 10},
        "geometry": {"type": "LineString", "coordinates": [)" +
      coords + R"(]}},
       {"type": "Feature", "properties": {"role": "home"},
        "geometry": {"type": "Point", "coordinates": [8.0, 47.0]}}]})";
  const auto missions = parse_waypoint_missions(geojson, "mission.geojson");
  ASSERT_EQ(missions.size(), 1u);
  EXPECT_EQ(missions[0].drone, "drone-2");
  ASSERT_EQ(missions[0].points.size(), 3u);  // home legs implied
  DroneProfile d = quad();
  d.power.mechanical = {150.0, 10.0, 1.0, 35.0};  // all parasitic: 150 (v/10)^3
  d.drone.max_airspeed_m_s = 30;
  const DroneBudget calm = budget(missions[0], d);
  EXPECT_NEAR(calm.distance_m, 700.0, 1e-3);
  EXPECT_NEAR(calm.flight_time_s, 40 / 2.5 + 70.0 + 40 / 2.0, 1e-3);
  // 6 m/s from the east: eastbound legs need 16 m/s of air, westbound 4, north/south sqrt(136).
  d.wind = {6.0, 90.0};
  const DroneBudget windy = budget(missions[0], d);
  const double cruise = [&] {
    auto p = [](double v) { return 150.0 * std::pow(v / 10.0, 3) + 10.0; };
    return p(16.0) * 30.0 + p(4.0) * 30.0 + p(std::sqrt(136.0)) * 10.0;
  }();
  EXPECT_NEAR(windy.energy_j, cruise + 210.0 * 16.0 + 130.0 * 20.0, 0.5);
}

std::string budget_error_of(const std::string& text) {
  try {
    parse_waypoint_missions(text, "m.json");
  } catch (const base::InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(Budget, BadMissionsAreNamed) {
  EXPECT_EQ(budget_error_of("{"),
            "m.json: line 1, column 2: invalid JSON (syntax error while parsing object key - "
            "unexpected end of input; expected string literal)");
  EXPECT_EQ(budget_error_of(R"({"fileType": "Plan", "fileType": "Plan"})"),
            "m.json: the key \"fileType\" appears twice in one object; which one holds is "
            "ambiguous");
  EXPECT_EQ(budget_error_of(R"({"fileType": 1e999})"),
            "m.json: invalid JSON (number overflow parsing '1e999')");
  EXPECT_EQ(budget_error_of("[]"), "m.json: expected a JSON object");
  EXPECT_EQ(
      budget_error_of(R"({"type": "Feature"})"),
      "m.json: neither a GeoJSON FeatureCollection (mission.geojson), a QGC plan nor a QGC WPL "
      "110 file");
  EXPECT_EQ(budget_error_of(R"({"type": "FeatureCollection", "features": []})"),
            "m.json: no feature with role 'path' (a drone's flight)");
  EXPECT_EQ(
      budget_error_of(R"({"type": "FeatureCollection", "features": [{"properties": {"role": "path"},
        "geometry": {"type": "LineString", "coordinates": [[8, 47], [8.1, 47]]}}]})"),
      "m.json: feature 0: the path has no altitude (give properties.altitude_m or [lon, lat, alt] "
      "positions)");
  EXPECT_EQ(
      budget_error_of(
          R"({"type": "FeatureCollection", "features": [{"properties": {"role": "path", "altitude_m": 30},
        "geometry": {"type": "LineString", "coordinates": [[8, 47], [8.1, 97]]}}]})"),
      "m.json: feature 0, position 1: latitude must be within ±90 and longitude within ±180 "
      "degrees");
  EXPECT_EQ(budget_error_of(R"({"fileType": "Plan", "mission": {"plannedHomePosition": [47, 8, 0],
        "items": [{"type": "SimpleItem", "command": 16, "frame": 3, "params": [0, 0, 0]}]}})"),
            "m.json: item 1: 'params' must hold 7 values");
  EXPECT_EQ(
      budget_error_of(
          R"({"fileType": "Plan", "mission": {"plannedHomePosition": [47, 8, 0], "items": []}})"),
      "m.json: the mission has no positional item");
}

}  // namespace
}  // namespace swath::energy
