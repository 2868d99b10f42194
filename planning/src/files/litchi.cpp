// Litchi mission CSV (docs/swath-plan.md), written by swath::missions (writers.hpp) from the
// flight's export points.
#include "common.hpp"

namespace swath::planning {

std::vector<std::string> litchi_csv(const SurveyPlan& plan, const Flight& flight) {
  missions::LitchiSettings settings;
  settings.max_rows = kLitchiMaxWaypoints;
  settings.gimbal_pitch_deg = plan.request.triggering.gimbal_pitch_deg;
  settings.speed_m_s = flight.drone->speed_m_s;
  settings.trigger = plan.request.triggering.mode;
  settings.trigger_value = files::trigger_value(flight);
  return missions::write_litchi_csv(files::export_points(plan, flight), settings);
}

}  // namespace swath::planning
