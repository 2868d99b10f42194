// The QGroundControl Survey complex item (--qgc-survey), checked by the rules of QGC's own loader
// (SurveyComplexItem::_loadV4V5, TransectStyleComplexItem::_load, CameraCalc::load version 1,
// CameraSpec::load, MissionItem::load: required keys and their JSON types, as QGC validates them),
// by QGC's own camera arithmetic (CameraCalc::_recalcTriggerDistance: what QGC recomputes when the
// survey is edited gives swath's spacing and trigger distance back), and by the mission it flies:
// the items, flattened, are the waypoint plan's items.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "meadow_survey.hpp"
#include "swath/base/input_error.hpp"
#include "swath/geometry/min_height.hpp"
#include "swath/planning/survey_files.hpp"
#include "swath/vehicle/drone.hpp"

namespace swath::planning {
namespace {

using nlohmann::json;

enum class T { number, boolean, string, array, object };

bool has_type(const json& v, T t) {
  switch (t) {
    case T::number:  // QGC accepts null for a Double (NaN)
      return v.is_number() || v.is_null();
    case T::boolean:
      return v.is_boolean();
    case T::string:
      return v.is_string();
    case T::array:
      return v.is_array();
    case T::object:
      return v.is_object();
  }
  return false;
}

struct Key {
  const char* name;
  T type;
  bool required;
};

// JsonHelper::validateKeys: a required key must be there, any key there must have its type.
void validate(const json& o, const std::vector<Key>& keys, const std::string& where) {
  ASSERT_TRUE(o.is_object()) << where;
  for (const Key& k : keys) {
    if (!o.contains(k.name)) {
      EXPECT_FALSE(k.required) << where << ": required key " << k.name << " missing";
      continue;
    }
    EXPECT_TRUE(has_type(o[k.name], k.type))
        << where << ": key " << k.name << " has the wrong type";
  }
}

// loadGeoCoordinateArray without altitude: [lat, lon] pairs of numbers within range.
void validate_coordinates(const json& a, std::size_t at_least, const std::string& where) {
  ASSERT_TRUE(a.is_array()) << where;
  EXPECT_GE(a.size(), at_least) << where;
  for (const json& p : a) {
    ASSERT_TRUE(p.is_array() && p.size() >= 2 && p[0].is_number() && p[1].is_number()) << where;
    EXPECT_LE(std::abs(p[0].get<double>()), 90.0) << where;
    EXPECT_LE(std::abs(p[1].get<double>()), 180.0) << where;
  }
}

void validate_simple_item(const json& item, const std::string& where) {
  validate(item,
           {{"autoContinue", T::boolean, true},
            {"command", T::number, true},
            {"doJumpId", T::number, true},
            {"frame", T::number, true},
            {"params", T::array, true},
            {"type", T::string, true}},
           where);
  EXPECT_EQ(item["type"], "SimpleItem") << where;
  EXPECT_EQ(item["params"].size(), 7u) << where;
}

// Everything QGC checks on opening the file; the survey item returned.
json load_like_qgc(const std::string& text) {
  const json root = json::parse(text);
  validate(root,
           {{"fileType", T::string, true},
            {"version", T::number, true},
            {"mission", T::object, true},
            {"geoFence", T::object, false},
            {"rallyPoints", T::object, false}},
           "plan");
  EXPECT_EQ(root["fileType"], "Plan");
  const json& m = root["mission"];
  validate(m,
           {{"version", T::number, true},
            {"firmwareType", T::number, true},
            {"vehicleType", T::number, false},
            {"cruiseSpeed", T::number, false},
            {"hoverSpeed", T::number, false},
            {"items", T::array, true},
            {"plannedHomePosition", T::array, true}},
           "mission");
  json survey;
  for (const json& item : m["items"]) {
    if (item["type"] == "SimpleItem") {
      validate_simple_item(item, "item");
      continue;
    }
    EXPECT_EQ(item["type"], "ComplexItem");
    EXPECT_EQ(item["complexItemType"], "survey");
    EXPECT_TRUE(survey.is_null()) << "one survey";
    survey = item;
  }
  if (survey.is_null()) {
    ADD_FAILURE() << "no survey item";
    return survey;
  }
  EXPECT_EQ(survey["version"], 5);  // SurveyComplexItem::load: 2..5; v5 needs splitConcavePolygons
  validate(survey,
           {{"type", T::string, true},
            {"complexItemType", T::string, true},
            {"entryLocation", T::number, true},
            {"angle", T::number, true},
            {"flyAlternateTransects", T::boolean, false},
            {"splitConcavePolygons", T::boolean, true},
            {"polygon", T::array, true},
            {"TransectStyleComplexItem", T::object, true}},
           "survey");
  validate_coordinates(survey["polygon"], 3, "survey polygon");
  const json& tsci = survey["TransectStyleComplexItem"];
  EXPECT_EQ(tsci["version"], 2);
  validate(tsci,
           {{"version", T::number, true},
            {"TurnAroundDistance", T::number, true},
            {"CameraTriggerInTurnAround", T::boolean, true},
            {"HoverAndCapture", T::boolean, true},
            {"Refly90Degrees", T::boolean, true},
            {"CameraCalc", T::object, true},
            {"VisualTransectPoints", T::array, true},
            {"Items", T::array, true},
            {"CameraShots", T::number, true}},
           "TransectStyleComplexItem");
  validate_coordinates(tsci["VisualTransectPoints"], 2, "VisualTransectPoints");
  for (const json& item : tsci["Items"]) validate_simple_item(item, "survey item");
  const json& cc = tsci["CameraCalc"];
  EXPECT_EQ(cc["version"], 1);  // 4.0-4.1 load only 1; 4.2+ convert 1 to 2
  validate(cc,
           {{"CameraName", T::string, true},
            {"AdjustedFootprintSide", T::number, true},
            {"AdjustedFootprintFrontal", T::number, true},
            {"DistanceToSurface", T::number, true},
            {"DistanceToSurfaceRelative", T::boolean, true}},
           "CameraCalc");
  EXPECT_NE(cc["CameraName"], "Manual (no camera specs)");  // so the rest is required:
  validate(cc,
           {{"ValueSetIsDistance", T::boolean, true},
            {"ImageDensity", T::number, true},
            {"FrontalOverlap", T::number, true},
            {"SideOverlap", T::number, true},
            {"SensorWidth", T::number, true},
            {"SensorHeight", T::number, true},
            {"ImageWidth", T::number, true},
            {"ImageHeight", T::number, true},
            {"FocalLength", T::number, true},
            {"Landscape", T::boolean, true},
            {"FixedOrientation", T::boolean, true},
            {"MinTriggerInterval", T::number, true}},
           "CameraCalc");
  return survey;
}

SurveyPlan meadow(const std::function<void(SurveyRequest&)>& edit = {}) {
  SurveyRequest r = test::meadow_request(70);
  r.home = geometry::GeoPoint{47.3965, 8.5405, 0};
  if (edit) edit(r);
  return plan_survey(r);
}

TEST(QgcSurvey, LoadsByQgcsRulesAndFliesTheWaypointPlansItems) {
  for (const ImageOrientation o : {ImageOrientation::landscape, ImageOrientation::portrait}) {
    const SurveyPlan plan = meadow([o](SurveyRequest& r) { r.orientation = o; });
    ASSERT_TRUE(qgc_survey_possible(plan));
    const Flight flight = flights_of(plan).at(0);
    const json survey = load_like_qgc(qgc_survey_plan(plan, flight));
    ASSERT_FALSE(survey.is_null());
    const json& cc = survey["TransectStyleComplexItem"]["CameraCalc"];
    // QGC's CameraCalc::_recalcTriggerDistance, with the altitude given (ValueSetIsDistance).
    const double density = cc["DistanceToSurface"].get<double>() * cc["SensorWidth"].get<double>() *
                           100.0 /
                           (cc["ImageWidth"].get<double>() * cc["FocalLength"].get<double>());
    EXPECT_NEAR(cc["ImageDensity"].get<double>(), density, 1e-6);
    const bool landscape = cc["Landscape"];
    EXPECT_EQ(landscape, o == ImageOrientation::landscape);
    const double side =
        (landscape ? cc["ImageWidth"] : cc["ImageHeight"]).get<double>() * density / 100;
    const double frontal =
        (landscape ? cc["ImageHeight"] : cc["ImageWidth"]).get<double>() * density / 100;
    EXPECT_NEAR(side * (100 - cc["SideOverlap"].get<double>()) / 100, plan.imaging.line_spacing_m,
                1e-4);
    EXPECT_NEAR(frontal * (100 - cc["FrontalOverlap"].get<double>()) / 100,
                plan.imaging.trigger_distance_m, 1e-4);
    EXPECT_NEAR(cc["AdjustedFootprintSide"].get<double>(), plan.imaging.line_spacing_m, 1e-6);
    EXPECT_NEAR(cc["DistanceToSurface"].get<double>(), 70.0, 1e-9);
    // The survey's own parameters.
    EXPECT_NEAR(survey["angle"].get<double>(), geometry::line_bearing_deg(plan.sweep.angle_deg),
                1e-6);
    EXPECT_NEAR(survey["TransectStyleComplexItem"]["TurnAroundDistance"].get<double>(),
                plan.turnaround_m, 1e-6);
    EXPECT_EQ(survey["TransectStyleComplexItem"]["CameraShots"], flight.photos->size());
    const auto& ring = plan.request.field.geo_rings.at(0);
    ASSERT_EQ(survey["polygon"].size(), ring.size() - (ring.front() == ring.back() ? 1 : 0));
    for (std::size_t k = 0; k < survey["polygon"].size(); ++k) {
      EXPECT_NEAR(survey["polygon"][k][0].get<double>(), ring[k].lat_deg, 1e-9);
      EXPECT_NEAR(survey["polygon"][k][1].get<double>(), ring[k].lon_deg, 1e-9);
    }
    // Flattened, the items are the waypoint plan's: QGC flies them until the survey is edited.
    const json plain = json::parse(qgc_plan(plan, flight))["mission"]["items"];
    const json with = json::parse(qgc_survey_plan(plan, flight))["mission"]["items"];
    std::vector<json> flat;
    for (const json& item : with) {
      if (item["type"] == "SimpleItem") {
        flat.push_back(item);
        continue;
      }
      for (const json& inner : item["TransectStyleComplexItem"]["Items"]) flat.push_back(inner);
    }
    ASSERT_EQ(flat.size(), plain.size());
    for (std::size_t k = 0; k < flat.size(); ++k) {
      EXPECT_EQ(flat[k]["command"], plain[k]["command"]) << k;
      EXPECT_EQ(flat[k]["frame"], plain[k]["frame"]) << k;
      EXPECT_EQ(flat[k]["params"], plain[k]["params"]) << k;
      EXPECT_EQ(flat[k]["doJumpId"], plain[k]["doJumpId"]) << k;
    }
    EXPECT_EQ(with.front()["command"], 22);  // take-off before the survey
    EXPECT_EQ(with.back()["command"], 20);   // return after it
  }
}

TEST(QgcSurvey, IsRefusedWhereQgcsOwnTransectsWouldNotBeSwaths) {
  std::string why;
  const SurveyPlan zone = meadow([](SurveyRequest& r) {
    r.exclusions.push_back(
        {{47.3985, 8.5420, 0}, {47.3985, 8.5428, 0}, {47.3990, 8.5428, 0}, {47.3990, 8.5420, 0}});
  });
  EXPECT_FALSE(qgc_survey_possible(zone, &why));
  EXPECT_NE(why.find("convex areas without holes"), std::string::npos) << why;
  const SurveyPlan two = meadow([](SurveyRequest& r) {
    r.fleet = vehicle::equal_fleet(2, {47.3965, 8.5405, 0});
  });
  EXPECT_FALSE(qgc_survey_possible(two, &why));
  FileOptions o;
  o.qgc_survey = true;
  try {
    survey_files(two, o);
    ADD_FAILURE() << "written";
  } catch (const base::InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--qgc-survey: ", 0), 0u) << e.what();
  }
  // A plain plan writes it, named after the flight.
  bool found = false;
  for (const auto& [name, text] : survey_files(meadow(), o))
    found = found || name == "drone-1-survey.plan";
  EXPECT_TRUE(found);
}

}  // namespace
}  // namespace swath::planning
