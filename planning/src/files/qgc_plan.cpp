// QGroundControl .plan (docs/formats.md and docs/swath-plan.md), written by swath::missions
// (writers.hpp) from the plan: the items, the drone's home and speed, fences, rally, and QGC's
// Survey complex item.
#include "common.hpp"
#include "swath/base/number_text.hpp"
#include "swath/geometry/min_height.hpp"

namespace swath::planning {

using base::round_to;

namespace {

// QGC's CameraCalc of the plan's camera and imaging (a "Custom Camera" with swath's camera), and
// the survey's settings.
missions::QgcSurvey qgc_survey(const SurveyPlan& plan, const Flight& flight) {
  const Camera& c = plan.request.camera;
  const Imaging& im = plan.imaging;
  const SurveyRequest& r = plan.request;
  missions::QgcSurvey s;
  s.adjusted_footprint_frontal_m = round_to(im.trigger_distance_m, 6);
  s.adjusted_footprint_side_m = round_to(im.line_spacing_m, 6);
  s.distance_to_surface_m = round_to(im.altitude_m, 6);
  s.focal_length_mm = c.focal_length_mm;
  s.frontal_overlap_pct = round_to(100.0 * (1.0 - im.trigger_distance_m / im.footprint_along_m), 6);
  s.image_density_cm_px = round_to(im.gsd_m * 100.0, 8);
  s.image_height_px = c.image_height_px;
  s.image_width_px = c.image_width_px;
  s.landscape = plan.request.orientation == ImageOrientation::landscape;
  s.min_trigger_interval_s = c.min_trigger_interval_s.value_or(0.0);
  s.sensor_height_mm = c.sensor_height_mm;
  s.sensor_width_mm = c.sensor_width_mm;
  s.side_overlap_pct = round_to(100.0 * (1.0 - im.line_spacing_m / im.footprint_across_m), 6);
  s.camera_shots = flight.photos ? flight.photos->size() : 0;
  s.trigger_in_turnaround = r.triggering.photos_in_turns;
  s.hover_and_capture = r.triggering.mode == TriggerMode::hover;
  s.refly_90_degrees = r.crosshatch;
  s.turnaround_m = round_to(plan.turnaround_m, 6);
  s.angle_deg = round_to(geometry::line_bearing_deg(plan.sweep.angle_deg), 6);
  std::vector<geometry::GeoPoint> outline = r.field.geo_rings.at(0);
  if (outline.size() > 1 && outline.front() == outline.back()) outline.pop_back();  // QGC: open
  for (const geometry::GeoPoint& g : outline) s.polygon.push_back(files::rounded(g));
  return s;
}

}  // namespace

std::string qgc_plan(const SurveyPlan& plan, const Flight& flight) {
  return missions::write_qgc_plan(files::mission_file(plan, flight), files::qgc_settings(plan));
}

bool qgc_survey_possible(const SurveyPlan& plan, std::string* why) {
  auto no = [why](const char* reason) {
    if (why) *why = reason;
    return false;
  };
  if (plan.handling != Handling::convex || !plan.area.holes.empty() || !plan.no_fly.empty() ||
      !plan.extra_pieces.empty())
    return no(
        "QGroundControl's survey item is written for convex areas without holes or "
        "no-fly zones (its own transects would cross them when edited)");
  if (plan.drones.size() != 1) return no("QGroundControl's survey item is one drone's");
  if (!plan.drones[0].sorties.empty()) return no("a survey item cannot hold several sorties");
  if (plan.terrain)
    return no(
        "a survey item keeps one altitude; QGroundControl follows terrain itself with its "
        "survey's terrain altitude mode");
  return true;
}

std::string qgc_survey_plan(const SurveyPlan& plan, const Flight& flight) {
  const auto& items = flight.mission->items;
  missions::QgcSurvey survey = qgc_survey(plan, flight);
  // Outside the survey: the take-off before it, the return or landing after it.
  std::size_t first = 0, last = items.size();
  while (first < last && items[first].kind == ItemKind::takeoff) ++first;
  while (last > first &&
         (items[last - 1].kind == ItemKind::return_to_launch ||
          items[last - 1].kind == ItemKind::land || items[last - 1].kind == ItemKind::land_start))
    --last;
  survey.first = first;
  survey.last = last;
  for (std::size_t k = first; k < last; ++k)
    if (items[k].kind == ItemKind::waypoint)
      survey.transect_points.push_back(files::geo(plan, items[k].position));
  return missions::write_qgc_plan(files::mission_file(plan, flight), files::qgc_settings(plan),
                                  &survey);
}

}  // namespace swath::planning
