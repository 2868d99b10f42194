// The set of files of a plan, and its flights.
#include <algorithm>
#include <tuple>
#include <utility>

#include "common.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
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

namespace {

// DJI Pilot 2 flies waypoint speeds from 1 to 15 m/s: a cruise speed outside is refused, as is a
// slow-down before a stop beside a no-fly zone below 1 m/s (swath plan --dji plans none:
// SurveyRequest::slowest_approach_m_s), which DJI would fly at 1 m/s and overrun further.
void check_dji_speeds(const SurveyPlan& plan) {
  using base::fixed_text;
  for (const DronePlan& d : plan.drones)
    if (!(d.speed_m_s >= missions::kDjiMinSpeed_m_s && d.speed_m_s <= missions::kDjiMaxSpeed_m_s))
      throw base::InputError("--dji: drone " + d.name + " flies at " + fixed_text(d.speed_m_s, 1) +
                             " m/s, outside DJI's waypoint speeds (1 to 15 m/s); set --speed or "
                             "the fleet's speed_m_s within them");
  for (const Flight& f : flights_of(plan))
    for (const MissionItem& item : f.mission->items)
      if (item.kind == ItemKind::change_speed && item.value < missions::kDjiMinSpeed_m_s)
        throw base::InputError("--dji: flight " + f.file_stem + " slows to " +
                               fixed_text(item.value, 2) +
                               " m/s before a stop beside a no-fly zone, below DJI's least "
                               "waypoint speed (1 m/s); plan with a slowest approach of 1 m/s");
}

// DJI Pilot 2 takes heights up to 1500 m above the take-off point (takeOffSecurityHeight; WPML
// documents no other limit for executeHeight): a survey above is refused, not cut.
void check_dji_heights(const SurveyPlan& plan, double highest_m) {
  for (const DronePlan& d : plan.drones)
    highest_m = std::max(highest_m, plan.imaging.altitude_m + d.layer_m);
  if (highest_m > missions::kDjiMaxHeight_m)
    throw base::InputError("--dji: the altitude " + base::fixed_text(highest_m, 1) +
                           " m is above DJI Pilot 2's highest, 1500 m above the take-off point "
                           "(takeOffSecurityHeight); fly lower or drop --dji");
}

}  // namespace

void check_exports(const SurveyPlan& plan, const FileOptions& options) {
  using base::InputError;
  for (const auto& [asked, flag, app] : {std::tuple{options.litchi, "--litchi", "Litchi"},
                                         std::tuple{options.dji, "--dji", "DJI Pilot 2"}})
    if (asked && plan.request.vehicle == Vehicle::fixedwing)
      throw InputError(std::string(flag) + ": " + app +
                       " flies DJI multirotors, not a fixed-wing plan; drop " + flag +
                       " or plan for --vehicle multirotor");
  if (options.dji)  // WPML numbers a wayline's points 0 to 65535 (wpml:index)
    for (const Flight& f : flights_of(plan)) {
      std::size_t points = 0;
      for (const MissionItem& item : f.mission->items)
        points += item.kind == ItemKind::waypoint || item.kind == ItemKind::land;
      if (points > kWpmlMaxWaypoints)
        throw InputError("--dji: flight " + f.file_stem + " has " + std::to_string(points) +
                         " waypoints, more than a DJI WPML wayline holds (65,536); cut it with "
                         "--sorties auto or fewer --waypoint-spacing points");
    }
  if (std::string why; options.qgc_survey && !qgc_survey_possible(plan, &why))
    throw InputError("--qgc-survey: " + why + "; use the .plan of waypoints instead");
  if (!options.litchi && !options.dji) return;
  // With terrain, waypoints climb and descend with the ground: a valley below home goes below it.
  double highest_m = plan.imaging.altitude_m, lowest_m = plan.imaging.altitude_m;
  for (const Flight& f : flights_of(plan))
    for (const MissionItem& item : f.mission->items)
      if (positional(item.kind)) {
        highest_m = std::max(highest_m, item.altitude_m);
        lowest_m = std::min(lowest_m, item.altitude_m);
      }
  if (lowest_m < kDjiMinAltitude_m) {
    const auto [flag, app] =
        options.litchi ? std::pair{"--litchi", "Litchi's"} : std::pair{"--dji", "DJI Pilot 2's"};
    throw InputError(std::string(flag) + ": the altitude " + base::fixed_text(lowest_m, 1) +
                     " m is below " + app +
                     " lowest waypoint, 200 m below the take-off point; take off lower down "
                     "(--home) or drop " +
                     flag);
  }
  if (options.dji) {
    check_dji_speeds(plan);
    check_dji_heights(plan, highest_m);
  }
  if (!options.litchi) return;
  if (highest_m > kLitchiMaxAltitude_m)
    throw InputError("--litchi: the altitude " + base::fixed_text(highest_m, 1) +
                     " m is above Litchi's highest waypoint, 500 m above the take-off point");
  for (const DronePlan& d : plan.drones)
    if (d.speed_m_s > kLitchiMaxSpeed_m_s)
      throw InputError("--litchi: drone " + d.name + " flies at " +
                       base::fixed_text(d.speed_m_s, 1) +
                       " m/s, faster than Litchi's waypoint speeds (at most 15 m/s); lower "
                       "--speed or the fleet's speed_m_s");
}

std::vector<std::string> export_warnings(const SurveyPlan& plan, const FileOptions& options) {
  std::vector<std::string> out;
  if (options.dji && !plan.request.camera.dji)
    out.push_back("--dji: the camera '" + plan.request.camera.name +
                  "' has no DJI enums (dji_drone_enum, dji_payload_enum in its camera file), so "
                  "the KMZ names no aircraft and payload (wpml:droneInfo, wpml:payloadInfo); DJI "
                  "Pilot 2 needs them to open it: add them to a copy of the camera file");
  return out;
}

std::vector<std::pair<std::string, std::string>> survey_files(const SurveyPlan& plan,
                                                              const FileOptions& options) {
  check_exports(plan, options);
  const files::GeoMemo memo(plan);  // the writers share their points' positions
  std::vector<std::pair<std::string, std::string>> files{{"mission.geojson", mission_geojson(plan)},
                                                         {"summary.json", summary_json(plan)}};
  for (const Flight& f : flights_of(plan)) {
    files.push_back({f.file_stem + ".plan", qgc_plan(plan, f)});
    if (options.qgc_survey)
      files.push_back({f.file_stem + "-survey.plan", qgc_survey_plan(plan, f)});
    files.push_back({f.file_stem + ".waypoints", wpl_110(plan, f)});
    if (options.litchi) {
      // One part: NAME-litchi.csv; several: NAME-litchi-1.csv, -2, ... (as sorties are numbered).
      std::vector<std::string> parts = litchi_csv(plan, f);
      for (std::size_t k = 0; k < parts.size(); ++k) {
        std::string name = f.file_stem + "-litchi";
        if (parts.size() > 1) name += '-' + std::to_string(k + 1);
        files.push_back({name + ".csv", std::move(parts[k])});
      }
    }
    if (options.dji) files.push_back({f.file_stem + ".kmz", dji_kmz(plan, f)});
  }
  files.push_back({"waypoints.csv", waypoints_csv(plan)});
  files.push_back({"mission.kml", mission_kml(plan)});
  files::PhotoTexts photos = files::photo_texts(plan);
  files.push_back({"photos.geojson", std::move(photos.geojson)});
  files.push_back({"photos.csv", std::move(photos.csv)});
  if (options.fence_files) {
    files.push_back({"fence.waypoints", fence_waypoints(plan)});
    files.push_back({"fence.fen", fence_fen(plan)});
    files.push_back({"rally.waypoints", rally_waypoints(plan)});
  }
  return files;
}

}  // namespace swath::planning
