#include "swath/planning/survey.hpp"

#include <cmath>
#include <sstream>

#include "swath/geometry/convex_hull.hpp"
#include "swath/geometry/input_error.hpp"

namespace swath::planning {

using geometry::InputError;

namespace {

std::string fixed1(double v) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(1);
  s << v;
  return s.str();
}

}  // namespace

SurveyPlan plan_survey(const SurveyRequest& request) {
  SurveyPlan plan;
  plan.request = request;
  const geometry::Field& field = request.field;
  if (!field.frame)
    throw InputError(field.source +
                     ": the area is in local metres; give --origin LAT,LON to place it on the map");

  plan.facts = geometry::describe_area(field.polygon);
  const geometry::Classification& c = plan.facts.classification;
  if (c.type == geometry::AreaType::self_intersecting) {
    const geometry::GeoPoint p = field.frame->to_geo(c.crossing->point);
    std::ostringstream s;
    s.precision(8);
    s << field.source << ": the area crosses itself at " << p.lat_deg << ", " << p.lon_deg
      << " (lat, lon); 'swath classify' names the edges; fix the vertex order";
    throw InputError(s.str());
  }
  if (c.type == geometry::AreaType::concave && request.concave == ConcaveMode::reject)
    throw InputError(field.source + ": the area is not convex (" +
                     std::to_string(c.reflex_vertices.size()) + " reflex vertices" +
                     (field.polygon.holes.empty() ? "" : ", holes") +
                     ") and --concave reject refuses it; use --concave hull");
  plan.flown_area = c.type == geometry::AreaType::convex
                        ? field.polygon
                        : geometry::Polygon{geometry::convex_hull(field.polygon.outer), {}};

  if (const auto* p = std::get_if<PhotogrammetryMode>(&request.mode)) {
    plan.imaging = photogrammetry_imaging(request.camera, *p, request.orientation);
    if (request.pattern) {
      const Imaging target =
          detection_imaging(request.camera, *request.pattern, request.orientation, "pattern");
      plan.imaging.h_max_m = target.h_max_m;
      plan.imaging.h_min_m = target.h_min_m;
    }
  } else {
    plan.imaging = detection_imaging(request.camera, std::get<DetectionMode>(request.mode),
                                     request.orientation);
  }

  switch (request.angle_search) {
    case AngleSearch::exact:
      plan.direction = geometry::min_height_rotation(plan.flown_area.outer);
      break;
    case AngleSearch::scan:
      if (!(request.angle_step_deg > 0 && request.angle_step_deg <= 90))
        throw InputError("--angle-step must be in (0, 90] degrees");
      plan.direction = geometry::min_height_scan(plan.flown_area.outer, request.angle_step_deg);
      break;
    case AngleSearch::fixed: {
      if (!std::isfinite(request.line_bearing_deg))
        throw InputError("--angle must be a finite number of degrees");
      const double angle =
          std::fmod(std::fmod(90.0 - request.line_bearing_deg, 180.0) + 180.0, 180.0);
      plan.direction = {angle, geometry::height_at(plan.flown_area.outer, angle)};
      break;
    }
  }

  if (!(request.turnaround_m >= 0 && std::isfinite(request.turnaround_m)))
    throw InputError("--turnaround must be >= 0 m");
  if (request.waypoint_spacing_m && !(*request.waypoint_spacing_m > 0))
    throw InputError("--waypoint-spacing must be > 0 m");
  plan.speed_m_s = request.speed_m_s.value_or(request.vehicle == Vehicle::multirotor ? 5.0 : 15.0);
  if (!(plan.speed_m_s > 0 && std::isfinite(plan.speed_m_s)))
    throw InputError("--speed must be > 0 m/s");

  SweepSettings sweep_settings;
  sweep_settings.angle_deg = plan.direction.angle_deg;
  sweep_settings.line_spacing_m = plan.imaging.line_spacing_m;
  sweep_settings.footprint_width_m = plan.imaging.footprint_across_m;
  sweep_settings.placement = request.placement;
  sweep_settings.turnaround_m = request.turnaround_m;
  plan.sweep = plan_sweep(plan.flown_area, sweep_settings);

  std::optional<geometry::Point2> home_local;
  if (request.home) home_local = field.frame->to_local(*request.home);
  StartCorner start = request.start;
  if (start == StartCorner::nearest_home && !home_local) start = StartCorner::sw;
  const std::vector<SweepLine> ordered = order_lines(plan.sweep, start, home_local);
  const geometry::Point2 home = home_local ? *home_local : ordered.front().start;
  plan.home = field.frame->to_geo(home);

  MissionSettings mission_settings;
  mission_settings.altitude_m = plan.imaging.altitude_m;
  mission_settings.speed_m_s = plan.speed_m_s;
  mission_settings.trigger_distance_m = plan.imaging.trigger_distance_m;
  mission_settings.waypoint_spacing_m = request.waypoint_spacing_m;
  plan.mission = build_mission(1, home, ordered, mission_settings);

  plan.coverage = measure_coverage(field.polygon, plan.mission.lines, plan.sweep.angle_deg,
                                   plan.imaging.footprint_across_m);

  if (const auto& interval = request.camera.min_trigger_interval_s) {
    const double seconds = plan.imaging.trigger_distance_m / plan.speed_m_s;
    if (seconds < *interval)
      plan.warnings.push_back(
          "at " + fixed1(plan.speed_m_s) + " m/s the camera must trigger every " + fixed1(seconds) +
          " s, faster than its " + fixed1(*interval) + " s minimum; fly at most " +
          fixed1(plan.imaging.trigger_distance_m / *interval) + " m/s");
  }
  if (request.pattern && plan.imaging.altitude_m > *plan.imaging.h_max_m * (1 + 1e-12))
    plan.warnings.push_back("the altitude " + fixed1(plan.imaging.altitude_m) +
                            " m is above h_max " + fixed1(*plan.imaging.h_max_m) +
                            " m: the pattern spans fewer pixels than required");
  if (plan.mission.waypoint_count > 700)
    plan.warnings.push_back(std::to_string(plan.mission.waypoint_count) +
                            " waypoints: more than ArduPilot's classic limit of 700 items");
  return plan;
}

}  // namespace swath::planning
