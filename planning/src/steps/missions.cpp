// Step 6 of plan_survey(): each drone's mission and photos, and the fence (survey_steps.hpp).
#include <algorithm>

#include "swath/geometry/offset.hpp"
#include "swath/planning/survey_steps.hpp"

namespace swath::planning::steps {

MissionSettings mission_settings(const SurveyPlan& plan, const DronePlan& drone) {
  MissionSettings s;
  s.altitude_m = plan.imaging.altitude_m;
  s.speed_m_s = drone.speed_m_s;
  s.trigger_distance_m = plan.imaging.trigger_distance_m;
  s.waypoint_spacing_m = plan.request.waypoint_spacing_m;
  s.vehicle = plan.request.vehicle;
  s.triggering = plan.request.triggering;
  s.land = plan.request.land;
  s.climb_speed_m_s = drone.climb_speed_m_s;
  s.descent_speed_m_s = drone.descent_speed_m_s;
  // Stop at line ends beside a no-fly zone (within the clearance and the corner allowance): a
  // turn flown through there would swing towards the zone.
  if (!plan.no_fly.empty() && plan.request.vehicle == Vehicle::multirotor) {
    const double near_m = plan.request.clearance_m + kCornerAllowance_m;
    s.stop_at = [&plan, near_m](geometry::Point2 p) {
      return geometry::least_distance({p}, plan.no_fly) < near_m;
    };
  }
  return s;
}

namespace {

// The inclusion fence: `outlines` grown by `margin_m`. A long outline (over 500 vertices) is
// simplified within 5 % of the margin (at most 5 m) first: its wiggles no longer each give the
// fence vertices (a 10,000-vertex field's took seconds and gave 1,869), and the fence still holds
// everything within the margin, reaching up to the tolerance further. A fence of more vertices
// than an autopilot stores in one polygon (kFenceVertexLimit) is simplified within 10, 20, 40 and
// 80 % of the margin in turn until it fits: still holding everything within the margin, reaching
// at most 2 (margin + tolerance) + tolerance beyond the outline. Other outlines are grown exactly,
// the fence at the margin.
std::vector<geometry::Ring> fence_for(const std::vector<geometry::Ring>& outlines,
                                      double margin_m) {
  std::size_t vertices = 0;
  for (const geometry::Ring& r : outlines) vertices += r.size();
  std::vector<geometry::Ring> fence =
      vertices > 500 ? geometry::grow_simplified(outlines, margin_m, std::min(5.0, 0.05 * margin_m))
                     : geometry::grow(outlines, margin_m);
  for (const double share : {0.1, 0.2, 0.4, 0.8}) {
    if (most_vertices(fence) <= kFenceVertexLimit) break;
    fence = geometry::grow_simplified(outlines, margin_m, share * margin_m);
  }
  return fence;
}

// The exclusion fence of each no-fly zone as written: the zone as given, or where it has more
// vertices than an autopilot stores in one polygon, the zone simplified outward (grow_simplified
// by 0 within c/48, c/24, c/12 and c/6 in turn, c the clearance, until it fits): it holds the whole
// zone and reaches at most half the clearance beyond it, so the flight, kept the clearance from the
// zone, never enters it. Where none fits (no clearance, a zone too intricate) the zone as given,
// and a warning (warn_about_fences).
std::vector<std::vector<geometry::GeoPoint>> exclusion_fences(const SurveyPlan& plan) {
  std::vector<std::vector<geometry::GeoPoint>> fences = plan.no_fly_geo;
  const double c = plan.request.clearance_m;
  for (std::size_t z = 0; z < fences.size() && z < plan.no_fly.size(); ++z) {
    if (fences[z].size() <= kFenceVertexLimit || !(c > 0)) continue;
    for (const double share : {1.0 / 48, 1.0 / 24, 1.0 / 12, 1.0 / 6}) {
      const std::vector<geometry::Ring> grown =
          geometry::grow_simplified({plan.no_fly[z]}, 0.0, share * c);
      if (grown.size() != 1 || grown.front().size() > kFenceVertexLimit) continue;
      fences[z].clear();
      for (const geometry::Point2& p : grown.front())
        fences[z].push_back(plan.request.field.frame->to_geo(p));
      break;
    }
  }
  return fences;
}

}  // namespace

std::size_t most_vertices(const std::vector<geometry::Ring>& rings) {
  std::size_t most = 0;
  for (const geometry::Ring& r : rings) most = std::max(most, r.size());
  return most;
}

void missions(SurveyPlan& plan) {
  const Routes routes(plan);
  const InsideTest inside = routes.inside_test();
  for (DronePlan& d : plan.drones) {
    d.mission = mission_for_path(d.number, d.home, d.work.path, mission_settings(plan, d),
                                 routes.leg(), inside);
    d.photos = planned_photos(d.mission, plan.imaging.trigger_distance_m);
  }
  // The inclusion fence: the area grown by the margin (docs/swath-plan.md).
  plan.fence_margin_m = plan.request.fence_margin_m.value_or(
      plan.turnaround_m + plan.imaging.footprint_across_m / 2 + 10);
  std::vector<geometry::Ring> outlines{plan.area.outer};
  outlines.insert(outlines.end(), plan.extra_pieces.begin(), plan.extra_pieces.end());
  plan.fence = fence_for(outlines, plan.fence_margin_m);
  plan.exclusion_fences_geo = exclusion_fences(plan);
}

}  // namespace swath::planning::steps
