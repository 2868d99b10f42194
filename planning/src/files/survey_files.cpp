// The set of files of a plan, and its flights.
#include "common.hpp"
#include "swath/planning/plan_features.hpp"

namespace swath::planning {

std::vector<Flight> flights_of(const SurveyPlan& plan) {
  std::vector<Flight> out;
  for (const DronePlan& d : plan.drones) {
    if (d.sorties.empty()) {
      out.push_back({&d, &d.mission, &d.photos, 0, d.file_stem});
      continue;
    }
    for (const Sortie& s : d.sorties)
      out.push_back(
          {&d, &s.mission, &s.photos, s.number, d.file_stem + "-" + std::to_string(s.number)});
  }
  return out;
}

std::string mission_geojson(const SurveyPlan& plan) {
  return mission_geojson(plan_features(plan));
}

std::vector<std::pair<std::string, std::string>> survey_files(const SurveyPlan& plan,
                                                              const FileOptions& options) {
  std::vector<std::pair<std::string, std::string>> files{{"mission.geojson", mission_geojson(plan)},
                                                         {"summary.json", summary_json(plan)}};
  for (const Flight& f : flights_of(plan)) {
    files.push_back({f.file_stem + ".plan", qgc_plan(plan, f)});
    files.push_back({f.file_stem + ".waypoints", wpl_110(plan, f)});
  }
  files.push_back({"waypoints.csv", waypoints_csv(plan)});
  files.push_back({"mission.kml", mission_kml(plan)});
  files.push_back({"photos.geojson", photos_geojson(plan)});
  files.push_back({"photos.csv", photos_csv(plan)});
  if (options.fence_files) {
    files.push_back({"fence.waypoints", fence_waypoints(plan)});
    files.push_back({"fence.fen", fence_fen(plan)});
    files.push_back({"rally.waypoints", rally_waypoints(plan)});
  }
  return files;
}

}  // namespace swath::planning
