// WPL 110 files (Mission Planner): missions, and ArduPilot polygon fences and rally points,
// written by swath::missions (writers.hpp) from the plan.
#include "common.hpp"

namespace swath::planning {

std::string wpl_110(const SurveyPlan& plan, const Flight& flight) {
  return missions::write_wpl(files::mission_file(plan, flight));
}

std::string fence_waypoints(const SurveyPlan& plan) {
  return missions::write_wpl_fences(files::fence_file(plan));
}

std::string fence_fen(const SurveyPlan& plan) {
  return missions::write_fen(files::fence_file(plan));
}

std::string rally_waypoints(const SurveyPlan& plan) {
  missions::Mission rally;
  for (const DronePlan& d : plan.drones) rally.rally_points.push_back(files::rounded(d.home_geo));
  return missions::write_wpl_rally(rally);
}

}  // namespace swath::planning
