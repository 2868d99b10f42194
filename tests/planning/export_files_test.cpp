// The Litchi CSV and DJI WPML KMZ exports (docs/swath-plan.md), read back with readers written here
// (CSV split by hand; the KMZ unzipped with libzip's reader and its XML parsed with pugixml) and
// checked against the planned mission: points, heights, speeds, headings (an independent bearing
// on the WGS84 ellipsoid's local radii), photos (against the planned photo count), splits.
#include <gtest/gtest.h>
#include <pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "../support/zip_entries.hpp"
#include "meadow_survey.hpp"
#include "swath/base/input_error.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/planning/survey_files.hpp"

namespace swath::planning {
namespace {

constexpr double kPi = 3.14159265358979323846;

SurveyPlan meadow(double altitude_m, const std::function<void(SurveyRequest&)>& edit = {}) {
  SurveyRequest r = test::meadow_request(altitude_m);
  r.home = geometry::GeoPoint{47.3965, 8.5405, 0};
  if (edit) edit(r);
  return plan_survey(r);
}

// The flight's planned points in WGS84: its NAV_WAYPOINTs, then the home when it lands.
std::vector<geometry::GeoPoint> planned_points(const SurveyPlan& plan, const Flight& f) {
  std::vector<geometry::GeoPoint> out;
  for (const MissionItem& it : f.mission->items)
    if (it.kind == ItemKind::waypoint || it.kind == ItemKind::land)
      out.push_back(plan.request.field.frame->to_geo(it.position));
  return out;
}

// Bearing from a to b, degrees clockwise from true north, from the ellipsoid's meridian and
// prime-vertical radii at the mean latitude (a second method: the writer uses geodesics).
double bearing_deg(const geometry::GeoPoint& a, const geometry::GeoPoint& b) {
  const double wgs_a = 6378137.0, f = 1 / 298.257223563, e2 = f * (2 - f);
  const double phi = (a.lat_deg + b.lat_deg) / 2 * kPi / 180;
  const double w = 1 - e2 * std::sin(phi) * std::sin(phi);
  const double m = wgs_a * (1 - e2) / std::pow(w, 1.5), n = wgs_a / std::sqrt(w);
  const double east = (b.lon_deg - a.lon_deg) * kPi / 180 * n * std::cos(phi);
  const double north = (b.lat_deg - a.lat_deg) * kPi / 180 * m;
  const double deg = std::atan2(east, north) * 180 / kPi;
  return deg < 0 ? deg + 360 : deg;
}

double angle_gap_deg(double a, double b) {
  return std::abs(std::remainder(a - b, 360.0));
}

// Whether the leg a-b lies along one of the mission's sweep lines (within 1 cm).
bool on_a_line(const SurveyPlan& plan, const DroneMission& m, const geometry::GeoPoint& a,
               const geometry::GeoPoint& b) {
  const geometry::Point2 p = plan.request.field.frame->to_local(a);
  const geometry::Point2 q = plan.request.field.frame->to_local(b);
  for (const SweepLine& l : m.lines) {
    const geometry::Point2 d = l.end - l.start;
    const double len = std::hypot(d.x, d.y);
    auto off = [&](geometry::Point2 x) {
      const geometry::Point2 v = x - l.start;
      const double t = (v.x * d.x + v.y * d.y) / (len * len);
      return t < -1e-6 || t > 1 + 1e-6 ? 1e9 : std::abs(v.x * d.y - v.y * d.x) / len;
    };
    if (off(p) < 0.01 && off(q) < 0.01) return true;
  }
  return false;
}

// Photos the camera takes on a run of photo legs from the run's start: one there, then one every
// `interval` metres flown (the autopilot's distance trigger, planned_photos()'s rule).
std::size_t photos_on_run(const SurveyPlan& plan, const std::vector<geometry::GeoPoint>& run,
                          double interval) {
  double length = 0;
  for (std::size_t i = 0; i + 1 < run.size(); ++i)
    length += geometry::distance(plan.request.field.frame->to_local(run[i]),
                                 plan.request.field.frame->to_local(run[i + 1]));
  return static_cast<std::size_t>(std::floor(length / interval + 1e-9)) + 1;
}

// ---- Litchi: a CSV reader written here ----

struct LitchiFile {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  double number(std::size_t row, const std::string& column) const {
    return std::stod(rows.at(row).at(column));
  }
};

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, ',')) out.push_back(cell);
  return out;
}

LitchiFile read_litchi(const std::string& text) {
  LitchiFile f;
  std::stringstream in(text);
  std::string line;
  std::getline(in, line);
  f.header = cells(line);
  while (std::getline(in, line)) {
    const std::vector<std::string> c = cells(line);
    EXPECT_EQ(c.size(), f.header.size()) << line;
    std::map<std::string, std::string> row;
    for (std::size_t k = 0; k < c.size() && k < f.header.size(); ++k) row[f.header[k]] = c[k];
    f.rows.push_back(row);
  }
  return f;
}

geometry::GeoPoint litchi_point(const LitchiFile& f, std::size_t row) {
  return {f.number(row, "latitude"), f.number(row, "longitude"), 0};
}

TEST(LitchiCsv, HasLitchisColumnsAndParsesBackToThePlannedWaypoints) {
  const SurveyPlan plan = meadow(80, [](SurveyRequest& r) { r.triggering.gimbal_pitch_deg = -80; });
  const Flight flight = flights_of(plan).at(0);
  const std::vector<std::string> parts = litchi_csv(plan, flight);
  ASSERT_EQ(parts.size(), 1u);
  const LitchiFile f = read_litchi(parts[0]);
  std::vector<std::string> columns{"latitude",     "longitude",       "altitude(m)",
                                   "heading(deg)", "curvesize(m)",    "rotationdir",
                                   "gimbalmode",   "gimbalpitchangle"};
  for (int k = 1; k <= 15; ++k) {
    columns.push_back("actiontype" + std::to_string(k));
    columns.push_back("actionparam" + std::to_string(k));
  }
  for (const char* c :
       {"altitudemode", "speed(m/s)", "poi_latitude", "poi_longitude", "poi_altitude(m)",
        "poi_altitudemode", "photo_timeinterval", "photo_distinterval"})
    columns.push_back(c);
  EXPECT_EQ(f.header, columns);

  const std::vector<geometry::GeoPoint> planned = planned_points(plan, flight);
  ASSERT_EQ(f.rows.size(), planned.size());
  const DroneMission& m = plan.drones[0].mission;
  const double d = plan.imaging.trigger_distance_m;
  std::size_t photos = 0;
  for (std::size_t i = 0; i < f.rows.size(); ++i) {
    const geometry::GeoPoint g = litchi_point(f, i);
    EXPECT_NEAR(g.lat_deg, planned[i].lat_deg, 1e-7) << i;
    EXPECT_NEAR(g.lon_deg, planned[i].lon_deg, 1e-7) << i;
    EXPECT_DOUBLE_EQ(f.number(i, "altitude(m)"), 80.0);
    EXPECT_EQ(f.rows[i].at("altitudemode"), "0");
    EXPECT_DOUBLE_EQ(f.number(i, "speed(m/s)"), 5.0);
    EXPECT_EQ(f.rows[i].at("gimbalmode"), "2");
    EXPECT_DOUBLE_EQ(f.number(i, "gimbalpitchangle"), -80.0);
    const bool last = i + 1 == f.rows.size();
    const double leg =
        last ? bearing_deg(planned[i - 1], planned[i]) : bearing_deg(planned[i], planned[i + 1]);
    EXPECT_LE(angle_gap_deg(f.number(i, "heading(deg)"), leg), 0.5) << i;
    // Photos by distance from each line's start, nowhere else; never by time.
    const bool line_start = std::any_of(m.lines.begin(), m.lines.end(), [&](const SweepLine& l) {
      return geometry::distance(plan.request.field.frame->to_local(g), l.start) < 0.01;
    });
    EXPECT_EQ(f.number(i, "photo_timeinterval"), -1) << i;
    if (line_start) {
      EXPECT_NEAR(f.number(i, "photo_distinterval"), d, 1e-3) << i;
      EXPECT_TRUE(on_a_line(plan, m, planned[i], planned[i + 1])) << i;
      photos += photos_on_run(plan, {planned[i], planned[i + 1]}, d);
    } else {
      EXPECT_EQ(f.number(i, "photo_distinterval"), -1) << i;
    }
    for (int k = 1; k <= 15; ++k)
      EXPECT_EQ(f.rows[i].at("actiontype" + std::to_string(k)), "-1") << i;
  }
  // The camera's runs give exactly the photos swath planned (photos.csv).
  EXPECT_EQ(photos, plan.drones[0].photos.size());
}

TEST(LitchiCsv, SplitsAbove99WaypointsIntoPartsThatContinueOneAnother) {
  const SurveyPlan plan = meadow(60, [](SurveyRequest& r) { r.waypoint_spacing_m = 20; });
  const Flight flight = flights_of(plan).at(0);
  const std::vector<geometry::GeoPoint> planned = planned_points(plan, flight);
  ASSERT_GT(planned.size(), 2 * kLitchiMaxWaypoints) << "the test needs three parts";
  const std::vector<std::string> parts = litchi_csv(plan, flight);
  ASSERT_EQ(parts.size(), (planned.size() - 2) / (kLitchiMaxWaypoints - 1) + 1);
  std::vector<geometry::GeoPoint> joined;
  std::vector<double> distinterval;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const LitchiFile f = read_litchi(parts[k]);
    ASSERT_LE(f.rows.size(), kLitchiMaxWaypoints);
    ASSERT_GE(f.rows.size(), 2u);
    // No photos after a part's last point: its mission ends there.
    EXPECT_EQ(f.number(f.rows.size() - 1, "photo_distinterval"), -1);
    if (k > 0) {  // the first point of part k is the last of part k - 1
      const geometry::GeoPoint first = litchi_point(f, 0);
      EXPECT_EQ(first.lat_deg, joined.back().lat_deg);
      EXPECT_EQ(first.lon_deg, joined.back().lon_deg);
      joined.pop_back();
      distinterval.pop_back();
    }
    for (std::size_t i = 0; i < f.rows.size(); ++i) {
      joined.push_back(litchi_point(f, i));
      distinterval.push_back(f.number(i, "photo_distinterval"));
    }
  }
  ASSERT_EQ(joined.size(), planned.size());
  const DroneMission& m = plan.drones[0].mission;
  std::size_t photos = 0;
  std::vector<geometry::GeoPoint> run;
  for (std::size_t i = 0; i < joined.size(); ++i) {
    EXPECT_NEAR(joined[i].lat_deg, planned[i].lat_deg, 1e-7) << i;
    EXPECT_NEAR(joined[i].lon_deg, planned[i].lon_deg, 1e-7) << i;
    // With points along the lines, every leg on a line carries the interval (DJI's waypoint
    // missions take it for the leg to the next point), and only those.
    const bool along = i + 1 < joined.size() && on_a_line(plan, m, joined[i], joined[i + 1]);
    EXPECT_EQ(distinterval[i] > 0, along) << i;
    if (along) {
      if (run.empty()) run.push_back(joined[i]);
      run.push_back(joined[i + 1]);
    } else if (!run.empty()) {
      photos += photos_on_run(plan, run, plan.imaging.trigger_distance_m);
      run.clear();
    }
  }
  EXPECT_EQ(photos, plan.drones[0].photos.size());
  // The file names: numbered parts, as sorties are numbered.
  FileOptions options;
  options.litchi = true;
  std::vector<std::string> names;
  for (const auto& [name, content] : survey_files(plan, options))
    if (name.find("litchi") != std::string::npos) names.push_back(name);
  ASSERT_EQ(names.size(), parts.size());
  EXPECT_EQ(names[0], "drone-1-litchi-1.csv");
  EXPECT_EQ(names[1], "drone-1-litchi-2.csv");
}

TEST(LitchiCsv, HoverShotsTimeTriggerAndLanding) {
  const SurveyPlan hover = meadow(80, [](SurveyRequest& r) {
    r.triggering.mode = TriggerMode::hover;
    r.land = true;
  });
  const Flight flight = flights_of(hover).at(0);
  std::size_t shots = 0, rows = 0;
  LitchiFile last_part;
  const std::vector<std::string> parts = litchi_csv(hover, flight);
  ASSERT_GT(parts.size(), 1u) << "a split: the shared point's shot is taken once";
  for (const std::string& part : parts) {
    const LitchiFile f = read_litchi(part);
    for (std::size_t i = 0; i < f.rows.size(); ++i) {
      // A photo at a point comes after a 1 s stay; no interval photos in hover mode.
      if (f.rows[i].at("actiontype2") == "1") {
        EXPECT_EQ(f.rows[i].at("actiontype1"), "0");
        EXPECT_EQ(f.rows[i].at("actionparam1"), "1000");
        ++shots;
      }
      EXPECT_EQ(f.number(i, "photo_distinterval"), -1);
    }
    rows += f.rows.size();
    last_part = f;
  }
  EXPECT_EQ(shots, hover.drones[0].photos.size());
  // With --land the home is the last point, where Litchi's "land" finish action lands.
  const geometry::GeoPoint end = litchi_point(last_part, last_part.rows.size() - 1);
  EXPECT_NEAR(end.lat_deg, hover.drones[0].home_geo.lat_deg, 1e-7);
  EXPECT_NEAR(end.lon_deg, hover.drones[0].home_geo.lon_deg, 1e-7);
  EXPECT_GT(rows, 0u);

  const SurveyPlan timed =
      meadow(80, [](SurveyRequest& r) { r.triggering.mode = TriggerMode::time; });
  const LitchiFile f = read_litchi(litchi_csv(timed, flights_of(timed).at(0)).at(0));
  std::size_t timed_rows = 0;
  for (std::size_t i = 0; i < f.rows.size(); ++i)
    if (f.number(i, "photo_timeinterval") > 0) {
      EXPECT_NEAR(f.number(i, "photo_timeinterval"), timed.imaging.trigger_distance_m / 5.0, 1e-3);
      EXPECT_EQ(f.number(i, "photo_distinterval"), -1);
      ++timed_rows;
    }
  EXPECT_EQ(timed_rows, timed.drones[0].mission.lines.size());
}

// ---- DJI: the KMZ unzipped with libzip's reader, its XML parsed with pugixml ----

// The KMZ's entries; none, and a failure, when libzip cannot read it.
std::map<std::string, std::string> unzip(const std::string& bytes) {
  auto entries = test::zip_entries(bytes);
  EXPECT_TRUE(entries) << "libzip cannot read the KMZ";
  return entries.value_or(std::map<std::string, std::string>{});
}

std::string text(const pugi::xml_node& n, const char* child) {
  return n.child(child).text().as_string();
}

double value(const pugi::xml_node& n, const char* child) {
  EXPECT_TRUE(n.child(child)) << child;
  return n.child(child).text().as_double();
}

TEST(DjiKmz, UnzipsToTemplateAndWaylinesThatParseBackToThePlan) {
  SurveyRequest r = test::meadow_request(80);
  r.home = geometry::GeoPoint{47.3965, 8.5405, 0};
  r.camera = find_camera("dji-mavic-3e", std::string(SWATH_SOURCE_DIR) + "/share/cameras");
  r.triggering.gimbal_pitch_deg = -75;
  const SurveyPlan plan = plan_survey(r);
  const Flight flight = flights_of(plan).at(0);
  const auto entries = unzip(dji_kmz(plan, flight));
  ASSERT_EQ(entries.size(), 2u);
  ASSERT_TRUE(entries.count("wpmz/template.kml"));
  ASSERT_TRUE(entries.count("wpmz/waylines.wpml"));

  pugi::xml_document waylines;
  ASSERT_TRUE(waylines.load_string(entries.at("wpmz/waylines.wpml").c_str()));
  const pugi::xml_node doc = waylines.child("kml").child("Document");
  EXPECT_STREQ(waylines.child("kml").attribute("xmlns:wpml").value(),
               "http://www.dji.com/wpmz/1.0.2");
  const pugi::xml_node config = doc.child("wpml:missionConfig");
  EXPECT_EQ(text(config, "wpml:flyToWaylineMode"), "safely");
  EXPECT_EQ(text(config, "wpml:finishAction"), "goHome");
  EXPECT_EQ(text(config, "wpml:exitOnRCLost"), "executeLostAction");
  EXPECT_EQ(text(config, "wpml:executeRCLostAction"), "goBack");
  const double security = value(config, "wpml:takeOffSecurityHeight");
  EXPECT_TRUE(security >= 2 && security <= 1500);
  EXPECT_DOUBLE_EQ(value(config, "wpml:globalTransitionalSpeed"), 5.0);
  EXPECT_EQ(value(config.child("wpml:droneInfo"), "wpml:droneEnumValue"), 77);
  EXPECT_EQ(value(config.child("wpml:droneInfo"), "wpml:droneSubEnumValue"), 0);
  EXPECT_EQ(value(config.child("wpml:payloadInfo"), "wpml:payloadEnumValue"), 66);
  EXPECT_EQ(value(config.child("wpml:payloadInfo"), "wpml:payloadPositionIndex"), 0);

  const pugi::xml_node folder = doc.child("Folder");
  EXPECT_EQ(text(folder, "wpml:executeHeightMode"), "relativeToStartPoint");
  EXPECT_DOUBLE_EQ(value(folder, "wpml:autoFlightSpeed"), 5.0);
  const std::vector<geometry::GeoPoint> planned = planned_points(plan, flight);
  const DroneMission& m = plan.drones[0].mission;
  std::size_t i = 0, photos = 0, gimbal = 0, photo_groups = 0;
  std::set<int> group_ids;
  for (const pugi::xml_node& pm : folder.children("Placemark")) {
    ASSERT_LT(i, planned.size());
    EXPECT_EQ(value(pm, "wpml:index"), double(i));
    double lon = 0, lat = 0;
    ASSERT_EQ(std::sscanf(pm.child("Point").child("coordinates").text().as_string(), " %lf,%lf",
                          &lon, &lat),
              2);
    EXPECT_NEAR(lat, planned[i].lat_deg, 1e-7) << i;
    EXPECT_NEAR(lon, planned[i].lon_deg, 1e-7) << i;
    EXPECT_DOUBLE_EQ(value(pm, "wpml:executeHeight"), 80.0);
    EXPECT_DOUBLE_EQ(value(pm, "wpml:waypointSpeed"), 5.0);
    const pugi::xml_node heading = pm.child("wpml:waypointHeadingParam");
    EXPECT_EQ(text(heading, "wpml:waypointHeadingMode"), "followWayline");
    const bool last = i + 1 == planned.size();
    const double leg =
        last ? bearing_deg(planned[i - 1], planned[i]) : bearing_deg(planned[i], planned[i + 1]);
    EXPECT_LE(angle_gap_deg(value(heading, "wpml:waypointHeadingAngle"), leg), 0.5 + 1e-9) << i;
    EXPECT_EQ(text(pm.child("wpml:waypointTurnParam"), "wpml:waypointTurnMode"),
              "toPointAndStopWithDiscontinuityCurvature");
    for (const pugi::xml_node& g : pm.children("wpml:actionGroup")) {
      EXPECT_TRUE(group_ids.insert(int(value(g, "wpml:actionGroupId"))).second);
      const std::size_t start = std::size_t(value(g, "wpml:actionGroupStartIndex"));
      const std::size_t end = std::size_t(value(g, "wpml:actionGroupEndIndex"));
      EXPECT_EQ(start, i) << "a group is declared at the point it starts";
      const std::string trigger = text(g.child("wpml:actionTrigger"), "wpml:actionTriggerType");
      const std::string func = text(g.child("wpml:action"), "wpml:actionActuatorFunc");
      if (func == "gimbalRotate") {
        ++gimbal;
        EXPECT_EQ(i, 0u);
        EXPECT_EQ(trigger, "reachPoint");
        const pugi::xml_node p = g.child("wpml:action").child("wpml:actionActuatorFuncParam");
        EXPECT_EQ(value(p, "wpml:gimbalPitchRotateEnable"), 1);
        EXPECT_DOUBLE_EQ(value(p, "wpml:gimbalPitchRotateAngle"), -75.0);
        continue;
      }
      // Photos: from a line's start to that line's end, every trigger distance.
      ASSERT_EQ(func, "takePhoto");
      ASSERT_EQ(trigger, "multipleDistance");
      ++photo_groups;
      EXPECT_NEAR(value(g.child("wpml:actionTrigger"), "wpml:actionTriggerParam"),
                  plan.imaging.trigger_distance_m, 1e-3);
      ASSERT_LT(end, planned.size());
      EXPECT_TRUE(std::any_of(m.lines.begin(), m.lines.end(),
                              [&](const SweepLine& l) {
                                auto local = [&](std::size_t k) {
                                  return plan.request.field.frame->to_local(planned[k]);
                                };
                                return geometry::distance(local(start), l.start) < 0.01 &&
                                       geometry::distance(local(end), l.end) < 0.01;
                              }))
          << "group " << start << "-" << end << " is not a line";
      photos += photos_on_run(plan,
                              std::vector<geometry::GeoPoint>(planned.begin() + long(start),
                                                              planned.begin() + long(end) + 1),
                              plan.imaging.trigger_distance_m);
    }
    ++i;
  }
  EXPECT_EQ(i, planned.size());
  EXPECT_EQ(gimbal, 1u);
  EXPECT_EQ(photo_groups, m.lines.size());
  EXPECT_EQ(photos, plan.drones[0].photos.size());

  // The template: the same points as a waypoint template DJI Pilot 2 edits.
  pugi::xml_document tmpl;
  ASSERT_TRUE(tmpl.load_string(entries.at("wpmz/template.kml").c_str()));
  const pugi::xml_node tf = tmpl.child("kml").child("Document").child("Folder");
  EXPECT_EQ(text(tf, "wpml:templateType"), "waypoint");
  EXPECT_EQ(text(tf.child("wpml:waylineCoordinateSysParam"), "wpml:coordinateMode"), "WGS84");
  EXPECT_EQ(text(tf.child("wpml:waylineCoordinateSysParam"), "wpml:heightMode"),
            "relativeToStartPoint");
  EXPECT_DOUBLE_EQ(value(tf, "wpml:globalHeight"), 80.0);
  EXPECT_EQ(text(tf, "wpml:gimbalPitchMode"), "usePointSetting");
  std::size_t template_points = 0;
  for (const pugi::xml_node& pm : tf.children("Placemark")) {
    EXPECT_DOUBLE_EQ(value(pm, "wpml:gimbalPitchAngle"), -75.0);
    EXPECT_DOUBLE_EQ(value(pm, "wpml:waypointSpeed"), 5.0);
    ++template_points;
  }
  EXPECT_EQ(template_points, planned.size());
}

// Drones from one home fly in altitude layers (deconfliction): each drone's KMZ returns home at
// its own layer's height (globalRTHHeight), the height its waypoints are flown at, not at one
// shared height where the drones would meet on the way home.
TEST(DjiKmz, EachDroneReturnsHomeInItsOwnLayer) {
  const SurveyPlan plan = meadow(80, [](SurveyRequest& r) {
    r.camera = find_camera("dji-mavic-3e", std::string(SWATH_SOURCE_DIR) + "/share/cameras");
    vehicle::Fleet fleet;
    fleet.home = *r.home;
    for (const char* name : {"a", "b", "c"}) {
      vehicle::Drone d;
      d.name = name;
      d.battery_level = 1.0;
      d.endurance_s = 3600;
      fleet.drones.push_back(d);
    }
    r.fleet = fleet;
  });
  std::set<double> rth_heights;
  for (const Flight& flight : flights_of(plan)) {
    SCOPED_TRACE(flight.file_stem);
    const auto entries = unzip(dji_kmz(plan, flight));
    pugi::xml_document w;
    ASSERT_TRUE(w.load_string(entries.at("wpmz/waylines.wpml").c_str()));
    const pugi::xml_node doc = w.child("kml").child("Document");
    const double rth_m = value(doc.child("wpml:missionConfig"), "wpml:globalRTHHeight");
    std::set<double> flown;
    for (const pugi::xml_node& pm : doc.child("Folder").children("Placemark"))
      flown.insert(value(pm, "wpml:executeHeight"));
    ASSERT_EQ(flown.size(), 1u);
    EXPECT_DOUBLE_EQ(rth_m, *flown.begin());
    rth_heights.insert(rth_m);
    // The template DJI Pilot 2 edits: the layer as its global height, every point on it.
    pugi::xml_document t;
    ASSERT_TRUE(t.load_string(entries.at("wpmz/template.kml").c_str()));
    const pugi::xml_node tf = t.child("kml").child("Document").child("Folder");
    EXPECT_DOUBLE_EQ(value(tf, "wpml:globalHeight"), rth_m);
    for (const pugi::xml_node& pm : tf.children("Placemark"))
      EXPECT_EQ(text(pm, "wpml:useGlobalHeight"), "1");
  }
  // Three drones from one home: three layers, 10 m apart from the imaging altitude up.
  EXPECT_EQ(rth_heights, (std::set<double>{80, 90, 100}));
}

TEST(DjiKmz, LandingUnknownCameraAndTimeTrigger) {
  // The Sony has no DJI enums: no droneInfo or payloadInfo, and a warning saying so.
  const SurveyPlan plan = meadow(80, [](SurveyRequest& r) {
    r.land = true;
    r.triggering.mode = TriggerMode::time;
  });
  const Flight flight = flights_of(plan).at(0);
  pugi::xml_document w;
  ASSERT_TRUE(w.load_string(dji_waylines_wpml(plan, flight).c_str()));
  const pugi::xml_node doc = w.child("kml").child("Document");
  EXPECT_EQ(text(doc.child("wpml:missionConfig"), "wpml:finishAction"), "autoLand");
  EXPECT_FALSE(doc.child("wpml:missionConfig").child("wpml:droneInfo"));
  FileOptions options;
  options.dji = true;
  const auto warnings = export_warnings(plan, options);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("has no DJI enums"), std::string::npos);
  EXPECT_TRUE(export_warnings(plan, {}).empty());
  // The last point is the home, where autoLand lands.
  pugi::xml_node last;
  std::size_t timed = 0;
  for (const pugi::xml_node& pm : doc.child("Folder").children("Placemark")) {
    last = pm;
    for (const pugi::xml_node& g : pm.children("wpml:actionGroup"))
      if (text(g.child("wpml:actionTrigger"), "wpml:actionTriggerType") == "multipleTiming") {
        EXPECT_NEAR(value(g.child("wpml:actionTrigger"), "wpml:actionTriggerParam"),
                    plan.imaging.trigger_distance_m / 5.0, 1e-3);
        ++timed;
      }
  }
  double lon = 0, lat = 0;
  ASSERT_EQ(std::sscanf(last.child("Point").child("coordinates").text().as_string(), " %lf,%lf",
                        &lon, &lat),
            2);
  EXPECT_NEAR(lat, plan.drones[0].home_geo.lat_deg, 1e-7);
  EXPECT_NEAR(lon, plan.drones[0].home_geo.lon_deg, 1e-7);
  EXPECT_EQ(timed, plan.drones[0].mission.lines.size());
}

TEST(Exports, SameInputSameBytesInAnyTimeZone) {
  FileOptions options;
  options.litchi = options.dji = true;
  const auto a = survey_files(meadow(60), options);
  const char* tz = std::getenv("TZ");
  const std::string saved = tz ? tz : "";
  setenv("TZ", "Pacific/Chatham", 1);  // UTC+13:45 in January
  tzset();
  const auto b = survey_files(meadow(60), options);
  if (tz)
    setenv("TZ", saved.c_str(), 1);
  else
    unsetenv("TZ");
  tzset();
  EXPECT_EQ(a, b);
  EXPECT_EQ(a.size(), 10u);
}

TEST(Exports, RefusedWhereTheAppCannotFlyThePlan) {
  FileOptions litchi, dji;
  litchi.litchi = true;
  dji.dji = true;
  auto message = [](const SurveyPlan& plan, const FileOptions& o) -> std::string {
    try {
      check_exports(plan, o);
    } catch (const base::InputError& e) {
      return e.what();
    }
    return "accepted";
  };
  SurveyPlan plan = meadow(60);
  EXPECT_EQ(message(plan, litchi), "accepted");
  plan.request.vehicle = Vehicle::fixedwing;
  EXPECT_NE(message(plan, litchi).find("--litchi: Litchi flies DJI multirotors"),
            std::string::npos);
  EXPECT_NE(message(plan, dji).find("--dji: DJI Pilot 2 flies DJI multirotors"), std::string::npos);
  EXPECT_EQ(message(plan, {}), "accepted");
  SurveyPlan fast = meadow(60, [](SurveyRequest& r) { r.speed_m_s = 18; });
  EXPECT_NE(message(fast, litchi).find("faster than Litchi's waypoint speeds"), std::string::npos);
  EXPECT_NE(message(fast, dji).find("--dji: drone drone-1 flies at 18.0 m/s, outside DJI's"),
            std::string::npos);
  // A wayline numbers at most 65,536 points.
  SurveyPlan big = meadow(60);
  std::vector<MissionItem>& items = big.drones[0].mission.items;
  std::size_t points = 0;
  for (const MissionItem& it : items) points += it.kind == ItemKind::waypoint;
  items.insert(items.end() - 1, kWpmlMaxWaypoints - points, MissionItem{});
  EXPECT_EQ(message(big, dji), "accepted");
  items.insert(items.end() - 1, MissionItem{});
  EXPECT_NE(message(big, dji).find("--dji: flight drone-1 has 65537 waypoints"), std::string::npos);
  // The writer on its own caps the transitional speed at WPML's 15 m/s; the waypoints keep 18.
  pugi::xml_document w;
  ASSERT_TRUE(w.load_string(dji_waylines_wpml(fast, flights_of(fast).at(0)).c_str()));
  const pugi::xml_node doc = w.child("kml").child("Document");
  EXPECT_DOUBLE_EQ(value(doc.child("wpml:missionConfig"), "wpml:globalTransitionalSpeed"), 15.0);
  EXPECT_DOUBLE_EQ(value(doc.child("Folder").child("Placemark"), "wpml:waypointSpeed"), 18.0);
}

}  // namespace
}  // namespace swath::planning
