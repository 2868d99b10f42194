// Step 6 of plan_survey(): each drone's mission and photos, and the fence (survey_steps.hpp).
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "leg_within.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/geometry/autopilot_track.hpp"
#include "swath/geometry/offset.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/planning/survey_files.hpp"
#include "swath/planning/survey_steps.hpp"

namespace swath::planning::steps {

namespace detail {
namespace {

// The clearance below which a leg is measured rather than placed (clearly_inside): far above the
// rounding of any coordinate (local metres), so that no predicate, exact or not, can see such a
// leg touch the ring.
constexpr double kLegClearance_m = 1e-3;

// Whether the closed segment a-b lies in the open interior of `ring` (even-odd rule) at least
// kLegClearance_m from every edge: both ends strictly inside (exact predicate) and no edge sharing
// a point with the segment (exact) or nearer than the clearance. The inside/outside parity cannot
// change along a segment that meets no edge, so every point of it is inside.
bool clearly_inside(geometry::Point2 a, geometry::Point2 b, const geometry::Ring& ring) {
  if (geometry::locate_point(a, ring) != geometry::Containment::inside ||
      geometry::locate_point(b, ring) != geometry::Containment::inside)
    return false;
  constexpr double c_m = kLegClearance_m;
  const double x0 = std::min(a.x, b.x) - c_m, x1 = std::max(a.x, b.x) + c_m;
  const double y0 = std::min(a.y, b.y) - c_m, y1 = std::max(a.y, b.y) + c_m;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const geometry::Point2 c = ring[i], d = ring[(i + 1) % ring.size()];
    // An edge whose box misses the leg's box widened by the clearance is farther than it.
    if (std::max(c.x, d.x) < x0 || std::min(c.x, d.x) > x1 || std::max(c.y, d.y) < y0 ||
        std::min(c.y, d.y) > y1)
      continue;
    if (geometry::segments_intersect(a, b, c, d)) return false;
    // Two segments that do not meet are nearest at an end of one of them.
    const double nearest_m =
        std::min({geometry::distance_to_segment(a, c, d), geometry::distance_to_segment(b, c, d),
                  geometry::distance_to_segment(c, a, b), geometry::distance_to_segment(d, a, b)});
    if (nearest_m < c_m) return false;
  }
  return true;
}

}  // namespace

bool leg_within(geometry::Point2 a, geometry::Point2 b, const std::vector<geometry::Ring>& rings) {
  const double length_m = geometry::distance(a, b);
  if (length_m > 0) {
    // Why the shortcut gives the measured answer: a leg in the interior of one ring (of at least
    // 3 vertices, as length_inside counts them) and a millimetre clear of its edges is its own
    // intersection with that ring's polygon, so length_inside() is at least its length computed
    // again, within a few ulps of length_m (far below the 1e-6 m tolerance for legs under
    // 10^6 km); the other rings add lengths >= 0. Legs the shortcut cannot place are measured as
    // before (property test: LegWithin in mission_test.cpp, against length_inside on random legs
    // and rings).
    for (const geometry::Ring& r : rings)
      if (r.size() >= 3 && clearly_inside(a, b, r)) return true;
    return geometry::length_inside({a, b}, rings) >= length_m - 1e-6;
  }
  return std::any_of(rings.begin(), rings.end(), [a](const geometry::Ring& r) {
    return geometry::locate_point(a, r) != geometry::Containment::outside;
  });
}

}  // namespace detail

namespace {

// How far from p along the unit direction u before the closed areas `rings` (the zones grown by
// the clearance): 0 when p is inside one or on its edge heading in, +infinity when the ray meets
// none. A point on an edge heading out (a line end on the clearance band) is free.
double ray_to_rings_m(geometry::Point2 p, geometry::Point2 u,
                      const std::vector<geometry::Ring>& rings) {
  constexpr double kStep_m = 1e-4;
  const geometry::Point2 ahead = p + u * kStep_m;
  double least = INFINITY;
  for (const geometry::Ring& r : rings) {
    if (geometry::locate_point(ahead, r) != geometry::Containment::outside) return 0.0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      const geometry::Point2 a = r[i], e = r[(i + 1) % r.size()] - a, w = a - p;
      const double det = e.x * u.y - e.y * u.x;  // u x e, solving p + t u = a + s e
      if (std::abs(det) < 1e-12) continue;
      const double t = (e.x * w.y - e.y * w.x) / det, sa = (u.x * w.y - u.y * w.x) / det;
      if (t > kStep_m && sa >= 0 && sa <= 1) least = std::min(least, t);
    }
  }
  return least;
}

// Whether the track an autopilot flies along leg a-b (`track`) keeps the clearance of the zones
// wherever the straight leg keeps it: no nearer any of them than the clearance, or where the leg
// itself comes nearer (a line end on the band), than the leg less a negligible bow. Ruled out
// by the cheap bound first, then by the bow measured; else the tracks are measured.
bool track_keeps_clear(const geometry::AutopilotTrack& track, geometry::Point2 a,
                       geometry::Point2 b, const std::vector<geometry::Ring>& zones,
                       double clearance_m) {
  using geometry::AutopilotTrack;
  const double bound = track.bow_bound_m(a, b);
  if (bound < AutopilotTrack::kNegligibleBow_m) return true;
  const double chord_m = geometry::least_distance({a, b}, zones);
  if (chord_m - bound >= clearance_m) return true;
  const double bow = track.bow_m(a, b);
  if (bow < AutopilotTrack::kNegligibleBow_m || chord_m - bow >= clearance_m) return true;
  const double keep_m = std::min(clearance_m, chord_m - AutopilotTrack::kNegligibleBow_m);
  for (const std::vector<geometry::Point2>& points :
       track.tracks(a, b, AutopilotTrack::pieces_for(bow)))
    if (geometry::least_distance(points, zones) < keep_m) return false;
  return true;
}

// Whether each of `n` equal legs a-b is cut into (as MissionBuilder::through_to cuts it) keeps
// the clearance on its track.
bool pieces_keep_clear(const geometry::AutopilotTrack& track, geometry::Point2 a,
                       geometry::Point2 b, int n, const std::vector<geometry::Ring>& zones,
                       double clearance_m) {
  geometry::Point2 from = a;
  for (int k = 1; k <= n; ++k) {
    const geometry::Point2 to = k == n ? b : a + (b - a) * (static_cast<double>(k) / n);
    if (!track_keeps_clear(track, from, to, zones, clearance_m)) return false;
    from = to;
  }
  return true;
}

}  // namespace

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
  s.accel_m_s2 = drone.accel_m_s2;
  s.slowest_approach_m_s = plan.request.slowest_approach_m_s;
  // A leg long enough to bow (at high latitudes, far homes) is written as several; most legs are
  // ruled out by the cheap bound, without converting their ends.
  if (const auto& frame = plan.request.field.frame) {
    const auto track = std::make_shared<const geometry::AutopilotTrack>(*frame, drone.home);
    s.bow_m = [track](geometry::Point2 a, geometry::Point2 b) {
      return track->bow_bound_m(a, b) > kMaxBow_m ? track->bow_m(a, b) : 0.0;
    };
    // A leg beside a zone may keep only centimetres more than the clearance: its track must not
    // stray across them (the preflight check measures it). The first guess: legs straying no
    // more than the leg's slack; then twice as many until every track keeps clear.
    if (!plan.no_fly.empty())
      s.pieces_kept_clear = [track, &plan](geometry::Point2 a, geometry::Point2 b, int pieces) {
        const std::vector<geometry::Ring>& zones = plan.no_fly;
        const double clearance_m = plan.request.clearance_m;
        if (pieces_keep_clear(*track, a, b, pieces, zones, clearance_m)) return pieces;
        const double slack_m = std::max(geometry::least_distance({a, b}, zones) - clearance_m,
                                        geometry::AutopilotTrack::kNegligibleBow_m);
        int n = std::max(
            pieces + 1,
            static_cast<int>(std::min(1000.0, std::ceil(std::sqrt(track->bow_m(a, b) / slack_m)))));
        while (n < 1000 && !pieces_keep_clear(*track, a, b, n, zones, clearance_m))
          n = std::min(1000, 2 * n);
        return n;
      };
  }
  // Stop at line ends beside a no-fly zone (within the clearance and the corner allowance): a
  // turn flown through there would swing towards the zone.
  if (!plan.no_fly.empty() && plan.request.vehicle == Vehicle::multirotor) {
    const double near_m = plan.request.clearance_m + kCornerAllowance_m;
    s.stop_at = [&plan, near_m](geometry::Point2 p) {
      return geometry::least_distance({p}, plan.no_fly) < near_m;
    };
    s.free_run_m = [&plan](geometry::Point2 p, geometry::Point2 u) {
      return ray_to_rings_m(p, u, plan.no_fly_grown);
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
std::vector<geometry::Ring> grown_fence(const std::vector<geometry::Ring>& outlines,
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

// Whether every vertex of every outline lies inside the fence (not outside every ring of it).
bool holds_outlines(const std::vector<geometry::Ring>& fence,
                    const std::vector<geometry::Ring>& outlines) {
  for (const geometry::Ring& outline : outlines)
    for (const geometry::Point2 p : outline)
      if (std::none_of(fence.begin(), fence.end(), [p](const geometry::Ring& r) {
            return geometry::locate_point(p, r) != geometry::Containment::outside;
          }))
        return false;
  return true;
}

std::vector<geometry::Ring> fence_for(const std::vector<geometry::Ring>& outlines,
                                      double margin_m) {
  std::vector<geometry::Ring> fence = grown_fence(outlines, margin_m);
  // Boost's buffer of an area with many strips reaching out of it (a crosshatch's overruns at
  // 12 m/s and more) returned fences missing strips, or in several polygons the vehicle had to be
  // inside all of: the meadow at 20 m, 12 m/s, left a stop 4.33 m outside its fence, at a 20 m
  // margin the home 279 m outside one of five. Such a fence is grown again piece by piece.
  if (!holds_outlines(fence, outlines)) return geometry::grow_each(outlines, margin_m);
  if (fence.size() > 1) {  // separate pieces (a repaired area's) stay separate
    std::vector<geometry::Ring> each = geometry::grow_each(outlines, margin_m);
    if (each.size() < fence.size()) return each;
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
      const geometry::LocalFrame& frame = *plan.request.field.frame;
      for (const geometry::Point2& p : geometry::densify_local_edges(frame, grown.front()))
        fences[z].push_back(frame.to_geo(p));
      break;
    }
  }
  return fences;
}

// How far a written inclusion fence's edge, straight in longitude and latitude, may stray from
// the fence swath planned, as a share of the fence's margin (fences()).
constexpr double kFenceEdgeShareOfMargin = 0.01;

// A counter-clockwise rectangle `half_width_m` either side of a-b and past its ends.
geometry::Ring strip_along(geometry::Point2 a, geometry::Point2 b, double half_width_m) {
  const double length_m = geometry::distance(a, b);
  const geometry::Point2 u = length_m > 0 ? (b - a) * (1 / length_m) : geometry::Point2{1, 0};
  const geometry::Point2 along = u * half_width_m, side{-along.y, along.x};
  return {a - along - side, b + along - side, b + along + side, a - along + side};
}

// Every leg of every flight as written (sorties where there are), and past each stop (a hold, a
// turn sharper than kStopTurn_deg, the end) the overrun along the incoming leg (stop_overrun_m).
std::vector<std::pair<geometry::Point2, geometry::Point2>> flown_legs(const SurveyPlan& plan) {
  std::vector<std::pair<geometry::Point2, geometry::Point2>> legs;
  for (const Flight& f : flights_of(plan)) {
    const std::vector<geometry::Point2>& path = f.mission->path;
    const double overrun_m = stop_overrun_m(f.drone->speed_m_s);
    for (std::size_t i = 0; i < path.size(); ++i) {
      legs.push_back({path[i], i + 1 < path.size() ? path[i + 1] : path[i]});
      if (i == 0 || plan.request.vehicle != Vehicle::multirotor) continue;
      const geometry::Point2 in = path[i] - path[i - 1];
      const double in_m = geometry::distance(path[i - 1], path[i]);
      if (in_m <= 0) continue;
      const bool stop =
          i + 1 == path.size() || turn_deg(path[i - 1], path[i], path[i + 1]) > kStopTurn_deg;
      if (stop) legs.push_back({path[i], path[i] + in * (overrun_m / in_m)});
    }
  }
  return legs;
}

}  // namespace

std::size_t most_vertices(const std::vector<geometry::Ring>& rings) {
  std::size_t most = 0;
  for (const geometry::Ring& r : rings) most = std::max(most, r.size());
  return most;
}

// The plan's items and photos within swath's limits (survey.hpp: they bound the memory of the
// files), counted on the missions as built, before any file is made.
void check_counts(const SurveyPlan& plan) {
  std::size_t items = 0, photos = 0;
  for (const DronePlan& d : plan.drones) items += d.mission.items.size(), photos += d.photos.size();
  if (items > kMaxWaypoints)
    throw base::InputError(
        "the plan takes " + std::to_string(items) + " mission items, more than swath's limit of " +
        std::to_string(kMaxWaypoints) + "; drop --waypoint-spacing or split the area");
  if (photos > kMaxPhotos)
    throw base::InputError("the plan takes " + std::to_string(photos) +
                           " photos, more than swath's limit of " + std::to_string(kMaxPhotos) +
                           "; fly higher, lower the overlaps or split the area");
}

namespace {

// The default fence margin: the turnaround, half the footprint and 10 m, or where a multirotor's
// stop runs further past a line's end (stop_overrun_m at the fastest drone's speed: 28.8 m at
// 12 m/s against 24.5 m on the meadow at 20 m) that overrun and 5 m more, so that what the
// preflight check adds past each stop lies inside the area's own fence rather than in strips
// grown out of it one by one. At 5 m/s (a 5 m overrun) the first is always the larger.
double default_fence_margin_m(const SurveyPlan& plan) {
  double overrun_m = 0.0;
  if (plan.request.vehicle == Vehicle::multirotor)
    for (const DronePlan& d : plan.drones)
      overrun_m = std::max(overrun_m, stop_overrun_m(d.speed_m_s));
  return plan.turnaround_m + std::max(plan.imaging.footprint_across_m / 2 + 10, overrun_m + 5);
}

}  // namespace

void missions(SurveyPlan& plan) {
  // PX4's RTL climbs to RTL_RETURN_ALT (60 m by default) before it flies home, through the other
  // drones' layers: several drones' PX4 multirotor flights fly home at their own layer and land
  // there (a plane's landing needs an approach: its RTL is left to the check).
  if (plan.request.firmware == Firmware::px4 && plan.drones.size() > 1 &&
      plan.request.vehicle == Vehicle::multirotor)
    plan.request.land = true;
  const Routes& routes = routes_of(plan);
  const InsideTest inside = routes.inside_test();
  for (DronePlan& d : plan.drones) {
    d.mission = mission_for_path(d.number, d.home, d.work.path, mission_settings(plan, d),
                                 routes.leg(), inside);
    d.photos = planned_photos(d.mission, plan.imaging.trigger_distance_m);
  }
  check_counts(plan);
  plan.fence_margin_m = plan.request.fence_margin_m.value_or(default_fence_margin_m(plan));
  plan.exclusion_fences_geo = exclusion_fences(plan);
}

namespace {

// The fences as written, in raw longitude: an area near the ±180° meridian whose fence, grown by
// the margin and the flown legs, reaches across it is refused here, before any file is made.
void refuse_fences_across_antimeridian(const SurveyPlan& plan) {
  if (!plan.request.field.frame) return;
  for (const geometry::Ring& ring : plan.fence) {
    std::vector<geometry::GeoPoint> geo;
    for (const geometry::Point2& p : ring) geo.push_back(plan.request.field.frame->to_geo(p));
    refuse_across_antimeridian(geo, "the inclusion fence (the area grown by the " +
                                        base::fixed_text(plan.fence_margin_m, 1) +
                                        " m fence margin, with every leg flown)");
  }
  for (std::size_t z = 0; z < plan.exclusion_fences_geo.size(); ++z)
    refuse_across_antimeridian(plan.exclusion_fences_geo[z],
                               "the exclusion fence of " + no_fly_name(plan, z));
}

}  // namespace

void fences(SurveyPlan& plan) {
  // The inclusion fence holds what is flown (docs/swath-plan.md): the area, and every leg of
  // every flight (home legs, transits around zones past the area's edge) with the overrun past
  // each stop, grown by the margin. Legs already inside the area's own fence add nothing; each
  // other one adds a metre-wide strip along it (a home alone, a metre square about it).
  std::vector<geometry::Ring> outlines{plan.area.outer};
  outlines.insert(outlines.end(), plan.extra_pieces.begin(), plan.extra_pieces.end());
  plan.fence = fence_for(outlines, plan.fence_margin_m);
  std::vector<geometry::Ring> strips;
  for (const auto& [a, b] : flown_legs(plan))
    if (!detail::leg_within(a, b, plan.fence)) strips.push_back(strip_along(a, b, 0.5));
  if (!strips.empty()) {
    outlines.insert(outlines.end(), strips.begin(), strips.end());
    plan.fence = fence_for(outlines, plan.fence_margin_m);
  }
  // An autopilot tests the fence with edges straight in longitude and latitude: a long edge (a
  // far home's transit, 80 km) bows away from the chord planned around by tens of metres, so
  // points along the chord keep each written edge within 1 % of the margin of it (at least
  // kEdgeDepartureTolerance_m): what is flown keeps 99 % of the margin from the fence the
  // autopilot tests, with a few points (ArduPilot's fence storage holds ~70).
  const double tolerance_m =
      std::max(geometry::kEdgeDepartureTolerance_m, plan.fence_margin_m * kFenceEdgeShareOfMargin);
  if (plan.request.field.frame)
    for (geometry::Ring& ring : plan.fence)
      ring = geometry::densify_local_edges(*plan.request.field.frame, ring, tolerance_m);
  refuse_fences_across_antimeridian(plan);
}

}  // namespace swath::planning::steps
