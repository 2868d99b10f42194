// Step 1 of plan_survey(): the area to fly (survey_steps.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/geometry/convex_hull.hpp"
#include "swath/geometry/decomposition.hpp"
#include "swath/geometry/offset.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/geometry/repair.hpp"
#include "swath/missions/stopping.hpp"
#include "swath/planning/survey_steps.hpp"

namespace swath::planning::steps {
namespace {

using base::fixed_text;
using base::InputError;
using geometry::GeoPoint;

std::string point_text(const geometry::Field& field, geometry::Point2 p) {
  const GeoPoint g = field.frame->to_geo(p);
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

std::string lat_lon_text(const GeoPoint& g) {
  return fixed_text(g.lat_deg, 5) + "," + fixed_text(g.lon_deg, 5);
}

// Geodesic distance from `p` to the nearest vertex of the area (the area is small beside the
// distances this judges).
double distance_to_area_m(const GeoPoint& p, const std::vector<GeoPoint>& ring) {
  double d = INFINITY;
  for (const GeoPoint& v : ring) d = std::min(d, geometry::geodesic_distance_m(p, v));
  return d;
}

// A home far from the area is almost always a typo: latitude and longitude swapped, or a sign
// lost (docs/swath-plan.md). Refused naming the distance and, where one of those
// readings lies within 1 km of the area, the home meant.
void check_home_near_area(const GeoPoint& home, const std::string& what,
                          const geometry::Field& field, bool far_home_allowed) {
  const std::vector<GeoPoint>& ring = field.geo_rings.at(0);
  const double d = distance_to_area_m(home, ring);
  if (d <= kMaxHomeDistance_m || (far_home_allowed && d <= kMaxFarHomeDistance_m)) return;
  std::string message = what + " " + lat_lon_text(home) + " (lat, lon) is " +
                        fixed_text(d / 1000, 0) + " km from the area";
  const GeoPoint readings[] = {{home.lon_deg, home.lat_deg, 0},
                               {-home.lat_deg, home.lon_deg, 0},
                               {home.lat_deg, -home.lon_deg, 0},
                               {-home.lat_deg, -home.lon_deg, 0}};
  const char* how[] = {"latitude and longitude swapped", "the latitude's sign flipped",
                       "the longitude's sign flipped", "both signs flipped"};
  std::string tail = "; homes";
  for (std::size_t k = 0; k < std::size(readings); ++k) {
    const GeoPoint& r = readings[k];
    if (std::abs(r.lat_deg) <= 90 && distance_to_area_m(r, ring) <= 1000) {
      message += "; did you mean " + lat_lon_text(r) + " (" + how[k] + ")?";
      tail = " Homes";
      break;
    }
  }
  if (far_home_allowed)  // beyond what any drone flies, and what the local frame can hold
    throw InputError(message + tail + " farther than " +
                         fixed_text(kMaxFarHomeDistance_m / 1000, 0) + " km are refused",
                     {base::Remedy::far_home_limit});
  throw InputError(message + tail + " farther than " + fixed_text(kMaxHomeDistance_m / 1000, 0) +
                       " km are refused",
                   {base::Remedy::far_home});
}

// Every home the plan will use: the request's and the fleet's own.
void check_homes(const SurveyRequest& request, const geometry::Field& field) {
  if (request.home) check_home_near_area(*request.home, "the home", field, request.far_home);
  if (!request.fleet) return;
  if (std::isfinite(request.fleet->home.lat_deg) &&
      request.fleet->home != request.home.value_or(GeoPoint{NAN, NAN, 0}))
    check_home_near_area(request.fleet->home, "the fleet's home", field, request.far_home);
  for (const vehicle::Drone& d : request.fleet->drones)
    if (d.home)
      check_home_near_area(*d.home, "drone " + d.name + "'s home", field, request.far_home);
}

}  // namespace

void refuse_across_antimeridian(const std::vector<GeoPoint>& ring, const std::string& what) {
  const auto edge = geometry::edge_across_antimeridian(ring);
  if (!edge) return;
  const auto at = [](const GeoPoint& g) {
    return fixed_text(g.lat_deg, 7) + ", " + fixed_text(g.lon_deg, 7);
  };
  throw InputError(what + " crosses the ±180° meridian (its edge from " + at(edge->a) + " to " +
                   at(edge->b) +
                   ", lat, lon), where ArduPilot's and PX4's fences, compared in "
                   "raw longitude, cannot hold it; plan each side of the meridian on its own");
}

namespace {

// The outer ring and the zones, before any planning: each becomes a fence (the area grown by the
// margin, a zone as given), which an autopilot cannot hold across the ±180° meridian. The grown
// fence is checked again when it is made (fences()).
void refuse_rings_across_antimeridian(const SurveyPlan& plan) {
  const geometry::Field& field = plan.request.field;
  std::vector<GeoPoint> outer;
  for (const geometry::Point2& p : field.polygon.outer) outer.push_back(field.frame->to_geo(p));
  refuse_across_antimeridian(outer, field.source + ": the area");
  for (std::size_t k = 0; k < plan.no_fly_geo.size(); ++k)
    refuse_across_antimeridian(plan.no_fly_geo[k], no_fly_name(plan, k));
}

// The no-fly zones: the field's holes, then the --exclude zones (as given and in the frame).
void collect_no_fly(SurveyPlan& plan) {
  const geometry::Field& field = plan.request.field;
  for (std::size_t h = 0; h < field.polygon.holes.size(); ++h) {
    plan.no_fly.push_back(field.polygon.holes[h]);
    plan.no_fly_geo.push_back(field.geo_rings.at(h + 1));
  }
  for (std::size_t k = 0; k < plan.request.exclusions.size(); ++k) {
    // A zone's edges are straight in longitude and latitude as drawn (RFC 7946): long ones are
    // followed in the frame within kZoneEdgeDepartureTolerance_m, so that the clearance is kept
    // from the zone as drawn. Its exclusion fence is written as
    // given: an autopilot reads those edges the same way.
    geometry::Ring local;
    for (const GeoPoint& g :
         geometry::densify_lonlat_edges(*field.frame, plan.request.exclusions[k], nullptr,
                                        geometry::kZoneEdgeDepartureTolerance_m))
      local.push_back(field.frame->to_local(g));
    geometry::NormalisedRing hole = geometry::normalise_ring(local, false);
    if (hole.ring.size() < 3)
      throw InputError(no_fly_name(plan, plan.no_fly.size()) +
                       " has fewer than 3 distinct vertices");
    plan.area.holes.push_back(hole.ring);
    plan.no_fly.push_back(std::move(hole.ring));
    plan.no_fly_geo.push_back(plan.request.exclusions[k]);
  }
}

// How far a multirotor arriving home at its cruise speed may run on past it, metres (the
// preflight check's stopping margin, missions::stopping_distance_m); a fixed wing does not stop.
double home_overrun_m(const SurveyRequest& r, const vehicle::Drone* drone) {
  if (r.vehicle != Vehicle::multirotor) return 0.0;
  const double plan_speed_m_s = r.speed_m_s.value_or(5.0);
  if (drone)
    return missions::stopping_distance_m(drone->speed_m_s.value_or(plan_speed_m_s),
                                         drone->accel_m_s2);
  return missions::stopping_distance_m(plan_speed_m_s, vehicle::kDefaultAccel_m_s2);
}

// A home within the clearance of a zone, or so near that its drone's stop there runs into the
// clearance: the take-off or the landing breaks it, and the plan's check refused it naming only
// a waypoint ("item 1 comes within 3.35 m", "item 76 (its stopping margin)").
void check_home_clear_of_zone(const SurveyPlan& plan, const std::string& what,
                              const std::string& home_text, geometry::Point2 p, std::size_t k,
                              double overrun_m) {
  const double clearance_m = plan.request.clearance_m;
  const double distance_m = geometry::least_distance({p}, {plan.no_fly[k]});
  const double needed_m = clearance_m + overrun_m;
  if (!(distance_m < needed_m)) return;
  // Rounded the safe way: the distance asked up, the clearance that fits down.
  const std::string needed_text = fixed_text(std::ceil(needed_m * 10) / 10, 1);
  std::string why = "less than the " + fixed_text(clearance_m, 1) + " m --clearance";
  if (overrun_m > 0)
    why = "less than the " + needed_text + " m it must keep (the " + fixed_text(clearance_m, 1) +
          " m --clearance and the " + fixed_text(overrun_m, 1) +
          " m its drone may run on past home as it stops)";
  const double lowered_m = std::floor((distance_m - overrun_m) * 10) / 10;
  std::string remedy = "move " + what + " at least " + needed_text + " m from the zone";
  if (lowered_m > 0) remedy += ", or lower --clearance to " + fixed_text(lowered_m, 1) + " m";
  throw InputError(home_text + " lies " + fixed_text(distance_m, 1) + " m from " +
                   no_fly_name(plan, k) + ", " + why + "; " + remedy);
}

// A home inside a hole or no-fly zone, or on its edge: every take-off and landing enters it (the
// router then found "no way round" for a leg, naming neither the home nor the zone). Nor may it
// lie within the clearance (with the drone's stop) of one.
void check_home_outside_zones(const SurveyPlan& plan, const GeoPoint& home, const std::string& what,
                              double overrun_m) {
  const geometry::Point2 p = plan.request.field.frame->to_local(home);
  const std::string home_text =
      what + " " + base::shortest_text(home.lat_deg) + "," + base::shortest_text(home.lon_deg);
  for (std::size_t k = 0; k < plan.no_fly.size(); ++k)
    if (geometry::locate_point(p, plan.no_fly[k]) != geometry::Containment::outside)
      throw InputError(home_text + " lies inside (or on the edge of) " + no_fly_name(plan, k) +
                       "; give a home outside the zones");
  for (std::size_t k = 0; k < plan.no_fly.size(); ++k)
    check_home_clear_of_zone(plan, what, home_text, p, k, overrun_m);
}

// Every home the plan will use against the zones, named as the user gave it.
void check_homes_outside_zones(const SurveyPlan& plan) {
  const SurveyRequest& r = plan.request;
  if (r.home) check_home_outside_zones(plan, *r.home, "--home", home_overrun_m(r, nullptr));
  if (!r.fleet) return;
  if (std::isfinite(r.fleet->home.lat_deg) &&
      r.fleet->home != r.home.value_or(GeoPoint{NAN, NAN, 0})) {
    double overrun_m = 0.0;  // the farthest of the drones that fly from it
    for (const vehicle::Drone& d : r.fleet->drones)
      if (!d.home) overrun_m = std::max(overrun_m, home_overrun_m(r, &d));
    check_home_outside_zones(plan, r.fleet->home, "the fleet's home", overrun_m);
  }
  for (const vehicle::Drone& d : r.fleet->drones)
    if (d.home)
      check_home_outside_zones(plan, *d.home, "drone " + d.name + "'s home", home_overrun_m(r, &d));
}

// Whether no-fly zones cross the area's boundary or each other, or lie outside the area: then the
// area is cut (cut_out_zones) instead of refused.
bool zones_need_cutting(const SurveyPlan& plan) {
  const geometry::Field& field = plan.request.field;
  const geometry::Classification& c = plan.facts.classification;
  if (c.type == geometry::AreaType::self_intersecting &&
      c.crossing->edge_b.ring > field.polygon.holes.size())
    return true;
  for (std::size_t h = field.polygon.holes.size(); h < plan.area.holes.size(); ++h)
    for (const geometry::Point2& p : plan.area.holes[h])
      if (geometry::locate_point(p, plan.area.outer) == geometry::Containment::outside) return true;
  return false;
}

// The area of the part of `ring` outside all of `others` (rings of either orientation), m².
double area_outside(const geometry::Ring& ring, const std::vector<geometry::Ring>& others) {
  auto ccw = [](geometry::Ring r) {
    if (geometry::signed_area(r) < 0) std::reverse(r.begin(), r.end());
    return r;
  };
  std::vector<geometry::Ring> obstacles;
  for (const geometry::Ring& r : others) obstacles.push_back(ccw(r));
  double a = 0;  // parts' outer rings counter-clockwise (+), their holes clockwise (-)
  for (const geometry::Ring& part : geometry::subtract(ccw(ring), 0, obstacles))
    a += geometry::signed_area(part);
  return a;
}

bool boxes_meet(const geometry::Ring& a, const geometry::Ring& b) {
  auto box = [](const geometry::Ring& r) {
    std::array<double, 4> x{INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (const geometry::Point2& p : r)
      x = {std::min(x[0], p.x), std::min(x[1], p.y), std::max(x[2], p.x), std::max(x[3], p.y)};
    return x;
  };
  const auto p = box(a), q = box(b);
  return p[0] <= q[2] && q[0] <= p[2] && p[1] <= q[3] && q[1] <= p[3];
}

// Why the zones are cut out rather than taken as holes, zone by zone: which cross the area's
// boundary, which lie outside it, which pairs overlap (one boolean difference per zone and per
// pair whose boxes meet; beyond 50 zones, one general sentence).
struct ZonesCut {
  std::string text;
  bool outside_only = false;  ///< every zone cut lies outside the area: nothing is cut from it
};
ZonesCut zones_cut_text(const SurveyPlan& plan) {
  const std::size_t holes = plan.request.field.polygon.holes.size();
  const std::vector<geometry::Ring>& zones = plan.no_fly;
  if (zones.size() > 50)
    return {"no-fly zones cross the area's boundary, lie outside it or overlap"};
  auto name = [&](std::size_t k) { return no_fly_name(plan, k); };
  const geometry::Ring& outer = plan.request.field.polygon.outer;
  std::vector<std::string> said;
  bool outside_only = true;
  for (std::size_t k = holes; k < zones.size(); ++k) {  // the file's holes lie inside the area
    const double whole = std::abs(geometry::signed_area(zones[k]));
    const double tolerance = 1e-6 * whole + 1e-6;
    const double outside = boxes_meet(zones[k], outer) ? area_outside(zones[k], {outer}) : whole;
    if (outside >= whole - tolerance) {
      said.push_back(name(k) + " lies outside the area");
      continue;
    }
    outside_only = false;
    if (outside > tolerance) said.push_back(name(k) + " crosses the area's boundary");
  }
  for (std::size_t i = 0; i < zones.size(); ++i)
    for (std::size_t j = std::max(i + 1, holes); j < zones.size(); ++j) {
      if (!boxes_meet(zones[i], zones[j])) continue;
      const double whole = std::abs(geometry::signed_area(zones[i]));
      if (area_outside(zones[i], {zones[j]}) < whole * (1 - 1e-6) - 1e-6)
        outside_only = false, said.push_back(name(i) + " and " + name(j) + " overlap");
    }
  // Zones that only touch (the boundary or each other) are cut out too.
  if (said.empty()) return {"no-fly zones touch the area's boundary or each other"};
  ZonesCut out{"", outside_only};
  for (std::size_t k = 0; k < said.size() && k < 6; ++k) out.text += (k ? "; " : "") + said[k];
  if (said.size() > 6) out.text += "; and " + std::to_string(said.size() - 6) + " more";
  return out;
}

// How much the zones are grown for cutting them out of the area (see cut_out_zones), metres.
constexpr double kCutMargin_m = 1e-3;

// The area less the union of its holes and no-fly zones (Boost.Geometry's boolean difference),
// in as many parts as that leaves: the largest is the area, the others are planned and joined
// like --repair's pieces (their own zones stay no-fly through the planning rings).
void cut_out_zones(SurveyPlan& plan) {
  const geometry::Field& field = plan.request.field;
  std::vector<geometry::Polygon> parts;
  // The zones grown by a millimetre: a zone's edge along the boundary (on a meridian or parallel,
  // which the local plane bends by micrometres) left Boost's difference a sliver short (a 100 m
  // square zone on the edge of a field took 153 m² of its 10,000 out of the area).
  for (geometry::Ring& ring : geometry::subtract(
           field.polygon.outer, 0, geometry::grow_keeping_holes(plan.no_fly, kCutMargin_m))) {
    if (geometry::signed_area(ring) > 0)
      parts.push_back({std::move(ring), {}});
    else if (!parts.empty())
      parts.back().holes.push_back(std::move(ring));
  }
  if (parts.empty()) throw InputError(field.source + ": the no-fly zones cover the whole area");
  std::stable_sort(parts.begin(), parts.end(), [](const auto& a, const auto& b) {
    return geometry::area(a) > geometry::area(b);
  });
  double total = 0;
  for (const geometry::Polygon& part : parts) total += geometry::area(part);
  plan.area = parts.front();
  for (std::size_t k = 1; k < parts.size(); ++k) {
    plan.extra_pieces.push_back(parts[k].outer);
    plan.extra_piece_holes.insert(plan.extra_piece_holes.end(), parts[k].holes.begin(),
                                  parts[k].holes.end());
  }
  const ZonesCut why = zones_cut_text(plan);
  plan.warnings.push_back(why.text + (why.outside_only
                                          ? "; the area is planned whole, " + fixed_text(total, 1) +
                                                " m², and transits keep out of the zones"
                                          : "; planned the area less the zones, " +
                                                std::to_string(parts.size()) + " part(s), " +
                                                fixed_text(total, 1) + " m² in all"));
}

// Refusals that need the classification: zones crossing the area or each other, a crossing
// outer ring, a concave area with --concave reject.
void check_classification(const SurveyPlan& plan) {
  const geometry::Field& field = plan.request.field;
  const geometry::Classification& c = plan.facts.classification;
  if (c.type == geometry::AreaType::self_intersecting &&
      c.crossing->edge_b.ring > field.polygon.holes.size()) {
    const GeoPoint p = field.frame->to_geo(c.crossing->point);
    std::ostringstream s;
    s.precision(8);
    s << no_fly_name(plan, c.crossing->edge_b.ring - 1)
      << " crosses the area's boundary or another zone at " << p.lat_deg << ", " << p.lon_deg
      << " (lat, lon); give zones inside the area that do not overlap";
    throw InputError(s.str());
  }
  if (c.type == geometry::AreaType::self_intersecting) {
    const GeoPoint p = field.frame->to_geo(c.crossing->point);
    std::ostringstream s;
    s.precision(8);
    // A hole meeting the outer ring or another hole: --repair mends the outer ring only, so it is
    // not the advice; a no-fly zone given with --exclude is cut out of the area wherever it lies.
    const std::size_t a = c.crossing->edge_a.ring, b = c.crossing->edge_b.ring;
    if (a != b) {
      s << field.source << ": hole " << std::max(a, b) - 1 << " touches or crosses "
        << (std::min(a, b) == 0 ? std::string("the outer ring")
                                : "hole " + std::to_string(std::min(a, b) - 1))
        << " at " << p.lat_deg << ", " << p.lon_deg
        << " (lat, lon); keep holes inside the outer ring and apart, or give the hole as a "
           "no-fly zone with --exclude (zones are cut out of the area wherever they lie)";
      throw InputError(s.str());
    }
    s << field.source << ": the area crosses itself at " << p.lat_deg << ", " << p.lon_deg
      << " (lat, lon)";
    throw InputError(s.str(), {base::Remedy::repair});
  }
  if (c.type == geometry::AreaType::concave && plan.request.concave == ConcaveMode::reject)
    throw InputError(field.source + ": the area is not convex (" +
                         std::to_string(c.reflex_vertices.size()) + " reflex vertices" +
                         (field.polygon.holes.empty() ? "" : ", holes") +
                         ") and the plan refuses concave areas",
                     {base::Remedy::concave_hull});
}

// The holes split routes around: bounded before the quadratic work (kMaxSplitHoles).
void check_split_size(const geometry::Polygon& area) {
  std::size_t vertices = 0;
  for (const geometry::Ring& hole : area.holes) vertices += hole.size();
  if (area.holes.size() > kMaxSplitHoles || vertices > kMaxSplitHoleVertices)
    throw InputError("the area has " + std::to_string(area.holes.size()) +
                         " holes and no-fly zones with " + std::to_string(vertices) +
                         " vertices, more than split's limit of " + std::to_string(kMaxSplitHoles) +
                         " holes and " + std::to_string(kMaxSplitHoleVertices) + " vertices",
                     {base::Remedy::simplify_zones, base::Remedy::concave_hull});
}

}  // namespace

std::vector<geometry::Ring> lined_rings(const SurveyPlan& plan) {
  std::vector<geometry::Ring> out{plan.flown_area.outer};
  out.insert(out.end(), plan.extra_pieces.begin(), plan.extra_pieces.end());
  return out;
}

namespace {

// The handling and the area the sweep flies.
void choose_handling(SurveyPlan& plan) {
  const geometry::Classification& c = plan.facts.classification;
  const bool convex = c.type == geometry::AreaType::convex && plan.extra_pieces.empty();
  const bool split = !convex && plan.request.concave == ConcaveMode::split;
  plan.handling = convex ? Handling::convex : split ? Handling::split : Handling::hull;
  if (!convex && !plan.no_fly.empty()) check_split_size(plan.area);
  if (plan.handling == Handling::hull) {
    std::vector<geometry::Point2> all_outer = plan.area.outer;
    for (const geometry::Ring& piece : plan.extra_pieces)
      all_outer.insert(all_outer.end(), piece.begin(), piece.end());
    // The hull replaces the outline; the no-fly zones stay no-fly.
    plan.flown_area = geometry::Polygon{geometry::convex_hull(all_outer), plan.area.holes};
  } else {
    plan.flown_area = plan.area;
  }
}

// Whether two of `rings` (pieces that do not overlap) come within a micrometre of each other.
bool rings_touch(const std::vector<geometry::Ring>& rings) {
  constexpr double kTouch_m = 1e-6;
  for (std::size_t i = 0; i < rings.size(); ++i) {
    std::vector<geometry::Point2> boundary = rings[i];
    boundary.push_back(rings[i].front());  // closed: least_distance() takes a path
    for (std::size_t j = i + 1; j < rings.size(); ++j)
      if (geometry::least_distance(boundary, {rings[j]}) <= kTouch_m) return true;
  }
  return false;
}

// The repaired pieces of an outline that touch at a point (a bowtie's crossing, a ring that
// touched itself at a vertex) are planned a millimetre apart, each inset by half of it: the
// decomposition takes rings that share no point (a ring touching itself ended in "bad merge").
constexpr double kTouchingPiecesGap_m = 1e-3;

// Lines and routes keep the clearance: zones grown by it, the outline shrunk by the boundary
// clearance (docs/swath-plan.md).
void planning_rings(SurveyPlan& plan) {
  const SurveyRequest& r = plan.request;
  double boundary_m = r.boundary_clearance_m;
  if (plan.handling != Handling::hull && !plan.extra_pieces.empty()) {
    std::vector<geometry::Ring> pieces{plan.flown_area.outer};
    pieces.insert(pieces.end(), plan.extra_pieces.begin(), plan.extra_pieces.end());
    if (rings_touch(pieces)) boundary_m = std::max(boundary_m, kTouchingPiecesGap_m / 2);
  }
  if (plan.no_fly.empty() && boundary_m == 0) {  // the area itself, as given
    plan.planning_rings = geometry::rings_of(plan.flown_area);
    if (plan.handling != Handling::hull)
      plan.planning_rings.insert(plan.planning_rings.end(), plan.extra_pieces.begin(),
                                 plan.extra_pieces.end());
    return;
  }
  plan.no_fly_grown = geometry::grow_keeping_holes(plan.no_fly, r.clearance_m);
  plan.planning_rings = geometry::subtract(plan.flown_area.outer, boundary_m, plan.no_fly_grown);
  if (plan.handling != Handling::hull)
    for (const geometry::Ring& piece : plan.extra_pieces)
      for (geometry::Ring& ring : geometry::subtract(piece, boundary_m, plan.no_fly_grown))
        plan.planning_rings.push_back(std::move(ring));
  if (plan.planning_rings.empty())
    throw InputError(r.field.source +
                         ": nothing of the area is left to fly once the no-fly zones "
                         "keep " +
                         fixed_text(r.clearance_m, 1) + " m and the boundary " +
                         fixed_text(r.boundary_clearance_m, 1) + " m of clearance",
                     {base::Remedy::lower_clearance});
}

}  // namespace

void area(SurveyPlan& plan) {
  geometry::Field& field = plan.request.field;
  if (!field.frame)
    throw InputError(field.source + ": the area is in local metres", {base::Remedy::origin});
  check_homes(plan.request, field);
  if (plan.request.repair) repair_outer_ring(plan);
  plan.area = field.polygon;
  collect_no_fly(plan);
  refuse_rings_across_antimeridian(plan);
  check_homes_outside_zones(plan);
  plan.facts = geometry::describe_area(plan.area);
  if (zones_need_cutting(plan)) {
    cut_out_zones(plan);
    plan.facts = geometry::describe_area(plan.area);
  }
  for (const geometry::Ring& piece : plan.extra_pieces)
    *plan.facts.area_m2 += geometry::signed_area(piece);
  for (const geometry::Ring& hole : plan.extra_piece_holes)  // clockwise: negative
    *plan.facts.area_m2 -= std::abs(geometry::signed_area(hole));
  check_classification(plan);
  choose_handling(plan);
  planning_rings(plan);
}

}  // namespace swath::planning::steps
