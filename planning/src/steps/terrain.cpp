// Step 7b of plan_survey(): terrain following (survey_steps.hpp, terrain.hpp, docs/swath-plan.md).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/planning/limits.hpp"
#include "swath/planning/survey_steps.hpp"

namespace swath::planning::steps {
namespace {

using base::fixed_text;

// A leg may pass this much lower than the tolerance allows: rounding, not a dip.
constexpr double kDip_m = 1e-6;

struct Follower {
  const SurveyPlan& plan;
  const TerrainRequest& request;
  TerrainFacts& facts;
  double steepest_m_s = 0.0;  // |vertical speed| of the steepest leg, for the warning

  geometry::GeoPoint geo(geometry::Point2 p) const { return plan.request.field.frame->to_geo(p); }

  std::string place(geometry::Point2 p) const {
    const geometry::GeoPoint g = geo(p);
    return "(" + fixed_text(g.lat_deg, 6) + ", " + fixed_text(g.lon_deg, 6) + ")";
  }

  // The ground along a-b (ground_profile: where its worst point under a straight leg lies).
  geometry::GroundProfile profile(geometry::Point2 a, geometry::Point2 b,
                                  const std::string& whose) const {
    const auto at = [&](double t) {
      return geometry::Point2{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
    };
    geometry::GroundProfile p = geometry::ground_profile(
        *request.ground, [&](double t) { return geo(at(t)); }, std::hypot(b.x - a.x, b.y - a.y));
    for (std::size_t k = 0; k < p.t.size(); ++k)
      if (!std::isfinite(p.ground_m[k]))
        throw base::InputError(request.ground->source() + ": the DEM has no height at " +
                               place(at(p.t[k])) + ", on " + whose +
                               ": give a DEM that covers the homes, the area and the legs between");
    return p;
  }

  // The samples to fly over (Douglas-Peucker within the tolerance), then every straight leg
  // between them measured against the ground between the samples too: where one passes lower
  // than the tolerance allows (over a hump between samples), the worst point becomes a sample and
  // the profile is simplified again. Lower is the unsafe side and is never left; higher (over a
  // hollow between samples) costs only photo quality, and the summary's range reports it.
  std::vector<std::size_t> breaks(geometry::GroundProfile& p, double length_m) const {
    constexpr int kRounds = 32;  // each round samples the dips; a few suffice
    std::vector<std::size_t> keep;
    for (int round = 0; round < kRounds; ++round) {
      std::vector<double> along(p.t.size());
      for (std::size_t k = 0; k < p.t.size(); ++k) along[k] = p.t[k] * length_m;
      keep = profile_breaks(along, p.ground_m, request.tolerance_m);
      std::vector<double> dips;
      for (std::size_t q = 0; q + 1 < keep.size(); ++q) {
        const std::size_t a = keep[q], b = keep[q + 1];
        const geometry::HeightAboveGround h =
            geometry::height_above_ground(p, a, b, p.ground_m[a], p.ground_m[b]);
        if (h.least_m < -request.tolerance_m - kDip_m) dips.push_back(h.t_least);
      }
      if (dips.empty()) break;
      for (const double t : dips) p.add(t);
    }
    return keep;
  }

  // The waypoints of one flight at the height above ground; waypoints added on the legs.
  void follow(const DronePlan& d, DroneMission& m) {
    const std::string whose = "drone " + d.name + "'s flight";
    const double agl = plan.imaging.altitude_m + d.layer_m;
    const double home_ground = profile(m.home, m.home, whose).ground_m[0];
    m.home_amsl_m = home_ground;
    std::vector<MissionItem> out;
    geometry::Point2 prev = m.home;
    bool airborne = false;
    auto set = [&](MissionItem& item, double ground) {
      item.altitude_m = ground + agl - home_ground;
      item.altitude_amsl_m = ground + agl;
    };
    for (MissionItem item : m.items) {
      const bool home_bound =
          item.kind == ItemKind::land || item.kind == ItemKind::return_to_launch;
      const bool leg = item.kind == ItemKind::waypoint || home_bound;
      if (item.kind == ItemKind::takeoff) {
        set(item, home_ground);
        airborne = true;
        prev = m.home;
      } else if (leg && airborne) {
        const geometry::Point2 to = home_bound ? m.home : item.position;
        const double length = std::hypot(to.x - prev.x, to.y - prev.y);
        geometry::GroundProfile g = profile(prev, to, whose);
        if (item.kind == ItemKind::return_to_launch && level_return_holds(g, agl)) {
          out.push_back(item);
          continue;
        }
        const std::vector<std::size_t> keep =
            length > 0 ? breaks(g, length) : std::vector<std::size_t>{0};
        measure(g, keep, length, d);
        // A landing flies to home level at its last height, then descends; a return to launch
        // flies straight home at the last height (ArduPilot climbs to RTL_ALT first, never
        // lower), over whatever rises on the way: a last waypoint above home first, so that the
        // way home follows the ground like the other legs.
        const bool homing = home_bound && keep.size() > 1 && length > 0;
        for (std::size_t q = 1; q + (homing ? 0 : 1) < keep.size(); ++q) {
          const double t = g.t[keep[q]];
          MissionItem added;
          added.kind = ItemKind::waypoint;
          added.position = {prev.x + t * (to.x - prev.x), prev.y + t * (to.y - prev.y)};
          set(added, g.ground_m[keep[q]]);
          out.push_back(added);
          ++facts.waypoints_added;
          ++m.waypoint_count;
        }
        if (item.kind != ItemKind::return_to_launch) set(item, g.ground_m.back());
        prev = to;
      }
      out.push_back(item);
    }
    m.items = std::move(out);
  }

  // Whether a return to launch flown level at the last waypoint's height stays within the
  // tolerance of the height asked above the ground on its way home (flat ground: no waypoint).
  bool level_return_holds(const geometry::GroundProfile& g, double agl_m) const {
    const double z_m = g.ground_m.front() + agl_m;
    const geometry::HeightAboveGround h =
        geometry::height_above_ground(g, 0, g.t.size() - 1, z_m, z_m);
    return h.least_m >= agl_m - request.tolerance_m - kDip_m &&
           h.most_m <= agl_m + request.tolerance_m + kDip_m;
  }

  // Heights above ground along the straight lines between the kept samples (their least and most
  // between samples too), ground range, steepness.
  void measure(const geometry::GroundProfile& g, const std::vector<std::size_t>& keep,
               double length_m, const DronePlan& d) {
    const double agl = plan.imaging.altitude_m + d.layer_m;
    for (std::size_t q = 0; q + 1 < keep.size(); ++q) {
      const std::size_t a = keep[q], b = keep[q + 1];
      const geometry::HeightAboveGround h =
          geometry::height_above_ground(g, a, b, g.ground_m[a] + agl, g.ground_m[b] + agl);
      facts.agl_min_m = std::min(facts.agl_min_m, h.least_m);
      facts.agl_max_m = std::max(facts.agl_max_m, h.most_m);
      for (std::size_t k = a; k <= b; ++k) {
        facts.ground_min_m = std::min(facts.ground_min_m, g.ground_m[k]);
        facts.ground_max_m = std::max(facts.ground_max_m, g.ground_m[k]);
      }
      const double span = (g.t[b] - g.t[a]) * length_m;
      if (span <= 0) continue;
      const double vertical_m_s = (g.ground_m[b] - g.ground_m[a]) / span * d.speed_m_s;
      facts.climb_max_m_s = std::max(facts.climb_max_m_s, vertical_m_s);
      facts.descent_max_m_s = std::min(facts.descent_max_m_s, vertical_m_s);
      if (vertical_m_s > d.climb_speed_m_s || -vertical_m_s > d.descent_speed_m_s) {
        ++facts.legs_too_steep;
        if (std::abs(vertical_m_s) > steepest_m_s) steepest_m_s = std::abs(vertical_m_s);
      }
    }
  }
};

std::string tolerance_or_altitude(double altitude_m) {
  const double most_m = altitude_m - geometry::kLeastHeightAboveGround_m;
  if (most_m < limits::kTerrainTolerance_m.lo) return "a higher --altitude";
  return "at most --terrain-tolerance " + fixed_text(most_m, 1) + " or a higher --altitude";
}

// Legs may pass the tolerance below the altitude: refused where that is below the least height
// the plan's check demands, before a plan it would refuse is made.
void check_least_height(double altitude_m, double tolerance_m) {
  const double lowest_m = altitude_m - tolerance_m;
  if (lowest_m >= geometry::kLeastHeightAboveGround_m) return;
  throw base::InputError(
      "--terrain-tolerance " + fixed_text(tolerance_m, 1) + " m at an altitude of " +
      fixed_text(altitude_m, 1) + " m (--altitude) lets legs pass " + fixed_text(lowest_m, 1) +
      " m above the ground, below the least " + fixed_text(geometry::kLeastHeightAboveGround_m, 1) +
      " m: give " + tolerance_or_altitude(altitude_m));
}

}  // namespace

void terrain(SurveyPlan& plan) {
  if (!plan.request.terrain) return;
  const TerrainRequest& request = *plan.request.terrain;
  if (!request.ground) throw std::invalid_argument("terrain: no ground");
  if (!(request.tolerance_m > 0))
    throw base::InputError("--terrain-tolerance must be > 0 m (got " +
                           fixed_text(request.tolerance_m, 3) + ")");
  check_least_height(plan.imaging.altitude_m, request.tolerance_m);
  TerrainFacts facts;
  facts.source = request.ground->source();
  facts.frame = request.frame;
  facts.height_above_ground_m = plan.imaging.altitude_m;
  facts.tolerance_m = request.tolerance_m;
  constexpr double inf = std::numeric_limits<double>::infinity();
  facts.ground_min_m = facts.agl_min_m = inf;
  facts.ground_max_m = facts.agl_max_m = -inf;
  Follower f{plan, request, facts};
  for (DronePlan& d : plan.drones) {
    f.follow(d, d.mission);
    for (Sortie& s : d.sorties) f.follow(d, s.mission);
  }
  if (!std::isfinite(facts.agl_min_m)) {  // nothing flown level (no legs)
    facts.agl_min_m = facts.agl_max_m = plan.imaging.altitude_m;
    facts.ground_min_m = facts.ground_max_m = 0.0;
  }
  const double per_m = plan.imaging.gsd_m / plan.imaging.altitude_m;
  facts.gsd_min_m = facts.agl_min_m * per_m;
  facts.gsd_max_m = facts.agl_max_m * per_m;
  if (facts.legs_too_steep > 0)
    plan.warnings.push_back(
        std::to_string(facts.legs_too_steep) +
        (facts.legs_too_steep == 1 ? " leg follows" : " legs follow") +
        " the ground up or down faster than the drone climbs or descends (steepest " +
        fixed_text(f.steepest_m_s, 1) +
        " m/s): the autopilot slows down on them; fly slower or lay the lines along the slope");
  plan.terrain = facts;
}

}  // namespace swath::planning::steps
