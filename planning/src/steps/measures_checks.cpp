// Steps 8 and 9 of plan_survey(): what the plan achieves, and what it refuses or warns about
// (survey_steps.hpp).
#include <algorithm>
#include <cmath>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/geometry/decomposition.hpp"
#include "swath/geometry/offset.hpp"
#include "swath/missions/fence_storage.hpp"
#include "swath/planning/survey_steps.hpp"

namespace swath::planning::steps {
namespace {

using base::fixed_text;
using base::InputError;

// Every flight a drone makes: its sorties, or its one mission.
std::vector<const DroneMission*> flights_of(const DronePlan& d) {
  std::vector<const DroneMission*> out;
  for (const Sortie& s : d.sorties) out.push_back(&s.mission);
  if (out.empty()) out.push_back(&d.mission);
  return out;
}

// Lines of the first pass (parallel to the sweep): the coverage measure takes one direction, and
// the first pass alone covers the area (the crosshatch pass adds views, not area).
std::vector<SweepLine> first_pass_lines(const SurveyPlan& plan) {
  const geometry::Point2 axis = rotate({1, 0}, plan.sweep.angle_deg);
  std::vector<SweepLine> out;
  for (const DronePlan& d : plan.drones)
    for (const SweepLine& l : d.mission.lines) {
      const geometry::Point2 v = l.end - l.start;
      const double length = std::hypot(v.x, v.y);
      if (length == 0 || std::abs(geometry::cross(axis, v)) <= 1e-6 * length) out.push_back(l);
    }
  return out;
}

// Turns and transits outside the area: each path from its first line's start to its last
// line's end, less the lines' own length outside. The legs to and from home are not counted:
// a home outside the area cannot be reached inside it.
double transit_outside_m(const SurveyPlan& plan) {
  std::vector<geometry::Ring> rings = geometry::rings_of(plan.area);
  rings.insert(rings.end(), plan.extra_pieces.begin(), plan.extra_pieces.end());
  rings.insert(rings.end(), plan.extra_piece_holes.begin(), plan.extra_piece_holes.end());
  const geometry::VisibilityRouter measure(rings, geometry::Routing::measure_only);
  double outside = 0;
  for (const DronePlan& d : plan.drones) {
    const DroneMission& m = d.mission;
    if (m.lines.empty()) continue;
    const auto& path = m.path;
    // The first line's start and the last one's end among the path's points (a waypoint within
    // 5 cm of the one before it is merged into it: mission.cpp's MissionBuilder::waypoint).
    auto at = [](geometry::Point2 q) {
      return [q](geometry::Point2 p) { return geometry::distance(p, q) < 0.051; };
    };
    const auto first = static_cast<std::size_t>(
        std::find_if(path.begin(), path.end(), at(m.lines.front().start)) - path.begin());
    const auto from_end = static_cast<std::size_t>(
        std::find_if(path.rbegin(), path.rend(), at(m.lines.back().end)) - path.rbegin());
    if (first >= path.size() || from_end >= path.size()) continue;
    const std::size_t last = path.size() - 1 - from_end;
    for (std::size_t i = first; i < last; ++i)
      outside += measure.length_outside(path[i], path[i + 1]);
  }
  return std::max(0.0, outside - plan.coverage.line_length_outside_m);
}

// " in FILE" after what the fleet file gives, where the fleet came from one.
std::string in_fleet_file(const SurveyRequest& r) {
  return r.fleet_name.empty() ? "" : " in " + r.fleet_name;
}

// What gets a drone past a flight longer than its battery, among the options not given already.
// Not the balance on flight time: the division has cut on it wherever shares were too long.
std::vector<base::Remedy> battery_remedies(const SurveyRequest& r) {
  std::vector<base::Remedy> out{base::Remedy::add_drones_or_battery};
  if (!r.sorties) out.push_back(base::Remedy::sorties);
  return out;
}

// No sortie is written longer than the battery it takes off with (docs/swath-plan.md): the
// charge the fleet file gives (battery_level x endurance_s; a sortie after the first, a full
// battery), in flight time as the mission flies it (climbs, stops and descents, the layer, the
// terrain). The sorties step cut each within it less the reserve: this is the last word.
void check_sortie_charge(const SurveyPlan& plan, const DronePlan& d) {
  if (!d.charge_from_fleet || d.sorties.empty()) return;
  for (std::size_t k = 0; k < d.sorties.size(); ++k) {
    const double battery_s = *d.endurance_s * (k == 0 ? d.battery_level : 1.0);
    const double flight_s = d.sorties[k].mission.flight_time_s;
    if (flight_s <= battery_s * (1 + 1e-9)) continue;
    const std::string battery =
        k == 0 ? "battery_level " + base::shortest_text(d.battery_level) + " x endurance_s " +
                     base::shortest_text(*d.endurance_s)
               : "a full battery, endurance_s " + base::shortest_text(*d.endurance_s);
    throw InputError("drone " + d.name + "'s sortie " + std::to_string(k + 1) + " takes " +
                         duration_text(flight_s) + ", longer than the " + duration_text(battery_s) +
                         " its battery holds (" + battery + in_fleet_file(plan.request) + ")",
                     battery_remedies(plan.request));
  }
}

// Where the charge a drone takes off with comes from, for the refusal: the fleet file's keys or
// the options, and the reserve (a pilot who lands with less in hand says so with --reserve).
std::string charge_source(const SurveyPlan& plan, const DronePlan& d) {
  const std::string reserve = base::shortest_text(plan.request.reserve);
  if (d.charge_from_fleet)
    return "battery_level " + base::shortest_text(d.battery_level) + " x endurance_s " +
           base::shortest_text(*d.endurance_s) + in_fleet_file(plan.request) + ", --reserve " +
           reserve;
  const std::string level = d.battery_level < 1
                                ? "battery_level " + base::shortest_text(d.battery_level) +
                                      in_fleet_file(plan.request) + " x "
                                : "";
  return level + "--endurance " + base::shortest_text(*d.endurance_s) + ", --reserve " + reserve;
}

// A drone's one flight (no sorties) must land with the reserve in hand: the charge it takes off
// with (battery_level x endurance) less the reserve the sorties keep, in flight time as the
// mission flies it. A drone that runs out mid-survey is not safe by construction: refused, not
// warned (docs/swath-plan.md).
void check_flight_within_charge(const SurveyPlan& plan, const DronePlan& d) {
  if (!d.endurance_s || !d.sorties.empty()) return;
  const double usable_s = *d.endurance_s * d.battery_level * (1 - plan.request.reserve);
  const double flight_s = d.mission.flight_time_s;
  if (flight_s <= usable_s * (1 + 1e-9)) return;
  std::vector<base::Remedy> remedies = battery_remedies(plan.request);
  remedies.push_back(base::Remedy::higher_altitude);
  throw InputError("drone " + d.name + "'s flight takes " + duration_text(flight_s) +
                       ", longer than the " + duration_text(usable_s) +
                       " its battery gives less the " + fixed_text(100 * plan.request.reserve, 0) +
                       " % reserve (" + charge_source(plan, d) + ")",
                   remedies);
}

void check_range(const SurveyPlan& plan, const DronePlan& d, std::vector<std::string>& warnings) {
  // With sorties a drone flies as many batteries as its share needs (check_sortie_charge: each
  // fits).
  if (!plan.request.fleet || plan.request.sorties) return;
  const auto range = plan.request.fleet->drones[static_cast<std::size_t>(d.number - 1)].range_m();
  if (!range || !d.sorties.empty() || d.mission.path_length_m <= *range) return;
  const std::string what = "drone " + d.name + "'s flight (" +
                           std::to_string(std::lround(d.mission.path_length_m)) +
                           " m) is longer than its range (" + std::to_string(std::lround(*range)) +
                           " m" + in_fleet_file(plan.request) + ")";
  if (!plan.request.allow_partial) {
    std::vector<base::Remedy> remedies = battery_remedies(plan.request);
    remedies.push_back(base::Remedy::allow_partial);
    throw InputError(what, remedies);
  }
  warnings.push_back(what);
}

void warn_about_drone(const SurveyPlan& plan, const DronePlan& d,
                      std::vector<std::string>& warnings) {
  if (plan.divided && d.mission.work_length_m < 1.0)
    warnings.push_back("drone " + d.name +
                       " gets no survey work (its share is used up by the flight to the area and "
                       "back); leave it out of the fleet");
  for (const DroneMission* m : flights_of(d))
    if (m->items.size() > kAutopilotItemLimit) {
      warnings.push_back("drone " + d.name + "'s mission has " + std::to_string(m->items.size()) +
                         " items, more than ArduPilot's classic limit of 700 (some autopilots "
                         "hold fewer): divide it among drones or drop --waypoint-spacing");
      break;
    }
  if (!d.endurance_s && d.sorties.empty()) {
    // No endurance given: against a typical one (an 18-hour single-drone plan went unwarned).
    const double typical_s = plan.request.vehicle == Vehicle::multirotor
                                 ? kTypicalMultirotorEndurance_s
                                 : kTypicalFixedWingEndurance_s;
    if (d.mission.flight_time_s > typical_s)
      warnings.push_back(
          "drone " + d.name + "'s flight takes " + duration_text(d.mission.flight_time_s) +
          ", longer than a typical " +
          (plan.request.vehicle == Vehicle::multirotor ? "multirotor's " : "fixed-wing's ") +
          duration_text(typical_s) +
          " on one battery, and no endurance was given; give --endurance (or the fleet's "
          "endurance_s) and --sorties auto, or add drones");
  }
  // Fixed-wing: a U-turn between lines closer than two turn radii (few lines, or split cells).
  if (plan.turn_radius_m > 0) {
    int tight = 0;
    for (std::size_t i = 0; i + 1 < d.mission.lines.size(); ++i)
      tight += geometry::distance(d.mission.lines[i].end, d.mission.lines[i + 1].start) <
               2 * plan.turn_radius_m - 1e-6;
    if (tight > 0)
      warnings.push_back("drone " + d.name + " has " + std::to_string(tight) +
                         " turns between lines closer than twice its turn radius (" +
                         fixed_text(2 * plan.turn_radius_m, 1) +
                         " m): it will overshoot them; fly slower or bank more");
  }
}

// Fences an autopilot cannot store: the inclusion fence (missions() simplifies it to fit where it
// can) and the zones, kept as given (docs/swath-plan.md), above kFenceVertexLimit vertices.
void warn_about_fences(const SurveyPlan& plan, std::vector<std::string>& warnings) {
  if (const std::size_t most = most_vertices(plan.fence); most > kFenceVertexLimit)
    warnings.push_back("the inclusion fence keeps " + std::to_string(most) +
                       " vertices, more than the " + std::to_string(kFenceVertexLimit) +
                       " PX4 stores in one polygon; give a smaller --fence-margin or a simpler "
                       "outline");
  // Zones of more vertices are written simplified outward (missions.cpp, exclusion_fences) where
  // the clearance leaves room; these are the ones where it did not.
  for (std::size_t z = 0; z < plan.exclusion_fences_geo.size(); ++z)
    if (plan.exclusion_fences_geo[z].size() > kFenceVertexLimit) {
      warnings.push_back(no_fly_name(plan, z) + " has " +
                         std::to_string(plan.exclusion_fences_geo[z].size()) +
                         " vertices, more than the " + std::to_string(kFenceVertexLimit) +
                         " PX4 stores in one exclusion fence, and swath could not simplify it "
                         "within half the clearance (" +
                         fixed_text(plan.request.clearance_m / 2, 2) +
                         " m); simplify it (outward) or give a larger --clearance");
      break;
    }
  // ArduPilot keeps every fence polygon and circle in one storage area of a few hundred bytes,
  // and refuses an upload that does not fit (AC_PolyFence_loader::write_fence); PX4 takes 64
  // fence items in all, however they are split into polygons.
  std::vector<std::size_t> points;
  for (const geometry::Ring& ring : plan.fence) points.push_back(ring.size());
  for (const auto& zone : plan.exclusion_fences_geo) points.push_back(zone.size());
  const missions::FenceStorage storage = missions::ardupilot_fence_storage(points, 0);
  const std::string warning =
      plan.request.firmware == Firmware::ardupilot
          ? missions::fence_storage_warning(storage, plan.request.vehicle != Vehicle::multirotor)
          : missions::px4_fence_warning(storage);
  if (!warning.empty()) warnings.push_back(warning);
}

}  // namespace

void measures(SurveyPlan& plan) {
  if (plan.region_angles_deg.empty()) {
    plan.coverage = measure_coverage(measured_area(plan), first_pass_lines(plan),
                                     plan.sweep.angle_deg, plan.imaging.footprint_across_m);
  } else {  // a direction per region (never with a crosshatch pass): every line, its own way
    std::vector<SweepLine> lines;
    for (const DronePlan& d : plan.drones)
      lines.insert(lines.end(), d.mission.lines.begin(), d.mission.lines.end());
    plan.coverage =
        measure_coverage_any_direction(measured_area(plan), lines, plan.imaging.footprint_across_m);
  }
  plan.transit_outside_m = transit_outside_m(plan);
  // The clearance actually kept, over every leg of every flight, home legs included.
  if (!plan.no_fly.empty()) {
    double least = INFINITY;
    for (const DronePlan& d : plan.drones)
      for (const DroneMission* m : flights_of(d))
        least = std::min(least, geometry::least_distance(m->path, plan.no_fly));
    plan.clearance.no_fly_m = least;
  }
}

// The share of the area the photos must see before the plan says otherwise.
constexpr double kPromisedCoverage = 0.999;

void checks(SurveyPlan& plan) {
  const SurveyRequest& r = plan.request;
  if (!(plan.coverage.covered_fraction > 0))
    throw InputError(r.field.source + ": the plan covers none of the area (" +
                     std::to_string(plan.sweep.lines.size()) +
                     " lines); check the altitude, overlaps and turnaround");
  if (plan.division.unflown_path_m > 0 && !r.allow_partial)
    throw InputError("the fleet cannot fly the whole survey: " +
                         fixed_text(plan.division.unflown_path_m, 1) + " m of path and " +
                         fixed_text(plan.coverage.area_m2 - plan.coverage.covered_area_m2, 1) +
                         " m² of area stay unflown",
                     {base::Remedy::add_drones_or_battery, base::Remedy::allow_partial});
  std::vector<std::string>& warnings = plan.warnings;
  // Below the coverage swath promises (docs/swath-plan.md: 99.9 %): ground thinner than the lines
  // can reach inside it (a strip round a large hole, a star's points), said rather than left to the
  // summary (a 2,000-point star was covered 95 % with no word). Not where the fleet leaves path
  // unflown (--allow-partial): that is said above.
  // With holes or zones, their clearance keeps the lines off ground too (a small field inside
  // a wide --clearance: 2 % covered), which the sentence says first.
  if (plan.coverage.covered_fraction < kPromisedCoverage && plan.division.unflown_path_m == 0)
    warnings.push_back(
        "the photos cover " + fixed_text(100 * plan.coverage.covered_fraction, 2) +
        " % of the area (" + fixed_text(plan.coverage.area_m2 - plan.coverage.covered_area_m2, 1) +
        " m² unseen), less than 99.9 %: " +
        (plan.no_fly.empty() || !(r.clearance_m > 0)
             ? std::string()
             : "the lines keep --clearance (" + fixed_text(r.clearance_m, 1) +
                   " m) from the holes and no-fly zones, or ") +
        "parts of it are too narrow or too pointed for the lines to reach (coverage.png with "
        "--render shows where)");
  for (const DronePlan& d : plan.drones) {
    check_sortie_charge(plan, d);
    check_flight_within_charge(plan, d);
  }
  if (plan.division.recut_within_limits)
    warnings.push_back(
        "shares in proportion to the capabilities would fly a drone beyond its range or charge; "
        "the work was divided as --balance makespan divides it");
  for (const DronePlan& d : plan.drones) check_range(plan, d, warnings);
  if (const auto& interval = r.camera.min_trigger_interval_s) {
    const double seconds = plan.imaging.trigger_distance_m / plan.speed_m_s;
    if (seconds < *interval)
      warnings.push_back("at " + fixed_text(plan.speed_m_s, 1) +
                         " m/s the camera must trigger every " + fixed_text(seconds, 1) +
                         " s, faster than its " + fixed_text(*interval, 1) +
                         " s minimum; fly at most " +
                         fixed_text(plan.imaging.trigger_distance_m / *interval, 1) + " m/s");
  }
  if (r.pattern && plan.imaging.altitude_m > *plan.imaging.h_max_m * (1 + 1e-12))
    warnings.push_back("the altitude " + fixed_text(plan.imaging.altitude_m, 1) +
                       " m is above h_max " + fixed_text(*plan.imaging.h_max_m, 1) +
                       " m: the pattern spans fewer pixels than required");
  if (plan.imaging.altitude_m > kLegalAltitude_m)
    warnings.push_back("the altitude " + fixed_text(plan.imaging.altitude_m, 1) +
                       " m is above 120 m, the common legal limit for drones (EU open category, "
                       "US Part 107): fly it only with a permit that allows it");
  for (const DronePlan& d : plan.drones) warn_about_drone(plan, d, warnings);
  warn_about_fences(plan, warnings);
  if (plan.clearance.no_fly_m && *plan.clearance.no_fly_m < r.clearance_m - 0.01)
    warnings.push_back("the flight comes within " + fixed_text(*plan.clearance.no_fly_m, 1) +
                       " m of a no-fly zone, less than the " + fixed_text(r.clearance_m, 1) +
                       " m clearance (a home or line end inside the clearance band)");
}

}  // namespace swath::planning::steps
