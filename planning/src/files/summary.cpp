// summary.json: every figure of the plan (docs/formats.md and docs/swath-plan.md).
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "common.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/geometry/min_height.hpp"

namespace swath::planning {
namespace {

using base::round_to;
using nlohmann::ordered_json;

const char* to_string(LinePlacement p) {
  return p == LinePlacement::centered ? "centered" : "paper";
}
const char* to_string(AngleSearch a) {
  return a == AngleSearch::exact ? "exact" : a == AngleSearch::scan ? "scan" : "fixed";
}
const char* to_string(TriggerMode m) {
  return m == TriggerMode::distance ? "distance" : m == TriggerMode::time ? "time" : "hover";
}

ordered_json optional_number(const std::optional<double>& v, int decimals) {
  return v ? ordered_json(round_to(*v, decimals)) : ordered_json();
}

ordered_json lat_lon(const geometry::GeoPoint& g) {
  const geometry::GeoPoint r = files::rounded(g);
  return {{"lat_deg", r.lat_deg}, {"lon_deg", r.lon_deg}};
}

ordered_json sortie_json(const SurveyPlan& plan, const DronePlan& d, const Sortie& s) {
  ordered_json j = {{"sortie", s.number},
                    {"file", d.file_stem + "-" + std::to_string(s.number)},
                    {"resume", lat_lon(plan.request.field.frame->to_geo(s.resume))},
                    {"path_length_m", round_to(s.mission.path_length_m, 3)},
                    {"work_length_m", round_to(s.mission.work_length_m, 3)},
                    {"flight_time_s", round_to(s.mission.flight_time_s, 2)},
                    {"photos", s.photos.size()},
                    {"items", s.mission.items.size()}};
  // Several drones' sorties are staggered (deconflict); one drone's fly one after another.
  if (plan.drones.size() > 1) j["launch_offset_s"] = round_to(s.launch_offset_s, 1);
  return j;
}

ordered_json drone_json(const SurveyPlan& plan, const DronePlan& dp) {
  const DroneMission& m = dp.mission;
  ordered_json d = {{"drone", dp.number},
                    {"name", dp.name},
                    {"file", dp.file_stem},
                    {"home", lat_lon(dp.home_geo)},
                    {"share", plan.divided ? round_to(dp.work.share, 6) : 1.0},
                    {"speed_m_s", round_to(dp.speed_m_s, 3)},
                    {"altitude_m", round_to(plan.imaging.altitude_m + dp.layer_m, 3)},
                    {"layer_m", round_to(dp.layer_m, 3)},
                    {"launch_offset_s", round_to(dp.launch_offset_s, 1)},
                    {"path_length_m", round_to(m.path_length_m, 3)},
                    {"work_length_m", round_to(m.work_length_m, 3)},
                    {"transit_length_m", round_to(m.transit_length_m, 3)},
                    {"flight_time_s", round_to(m.flight_time_s, 2)},
                    {"flight_time", duration_text(m.flight_time_s)},
                    {"endurance_s", optional_number(dp.endurance_s, 1)},
                    {"lines", m.lines.size()},
                    {"turns", m.lines.empty() ? 0 : m.lines.size() - 1},
                    {"waypoints", m.waypoint_count},
                    {"items", m.items.size()},
                    {"photos", dp.photos.size()},
                    {"region_area_m2", nullptr},
                    {"home_cost_m", nullptr},
                    {"budget_m", nullptr}};
  if (plan.divided) {
    const DroneWork& w = dp.work;
    if (!w.region.empty()) {
      double a = 0;
      for (const geometry::Ring& piece : w.region) a += geometry::signed_area(piece);
      d["region_area_m2"] = round_to(a, 3);
    }
    d["home_cost_m"] = round_to(w.home_cost_m, 3);
    d["budget_m"] = optional_number(w.budget_m, 3);
  }
  ordered_json sorties = ordered_json::array();
  for (const Sortie& s : dp.sorties) sorties.push_back(sortie_json(plan, dp, s));
  d["sorties"] = sorties;
  return d;
}

// How the flights are flown: vehicle, camera triggering, clearance kept, fence, photos.
ordered_json flight_json(const SurveyPlan& plan) {
  const SurveyRequest& r = plan.request;
  std::size_t photos = 0;
  for (const DronePlan& d : plan.drones) photos += d.photos.size();
  return {{"vehicle", r.vehicle == Vehicle::multirotor ? "multirotor" : "fixedwing"},
          {"turn_radius_m", round_to(plan.turn_radius_m, 3)},
          {"end", r.land ? "land" : "return_to_launch"},
          {"trigger", to_string(r.triggering.mode)},
          {"photos_in_turns", r.triggering.photos_in_turns},
          {"gimbal_pitch_deg", round_to(r.triggering.gimbal_pitch_deg, 3)},
          {"photos", photos},
          {"clearance_m", round_to(r.clearance_m, 3)},
          {"boundary_clearance_m", round_to(r.boundary_clearance_m, 3)},
          {"outside_margin_m", round_to(r.outside_margin_m, 3)},
          {"min_no_fly_distance_m", optional_number(plan.clearance.no_fly_m, 3)},
          {"no_fly_zones", plan.no_fly.size()},
          {"fence_margin_m", round_to(plan.fence_margin_m, 3)}};
}

// How the shares were cut: as asked, or by makespan where shares in proportion to the
// capabilities would have flown a drone beyond its range or charge (the recut's warning).
const char* division_balance(const SurveyRequest& r, const DivisionResult& dv) {
  return r.balance == Balance::makespan || dv.recut_within_limits ? "makespan" : "capability";
}

}  // namespace

std::string summary_json(const SurveyPlan& plan, const std::vector<std::string>& files) {
  const geometry::AreaFacts& f = plan.facts;
  const SurveyRequest& r = plan.request;
  ordered_json j;
  j["swath_version"] = "0.1.0";
  j["field"] = r.field.source;
  j["area"] = {{"type", std::string(geometry::to_string(f.classification.type))},
               {"vertices", f.vertex_count},
               {"holes", r.field.polygon.holes.size()},
               {"area_m2", optional_number(f.area_m2, 3)},
               {"regularity",
                f.regularity ? ordered_json(round_to(f.regularity->overall, 6)) : ordered_json()},
               {"concave_mode", r.concave == ConcaveMode::split  ? "split"
                                : r.concave == ConcaveMode::hull ? "hull"
                                                                 : "reject"},
               {"handling", to_string(plan.handling)},
               {"no_fly_zones", r.exclusions.size()},
               {"repaired_pieces", plan.extra_pieces.empty() && !r.repair
                                       ? ordered_json()
                                       : ordered_json(1 + plan.extra_pieces.size())},
               {"cells", plan.cells.size()},
               {"cells_from", !plan.split_method                       ? ordered_json()
                              : *plan.split_method == SplitCells::runs ? ordered_json("lanes")
                                                                       : ordered_json("polygon")},
               {"flown_area_m2", round_to(geometry::area(plan.flown_area), 3)}};
  j["sweep"] = {
      {"bearing_deg", round_to(geometry::line_bearing_deg(plan.sweep.angle_deg), 6)},
      {"angle_local_deg", round_to(plan.sweep.angle_deg, 6)},
      {"angle_search", plan.handling == Handling::split && r.angle_search != AngleSearch::fixed
                           ? "shortest-path"
                           : to_string(r.angle_search)},
      {"directions_evaluated", plan.direction_candidates},
      {"height_m", round_to(plan.sweep.height_m, 4)},
      {"line_placement", to_string(r.placement)},
      {"lines", plan.sweep.lines.size()},
      {"turnaround_m", round_to(plan.turnaround_m, 3)},
      {"crosshatch", r.crosshatch}};
  if (!plan.region_angles_deg.empty()) {  // --directions per-region won: each region's direction
    ordered_json regions = ordered_json::array();
    for (std::size_t k = 0; k < plan.region_angles_deg.size(); ++k)
      regions.push_back(
          {{"bearing_deg", round_to(geometry::line_bearing_deg(plan.region_angles_deg[k]), 6)},
           {"angle_local_deg", round_to(plan.region_angles_deg[k], 6)},
           {"area_m2", round_to(std::abs(geometry::signed_area(plan.regions[k])), 3)}});
    j["sweep"]["regions"] = regions;
  }
  const Imaging& im = plan.imaging;
  j["camera"] = {
      {"name", r.camera.name},
      {"mode", std::holds_alternative<PhotogrammetryMode>(r.mode) ? "photogrammetry" : "detection"},
      {"orientation", r.orientation == ImageOrientation::landscape ? "landscape" : "portrait"},
      {"altitude_m", round_to(im.altitude_m, 4)},
      {"gsd_cm_per_px", round_to(im.gsd_m * 100, 5)},
      {"footprint_across_m", round_to(im.footprint_across_m, 4)},
      {"footprint_along_m", round_to(im.footprint_along_m, 4)},
      {"line_spacing_m", round_to(im.line_spacing_m, 4)},
      {"trigger_distance_m", round_to(im.trigger_distance_m, 4)},
      {"h_min_m", optional_number(im.h_min_m, 4)},
      {"h_max_m", optional_number(im.h_max_m, 4)}};
  if (plan.terrain) {
    const TerrainFacts& t = *plan.terrain;
    j["terrain"] = {{"dem", t.source},
                    {"altitude_frame", frame_name(t.frame)},
                    {"height_above_ground_m", round_to(t.height_above_ground_m, 4)},
                    {"tolerance_m", round_to(t.tolerance_m, 4)},
                    {"ground_min_m", round_to(t.ground_min_m, 3)},
                    {"ground_max_m", round_to(t.ground_max_m, 3)},
                    {"agl_min_m", round_to(t.agl_min_m, 3)},
                    {"agl_max_m", round_to(t.agl_max_m, 3)},
                    {"gsd_min_cm_per_px", round_to(t.gsd_min_m * 100, 5)},
                    {"gsd_max_cm_per_px", round_to(t.gsd_max_m * 100, 5)},
                    {"waypoints_added", t.waypoints_added},
                    {"climb_max_m_s", round_to(t.climb_max_m_s, 3)},
                    {"descent_max_m_s", round_to(-t.descent_max_m_s, 3)},
                    {"legs_too_steep", t.legs_too_steep}};
  }
  ordered_json drones = ordered_json::array();
  for (const DronePlan& dp : plan.drones) drones.push_back(drone_json(plan, dp));
  j["drones"] = drones;
  if (plan.divided) {
    double longest = 0, shortest = std::numeric_limits<double>::infinity();
    for (const DronePlan& dp : plan.drones) {
      longest = std::max(longest, dp.mission.flight_time_s);
      if (!dp.mission.lines.empty()) shortest = std::min(shortest, dp.mission.flight_time_s);
    }
    const DivisionResult& dv = plan.division;
    j["division"] = {
        {"mode", r.division == DivisionMode::path ? "path" : "region"},
        {"balance", division_balance(r, dv)},
        {"makespan_s", round_to(longest, 2)},
        {"max_over_min_flight_time", shortest > 0 && std::isfinite(shortest)
                                         ? ordered_json(round_to(longest / shortest, 4))
                                         : ordered_json()},
        {"estimated_makespan_s", round_to(dv.makespan_s, 2)},
        {"proportional_estimated_makespan_s", round_to(dv.proportional_makespan_s, 2)},
        {"shorter_than_proportional_percent",
         ordered_json(dv.proportional_makespan_s > 0
                          ? round_to(100 * (1 - dv.makespan_s / dv.proportional_makespan_s), 3)
                          : 0.0)},
        {"unflown_path_m", round_to(dv.unflown_path_m, 3)}};
    // Where the balance asked for is not the one the shares were cut by (docs/formats.md).
    if (dv.recut_within_limits) j["division"]["balance_asked"] = "capability";
  }
  j["home"] = {{"lat_deg", round_to(plan.home.lat_deg, 9)},
               {"lon_deg", round_to(plan.home.lon_deg, 9)}};
  const CoverageMeasure& c = plan.coverage;
  j["coverage"] = {
      {"covered_fraction", round_to(c.covered_fraction, 6)},
      {"outside_fraction", round_to(c.outside_fraction, 6)},
      {"uncovered_area_m2", round_to(c.area_m2 - c.covered_area_m2, 3)},
      {"swath_area_m2", round_to(c.swath_area_m2, 3)},
      {"line_length_m", round_to(c.line_length_m, 3)},
      {"line_length_outside_m", round_to(c.line_length_outside_m, 3)},
      {"transit_outside_m", round_to(plan.transit_outside_m, 3)},
      {"line_outside_fraction",
       round_to(c.line_length_m > 0 ? c.line_length_outside_m / c.line_length_m : 0.0, 6)}};
  j["flight"] = flight_json(plan);
  j["warnings"] = plan.warnings;
  if (!files.empty()) j["files"] = files;
  return base::json_text(j, 2) + "\n";
}

}  // namespace swath::planning
