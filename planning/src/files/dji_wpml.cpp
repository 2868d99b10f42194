// DJI WPML KMZ (docs/swath-plan.md), written by swath::missions (writers.hpp) from the flight's
// export points.
#include "common.hpp"

namespace swath::planning {
namespace {

missions::DjiSettings dji_settings(const SurveyPlan& plan, const Flight& flight) {
  missions::DjiSettings s;
  s.land = plan.request.land;
  s.enums = plan.request.camera.dji;
  s.speed_m_s = flight.drone->speed_m_s;
  // The drone's own altitude layer (deconfliction): its return home (globalRTHHeight) and its
  // global height stay in that layer, apart from the other drones'.
  s.altitude_m = plan.imaging.altitude_m + flight.drone->layer_m;
  s.gimbal_pitch_deg = plan.request.triggering.gimbal_pitch_deg;
  s.trigger = plan.request.triggering.mode;
  s.trigger_value = files::trigger_value(flight);
  return s;
}

}  // namespace

std::string dji_waylines_wpml(const SurveyPlan& plan, const Flight& flight) {
  return missions::write_dji_waylines_wpml(files::export_points(plan, flight),
                                           dji_settings(plan, flight));
}

std::string dji_template_kml(const SurveyPlan& plan, const Flight& flight) {
  return missions::write_dji_template_kml(files::export_points(plan, flight),
                                          dji_settings(plan, flight));
}

std::string dji_kmz(const SurveyPlan& plan, const Flight& flight) {
  return missions::write_dji_kmz(files::export_points(plan, flight), dji_settings(plan, flight));
}

}  // namespace swath::planning
