// Every file `swath plan` writes, parsed back and checked against the plan.
#include "swath/planning/survey_files.hpp"
#include "meadow_survey.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "files/geo_memo.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/output_set.hpp"

namespace swath::planning {
namespace {

using nlohmann::json;

SurveyPlan meadow_plan(std::optional<geometry::GeoPoint> home = std::nullopt) {
  SurveyRequest r = test::meadow_request(80);
  r.home = home;
  r.waypoint_spacing_m = 150;
  return plan_survey(r);
}

// The one flight of a one-drone plan.
Flight only_flight(const SurveyPlan& plan) {
  return flights_of(plan).at(0);
}

const DroneMission& mission_of(const SurveyPlan& plan) {
  return plan.drones.at(0).mission;
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> cells;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, sep)) cells.push_back(cell);
  if (!line.empty() && line.back() == sep) cells.push_back("");
  return cells;
}

TEST(QgcPlan, ParsesBackWithRequiredKeysCommandsFramesAndPlannedCoordinates) {
  const SurveyPlan plan = meadow_plan(geometry::GeoPoint{47.3965, 8.5405, 0});
  const json j = json::parse(qgc_plan(plan, only_flight(plan)));
  EXPECT_EQ(j["fileType"], "Plan");
  EXPECT_EQ(j["version"], 1);
  EXPECT_EQ(j["geoFence"]["version"], 2);
  EXPECT_EQ(j["rallyPoints"]["version"], 2);
  const json& m = j["mission"];
  EXPECT_EQ(m["version"], 2);
  EXPECT_EQ(m["firmwareType"], 3);
  EXPECT_EQ(m["vehicleType"], 2);
  for (const char* key : {"cruiseSpeed", "hoverSpeed", "plannedHomePosition", "items"})
    EXPECT_TRUE(m.contains(key)) << key;
  EXPECT_NEAR(m["plannedHomePosition"][0].get<double>(), 47.3965, 1e-9);
  EXPECT_NEAR(m["plannedHomePosition"][1].get<double>(), 8.5405, 1e-9);

  const json& items = m["items"];
  ASSERT_EQ(items.size(), mission_of(plan).items.size());
  EXPECT_EQ(items.front()["command"], 22);
  EXPECT_EQ(items.back()["command"], 20);
  int triggers_on = 0, triggers_off = 0;
  std::size_t waypoint = 0;
  std::vector<geometry::Point2> planned;  // the mission's waypoints in order
  for (const MissionItem& it : mission_of(plan).items)
    if (it.kind == ItemKind::waypoint) planned.push_back(it.position);
  for (std::size_t i = 0; i < items.size(); ++i) {
    const json& it = items[i];
    EXPECT_EQ(it["type"], "SimpleItem");
    EXPECT_EQ(it["doJumpId"], i + 1);
    EXPECT_EQ(it["autoContinue"], true);
    ASSERT_EQ(it["params"].size(), 7u);
    const int command = it["command"];
    if (command == 16) {
      EXPECT_EQ(it["frame"], 3);
      const geometry::GeoPoint g = plan.request.field.frame->to_geo(planned[waypoint++]);
      EXPECT_NEAR(it["params"][4].get<double>(), g.lat_deg, 1e-7);
      EXPECT_NEAR(it["params"][5].get<double>(), g.lon_deg, 1e-7);
      EXPECT_DOUBLE_EQ(it["params"][6].get<double>(), plan.imaging.altitude_m);
    } else if (command == 206) {
      EXPECT_EQ(it["frame"], 2);
      const double distance = it["params"][0];
      (distance > 0 ? triggers_on : triggers_off)++;
      if (distance > 0) {
        EXPECT_NEAR(distance, plan.imaging.trigger_distance_m, 1e-3);
        EXPECT_EQ(it["params"][2], 1) << "one photo at the start of the line";
      }
    } else if (command == 178) {
      EXPECT_EQ(it["params"][0], 1) << "ground speed (multirotor)";
      EXPECT_DOUBLE_EQ(it["params"][1].get<double>(), plan.speed_m_s);
      EXPECT_EQ(it["params"][2], -1) << "throttle unchanged";
    } else if (command == 205) {
      EXPECT_DOUBLE_EQ(it["params"][0].get<double>(), -90.0);  // nadir
    } else {
      EXPECT_TRUE(command == 22 || command == 20) << command;
    }
  }
  EXPECT_EQ(waypoint, planned.size());
  // docs/swath-plan.md: photos on the lines only, the camera started and stopped at each line.
  EXPECT_EQ(triggers_on, int(mission_of(plan).lines.size()));
  EXPECT_EQ(triggers_off, int(mission_of(plan).lines.size()));
  // Take-off, the drone's speed and the gimbal before the first survey waypoint, then the camera.
  EXPECT_EQ(items[1]["command"], 178);
  EXPECT_EQ(items[2]["command"], 205);
  EXPECT_EQ(items[3]["command"], 16);
  EXPECT_EQ(items[4]["command"], 206);
}

TEST(QgcPlan, Px4FixedWing) {
  SurveyPlan plan = meadow_plan();
  plan.request.firmware = Firmware::px4;
  plan.request.vehicle = Vehicle::fixedwing;
  const json j = json::parse(qgc_plan(plan, only_flight(plan)));
  EXPECT_EQ(j["mission"]["firmwareType"], 12);
  EXPECT_EQ(j["mission"]["vehicleType"], 1);
}

TEST(Wpl110, TwelveTabSeparatedColumnsHomeFirstSameItems) {
  const SurveyPlan plan = meadow_plan();
  std::stringstream in(wpl_110(plan, only_flight(plan)));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "QGC WPL 110");
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) rows.push_back(split(line, '\t'));
  ASSERT_EQ(rows.size(), mission_of(plan).items.size() + 1);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), 12u) << i;
    EXPECT_EQ(std::stoul(rows[i][0]), i);
    EXPECT_EQ(rows[i][11], "1");
  }
  EXPECT_EQ(rows[0][1], "1");  // home is "current"
  EXPECT_NEAR(std::stod(rows[0][8]), plan.home.lat_deg, 1e-9);
  EXPECT_NEAR(std::stod(rows[0][9]), plan.home.lon_deg, 1e-9);
  EXPECT_EQ(rows[1][3], "22");
  EXPECT_EQ(rows[2][3], "178");
  EXPECT_EQ(rows.back()[3], "20");
  const geometry::GeoPoint first =
      plan.request.field.frame->to_geo(mission_of(plan).lines[0].start);
  EXPECT_EQ(rows[4][3], "16");
  EXPECT_NEAR(std::stod(rows[4][8]), first.lat_deg, 1e-7);
  EXPECT_NEAR(std::stod(rows[4][9]), first.lon_deg, 1e-7);
}

TEST(WaypointsCsv, HeaderAndRowsMatchTheMission) {
  const SurveyPlan plan = meadow_plan();
  std::stringstream in(waypoints_csv(plan));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "drone,flight,seq,lat,lon,alt_m,x_m,y_m,action");
  std::size_t n = 0;
  while (std::getline(in, line)) {
    const auto cells = split(line, ',');
    ASSERT_EQ(cells.size(), 9u) << line;
    EXPECT_EQ(cells[0], "1");
    EXPECT_EQ(cells[1], "drone-1");
    EXPECT_EQ(std::stoul(cells[2]), n);
    if (cells[8] == "waypoint") {
      const geometry::Point2 local{std::stod(cells[6]), std::stod(cells[7])};
      const geometry::GeoPoint g = plan.request.field.frame->to_geo(local);
      EXPECT_NEAR(std::stod(cells[3]), g.lat_deg, 1e-7);  // x/y and lat/lon agree
      EXPECT_NEAR(std::stod(cells[4]), g.lon_deg, 1e-7);
    }
    ++n;
  }
  EXPECT_EQ(n, mission_of(plan).items.size() + 1);
}

TEST(MissionGeojson, FeaturesCarryTheRolesOfTheDesign) {
  const SurveyPlan plan = meadow_plan();
  const json j = json::parse(mission_geojson(plan));
  EXPECT_EQ(j["type"], "FeatureCollection");
  std::map<std::string, int> roles;
  for (const json& f : j["features"]) {
    const std::string role = f["properties"]["role"];
    ++roles[role];
    if (role == "sweep") {
      EXPECT_EQ(f["properties"]["drone"], 1);
      EXPECT_NEAR(f["properties"]["footprint_width_m"].get<double>(),
                  plan.imaging.footprint_across_m, 1e-4);
      EXPECT_EQ(f["geometry"]["coordinates"].size(), 2u);
    }
    if (role == "path") {
      const json& c = f["geometry"]["coordinates"];
      EXPECT_EQ(c.front(), c.back()) << "home to home";
      EXPECT_EQ(c.size(), mission_of(plan).path.size());
    }
    if (role == "area") {
      const json& ring = f["geometry"]["coordinates"][0];
      EXPECT_EQ(ring.front(), ring.back()) << "closed ring";
      EXPECT_NEAR(ring[0][0].get<double>(), 8.54010, 1e-9);  // the file's first vertex, [lon, lat]
      EXPECT_NEAR(ring[0][1].get<double>(), 47.39702, 1e-9);
    }
  }
  EXPECT_EQ(roles["area"], 1);
  EXPECT_EQ(roles["path"], 1);
  EXPECT_EQ(roles["home"], 1);
  EXPECT_EQ(roles["sweep"], int(plan.sweep.lines.size()));
}

TEST(Summary, FiguresAgreeWithTheGeometry) {
  const SurveyPlan plan = meadow_plan();
  const json s = json::parse(summary_json(plan));
  EXPECT_EQ(s["area"]["type"], "convex");
  EXPECT_NEAR(s["area"]["area_m2"].get<double>(), geometry::area(plan.request.field.polygon), 1e-3);
  EXPECT_EQ(s["sweep"]["lines"], plan.sweep.lines.size());
  const double bearing = s["sweep"]["bearing_deg"];
  EXPECT_NEAR(std::fmod(bearing + s["sweep"]["angle_local_deg"].get<double>(), 180.0), 90.0, 1e-5);
  EXPECT_NEAR(s["sweep"]["height_m"].get<double>(),
              geometry::min_height_rotation(plan.request.field.polygon.outer).height_m, 1e-4);
  const json& d = s["drones"][0];
  double work = 0;
  for (const SweepLine& l : mission_of(plan).lines) work += geometry::distance(l.start, l.end);
  EXPECT_NEAR(d["work_length_m"].get<double>(), work, 1e-3);
  double path = 0;
  for (std::size_t i = 0; i + 1 < mission_of(plan).path.size(); ++i)
    path += geometry::distance(mission_of(plan).path[i], mission_of(plan).path[i + 1]);
  EXPECT_NEAR(d["path_length_m"].get<double>(), path, 1e-3);
  EXPECT_NEAR(d["transit_length_m"].get<double>() + d["work_length_m"].get<double>(), path, 2e-3);
  // The cruise at 5 m/s, the climb at 2.5 m/s and the descent at 1.5 m/s, plus at most one
  // acceleration and braking (v / a = 2 s) per waypoint.
  const double cruise = path / 5.0 + 80 / 2.5 + 80 / 1.5;
  EXPECT_GE(d["flight_time_s"].get<double>(), cruise);
  EXPECT_LE(d["flight_time_s"].get<double>(),
            cruise + 2.0 * double(mission_of(plan).waypoint_count));
  EXPECT_NEAR(s["camera"]["line_spacing_m"].get<double>(), 145.0 * 0.8 * 0.3, 1e-4);
  EXPECT_GE(s["coverage"]["covered_fraction"].get<double>(), 0.9999);
}

TEST(SurveyFiles, SameInputSameBytes) {
  const auto a = survey_files(meadow_plan());
  const auto b = survey_files(meadow_plan());
  ASSERT_EQ(a.size(), 8u);
  EXPECT_EQ(a, b);
}

// ---- The photo and waypoint writers against straightforward ones (fixed_text and std::to_string
// per field; photos.geojson as an nlohmann tree, dumped), on plans whose photos and waypoints are
// random: positions from 1 mm to 30 km either side of the origin, lines and sorties, two drones.

geometry::GeoPoint reference_geo(const SurveyPlan& plan, geometry::Point2 p) {
  const geometry::GeoPoint g = plan.request.field.frame->to_geo(p);
  return {base::round_to(g.lat_deg, 9), base::round_to(g.lon_deg, 9), 0.0};
}

std::string reference_photos_csv(const SurveyPlan& plan) {
  using base::fixed_text;
  std::string out = "drone,flight,line,photo,lat,lon,alt_m,x_m,y_m\n";
  for (const Flight& f : flights_of(plan))
    for (std::size_t k = 0; k < f.photos->size(); ++k) {
      const PhotoPoint& p = (*f.photos)[k];
      const geometry::GeoPoint g = reference_geo(plan, p.position);
      out += std::to_string(f.drone->number) + "," + f.file_stem + "," + std::to_string(p.line) +
             "," + std::to_string(k) + "," + fixed_text(g.lat_deg, 9) + "," +
             fixed_text(g.lon_deg, 9) + "," + fixed_text(plan.imaging.altitude_m, 3) + "," +
             fixed_text(p.position.x, 3) + "," + fixed_text(p.position.y, 3) + "\n";
    }
  return out;
}

std::string reference_photos_geojson(const SurveyPlan& plan) {
  nlohmann::ordered_json features = nlohmann::ordered_json::array();
  for (const Flight& f : flights_of(plan))
    for (std::size_t k = 0; k < f.photos->size(); ++k) {
      const PhotoPoint& p = (*f.photos)[k];
      const geometry::GeoPoint g = reference_geo(plan, p.position);
      nlohmann::ordered_json feature;
      feature["type"] = "Feature";
      feature["properties"] = {{"role", "photo"},
                               {"drone", f.drone->number},
                               {"flight", f.file_stem},
                               {"line", p.line},
                               {"photo", k},
                               {"altitude_m", base::round_to(plan.imaging.altitude_m, 3)}};
      feature["geometry"] = {{"type", "Point"}, {"coordinates", {g.lon_deg, g.lat_deg}}};
      features.push_back(feature);
    }
  nlohmann::ordered_json collection;
  collection["type"] = "FeatureCollection";
  collection["features"] = features;
  return base::json_text(collection, 1) + "\n";
}

std::string reference_waypoints_csv(const SurveyPlan& plan) {
  using base::fixed_text;
  std::string out = "drone,flight,seq,lat,lon,alt_m,x_m,y_m,action\n";
  for (const Flight& f : flights_of(plan)) {
    const std::string head = std::to_string(f.drone->number) + "," + f.file_stem + ",";
    auto row = [&](std::size_t seq, geometry::Point2 p, double alt, bool has_position,
                   const std::string& action) {
      out += head + std::to_string(seq) + ",";
      if (has_position) {
        const geometry::GeoPoint g = reference_geo(plan, p);
        out += fixed_text(g.lat_deg, 9) + "," + fixed_text(g.lon_deg, 9) + "," +
               fixed_text(alt, 3) + "," + fixed_text(p.x, 3) + "," + fixed_text(p.y, 3);
      } else {
        out += ",,,,";
      }
      out += "," + action + "\n";
    };
    row(0, f.mission->home, 0.0, true, "home");
    std::size_t seq = 1;
    for (const MissionItem& item : f.mission->items) {
      // The action names as waypoints.csv documents them, taken from the writer's own rows.
      row(seq++, item.position, item.altitude_m, positional(item.kind), "?");
    }
  }
  return out;
}

// The last column of every row (the action), which the reference leaves as "?".
std::string without_actions(const std::string& csv) {
  std::string out;
  std::stringstream lines(csv);
  for (std::string line; std::getline(lines, line);) out += line.substr(0, line.rfind(',')) + "\n";
  return out;
}

struct Random {
  std::uint64_t state;
  double unit() {  // [0, 1)
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  }
  // A coordinate of any magnitude from 1 mm to 30 km, either sign, now and then 0 or a half
  // millimetre (a rounding tie in x_m, y_m).
  double coordinate() {
    const double pick = unit();
    if (pick < 0.05) return 0.0;
    if (pick < 0.1) return (unit() < 0.5 ? -1 : 1) * (std::floor(unit() * 1e6) + 0.5) / 1000.0;
    return (unit() < 0.5 ? -1 : 1) * std::pow(10.0, -3.0 + 7.5 * unit());
  }
};

std::vector<PhotoPoint> random_photos(Random& random, std::size_t count) {
  std::vector<PhotoPoint> photos(count);
  for (PhotoPoint& p : photos) {
    p.position = {random.coordinate(), random.coordinate()};
    p.line = static_cast<int>(random.unit() * 2e6);
  }
  return photos;
}

void randomise_items(Random& random, DroneMission& mission) {
  mission.home = {random.coordinate(), random.coordinate()};
  for (MissionItem& item : mission.items) {
    item.position = {random.coordinate(), random.coordinate()};
    item.altitude_m = random.coordinate();
  }
}

TEST(PhotoAndWaypointFiles, TheWritersGiveTheStraightforwardTextsOnRandomPlans) {
  const SurveyPlan meadow = meadow_plan();
  Random random{52};
  for (int round = 0; round < 6; ++round) {
    SurveyPlan plan = meadow;
    plan.imaging.altitude_m = round == 0 ? 80.0 : 10.0 + random.unit() * 500.0;
    DronePlan& first = plan.drones.at(0);
    first.photos = random_photos(random, 400);
    randomise_items(random, first.mission);
    DronePlan second = first;  // flies in two sorties
    second.number = 2;
    second.file_stem = "alpha.2_x-y";
    for (int s = 1; s <= 2; ++s) {
      Sortie sortie;
      sortie.number = s;
      sortie.mission = first.mission;
      randomise_items(random, sortie.mission);
      sortie.photos = random_photos(random, 150);
      second.sorties.push_back(sortie);
    }
    plan.drones.push_back(second);
    if (round == 5) plan.drones[1].sorties.back().photos.clear();  // a flight with none

    const std::string csv = photos_csv(plan);
    ASSERT_EQ(csv, reference_photos_csv(plan)) << "round " << round;
    ASSERT_EQ(photos_geojson(plan), reference_photos_geojson(plan)) << "round " << round;
    const std::string waypoints = waypoints_csv(plan);
    ASSERT_EQ(without_actions(waypoints), without_actions(reference_waypoints_csv(plan)))
        << "round " << round;
    // The set holds the same texts as the single writers.
    const auto files = survey_files(plan);
    for (const auto& [name, text] : files) {
      if (name == "photos.csv") EXPECT_EQ(text, csv);
      if (name == "photos.geojson") EXPECT_EQ(text, reference_photos_geojson(plan));
      if (name == "waypoints.csv") EXPECT_EQ(text, waypoints);
    }
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 400 + 150 + (round == 5 ? 0 : 150));
  }
  // No photos at all: the empty collection as nlohmann writes it.
  SurveyPlan empty = meadow;
  empty.drones.at(0).photos.clear();
  EXPECT_EQ(photos_geojson(empty), reference_photos_geojson(empty));
  EXPECT_EQ(photos_csv(empty), "drone,flight,line,photo,lat,lon,alt_m,x_m,y_m\n");
}

// ---- The writers of one set share their points' positions (files::GeoMemo).

// Within a memo, geo() answers as without one: for points met again, for points that share one
// coordinate or differ from another in its last bit, 0 and -0, and for another plan's points.
TEST(GeoMemo, PositionsAsConvertedAlone) {
  const SurveyPlan plan = meadow_plan();
  SurveyPlan other = plan;  // another plan, its frame elsewhere on the Earth
  other.request.field.frame.emplace(geometry::GeoPoint{-33.9, 151.2, 0});
  Random random{7};
  std::vector<geometry::Point2> points;
  for (int k = 0; k < 300; ++k) {
    const geometry::Point2 p{random.coordinate(), random.coordinate()};
    points.push_back(p);
    points.push_back({p.x, random.coordinate()});       // the same x
    points.push_back({random.coordinate(), p.y});       // the same y
    points.push_back({std::nextafter(p.x, 1e9), p.y});  // one bit apart
    points.push_back({p.y, p.x});                       // swapped
  }
  points.push_back({0.0, 0.0});
  points.push_back({-0.0, 0.0});
  std::vector<geometry::GeoPoint> alone, other_alone;
  for (const geometry::Point2& p : points) {
    alone.push_back(files::geo(plan, p));
    other_alone.push_back(files::geo(other, p));
  }
  const files::GeoMemo memo(plan);
  for (int pass = 0; pass < 2; ++pass)  // the second pass from the memo
    for (std::size_t k = 0; k < points.size(); ++k) {
      ASSERT_EQ(files::geo(plan, points[k]), alone[k]) << k << " pass " << pass;
      ASSERT_EQ(files::geo(other, points[k]), other_alone[k]) << k << " pass " << pass;
    }
}

// The set (every writer under one memo) holds the texts each writer gives alone (no memo), on
// the meadow's plan and on plans with random items and photos and two drones in sorties.
TEST(SurveyFiles, TheSetHoldsTheTextsOfTheWritersAlone) {
  const SurveyPlan meadow = meadow_plan();
  Random random{53};
  for (int round = 0; round < 3; ++round) {
    SurveyPlan plan = meadow;
    if (round > 0) {
      DronePlan& first = plan.drones.at(0);
      first.photos = random_photos(random, 100);
      randomise_items(random, first.mission);
      DronePlan second = first;
      second.number = 2;
      second.file_stem = "drone-2";
      for (int s = 1; s <= 2; ++s) {
        Sortie sortie;
        sortie.number = s;
        sortie.mission = first.mission;
        sortie.photos = random_photos(random, 50);
        second.sorties.push_back(sortie);
      }
      plan.drones.push_back(second);
    }
    std::map<std::string, std::string> alone{{"mission.geojson", mission_geojson(plan)},
                                             {"waypoints.csv", waypoints_csv(plan)},
                                             {"mission.kml", mission_kml(plan)},
                                             {"photos.csv", photos_csv(plan)},
                                             {"photos.geojson", photos_geojson(plan)}};
    for (const Flight& f : flights_of(plan)) {
      alone[f.file_stem + ".plan"] = qgc_plan(plan, f);
      alone[f.file_stem + ".waypoints"] = wpl_110(plan, f);
    }
    std::size_t compared = 0;
    for (const auto& [name, text] : survey_files(plan)) {
      if (name == "summary.json") continue;  // summary_json() takes the set's names
      ASSERT_TRUE(alone.count(name)) << name;
      EXPECT_EQ(text, alone.at(name)) << name << " round " << round;
      ++compared;
    }
    EXPECT_EQ(compared, alone.size()) << "round " << round;
  }
}

}  // namespace
}  // namespace swath::planning
