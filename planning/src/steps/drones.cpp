// Step 5 of plan_survey(): who flies what (survey_steps.hpp).
#include <cmath>
#include <map>

#include "swath/base/input_error.hpp"
#include "swath/planning/split.hpp"
#include "swath/planning/survey_steps.hpp"

namespace swath::planning::steps {
namespace {

using base::InputError;
using geometry::Point2;

// A drone's name as a file name: [A-Za-z0-9._-] kept, spaces as '-', anything else dropped
// (DESIGN.md §14 "Homes and names"); "drone-<n>" when nothing usable is left.
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
    d.endurance_s = f.endurance_s ? f.endurance_s : r.endurance_s;
    plan.drones.push_back(std::move(d));
  }
}

std::vector<DroneResource> resources_of(const SurveyPlan& plan) {
  std::vector<DroneResource> out;
  for (std::size_t i = 0; i < plan.drones.size(); ++i) {
    const vehicle::Drone& f = plan.request.fleet->drones[i];
    out.push_back({plan.drones[i].name, plan.drones[i].home, plan.drones[i].speed_m_s, f.range_m(),
                   f.capability.value_or(1.0)});
  }
  return out;
}

// Region division (paper 001 Algorithm 4): bands swept one by one.
DivisionResult divide_by_region(const SurveyPlan& plan, const Routes& routes,
                                const std::vector<DroneResource>& resources) {
  const SurveyRequest& r = plan.request;
  const double angle = plan.sweep.angle_deg;
  const bool cells = plan.handling == Handling::split || plan.planning_rings.size() > 1;
  const geometry::VisibilityRouter straight(plan.planning_rings, 0);
  const BandSweep sweep_band = [&](const std::vector<geometry::Ring>& band,
                                   const DroneResource& drone, bool estimate) -> SurveyPath {
    if (!cells) {  // a convex area (or the hull): each band piece with the strip rule
      std::vector<SweepLine> lines;
      for (const geometry::Ring& piece : band) {
        SweepSettings s;
        s.angle_deg = angle;
        s.line_spacing_m = plan.imaging.line_spacing_m;
        s.footprint_width_m = plan.imaging.footprint_across_m;
        s.placement = r.placement;
        s.turnaround_m = plan.turnaround_m;
        const auto ordered = order_lines(plan_sweep(geometry::Polygon{piece, {}}, s),
                                         StartCorner::nearest_home, drone.home);
        lines.insert(lines.end(), ordered.begin(), ordered.end());
      }
      return survey_path(lines, r.waypoint_spacing_m);
    }
    SplitSettings s;
    s.line_spacing_m = plan.imaging.line_spacing_m;
    s.footprint_width_m = plan.imaging.footprint_across_m;
    s.placement = r.placement;
    s.turnaround_m = plan.turnaround_m;
    s.scan_step_deg = r.split_scan_step_deg;
    s.fixed_angle_deg = angle;
    const SplitPlan sp =
        plan_pieces(band, angle, drone.home, s, estimate ? straight : routes.inside);
    return survey_path(sp.lines, r.waypoint_spacing_m, estimate ? LegRoute{} : routes.leg());
  };
  return divide_region(plan.planning_rings, angle, resources, r.balance, sweep_band);
}

}  // namespace

void drones(SurveyPlan& plan) {
  name_drones(plan);
  const SurveyRequest& r = plan.request;
  const Routes routes(plan);
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
  const std::vector<DroneResource> resources = resources_of(plan);
  plan.division = r.division == DivisionMode::path ? divide_path(whole, resources, r.balance)
                                                   : divide_by_region(plan, routes, resources);
  for (std::size_t i = 0; i < plan.drones.size(); ++i)
    plan.drones[i].work = plan.division.drones[i];
}

}  // namespace swath::planning::steps
