// Step 5 of plan_survey(): who flies what (survey_steps.hpp).
#include <algorithm>
#include <cmath>
#include <map>

#include "swath/base/input_error.hpp"
#include "swath/geometry/decomposition.hpp"
#include "swath/planning/split.hpp"
#include "swath/planning/survey_steps.hpp"

namespace swath::planning::steps {
namespace {

using base::InputError;
using geometry::Point2;

// A drone's name as a file name: [A-Za-z0-9._-] kept, spaces as '-', anything else dropped
// (docs/swath-plan.md); "drone-<n>" when nothing usable is left.
std::string file_stem_of(const std::string& name, int number) {
  std::string stem;
  for (const char c : name) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '.' || c == '_' || c == '-';
    if (keep)
      stem += c;
    else if (c == ' ')
      stem += '-';
  }
  while (!stem.empty() && stem.front() == '.') stem.erase(stem.begin());  // no hidden files
  return stem.empty() ? "drone-" + std::to_string(number) : stem;
}

// One DronePlan per fleet drone (or the one drone), with its own home, speed and file name.
void name_drones(SurveyPlan& plan) {
  const SurveyRequest& r = plan.request;
  const geometry::LocalFrame& frame = *r.field.frame;
  if (!r.fleet) {
    DronePlan d;
    d.name = d.file_stem = "drone-1";
    d.home = plan.home_local;
    d.home_geo = plan.home;
    d.speed_m_s = plan.speed_m_s;
    d.endurance_s = r.endurance_s;
    plan.drones.push_back(std::move(d));
    return;
  }
  std::map<std::string, std::string> stems;  // file stem -> the name it came from
  for (std::size_t i = 0; i < r.fleet->drones.size(); ++i) {
    const vehicle::Drone& f = r.fleet->drones[i];
    DronePlan d;
    d.number = static_cast<int>(i + 1);
    d.name = f.name.empty() ? "drone-" + std::to_string(d.number) : f.name;
    d.file_stem = file_stem_of(d.name, d.number);
    const auto [it, fresh] = stems.emplace(d.file_stem, d.name);
    if (!fresh)
      throw InputError("the drones '" + it->second + "' and '" + d.name +
                       "' would both write their missions as " + d.file_stem +
                       ".plan; give them names that differ in letters or digits");
    // Own home, else the fleet's, else (--drones without --home: NaN) the plan's.
    if (f.home) {
      d.home_geo = *f.home;
    } else if (std::isfinite(r.fleet->home.lat_deg)) {
      d.home_geo = r.fleet->home;
    } else {
      d.home_geo = plan.home;
    }
    d.home = f.home || std::isfinite(r.fleet->home.lat_deg) ? frame.to_local(d.home_geo)
                                                            : plan.home_local;
    d.speed_m_s = f.speed_m_s.value_or(plan.speed_m_s);
    d.climb_speed_m_s = f.climb_speed_m_s;
    d.descent_speed_m_s = f.descent_speed_m_s;
    d.accel_m_s2 = f.accel_m_s2;
    d.endurance_s = f.endurance_s ? f.endurance_s : r.endurance_s;
    d.battery_level = f.battery_level.value_or(1.0);
    d.charge_from_fleet = f.battery_level && f.endurance_s;
    plan.drones.push_back(std::move(d));
  }
}

// The longest flight the division may give a drone: its charge less the reserve (what checks()
// lets it fly), less room for the climb to and descent from the highest layer deconflict() may
// give it afterwards (the metres of its range count neither the climbs nor the stops: 435 s on a
// 360 s charge passed within 1800 m).
std::optional<double> flight_limit_s(const SurveyPlan& plan, const DronePlan& d) {
  // --endurance or the fleet's endurance_s; with sorties a share flies as many batteries as it
  // needs.
  if (!d.endurance_s || plan.request.sorties) return std::nullopt;
  return *d.endurance_s * d.battery_level * (1 - plan.request.reserve) - layer_room_s(plan, d);
}

std::vector<DroneResource> resources_of(const SurveyPlan& plan) {
  std::vector<DroneResource> out;
  for (std::size_t i = 0; i < plan.drones.size(); ++i) {
    const vehicle::Drone& f = plan.request.fleet->drones[i];
    // With sorties a drone flies as many batteries as its share needs: no range limits it, and
    // the shares stay in proportion to the ranges (a fleet short of one battery each was refused
    // "add drones or battery" under --sorties auto).
    const std::optional<double> range_m = f.range_m();
    if (plan.request.sorties && range_m) {
      out.push_back({plan.drones[i].name, plan.drones[i].home, plan.drones[i].speed_m_s,
                     std::nullopt, *range_m, std::nullopt});
      continue;
    }
    out.push_back({plan.drones[i].name, plan.drones[i].home, plan.drones[i].speed_m_s, range_m,
                   f.capability.value_or(1.0), flight_limit_s(plan, plan.drones[i])});
  }
  return out;
}

// The flight a drone's mission will make of a survey path (the missions step builds the same).
FlightMeasure flight_measure(const SurveyPlan& plan, const Routes& routes,
                             std::vector<MissionSettings>& settings) {
  settings.clear();
  for (const DronePlan& d : plan.drones) settings.push_back(mission_settings(plan, d));
  return [&plan, &routes, &settings](std::size_t i, const SurveyPath& part) -> FlightCost {
    if (part.points.empty()) return {};
    const DronePlan& d = plan.drones[i];
    const DroneMission m =
        mission_for_path(d.number, d.home, part, settings[i], routes.leg(), routes.inside_test());
    return {m.flight_time_s, m.path_length_m};
  };
}

// Region division (paper 001 Algorithm 4 on the plan's own lanes, docs/swath-plan.md): the lanes
// cut into bands in proportion to the capabilities, or balanced on the drones' measured flights
// (--balance makespan), a band's last lane cut along its length where the shares need it. Every
// lane is flown, so the side overlap holds across the bands' seams (a band swept on its own with
// the strip rule needs fewer lanes, but its edge lanes' footprints only touch the next band's:
// 6 lanes on the meadow with 3 drones where the plan has 11). A convex area's
// share is flown as one zigzag; a split area's as the plan's runs (or cells), each restricted to
// the share, in the order plan_split would fly them.
DivisionResult divide_by_lanes(const SurveyPlan& plan, const Routes& routes,
                               const std::vector<DroneResource>& resources,
                               std::optional<double> spacing, const FlightMeasure& measure) {
  const double angle = plan.sweep.angle_deg;
  const bool cells = plan.handling == Handling::split || plan.planning_rings.size() > 1;
  const std::vector<SweepLine>& lanes = plan.sweep.lines;
  const bool by_cell = cells && plan.sweep_line_cell.size() == lanes.size();
  RunOrder run_order(routes.inside);
  const LaneSweep sweep = [&](std::size_t i, const std::vector<LanePiece>& pieces) -> SurveyPath {
    const Point2 home = plan.drones[i].home;
    if (!cells) {
      // The zigzag whose whole path (home legs and the turns) is shortest: a piece of a lane at
      // either end of the share can make the home legs alone pick a long turn to it.
      Sweep s;
      s.angle_deg = angle;
      for (const LanePiece& p : pieces) s.lines.push_back(p.line);
      std::vector<SweepLine> best;
      double best_m = INFINITY;
      for (const bool top_first : {false, true})
        for (const bool reverse_first : {false, true}) {
          std::vector<SweepLine> z = zigzag(s, top_first, reverse_first);
          double length_m =
              geometry::distance(home, z.front().start) + geometry::distance(z.back().end, home);
          for (std::size_t k = 0; k + 1 < z.size(); ++k)
            length_m += geometry::distance(z[k].end, z[k + 1].start);
          if (length_m < best_m - 1e-9) {
            best_m = length_m;
            best = std::move(z);
          }
        }
      return survey_path(best, spacing);
    }
    // Each run (a lane alone where the cells are unknown) keeps the pieces it holds.
    std::map<std::size_t, std::size_t> run_of;  // cell -> index in runs
    std::vector<Sweep> runs;
    std::vector<geometry::Ring> outlines;
    for (const LanePiece& p : pieces) {
      const std::size_t cell = by_cell ? plan.sweep_line_cell[p.lane] : p.lane;
      const auto [it, fresh] = run_of.emplace(cell, runs.size());
      if (fresh) {
        runs.push_back({angle, 0.0, {}});
        outlines.push_back(by_cell && cell < plan.cells.size() ? plan.cells[cell]
                                                               : geometry::Ring{});
      }
      runs[it->second].lines.push_back(p.line);
    }
    // Pieces come in flight order (a run may have been flown top first): bottom to top.
    for (Sweep& run : runs)
      std::sort(run.lines.begin(), run.lines.end(),
                [angle](const SweepLine& u, const SweepLine& v) {
                  return rotate(u.start, -angle).y < rotate(v.start, -angle).y;
                });
    const SplitPlan sp = run_order(std::move(outlines), std::move(runs), angle, home);
    return survey_path(sp.lines, spacing, routes.leg());
  };
  const Balance balance = plan.request.balance;
  // The regions tile the area to cover (the field minus the no-fly zones, with --repair's further
  // pieces), not the rings the lines keep their clearance in: their areas add up to the field's.
  std::vector<geometry::Ring> share_area = geometry::rings_of(plan.area);
  share_area.insert(share_area.end(), plan.extra_pieces.begin(), plan.extra_pieces.end());
  return divide_lanes(plan.planning_rings, angle, lanes, resources, sweep, measure,
                      by_cell ? plan.sweep_line_cell : std::vector<std::size_t>{}, share_area,
                      balance);
}

}  // namespace

void drones(SurveyPlan& plan) {
  name_drones(plan);
  const SurveyRequest& r = plan.request;
  const Routes& routes = routes_of(plan);
  // Hover photos are taken point by point: intermediate waypoints would only repeat them.
  const std::optional<double> spacing =
      r.triggering.mode == TriggerMode::hover ? std::nullopt : r.waypoint_spacing_m;
  const SurveyPath whole = survey_path(plan.survey_lines, spacing, routes.leg());
  if (!r.fleet) {
    plan.drones.front().work.path = whole;
    plan.drones.front().work.share = 1.0;
    return;
  }
  plan.divided = true;
  if (r.crosshatch && r.division == DivisionMode::region)
    throw InputError(
        "--crosshatch cannot be divided by region (the bands are cut across the first pass's "
        "lanes only and would drop the second pass); use --division path");
  const std::vector<DroneResource> resources = resources_of(plan);
  std::vector<MissionSettings> settings;
  const FlightMeasure measure = flight_measure(plan, routes, settings);
  if (r.division == DivisionMode::path)
    plan.division =
        divide_path(whole, resources, r.balance,
                    r.balance == Balance::makespan ? measure : FlightMeasure{}, measure);
  else
    plan.division = divide_by_lanes(plan, routes, resources, spacing, measure);
  // A cut in a line's turnaround beyond the area leaves a drone a stub of it outside the area.
  const std::vector<geometry::Ring> lined = lined_rings(plan);
  for (DroneWork& w : plan.division.drones) transit_stubs_outside(w.path, lined);
  for (std::size_t i = 0; i < plan.drones.size(); ++i)
    plan.drones[i].work = plan.division.drones[i];
}

}  // namespace swath::planning::steps
