#include "swath/planning/survey.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/geometry/convex_hull.hpp"
#include "swath/geometry/decomposition.hpp"
#include "swath/geometry/repair.hpp"
#include "swath/planning/split.hpp"

namespace swath::planning {

using base::fixed_text;

using base::InputError;

namespace {

std::string point_text(const geometry::Field& field, geometry::Point2 p) {
  const geometry::GeoPoint g = field.frame->to_geo(p);
  std::ostringstream s;
  s.precision(8);
  s << g.lat_deg << ", " << g.lon_deg << " (lat, lon)";
  return s.str();
}

// --repair: an outer ring that crosses itself becomes the areas it encloses.
void repair_outer_ring(SurveyPlan& plan) {
  geometry::Field& field = plan.request.field;
  const auto crossing = geometry::find_crossing(geometry::Polygon{field.polygon.outer, {}});
  if (!crossing) return;
  std::vector<geometry::Ring> pieces = geometry::enclosed_areas(field.polygon.outer);
  if (pieces.empty())
    throw InputError(field.source + ": the outer ring crosses itself and encloses no area");
  double total = 0;
  for (const geometry::Ring& p : pieces) total += geometry::signed_area(p);
  field.polygon.outer = pieces.front();
  field.source_index[0].assign(pieces.front().size(), 0);
  for (std::size_t i = 0; i < pieces.front().size(); ++i) field.source_index[0][i] = i;
  field.geo_rings[0].clear();
  for (const geometry::Point2& p : pieces.front())
    field.geo_rings[0].push_back(field.frame->to_geo(p));
  plan.extra_pieces.assign(pieces.begin() + 1, pieces.end());
  plan.warnings.push_back("repaired: the outer ring crosses itself at " +
                          point_text(field, crossing->point) + "; planned the " +
                          std::to_string(pieces.size()) + " area(s) it encloses, " +
                          fixed_text(total, 1) + " m² in all");
}

std::string lat_lon_text(const geometry::GeoPoint& g) {
  return fixed_text(g.lat_deg, 5) + "," + fixed_text(g.lon_deg, 5);
}

// Geodesic distance from `p` to the nearest vertex of the area (the area is small beside the
// distances this judges).
double distance_to_area_m(const geometry::GeoPoint& p,
                          const std::vector<geometry::GeoPoint>& ring) {
  double d = INFINITY;
  for (const geometry::GeoPoint& v : ring) d = std::min(d, geometry::geodesic_distance_m(p, v));
  return d;
}

// A home far from the area is almost always a typo: latitude and longitude swapped, or a sign
// lost (DESIGN.md §14 "Sanity checks"). Refused naming the distance and, where one of those
// readings lies within 1 km of the area, the home meant.
void check_home_near_area(const geometry::GeoPoint& home, const std::string& what,
                          const geometry::Field& field, bool far_home_allowed) {
  const std::vector<geometry::GeoPoint>& ring = field.geo_rings.at(0);
  const double d = distance_to_area_m(home, ring);
  if (d <= kMaxHomeDistance_m || (far_home_allowed && d <= kMaxFarHomeDistance_m)) return;
  std::string message = what + " " + lat_lon_text(home) + " (lat, lon) is " +
                        fixed_text(d / 1000, 0) + " km from the area";
  const geometry::GeoPoint readings[] = {{home.lon_deg, home.lat_deg, 0},
                                         {-home.lat_deg, home.lon_deg, 0},
                                         {home.lat_deg, -home.lon_deg, 0},
                                         {-home.lat_deg, -home.lon_deg, 0}};
  const char* how[] = {"latitude and longitude swapped", "the latitude's sign flipped",
                       "the longitude's sign flipped", "both signs flipped"};
  std::string tail = "; homes";
  for (std::size_t k = 0; k < std::size(readings); ++k) {
    const geometry::GeoPoint& r = readings[k];
    if (std::abs(r.lat_deg) <= 90 && distance_to_area_m(r, ring) <= 1000) {
      message += "; did you mean " + lat_lon_text(r) + " (" + how[k] + ")?";
      tail = " Homes";
      break;
    }
  }
  if (far_home_allowed)  // beyond what any drone flies, and what the local frame can hold
    throw InputError(message + tail + " farther than " +
                     fixed_text(kMaxFarHomeDistance_m / 1000, 0) +
                     " km are refused even with --far-home");
  throw InputError(message + tail + " farther than " + fixed_text(kMaxHomeDistance_m / 1000, 0) +
                   " km are refused unless --far-home is given");
}

// Every home the plan will use: the request's and the fleet's own.
void check_homes(const SurveyRequest& request, const geometry::Field& field) {
  if (request.home) check_home_near_area(*request.home, "the home", field, request.far_home);
  if (!request.fleet) return;
  if (std::isfinite(request.fleet->home.lat_deg) &&
      request.fleet->home != request.home.value_or(geometry::GeoPoint{NAN, NAN, 0}))
    check_home_near_area(request.fleet->home, "the fleet's home", field, request.far_home);
  for (const Drone& d : request.fleet->drones)
    if (d.home)
      check_home_near_area(*d.home, "drone " + d.name + "'s home", field, request.far_home);
}

// The holes split routes around: bounded before the quadratic work (kMaxSplitHoles).
void check_split_size(const geometry::Polygon& area) {
  std::size_t vertices = 0;
  for (const geometry::Ring& hole : area.holes) vertices += hole.size();
  if (area.holes.size() > kMaxSplitHoles || vertices > kMaxSplitHoleVertices)
    throw InputError("the area has " + std::to_string(area.holes.size()) +
                     " holes and no-fly zones with " + std::to_string(vertices) +
                     " vertices, more than split's limit of " + std::to_string(kMaxSplitHoles) +
                     " holes and " + std::to_string(kMaxSplitHoleVertices) +
                     " vertices; merge or simplify them, or give --concave hull");
}

// Divides the planned survey among the request's fleet: one mission per drone.
void divide_among_fleet(SurveyPlan& plan, geometry::Point2 plan_home,
                        const std::vector<geometry::Ring>& rings, bool split,
                        const SplitSettings& split_settings,
                        const geometry::VisibilityRouter& router, const LegRoute& route,
                        MissionSettings mission_settings) {
  const SurveyRequest& request = plan.request;
  const geometry::Field& field = request.field;
  std::vector<DroneResource> resources;
  for (const Drone& d : request.fleet->drones) {
    DroneResource r;
    r.name = d.name;
    // Own home, else the fleet's, else (--drones without --home: NaN) the plan's.
    r.home = d.home ? field.frame->to_local(*d.home)
             : std::isfinite(request.fleet->home.lat_deg)
                 ? field.frame->to_local(request.fleet->home)
                 : plan_home;
    r.speed_m_s = d.speed_m_s.value_or(plan.speed_m_s);
    r.range_m = d.range_m();
    r.capability = d.capability.value_or(1.0);
    resources.push_back(r);
  }
  const LegRoute leg_route = split ? route : LegRoute{};
  if (request.division == DivisionMode::path) {
    const SurveyPath whole = survey_path(plan.mission.lines, request.waypoint_spacing_m, leg_route);
    plan.division = divide_path(whole, resources, request.balance);
  } else {
    const double angle = plan.sweep.angle_deg;
    const geometry::VisibilityRouter straight(rings, 0);
    const BandSweep sweep_band = [&](const std::vector<geometry::Ring>& band,
                                     const DroneResource& drone, bool estimate) -> SurveyPath {
      if (!split) {  // a convex area (or the hull): each band piece with the strip rule
        std::vector<SweepLine> lines;
        for (const geometry::Ring& piece : band) {
          SweepSettings s;
          s.angle_deg = angle;
          s.line_spacing_m = plan.imaging.line_spacing_m;
          s.footprint_width_m = plan.imaging.footprint_across_m;
          s.placement = request.placement;
          s.turnaround_m = request.turnaround_m;
          const auto ordered = order_lines(plan_sweep(geometry::Polygon{piece, {}}, s),
                                           StartCorner::nearest_home, drone.home);
          lines.insert(lines.end(), ordered.begin(), ordered.end());
        }
        return survey_path(lines, request.waypoint_spacing_m);
      }
      SplitSettings s = split_settings;
      s.fixed_angle_deg = angle;
      const SplitPlan sp = plan_pieces(band, angle, drone.home, s, estimate ? straight : router);
      return survey_path(sp.lines, request.waypoint_spacing_m, estimate ? LegRoute{} : route);
    };
    plan.division = divide_region(split ? rings : geometry::rings_of(plan.flown_area), angle,
                                  resources, request.balance, sweep_band);
  }
  for (std::size_t i = 0; i < resources.size(); ++i) {
    mission_settings.speed_m_s = resources[i].speed_m_s;
    plan.drone_missions.push_back(mission_for_path(static_cast<int>(i + 1), resources[i].home,
                                                   plan.division.drones[i].path, mission_settings,
                                                   leg_route));
    if (resources[i].range_m && plan.drone_missions.back().path_length_m > *resources[i].range_m) {
      const std::string what =
          "drone " + resources[i].name + "'s flight (" +
          std::to_string(std::lround(plan.drone_missions.back().path_length_m)) +
          " m) is longer than its range (" + std::to_string(std::lround(*resources[i].range_m)) +
          " m)";
      if (!request.allow_partial)
        throw InputError(
            what + "; add drones or battery, use --balance makespan, or give --allow-partial");
      plan.warnings.push_back(what);
    }
    if (plan.drone_missions.back().work_length_m < 1.0)
      plan.warnings.push_back("drone " + resources[i].name +
                              " gets no survey work (its share is used up by the flight to the "
                              "area and back); leave it out of the fleet");
    plan.drone_names.push_back(resources[i].name);
    plan.drone_speeds_m_s.push_back(resources[i].speed_m_s);
  }
  plan.drone_work = plan.division.drones;
}

}  // namespace

geometry::Polygon measured_area(const SurveyPlan& plan) {
  geometry::Polygon measured = plan.area;
  measured.holes.insert(measured.holes.end(), plan.extra_pieces.begin(), plan.extra_pieces.end());
  return measured;
}

std::vector<const DroneMission*> missions_of(const SurveyPlan& plan) {
  std::vector<const DroneMission*> out;
  if (plan.drone_missions.empty()) {
    out.push_back(&plan.mission);
  } else {
    for (const DroneMission& m : plan.drone_missions) out.push_back(&m);
  }
  return out;
}

SurveyPlan plan_survey(const SurveyRequest& request) {
  SurveyPlan plan;
  plan.request = request;
  geometry::Field& field = plan.request.field;
  if (!field.frame)
    throw InputError(field.source +
                     ": the area is in local metres; give --origin LAT,LON to place it on the map");

  check_homes(request, field);
  if (request.repair) repair_outer_ring(plan);
  plan.area = field.polygon;
  for (std::size_t k = 0; k < request.exclusions.size(); ++k) {
    geometry::NormalisedRing hole = geometry::normalise_ring(request.exclusions[k], false);
    if (hole.ring.size() < 3)
      throw InputError("no-fly zone " + std::to_string(k) + " has fewer than 3 distinct vertices");
    plan.area.holes.push_back(std::move(hole.ring));
  }
  plan.facts = geometry::describe_area(plan.area);
  for (const geometry::Ring& piece : plan.extra_pieces)
    *plan.facts.area_m2 += geometry::signed_area(piece);
  const geometry::Classification& c = plan.facts.classification;
  if (c.type == geometry::AreaType::self_intersecting &&
      c.crossing->edge_b.ring > field.polygon.holes.size()) {
    const geometry::GeoPoint p = field.frame->to_geo(c.crossing->point);
    std::ostringstream s;
    s.precision(8);
    s << "no-fly zone " << (c.crossing->edge_b.ring - 1 - field.polygon.holes.size())
      << " crosses the area's boundary or another zone at " << p.lat_deg << ", " << p.lon_deg
      << " (lat, lon); give zones inside the area that do not overlap";
    throw InputError(s.str());
  }
  if (c.type == geometry::AreaType::self_intersecting) {
    const geometry::GeoPoint p = field.frame->to_geo(c.crossing->point);
    std::ostringstream s;
    s.precision(8);
    s << field.source << ": the area crosses itself at " << p.lat_deg << ", " << p.lon_deg
      << " (lat, lon); 'swath classify' names the edges; fix the vertex order, or give --repair to "
         "plan "
         "the areas it encloses";
    throw InputError(s.str());
  }
  if (c.type == geometry::AreaType::concave && request.concave == ConcaveMode::reject)
    throw InputError(field.source + ": the area is not convex (" +
                     std::to_string(c.reflex_vertices.size()) + " reflex vertices" +
                     (field.polygon.holes.empty() ? "" : ", holes") +
                     ") and --concave reject refuses it; use --concave hull");
  const bool convex = c.type == geometry::AreaType::convex && plan.extra_pieces.empty();
  const bool split = !convex && request.concave == ConcaveMode::split;
  if (split) check_split_size(plan.area);
  plan.handling = convex ? "convex" : split ? "split" : "hull";
  std::vector<geometry::Point2> all_outer = plan.area.outer;
  for (const geometry::Ring& piece : plan.extra_pieces)
    all_outer.insert(all_outer.end(), piece.begin(), piece.end());
  plan.flown_area =
      convex || split ? plan.area : geometry::Polygon{geometry::convex_hull(all_outer), {}};

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

  // A sliver (three points on one parallel, 1.5 km by 5 cm) is no area to survey: refused rather
  // than planned as a flight whose lines lie wholly outside it.
  const double narrowest_m = geometry::min_height_rotation(plan.area.outer).height_m;
  if (narrowest_m < kMinAreaWidth_m)
    throw InputError(field.source + ": the area is " + fixed_text(narrowest_m, 3) +
                     " m wide at its narrowest, less than swath's minimum of " +
                     fixed_text(kMinAreaWidth_m, 0) + " m; is it a line drawn as a polygon?");

  // Bounded work: a camera footprint of centimetres over kilometres would ask for millions of
  // lines or waypoints; refuse that instead of running out of time or memory.
  const double lines = plan.direction.height_m / plan.imaging.line_spacing_m;
  if (lines > double(kMaxSweepLines))
    throw InputError("the area is " + fixed_text(plan.direction.height_m, 1) +
                     " m across the lines and they are " +
                     fixed_text(plan.imaging.line_spacing_m, 3) +
                     " m apart: " + fixed_text(lines, 0) + " lines, more than swath's limit of " +
                     std::to_string(kMaxSweepLines) + "; fly higher or split the area");
  if (request.waypoint_spacing_m && *request.waypoint_spacing_m > 0 && plan.facts.area_m2) {
    const double points =
        *plan.facts.area_m2 / plan.imaging.line_spacing_m / *request.waypoint_spacing_m;
    if (points > double(kMaxWaypoints))
      throw InputError("--waypoint-spacing " + fixed_text(*request.waypoint_spacing_m, 3) +
                       " m would put about " + fixed_text(points, 0) +
                       " waypoints on the lines, more than swath's limit of " +
                       std::to_string(kMaxWaypoints));
  }
  if (!(request.turnaround_m >= 0 && std::isfinite(request.turnaround_m)))
    throw InputError("--turnaround must be >= 0 m");
  if (request.waypoint_spacing_m && !(*request.waypoint_spacing_m > 0))
    throw InputError("--waypoint-spacing must be > 0 m");
  plan.speed_m_s = request.speed_m_s.value_or(request.vehicle == Vehicle::multirotor ? 5.0 : 15.0);
  if (!(plan.speed_m_s > 0 && std::isfinite(plan.speed_m_s)))
    throw InputError("--speed must be > 0 m/s");

  // Home: given, or the area's south-west-most vertex.
  geometry::Point2 home = plan.area.outer.front();
  for (const geometry::Point2& p : plan.area.outer)
    if (p.x + p.y < home.x + home.y) home = p;
  if (request.home) home = field.frame->to_local(*request.home);
  plan.home = request.home ? *request.home : field.frame->to_geo(home);

  MissionSettings mission_settings;
  mission_settings.altitude_m = plan.imaging.altitude_m;
  mission_settings.speed_m_s = plan.speed_m_s;
  mission_settings.trigger_distance_m = plan.imaging.trigger_distance_m;
  mission_settings.waypoint_spacing_m = request.waypoint_spacing_m;
  std::vector<geometry::Ring> rings = geometry::rings_of(plan.area);
  rings.insert(rings.end(), plan.extra_pieces.begin(), plan.extra_pieces.end());

  const geometry::VisibilityRouter router(rings, split ? 300 : 0);
  const LegRoute route = [&router](geometry::Point2 a, geometry::Point2 b) {
    std::vector<geometry::Point2> p = router.path(a, b);
    return std::vector<geometry::Point2>(p.begin() + 1, p.end() - 1);
  };
  SplitSettings split_settings;
  split_settings.line_spacing_m = plan.imaging.line_spacing_m;
  split_settings.footprint_width_m = plan.imaging.footprint_across_m;
  split_settings.placement = request.placement;
  split_settings.turnaround_m = request.turnaround_m;
  split_settings.scan_step_deg = request.split_scan_step_deg;
  if (split) {
    if (request.angle_search == AngleSearch::fixed)
      split_settings.fixed_angle_deg = plan.direction.angle_deg;
    const SplitPlan sp = plan_split(rings, home, split_settings, router);
    plan.direction = {sp.angle_deg, geometry::height_at(plan.area.outer, sp.angle_deg)};
    plan.sweep = {sp.angle_deg, plan.direction.height_m, sp.lines};
    plan.cells = sp.cells;
    plan.direction_candidates = sp.candidates;
    plan.mission = build_mission(1, home, sp.lines, mission_settings, route);
  } else {
    SweepSettings sweep_settings;
    sweep_settings.angle_deg = plan.direction.angle_deg;
    sweep_settings.line_spacing_m = plan.imaging.line_spacing_m;
    sweep_settings.footprint_width_m = plan.imaging.footprint_across_m;
    sweep_settings.placement = request.placement;
    sweep_settings.turnaround_m = request.turnaround_m;
    plan.sweep = plan_sweep(plan.flown_area, sweep_settings);
    plan.cells = {plan.flown_area.outer};
    plan.mission =
        build_mission(1, home, order_lines(plan.sweep, request.start, home), mission_settings);
  }

  if (request.fleet)
    divide_among_fleet(plan, home, rings, split, split_settings, router, route, mission_settings);

  const geometry::Polygon measured = measured_area(plan);
  std::vector<SweepLine> flown;
  for (const DroneMission* m : missions_of(plan))
    flown.insert(flown.end(), m->lines.begin(), m->lines.end());
  plan.coverage =
      measure_coverage(measured, flown, plan.sweep.angle_deg, plan.imaging.footprint_across_m);
  if (!(plan.coverage.covered_fraction > 0))
    throw InputError(field.source + ": the plan covers none of the area (" +
                     std::to_string(plan.sweep.lines.size()) +
                     " lines); check the altitude, overlaps and turnaround");
  if (plan.division.unflown_path_m > 0 && !request.allow_partial)
    throw InputError(
        "the fleet cannot fly the whole survey: " + fixed_text(plan.division.unflown_path_m, 1) +
        " m of path and " + fixed_text(plan.coverage.area_m2 - plan.coverage.covered_area_m2, 1) +
        " m² of area stay unflown; add drones or battery, or give --allow-partial");
  // Turns and transits outside the area: each path from its first line's start to its last
  // line's end, less the lines' own length outside. The legs to and from home are not counted:
  // a home outside the area cannot be reached inside it.
  const geometry::VisibilityRouter measure(rings, 0);
  double outside = 0;
  for (const DroneMission* m : missions_of(plan)) {
    if (m->lines.empty()) continue;
    const auto& path = m->path;
    // From the first line's start to the last line's end, by position in the path.
    const auto first = static_cast<std::size_t>(
        std::find(path.begin(), path.end(), m->lines.front().start) - path.begin());
    const auto last =
        path.size() - 1 -
        static_cast<std::size_t>(std::find(path.rbegin(), path.rend(), m->lines.back().end) -
                                 path.rbegin());
    for (std::size_t i = first; i < last; ++i)
      outside += measure.length_outside(path[i], path[i + 1]);
  }
  plan.transit_outside_m = std::max(0.0, outside - plan.coverage.line_length_outside_m);

  if (const auto& interval = request.camera.min_trigger_interval_s) {
    const double seconds = plan.imaging.trigger_distance_m / plan.speed_m_s;
    if (seconds < *interval)
      plan.warnings.push_back("at " + fixed_text(plan.speed_m_s, 1) +
                              " m/s the camera must trigger every " + fixed_text(seconds, 1) +
                              " s, faster than its " + fixed_text(*interval, 1) +
                              " s minimum; fly at most " +
                              fixed_text(plan.imaging.trigger_distance_m / *interval, 1) + " m/s");
  }
  if (request.pattern && plan.imaging.altitude_m > *plan.imaging.h_max_m * (1 + 1e-12))
    plan.warnings.push_back("the altitude " + fixed_text(plan.imaging.altitude_m, 1) +
                            " m is above h_max " + fixed_text(*plan.imaging.h_max_m, 1) +
                            " m: the pattern spans fewer pixels than required");
  for (const DroneMission* m : missions_of(plan))
    if (m->items.size() > kAutopilotItemLimit)
      plan.warnings.push_back("drone " + std::to_string(m->drone) + "'s mission has " +
                              std::to_string(m->items.size()) +
                              " items, more than ArduPilot's classic limit of 700 (some autopilots "
                              "hold fewer): divide it among drones or drop --waypoint-spacing");
  return plan;
}

}  // namespace swath::planning
