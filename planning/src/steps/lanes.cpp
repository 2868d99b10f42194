// Step 4 of plan_survey(): the lines (survey_steps.hpp), and the routes the steps share.
#include <algorithm>
#include <cmath>
#include <memory>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/geometry/decomposition.hpp"
#include "swath/geometry/offset.hpp"
#include "swath/planning/split.hpp"
#include "swath/planning/survey_steps.hpp"

namespace swath::planning::steps {
namespace {

using base::InputError;
using geometry::Point2;

// Whether lines are laid in cells inside the planning rings (a concave area, holes, zones, or
// several pieces) rather than by one sweep with the strip rule.
bool in_cells(const SurveyPlan& plan) {
  return plan.handling == Handling::split || plan.planning_rings.size() > 1;
}

geometry::Ring bounding_box(const SurveyPlan& plan) {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  auto grow = [&](Point2 p) {
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  };
  for (const geometry::Ring& r : plan.planning_rings)
    for (const Point2& p : r) grow(p);
  for (const geometry::Ring& r : plan.no_fly_grown)
    for (const Point2& p : r) grow(p);
  grow(plan.home_local);
  if (plan.request.fleet)
    for (const vehicle::Drone& d : plan.request.fleet->drones)
      if (d.home) grow(plan.request.field.frame->to_local(*d.home));
  const double margin = 1000 + std::max(x1 - x0, y1 - y0);
  return {{x0 - margin, y0 - margin},
          {x1 + margin, y0 - margin},
          {x1 + margin, y1 + margin},
          {x0 - margin, y1 + margin}};
}

// How much less than the clearance the open router's zones are grown, metres: line ends lie on
// the clearance band (the planning rings less the grown zones, Boost's difference, then lines
// cut at its edges), some a few micrometres inside it by rounding, where the router counted
// them outside its area and flew the turn straight through the zone (a strip across a field).
constexpr double kOpenSlack_m = 0.005;

// The open: a box around everything with the zones grown by the clearance (less kOpenSlack_m) as
// holes (clockwise), and the pockets zones enclose as islands in them (counter-clockwise: inside
// by the router's odd count).
std::vector<geometry::Ring> open_rings(const SurveyPlan& plan) {
  if (plan.no_fly_grown.empty()) return {};
  std::vector<geometry::Ring> rings{bounding_box(plan)};
  const double grown_m = plan.request.clearance_m - kOpenSlack_m;
  const std::vector<geometry::Ring> zones =
      grown_m > 0 ? geometry::grow_keeping_holes(plan.no_fly, grown_m) : plan.no_fly_grown;
  for (geometry::Ring zone : zones) {
    std::reverse(zone.begin(), zone.end());
    rings.push_back(std::move(zone));
  }
  return rings;
}

std::vector<Point2> between(const std::vector<Point2>& path) {
  if (path.size() <= 2) return {};
  return {path.begin() + 1, path.end() - 1};
}

SweepSettings sweep_settings(const SurveyPlan& plan, double angle_deg) {
  SweepSettings s;
  s.angle_deg = angle_deg;
  s.line_spacing_m = plan.imaging.line_spacing_m;
  s.footprint_width_m = plan.imaging.footprint_across_m;
  s.placement = plan.request.placement;
  s.turnaround_m = plan.turnaround_m;
  return s;
}

SplitSettings split_settings(const SurveyPlan& plan) {
  SplitSettings s;
  s.line_spacing_m = plan.imaging.line_spacing_m;
  s.footprint_width_m = plan.imaging.footprint_across_m;
  s.placement = plan.request.placement;
  s.turnaround_m = plan.turnaround_m;
  s.keep_out_rings = plan.no_fly_grown;
  s.scan_step_deg = plan.request.split_scan_step_deg;
  s.cells = plan.request.split_cells;
  s.threads = plan.request.threads;
  // A direction per region only where the rest of the plan takes lines at several angles: the
  // crosshatch pass (at 90 degrees to the one direction) and region division (lanes cut along one
  // direction) keep one.
  const bool region_division = plan.request.fleet && plan.request.fleet->drones.size() > 1 &&
                               plan.request.division == DivisionMode::region;
  if (!plan.request.crosshatch && !region_division) s.directions = plan.request.split_directions;
  s.seen_rings = geometry::rings_of(plan.area);  // and --repair's further pieces
  s.seen_rings.insert(s.seen_rings.end(), plan.extra_pieces.begin(), plan.extra_pieces.end());
  s.seen_rings.insert(s.seen_rings.end(), plan.extra_piece_holes.begin(),
                      plan.extra_piece_holes.end());
  if (plan.request.outside_margin_m > 0) {  // the outlines grown by the margin, less the zones
    std::vector<geometry::Ring> outlines{plan.flown_area.outer};
    outlines.insert(outlines.end(), plan.extra_pieces.begin(), plan.extra_pieces.end());
    for (const geometry::Ring& grown : geometry::grow(outlines, plan.request.outside_margin_m))
      for (geometry::Ring& ring : geometry::subtract(grown, 0, plan.no_fly_grown))
        s.bridge_rings.push_back(std::move(ring));
  }
  return s;
}

// The limit on the lines laid (direction() refused on an estimate, the area's height over the
// spacing; a concave area takes several lines at one position: a 2,000-vertex star estimated
// below the limit takes 20,589). Split plans count them before laying any (SplitSettings::
// max_lines), at every direction they would try; this checks the lines as laid too.
void check_line_count(const SurveyPlan& plan, std::size_t lines) {
  if (lines <= kMaxSweepLines) return;
  throw InputError(plan.request.field.source + ": the area takes " + std::to_string(lines) +
                   " lines " + base::fixed_text(plan.imaging.line_spacing_m, 3) +
                   " m apart (where it is concave, several at one position), more than swath's "
                   "limit of " +
                   std::to_string(kMaxSweepLines) + "; fly higher or split the area");
}

// The lines of one pass at `angle_deg` (or the searched direction for the first split pass),
// flown from `from`.
std::vector<SweepLine> one_pass(SurveyPlan& plan, const Routes& routes,
                                std::optional<double> angle_deg, Point2 from, bool first) {
  if (in_cells(plan)) {
    SplitSettings s = split_settings(plan);
    if (angle_deg) s.fixed_angle_deg = *angle_deg;
    s.max_lines = kMaxSweepLines;
    s.limit_cross_pass = first && plan.request.crosshatch;
    if (first) s.progress = plan.request.progress;  // the search; the crosshatch pass is fixed
    SplitPlan sp;
    try {
      sp = plan_split(plan.planning_rings, from, s, routes.inside);
    } catch (const LaneLimitExceeded& e) {
      check_line_count(plan, e.lanes());
      throw;  // not reached: e.lanes() is above the limit
    }
    check_line_count(plan, sp.lines.size());
    if (first) {
      plan.direction = {sp.angle_deg, geometry::height_at(plan.area.outer, sp.angle_deg)};
      plan.sweep = {sp.angle_deg, plan.direction.height_m, sp.lines};
      plan.cells = sp.cells;
      plan.sweep_line_cell = sp.line_cell;
      plan.split_method = sp.method;
      plan.direction_candidates = sp.candidates;
      plan.regions = sp.regions;
      plan.region_angles_deg = sp.region_angles_deg;
    }
    return sp.lines;
  }
  const geometry::Polygon flown{plan.planning_rings.front(), {}};
  Sweep sweep =
      plan_sweep(flown, sweep_settings(plan, angle_deg.value_or(plan.direction.angle_deg)));
  keep_turnarounds_out(sweep.lines, plan.turnaround_m, plan.no_fly_grown);
  check_line_count(plan, sweep.lines.size());
  if (first) {
    plan.sweep = sweep;
    plan.cells = {flown.outer};
  }
  return order_lines(sweep, first ? plan.request.start : StartCorner::nearest_home, from);
}

// Fixed-wing (docs/swath-plan.md): where adjacent lines are closer than two turn radii, fly every
// k-th line, then the next class, so that each U-turn is at least 2r wide; each line is entered
// from the end nearer the previous one. Same lines, same coverage.
std::vector<SweepLine> interleave(const std::vector<SweepLine>& lines, double spacing_m,
                                  double turn_radius_m) {
  if (turn_radius_m <= 0 || spacing_m >= 2 * turn_radius_m || lines.size() < 3) return lines;
  const auto k = static_cast<std::size_t>(std::ceil(2 * turn_radius_m / spacing_m - 1e-9));
  std::vector<SweepLine> out;
  for (std::size_t c = 0; c < k; ++c)
    for (std::size_t i = c; i < lines.size(); i += k) {
      SweepLine line = lines[i];
      if (!out.empty() && geometry::distance(out.back().end, line.end) <
                              geometry::distance(out.back().end, line.start))
        std::swap(line.start, line.end);
      out.push_back(line);
    }
  return out;
}

}  // namespace

Routes::Routes(const SurveyPlan& plan)
    : inside(plan.planning_rings,
             in_cells(plan) ? geometry::Routing::routed : geometry::Routing::measure_only,
             kCornerAllowance_m),
      open(open_rings(plan), geometry::Routing::routed, kCornerAllowance_m),
      no_fly_(plan.no_fly),
      turnaround_m_(plan.turnaround_m) {}

const Routes& routes_of(SurveyPlan& plan) {
  if (!plan.routes) plan.routes = std::make_shared<const Routes>(plan);
  return *plan.routes;
}

LegRoute Routes::leg() const {
  return [this](Point2 a, Point2 b) {
    if (inside.routes() && inside.contains(a) && inside.contains(b)) {
      // Both ends inside, but in pieces no inside path joins (a zone across the whole field):
      // the router's straight fallback would cross the zone, so go around it in the open.
      std::vector<Point2> path = inside.path(a, b);
      if (path.size() > 2 || inside.visible(a, b)) return between(path);
    }
    return around(a, b);
  };
}

LegRoute Routes::open_leg() const {
  return [this](Point2 a, Point2 b) { return around(a, b); };
}

std::vector<Point2> Routes::around(Point2 a, Point2 b) const {
  std::vector<Point2> path = open.path(a, b);
  // No way round (an end within a zone's clearance band, or shut in by zones): a straight leg
  // may not enter a zone itself.
  if (path.size() == 2 && !open.visible(a, b) && !no_fly_.empty() &&
      geometry::least_distance({a, b}, no_fly_) <= 0)
    throw InputError("the leg from (" + base::fixed_text(a.x, 1) + ", " + base::fixed_text(a.y, 1) +
                     ") to (" + base::fixed_text(b.x, 1) + ", " + base::fixed_text(b.y, 1) +
                     ") m (east, north of the area's frame) finds no way round the no-fly zones "
                     "and would cross one; move the home or the zones, or lower " +
                     (turnaround_m_ > 0 ? "--turnaround or " : "") + "--clearance");
  return between(path);
}

InsideTest Routes::inside_test() const {
  return [this](Point2 a, Point2 b) { return inside.visible(a, b); };
}

void lanes(SurveyPlan& plan) {
  const Routes& routes = routes_of(plan);
  std::optional<double> fixed;
  if (plan.request.angle_search == AngleSearch::fixed || !in_cells(plan))
    fixed = plan.direction.angle_deg;
  plan.survey_lines = one_pass(plan, routes, fixed, plan.home_local, true);
  plan.survey_lines =
      interleave(plan.survey_lines, plan.imaging.line_spacing_m, plan.turn_radius_m);
  if (plan.request.crosshatch && !plan.survey_lines.empty()) {
    // The second pass at 90°, entered near where the first ended.
    std::vector<SweepLine> cross =
        one_pass(plan, routes, plan.sweep.angle_deg + 90, plan.survey_lines.back().end, false);
    cross = interleave(cross, plan.imaging.line_spacing_m, plan.turn_radius_m);
    plan.survey_lines.insert(plan.survey_lines.end(), cross.begin(), cross.end());
  }
}

}  // namespace swath::planning::steps
