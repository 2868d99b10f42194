#pragma once
// A plan's geometry as mission.geojson holds it (missions::PlanFeatures, whose writer and reader
// live with the other mission formats' in swath::missions) and the figures its pictures print.

#include <string>
#include <vector>

#include "swath/missions/mission_geojson.hpp"

namespace swath::planning {

struct SurveyPlan;

// mission.geojson's value, writer and reader are swath::missions'; the names stay usable here.
using missions::GeoRing;
using missions::mission_geojson;
using missions::parse_mission_geojson;
using missions::PlanFeatures;

/// The features of a plan.
PlanFeatures plan_features(const SurveyPlan& plan);

/// What the plan's survey lines cross, on the map (steps::lined_rings): the area for the photos
/// check of the plan's own files.
std::vector<GeoRing> lined_area(const SurveyPlan& plan);

/// The figures the pictures print, from summary.json (docs/formats.md).
struct PlanFigures {
  double covered_fraction = 0;
  int lines = 0;
  struct Drone {
    int drone = 0;
    std::string name;
    double path_length_m = 0, flight_time_s = 0;
  };
  std::vector<Drone> drones;
};

/// The figures of a plan, rounded as summary.json writes them.
PlanFigures plan_figures(const SurveyPlan& plan);

/// Reads them from summary.json; throws base::InputError naming `source` and the key.
PlanFigures parse_plan_figures(const std::string& summary_text, const std::string& source);

}  // namespace swath::planning
