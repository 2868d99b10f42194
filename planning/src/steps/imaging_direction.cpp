// Steps 2 and 3 of plan_survey(): imaging and direction (survey_steps.hpp).
#include <cmath>
#include <optional>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/geometry/offset.hpp"
#include "swath/planning/survey_steps.hpp"

namespace swath::planning::steps {
namespace {

using base::fixed_text;
using base::InputError;

constexpr double kGravity_m_s2 = 9.80665;
constexpr double kPi = 3.14159265358979323846;

// The area's south-west-most vertex that keeps the clearance from every hole and no-fly zone: the
// vertices where zones cut the area lie on a zone's edge, and a take-off there entered the zone.
geometry::Point2 default_home(const SurveyPlan& plan) {
  const double clearance_m = plan.request.clearance_m;
  std::optional<geometry::Point2> home;
  for (const geometry::Point2& p : plan.area.outer) {
    if (home && p.x + p.y >= home->x + home->y) continue;
    if (!plan.no_fly.empty() && geometry::least_distance({p}, plan.no_fly) < clearance_m) continue;
    home = p;
  }
  if (!home)
    throw InputError(plan.request.field.source + ": every vertex of the area lies within " +
                     fixed_text(clearance_m, 1) +
                     " m (--clearance) of a no-fly zone, so none can be the default home; "
                     "give --home LAT,LON clear of the zones, or lower --clearance");
  return *home;
}

geometry::SweepDirection search_direction(const SurveyPlan& plan) {
  const SurveyRequest& r = plan.request;
  const geometry::Ring& outer = plan.flown_area.outer;
  switch (r.angle_search) {
    case AngleSearch::exact:  // the area is simple here (classified, or repaired)
      return geometry::min_height_of_simple_ring(outer);
    case AngleSearch::scan:
      if (!(r.angle_step_deg > 0 && r.angle_step_deg <= 90))
        throw InputError("the angle step must be in (0, 90] degrees");
      return geometry::min_height_scan(outer, r.angle_step_deg);
    case AngleSearch::fixed:
      break;
  }
  if (!std::isfinite(r.line_bearing_deg))
    throw InputError("the line bearing must be a finite number of degrees");
  const double angle = std::fmod(std::fmod(90.0 - r.line_bearing_deg, 180.0) + 180.0, 180.0);
  return {angle, geometry::height_at(outer, angle)};
}

// Bounded work: a camera footprint of centimetres over kilometres would ask for millions of
// lines or waypoints; refuse that instead of running out of time or memory. A sliver (three
// points on one parallel, 1.5 km by 5 cm) is no area to survey either.
void check_work(const SurveyPlan& plan) {
  const SurveyRequest& r = plan.request;
  const double narrowest_m = geometry::min_height_of_simple_ring(plan.area.outer).height_m;
  if (narrowest_m < kMinAreaWidth_m)
    throw InputError(r.field.source + ": the area is " + fixed_text(narrowest_m, 3) +
                     " m wide at its narrowest, less than swath's minimum of " +
                     fixed_text(kMinAreaWidth_m, 0) + " m; is it a line drawn as a polygon?");
  const double lines = plan.direction.height_m / plan.imaging.line_spacing_m;
  if (lines > double(kMaxSweepLines))
    throw InputError("the area is " + fixed_text(plan.direction.height_m, 1) +
                     " m across the lines and they are " +
                     fixed_text(plan.imaging.line_spacing_m, 3) +
                     " m apart: " + fixed_text(lines, 0) + " lines, more than swath's limit of " +
                     std::to_string(kMaxSweepLines) + "; fly higher or split the area");
  if (r.waypoint_spacing_m && *r.waypoint_spacing_m > 0 && plan.facts.area_m2) {
    const double points = *plan.facts.area_m2 / plan.imaging.line_spacing_m / *r.waypoint_spacing_m;
    if (points > double(kMaxWaypoints))
      throw InputError("--waypoint-spacing " + fixed_text(*r.waypoint_spacing_m, 3) +
                       " m would put about " + fixed_text(points, 0) +
                       " waypoints on the lines, more than swath's limit of " +
                       std::to_string(kMaxWaypoints));
  }
  if (r.waypoint_spacing_m && !(*r.waypoint_spacing_m > 0))
    throw InputError("the waypoint spacing must be > 0 m");
}

// Speed, the fixed-wing turn radius at it, and the turnaround (docs/swath-plan.md).
void flight_figures(SurveyPlan& plan) {
  const SurveyRequest& r = plan.request;
  plan.speed_m_s = r.speed_m_s.value_or(r.vehicle == Vehicle::multirotor ? 5.0 : 15.0);
  if (!(plan.speed_m_s > 0 && std::isfinite(plan.speed_m_s)))
    throw InputError("the speed must be > 0 m/s");
  if (r.vehicle == Vehicle::fixedwing) {
    if (!(r.max_bank_deg > 0 && r.max_bank_deg < 80))
      throw InputError("the bank limit must be in (0, 80) degrees");
    plan.turn_radius_m =
        plan.speed_m_s * plan.speed_m_s / (kGravity_m_s2 * std::tan(r.max_bank_deg * kPi / 180));
  }
  // A fixed-wing needs about one turn radius after a turn to settle on the line.
  plan.turnaround_m = r.turnaround_m.value_or(plan.turn_radius_m);
  if (!(plan.turnaround_m >= 0 && std::isfinite(plan.turnaround_m)))
    throw InputError("the turnaround must be >= 0 m");
}

}  // namespace

void imaging(SurveyPlan& plan) {
  const SurveyRequest& r = plan.request;
  if (const auto* p = std::get_if<PhotogrammetryMode>(&r.mode)) {
    plan.imaging = photogrammetry_imaging(r.camera, *p, r.orientation);
    if (r.pattern) {
      const Imaging target = detection_imaging(r.camera, *r.pattern, r.orientation, "pattern");
      plan.imaging.h_max_m = target.h_max_m;
      plan.imaging.h_min_m = target.h_min_m;
    }
  } else {
    plan.imaging = detection_imaging(r.camera, std::get<DetectionMode>(r.mode), r.orientation);
  }
}

void direction(SurveyPlan& plan) {
  plan.direction = search_direction(plan);
  check_work(plan);
  flight_figures(plan);
  // Home: given, or the area's south-west-most vertex clear of the zones.
  const geometry::Field& field = plan.request.field;
  if (plan.request.home) {
    plan.home = *plan.request.home;
    plan.home_local = field.frame->to_local(plan.home);
  } else {
    plan.home_local = default_home(plan);
    plan.home = field.frame->to_geo(plan.home_local);
  }
}

}  // namespace swath::planning::steps
