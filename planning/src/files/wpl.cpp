// WPL 110 files (Mission Planner): missions, and ArduPilot polygon fences and rally points,
// written by swath::missions (writers.hpp) from the plan.
#include "common.hpp"

namespace swath::planning {

std::string wpl_110(const SurveyPlan& plan, const Flight& flight) {
  missions::Mission m = files::mission_file(plan, flight);
  // PX4's: params with no value written as such (missions::write_wpl).
  m.autopilot = plan.request.firmware == Firmware::px4 ? missions::Autopilot::px4
                                                       : missions::Autopilot::ardupilot;
  return missions::write_wpl(m);
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
