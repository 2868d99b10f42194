#pragma once
// The steps of plan_survey(), in pipeline order; each in its own source file
// (planning/src/steps/<step>.cpp) and each filling its part of the SurveyPlan. Exposed so that
// tests and benches can run a pipeline up to a step.

#include "swath/geometry/visibility.hpp"
#include "swath/planning/survey.hpp"

namespace swath::planning::steps {

/// 1. area: the frame, homes near the area (docs/swath-plan.md sanity), --repair, no-fly zones as
/// holes, the facts and their refusals (crossings, --concave reject), the handling (convex, hull,
/// split), the flown area, the planning rings (holes and zones grown by the clearance, the outer
/// ring shrunk by the boundary clearance) and the fence.
void area(SurveyPlan& plan);

/// 2. imaging: altitude, footprint, spacing and trigger distance from the camera and mode.
void imaging(SurveyPlan& plan);

/// 3. direction: the sweep direction (exact, scan or fixed), the refusals of degenerate slivers
/// and of work beyond the limits, speed, turnaround, the fixed-wing turn radius and the home.
void direction(SurveyPlan& plan);

/// 4. lanes: the lines over the planning rings (one sweep, or split cells) in flying order, the
/// crosshatch pass, and the fixed-wing interleave.
void lanes(SurveyPlan& plan);

/// 5. drones: one DronePlan per drone (names, file names, homes, speeds, endurance) and, with a
/// fleet, the division of the lines among them.
void drones(SurveyPlan& plan);

/// 6. missions: each drone's items (speed, gimbal, camera per line, routed legs, RTL or land),
/// its planned photos, the fence margin and the exclusion fences.
void missions(SurveyPlan& plan);

/// 7. sorties: with SurveyRequest::sorties, each drone's flight cut into battery-sized sorties.
void sorties(SurveyPlan& plan);

/// 7a. deconflict: with several drones, altitude layers (SurveyRequest::layer_spacing_m apart,
/// refused above SurveyRequest::ceiling_m) for drones whose paths come within kSeparation_m
/// (plus cut corners and overruns) of each other, and launch offsets where a drone climbs or
/// descends at its home through the layer of another that is near that home then.
void deconflict(SurveyPlan& plan);

/// 7b. terrain: with SurveyRequest::terrain, every flight's waypoints at the imaging altitude
/// above the DEM's ground, waypoints added where the ground departs from a leg's straight line
/// by more than the tolerance; the facts (heights flown, steep legs) and their warnings.
void terrain(SurveyPlan& plan);

/// 7c. fences: the inclusion fence from what is flown: the area and every leg of every flight
/// (home legs, transits, the overrun past each stop), grown by the fence margin and simplified
/// outward to kFenceVertexLimit vertices where it can; each home inside.
void fences(SurveyPlan& plan);

/// Refuses (InputError) a ring `what` (the area, a zone, a fence) with an edge across the ±180°
/// meridian as its longitudes would be written (geometry::edge_across_antimeridian): ArduPilot's
/// and PX4's fences, compared in raw longitude, cannot hold it.
void refuse_across_antimeridian(const std::vector<geometry::GeoPoint>& ring,
                                const std::string& what);

/// 8. measures: coverage, the clearance actually kept, turns and transits outside the area.
void measures(SurveyPlan& plan);

/// 9. checks: the refusals that need the whole plan (covers nothing, fleet short) and the
/// warnings (trigger interval, h_max, item limit, fence vertices, altitude, endurance, idle
/// drones).
void checks(SurveyPlan& plan);

/// How far the bends of routed legs keep from the corners they go round, beyond the clearance:
/// an autopilot flies through a bend without stopping and cuts it (ArduCopter's waypoint radius
/// WPNAV_RADIUS is 2 m; its SITL flights of swath's missions left the lines by up to 1.7 m).
inline constexpr double kCornerAllowance_m = 2.0;

/// The routes the steps share: inside the planning rings (split's turns and transits), and in the
/// open around the grown no-fly zones (legs to and from home, between a drone's pieces).
struct Routes {
  explicit Routes(const SurveyPlan& plan);
  geometry::VisibilityRouter inside;
  geometry::VisibilityRouter open;
  /// Points strictly between a and b on the shortest path inside the planning rings (when a and
  /// b are both inside them), else around the zones.
  LegRoute leg() const;
  /// The same in the open only (home legs).
  LegRoute open_leg() const;
  /// Whether a leg stays inside the planning rings (the missions' turns kept with the camera on,
  /// stops drawn back).
  InsideTest inside_test() const;

 private:
  /// The path around the zones in the open, its inner points; refused (InputError) where there is
  /// none and the straight leg would cross a zone.
  std::vector<geometry::Point2> around(geometry::Point2 a, geometry::Point2 b) const;
  std::vector<geometry::Ring> no_fly_;  // a copy: the routes may outlive a copy of the plan
  double turnaround_m_ = 0.0;           // named in the refusal as one thing to lower
};

/// The plan's shared routes, built on first use. Each router's pre-processing (its visibility
/// tables, the open's grown zones) is the same for every step, so it is done once a plan.
const Routes& routes_of(SurveyPlan& plan);

/// The time drone `d` may spend climbing to and descending from the highest altitude layer
/// deconflict() may give it (one per other drone of the plan), seconds: what a flight sized
/// before the layers are known keeps free of its battery.
double layer_room_s(const SurveyPlan& plan, const DronePlan& d);

/// The mission settings of one drone of the plan (altitude, its speed, camera, vehicle, end).
MissionSettings mission_settings(const SurveyPlan& plan, const DronePlan& drone);

/// What a survey line crosses (local frame): the flown area's outline (the hull with --concave
/// hull) and --repair's pieces. A run of the camera that meets none of them is a transit.
std::vector<geometry::Ring> lined_rings(const SurveyPlan& plan);

/// The most vertices of one of `rings` (0 for none): what a fence polygon must fit.
std::size_t most_vertices(const std::vector<geometry::Ring>& rings);

}  // namespace swath::planning::steps
