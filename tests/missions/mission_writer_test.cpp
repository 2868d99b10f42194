// The mission writers (swath/missions/writers.hpp) against the readers beside them: random
// missions (fixed seeds) written and read back give the same items, home, speed, fences and rally
// points, to the precision each format prints. MAV_CMD numbers are typed here on purpose: the
// MAVLink common message set's values, independent of commands.hpp.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/missions/mission.hpp"
#include "swath/missions/writers.hpp"

namespace swath {
namespace {

using missions::AltitudeFrame;
using missions::Item;
using missions::Mission;

// Commands swath writes: (command, navigation); navigation ones take a position frame.
const std::vector<std::pair<int, bool>> kCommands = {
    {16, true},    {21, true},   {22, true},   {178, false},  {206, false}, {2000, false},
    {2001, false}, {203, false}, {205, false}, {1000, false}, {20, false},  {189, false}};

struct Rng {
  std::mt19937 engine;
  double uniform(double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(engine); }
  int below(int n) { return std::uniform_int_distribution<>(0, n - 1)(engine); }
  double rounded(double lo, double hi, int decimals) {
    return base::round_to(uniform(lo, hi), decimals);
  }
  geometry::GeoPoint point() { return {rounded(-80, 80, 9), rounded(-179, 179, 9), 0.0}; }
};

Item random_item(Rng& rng) {
  const auto [command, navigation] = kCommands[std::size_t(rng.below(int(kCommands.size())))];
  Item item;
  item.command = command;
  if (navigation) {
    const int frames[] = {0, 3, 10};
    const AltitudeFrame altitude_frames[] = {AltitudeFrame::amsl, AltitudeFrame::relative,
                                             AltitudeFrame::terrain};
    const int f = rng.below(3);
    item.frame = frames[f];
    item.altitude_frame = altitude_frames[f];
    item.params = {rng.rounded(0, 30, 3), 0, 0, std::nan("")};
    item.position = rng.point();
    item.altitude_m = rng.rounded(-50, 500, 3);
  } else {
    item.frame = 2;
    item.params = {rng.rounded(-90, 90, 3), rng.rounded(0, 20, 3), rng.below(2) ? std::nan("") : 1,
                   0};
  }
  return item;
}

std::vector<geometry::GeoPoint> random_ring(Rng& rng) {
  std::vector<geometry::GeoPoint> ring;
  for (int k = 3 + rng.below(4); k > 0; --k) ring.push_back(rng.point());
  return ring;
}

Mission random_mission(std::uint32_t seed) {
  Rng rng{std::mt19937(seed)};
  Mission m;
  m.home = rng.point();
  m.home_amsl_m = rng.rounded(-10, 3000, 3);
  m.cruise_speed_m_s = rng.rounded(1, 25, 3);
  m.fixed_wing = rng.below(2) == 1;
  for (int k = 1 + rng.below(30); k > 0; --k) m.items.push_back(random_item(rng));
  for (int k = 1 + rng.below(2); k > 0; --k) m.inclusion_fences.push_back(random_ring(rng));
  for (int k = rng.below(3); k > 0; --k) m.exclusion_fences.push_back(random_ring(rng));
  for (int k = 1 + rng.below(3); k > 0; --k) m.rally_points.push_back(rng.point());
  return m;
}

// A param as the file gives it back: NaN is null in a .plan, 0 in a WPL row.
void expect_param(double written, double read, bool wpl, const std::string& where) {
  if (std::isnan(written)) {
    if (wpl)
      EXPECT_EQ(read, 0.0) << where;
    else
      EXPECT_TRUE(std::isnan(read)) << where;
    return;
  }
  EXPECT_NEAR(read, written, wpl ? 0.5e-6 : 0.0) << where;
}

void expect_points(const std::vector<geometry::GeoPoint>& written,
                   const std::vector<geometry::GeoPoint>& read, double tolerance_deg,
                   const std::string& where) {
  ASSERT_EQ(read.size(), written.size()) << where;
  for (std::size_t k = 0; k < written.size(); ++k) {
    EXPECT_NEAR(read[k].lat_deg, written[k].lat_deg, tolerance_deg) << where << " point " << k;
    EXPECT_NEAR(read[k].lon_deg, written[k].lon_deg, tolerance_deg) << where << " point " << k;
  }
}

// The items read back: commands, frames, params; positions and altitudes of the navigation ones
// (the readers keep no position for a command that flies to none).
void expect_items(const Mission& written, const Mission& read, bool wpl) {
  ASSERT_EQ(read.items.size(), written.items.size());
  const double degrees = wpl ? 0.5e-9 : 0.0, metres = wpl ? 0.5e-6 : 0.0;
  for (std::size_t k = 0; k < written.items.size(); ++k) {
    const Item &w = written.items[k], &r = read.items[k];
    const std::string where = "item " + std::to_string(k);
    EXPECT_EQ(r.command, w.command) << where;
    EXPECT_EQ(r.frame, w.frame) << where;
    EXPECT_EQ(r.altitude_frame, w.altitude_frame) << where;
    for (std::size_t p = 0; p < 4; ++p)
      expect_param(w.params[p], r.params[p], wpl, where + " param " + std::to_string(p + 1));
    if (!missions::is_navigation(w.command)) continue;
    EXPECT_NEAR(r.position.lat_deg, w.position.lat_deg, degrees) << where;
    EXPECT_NEAR(r.position.lon_deg, w.position.lon_deg, degrees) << where;
    EXPECT_NEAR(r.altitude_m, w.altitude_m, metres) << where;
  }
}

TEST(MissionWriters, QgcPlanReadsBackAsWritten) {
  for (std::uint32_t seed = 1; seed <= 100; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Mission m = random_mission(seed);
    const Mission read =
        missions::parse_mission(missions::write_qgc_plan(m, {12, 2}), "random.plan");
    EXPECT_EQ(read.format, "QGC plan");
    expect_points({m.home}, {read.home}, 0.0, "home");
    EXPECT_EQ(read.home_amsl_m, m.home_amsl_m);
    EXPECT_EQ(read.cruise_speed_m_s, m.cruise_speed_m_s);
    EXPECT_EQ(read.fixed_wing, m.fixed_wing);
    expect_items(m, read, false);
    ASSERT_EQ(read.inclusion_fences.size(), m.inclusion_fences.size());
    for (std::size_t k = 0; k < m.inclusion_fences.size(); ++k)
      expect_points(m.inclusion_fences[k], read.inclusion_fences[k], 0.0, "inclusion fence");
    ASSERT_EQ(read.exclusion_fences.size(), m.exclusion_fences.size());
    for (std::size_t k = 0; k < m.exclusion_fences.size(); ++k)
      expect_points(m.exclusion_fences[k], read.exclusion_fences[k], 0.0, "exclusion fence");
    expect_points(m.rally_points, read.rally_points, 0.0, "rally points");
  }
}

// ---- The .plan's items, written directly, against the nlohmann tree json_text dumps (the
// writer's former way, kept here): the same bytes for random missions, and for items whose numbers
// are not finite, negative or large, and for a mission without items.

using nlohmann::ordered_json;

ordered_json reference_polygon(const std::vector<geometry::GeoPoint>& ring) {
  ordered_json points = ordered_json::array();
  for (const geometry::GeoPoint& g : ring) points.push_back({g.lat_deg, g.lon_deg});
  return points;
}

std::string reference_qgc_plan(const Mission& m, const missions::QgcPlanSettings& settings) {
  ordered_json items = ordered_json::array();
  int jump_id = 1;
  for (const Item& item : m.items) {
    ordered_json j;
    if (item.altitude_frame != AltitudeFrame::none) {
      j["AMSLAltAboveTerrain"] = nullptr;
      j["Altitude"] = item.altitude_m;
      j["AltitudeMode"] = settings.altitude_mode;
    }
    j["autoContinue"] = true;
    j["command"] = item.command;
    j["doJumpId"] = jump_id++;
    j["frame"] = item.frame;
    ordered_json p = ordered_json::array();
    for (double v : {item.params[0], item.params[1], item.params[2], item.params[3],
                     item.position.lat_deg, item.position.lon_deg, item.altitude_m})
      p.push_back(std::isnan(v) ? ordered_json() : ordered_json(v));
    j["params"] = p;
    j["type"] = "SimpleItem";
    items.push_back(j);
  }
  ordered_json polygons = ordered_json::array();
  for (const auto& ring : m.inclusion_fences)
    polygons.push_back({{"inclusion", true}, {"polygon", reference_polygon(ring)}, {"version", 1}});
  for (const auto& ring : m.exclusion_fences)
    polygons.push_back(
        {{"inclusion", false}, {"polygon", reference_polygon(ring)}, {"version", 1}});
  ordered_json mission;
  mission["cruiseSpeed"] = m.cruise_speed_m_s;
  mission["firmwareType"] = settings.firmware_type;
  mission["globalPlanAltitudeMode"] = settings.altitude_mode;
  mission["hoverSpeed"] = m.cruise_speed_m_s;
  mission["items"] = items;
  mission["plannedHomePosition"] = {m.home.lat_deg, m.home.lon_deg, m.home_amsl_m};
  mission["vehicleType"] = m.fixed_wing ? 1 : 2;
  mission["version"] = 2;
  ordered_json rally = ordered_json::array();
  for (const geometry::GeoPoint& g : m.rally_points) rally.push_back({g.lat_deg, g.lon_deg, 0});
  ordered_json root;
  root["fileType"] = "Plan";
  root["geoFence"] = {{"circles", ordered_json::array()}, {"polygons", polygons}, {"version", 2}};
  root["groundStation"] = "swath";
  root["mission"] = mission;
  root["rallyPoints"] = {{"points", rally}, {"version", 2}};
  root["version"] = 1;
  return base::json_text(root, 4) + "\n";
}

TEST(MissionWriters, QgcPlanItemsAreTheTreesText) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (std::uint32_t seed = 301; seed <= 700; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    Mission m = random_mission(seed);
    Rng rng{std::mt19937(seed)};
    // Numbers of every kind where the writer prints them: not finite, whole, tiny, huge, negative.
    const double odd[] = {std::nan(""), kInf, -kInf, 0.0, -0.0, 5.0, 1e-300, 1e300, -123.5, 0.1};
    for (Item& item : m.items) {
      if (rng.below(3) == 0) item.altitude_m = odd[rng.below(10)];
      if (rng.below(3) == 0) item.params[std::size_t(rng.below(4))] = odd[rng.below(10)];
      if (rng.below(5) == 0) item.position.lat_deg = odd[rng.below(10)];
      if (rng.below(9) == 0) item.command = -rng.below(100000);
      if (rng.below(9) == 0) item.frame = 1000000 + rng.below(1000);
    }
    if (seed % 50 == 0) m.items.clear();
    if (seed % 7 == 0) m.inclusion_fences.clear();
    const missions::QgcPlanSettings settings{rng.below(20), rng.below(5) - 1};
    ASSERT_EQ(missions::write_qgc_plan(m, settings), reference_qgc_plan(m, settings));
  }
}

TEST(MissionWriters, WplMissionFencesAndRallyReadBackAsWritten) {
  for (std::uint32_t seed = 101; seed <= 200; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Mission m = random_mission(seed);
    Mission read = missions::parse_mission(missions::write_wpl(m), "random.waypoints");
    EXPECT_EQ(read.format, "WPL 110");
    expect_points({m.home}, {read.home}, 0.5e-9, "home");
    EXPECT_NEAR(read.home_amsl_m, m.home_amsl_m, 0.5e-6);
    expect_items(m, read, true);
    missions::add_wpl_fences(read, missions::write_wpl_fences(m), "fence.waypoints");
    missions::add_wpl_fences(read, missions::write_wpl_rally(m), "rally.waypoints");
    ASSERT_EQ(read.inclusion_fences.size(), m.inclusion_fences.size());
    for (std::size_t k = 0; k < m.inclusion_fences.size(); ++k)
      expect_points(m.inclusion_fences[k], read.inclusion_fences[k], 0.5e-9, "inclusion fence");
    ASSERT_EQ(read.exclusion_fences.size(), m.exclusion_fences.size());
    for (std::size_t k = 0; k < m.exclusion_fences.size(); ++k)
      expect_points(m.exclusion_fences[k], read.exclusion_fences[k], 0.5e-9, "exclusion fence");
    expect_points(m.rally_points, read.rally_points, 0.5e-9, "rally points");
  }
}

// The .fen list: the return point, then the first inclusion fence closed, "lat lon" a line.
TEST(MissionWriters, FenListsTheReturnPointThenTheClosedFence) {
  const Mission m = random_mission(7);
  std::vector<geometry::GeoPoint> expected{m.home};
  for (const auto& g : m.inclusion_fences.front()) expected.push_back(g);
  expected.push_back(m.inclusion_fences.front().front());
  std::istringstream lines(missions::write_fen(m));
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line.rfind("#", 0), 0u) << line;
  std::vector<geometry::GeoPoint> read;
  for (geometry::GeoPoint g; lines >> g.lat_deg >> g.lon_deg;) read.push_back(g);
  expect_points(expected, read, 0.5e-9, "fen");
}

std::vector<missions::ExportPoint> random_points(Rng& rng, int n) {
  std::vector<missions::ExportPoint> points;
  const geometry::GeoPoint origin{rng.uniform(-60, 60), rng.uniform(-170, 170), 0.0};
  for (int k = 0; k < n; ++k) {
    missions::ExportPoint p;
    p.geo = {base::round_to(origin.lat_deg + rng.uniform(-0.01, 0.01), 9),
             base::round_to(origin.lon_deg + rng.uniform(-0.01, 0.01), 9), 0.0};
    p.altitude_m = rng.rounded(10, 120, 3);
    p.heading_deg = rng.rounded(0, 359, 2);
    p.photo_leg = rng.below(2) == 1;
    points.push_back(p);
  }
  return points;
}

// The waypoints (NAV_WAYPOINT 16) a reader finds, in order.
std::vector<const Item*> waypoints(const Mission& m) {
  std::vector<const Item*> out;
  for (const Item& item : m.items)
    if (item.command == 16) out.push_back(&item);
  return out;
}

void expect_waypoints(const std::vector<missions::ExportPoint>& points, const Mission& read,
                      const std::string& where) {
  const std::vector<const Item*> found = waypoints(read);
  ASSERT_EQ(found.size(), points.size()) << where;
  for (std::size_t k = 0; k < points.size(); ++k) {
    EXPECT_NEAR(found[k]->position.lat_deg, points[k].geo.lat_deg, 0.5e-9) << where << " " << k;
    EXPECT_NEAR(found[k]->position.lon_deg, points[k].geo.lon_deg, 0.5e-9) << where << " " << k;
    EXPECT_NEAR(missions::above_home_m(*found[k], missions::home_amsl_m(read)),
                points[k].altitude_m, 0.5e-3)
        << where << " " << k;
  }
}

// Litchi parts continue one another: part k + 1 starts at the point part k ends at, so the
// parts' points without each later part's first are the flight's.
TEST(MissionWriters, LitchiPartsReadBackAsTheFlightsPoints) {
  for (std::uint32_t seed = 201; seed <= 230; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    Rng rng{std::mt19937(seed)};
    const auto points = random_points(rng, 2 + rng.below(250));
    missions::LitchiSettings settings;
    settings.max_rows = 99;
    settings.speed_m_s = rng.rounded(1, 15, 3);
    const auto parts = missions::write_litchi_csv(points, settings);
    ASSERT_EQ(parts.size(), points.size() <= 99 ? 1 : (points.size() - 2) / 98 + 1);
    std::vector<missions::ExportPoint> part_points;
    std::size_t first = 0;
    for (std::size_t k = 0; k < parts.size(); ++k) {
      const std::size_t end = std::min(points.size(), first + 99);
      const Mission read = missions::parse_mission(parts[k], "part.csv");
      expect_waypoints(
          {points.begin() + std::ptrdiff_t(first), points.begin() + std::ptrdiff_t(end)}, read,
          "part " + std::to_string(k + 1));
      first = end - 1;
    }
  }
}

// The cuts worked out by hand: 200 points, parts may end at points 50 and 97 only. Part 1 ends at
// 97 (the last allowed within its 99 rows: 98 rows), part 2 has no allowed point after its first
// and ends at its 99th row (point 195), part 3 holds the rest (points 195 to 199).
TEST(MissionWriters, LitchiPartsEndAtTheLastAllowedPointWorkedByHand) {
  Rng rng{std::mt19937(7)};
  const auto points = random_points(rng, 200);
  missions::LitchiSettings settings;
  settings.max_rows = 99;
  settings.speed_m_s = 5;
  settings.may_end_at = [](std::size_t i) { return i == 50 || i == 97; };
  const auto parts = missions::write_litchi_csv(points, settings);
  ASSERT_EQ(parts.size(), 3u);
  const std::size_t rows[] = {98, 99, 5};
  const std::size_t first[] = {0, 97, 195};
  for (std::size_t k = 0; k < 3; ++k) {
    const Mission read = missions::parse_mission(parts[k], "part.csv");
    expect_waypoints({points.begin() + std::ptrdiff_t(first[k]),
                      points.begin() + std::ptrdiff_t(first[k] + rows[k])},
                     read, "part " + std::to_string(k + 1));
  }
}

// The speed in force on each leg of a read mission, as ArduPilot flies its items: the last
// DO_CHANGE_SPEED (178, param2 m/s) before a waypoint (16) sets the leg into it.
std::vector<double> leg_speeds_m_s(const Mission& read) {
  std::vector<double> legs;  // legs[k]: from waypoint k to k + 1
  double speed = -1;
  bool first = true;
  for (const Item& item : read.items) {
    if (item.command == 178) speed = item.params[1];
    if (item.command != 16) continue;
    if (!first) legs.push_back(speed);
    first = false;
  }
  return legs;
}

// A part ends at the last point within Litchi's 99 rows that may_end_at allows (the next starting
// there), at the 99th row where none does; each row carries its leg's own speed, read back as the
// speed of the leg from that row (DJI's and Litchi's reading).
TEST(MissionWriters, LitchiPartsEndWhereAllowedAndCarryEachLegsSpeed) {
  for (std::uint32_t seed = 301; seed <= 330; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    Rng rng{std::mt19937(seed)};
    auto points = random_points(rng, 100 + rng.below(300));
    for (missions::ExportPoint& p : points)
      p.speed_m_s = rng.below(4) == 0 ? rng.rounded(1, 4.9, 3) : 0.0;
    std::vector<char> allowed(points.size());
    const int one_in = 1 + rng.below(60);  // sometimes none in a part's window
    for (char& a : allowed) a = rng.below(one_in) == 0;
    missions::LitchiSettings settings;
    settings.max_rows = 99;
    settings.speed_m_s = 5;
    settings.may_end_at = [&](std::size_t i) { return allowed[i] != 0; };
    const auto parts = missions::write_litchi_csv(points, settings);
    std::size_t first = 0;
    for (std::size_t k = 0; k < parts.size(); ++k) {
      std::size_t end = std::min(points.size(), first + 99);
      if (end < points.size()) {  // the last allowed point after the first, if any
        for (std::size_t last = end - 1; last > first; --last)
          if (allowed[last]) {
            end = last + 1;
            break;
          }
      }
      const std::vector<missions::ExportPoint> expected(points.begin() + std::ptrdiff_t(first),
                                                        points.begin() + std::ptrdiff_t(end));
      const Mission read = missions::parse_mission(parts[k], "part.csv");
      expect_waypoints(expected, read, "part " + std::to_string(k + 1));
      const std::vector<double> legs = leg_speeds_m_s(read);
      ASSERT_EQ(legs.size() + 1, expected.size());
      for (std::size_t i = 0; i < legs.size(); ++i)
        EXPECT_EQ(legs[i], expected[i].speed_m_s > 0 ? expected[i].speed_m_s : 5.0)
            << "part " << k + 1 << " leg " << i;
      first = end - 1;
    }
    EXPECT_EQ(first + 1, points.size()) << "the parts end at the flight's last point";
  }
}

TEST(MissionWriters, DjiKmzReadsBackAsItsPoints) {
  for (std::uint32_t seed = 231; seed <= 250; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    Rng rng{std::mt19937(seed)};
    auto points = random_points(rng, 2 + rng.below(60));
    for (missions::ExportPoint& p : points)  // a slower approach here and there
      p.speed_m_s = rng.below(4) == 0 ? rng.rounded(0.5, 2.5, 3) : 0.0;
    missions::DjiSettings settings;
    settings.speed_m_s = rng.rounded(1, 15, 3);
    settings.altitude_m = 60;
    settings.trigger_value = 20;
    const Mission read =
        missions::parse_mission(missions::write_dji_kmz(points, settings), "x.kmz");
    EXPECT_EQ(read.format, "DJI WPML");
    expect_waypoints(points, read, "kmz");
    // The speed: a DO_CHANGE_SPEED (178) before the first waypoint, param2 m/s.
    ASSERT_FALSE(read.items.empty());
    EXPECT_EQ(read.items.front().command, 178);
    // DJI flies no slower than 1 m/s: a slower point's speed is read as that.
    const auto flown_m_s = [&](const missions::ExportPoint& p) {
      return p.speed_m_s > 0 ? std::max(p.speed_m_s, 1.0) : settings.speed_m_s;
    };
    EXPECT_EQ(read.items.front().params[1], flown_m_s(points[0]));
    // Each waypoint's speed is its leg's to the next, read back so.
    const std::vector<double> legs = leg_speeds_m_s(read);
    ASSERT_EQ(legs.size() + 1, points.size());
    for (std::size_t i = 0; i < legs.size(); ++i)
      EXPECT_EQ(legs[i], flown_m_s(points[i])) << "leg " << i;
  }
}

}  // namespace
}  // namespace swath
