// Litchi mission CSV (docs/swath-plan.md), written by swath::missions (writers.hpp) from the
// flight's export points, cut into parts of at most Litchi's 99 waypoints.
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "../steps/leg_within.hpp"
#include "common.hpp"
#include "swath/base/input_error.hpp"
#include "swath/geometry/offset.hpp"
#include "swath/geometry/visibility.hpp"
#include "swath/missions/stopping.hpp"
#include "swath/planning/survey_steps.hpp"

namespace swath::planning {
namespace {

using geometry::Point2;

// Beyond the clearance, for the writers' rounding and the bow of a long straight leg home (the
// plan splits legs bowing more than this; a part's way home is one leg).
constexpr double kCutMargin_m = 0.5;
// A routed way home keeps this much more from the zones and the fence than kCutMargin_m asks: a
// leg along a grown zone's edge would otherwise meet the test below only to the rounding.
constexpr double kWaySlack_m = 0.25;
// Without a fence the routes are planned in a box this much larger than all there is.
constexpr double kOpenBox_m = 100.0;

// Where Litchi flies a part of a split flight (docs/swath-plan.md): each part is a mission of its
// own; Litchi flies from home straight to its first row and back home straight from its last,
// stopping there if it turns sharply. Each of those legs, and each stop's overrun along the leg
// into it, must keep the clearance from every no-fly zone and stay inside the inclusion fence,
// as the plan's check asks of the part. Where the straight way is not clear, the part carries a
// way home around the zones inside the fence (camera off), and the next part the same way back
// out, reversed.
class PartEnds {
 public:
  /// `points` and `local` (the same points in the plan's frame) are kept by reference.
  PartEnds(const SurveyPlan& plan, const Flight& flight,
           const std::vector<missions::ExportPoint>& points, const std::vector<Point2>& local)
      : plan_(plan), flight_(flight), points_(points), local_(local) {}

  /// Whether a part may end at point i with Litchi's straight ways home and back out.
  bool straight(std::size_t i) const { return clear_way(i, {}); }

  /// The points between point i and home of a way home around the zones and inside the fence
  /// that Litchi may fly straight from point to point, and back out reversed; none where no such
  /// way keeps clear.
  std::optional<std::vector<Point2>> routed(std::size_t i) const {
    if (i == 0 || i >= local_.size()) return std::nullopt;
    const std::vector<Point2> path = router().path(local_[i], home());
    std::vector<Point2> way(path.begin() + 1, path.end() - (path.size() > 1 ? 1 : 0));
    if (way.empty() || !clear_way(i, way)) return std::nullopt;
    return way;
  }

  Point2 home() const { return flight_.drone->home; }

 private:
  double cruise_m_s() const { return flight_.drone->speed_m_s; }
  // Whether the way point i -> way... -> home and its reverse keep clear: every leg, the stop at
  // point i coming from the point before it and from the way out, and the stops at the way's
  // bends coming from either side (Litchi stops where its straight lines turn sharply).
  bool clear_way(std::size_t i, const std::vector<Point2>& way) const {
    if (i == 0 || i >= local_.size()) return false;
    std::vector<Point2> all{local_[i]};
    all.insert(all.end(), way.begin(), way.end());
    all.push_back(home());
    const double into_m_s = points_[i - 1].speed_m_s > 0 ? points_[i - 1].speed_m_s : cruise_m_s();
    if (!clear(all[0], overrun(local_[i - 1], all[0], into_m_s))) return false;
    for (std::size_t k = 0; k + 1 < all.size(); ++k) {
      const Point2 a = all[k], b = all[k + 1];
      if (!clear(a, b) || !clear(a, overrun(b, a, cruise_m_s()))) return false;
      if (k + 2 < all.size() && !clear(b, overrun(a, b, cruise_m_s()))) return false;
    }
    return true;
  }
  // Where a stop at `to` coming from `from` at `speed_m_s` may end (the check's stopping margin).
  Point2 overrun(Point2 from, Point2 to, double speed_m_s) const {
    const double length_m = geometry::distance(from, to);
    if (!(length_m > 0)) return to;
    const double run_m = missions::stopping_distance_m(speed_m_s, flight_.drone->accel_m_s2);
    return to + (to - from) * (run_m / length_m);
  }
  bool clear(Point2 a, Point2 b) const {
    if (!plan_.no_fly.empty() &&
        geometry::least_distance({a, b}, plan_.no_fly) < plan_.request.clearance_m + kCutMargin_m)
      return false;
    return plan_.fence.empty() || steps::detail::leg_within(a, b, plan_.fence);
  }
  // The open inside the fence (shrunk by the margin) less the zones grown by the clearance and
  // the margin: made once, when a part first needs a way round.
  const geometry::VisibilityRouter& router() const {
    if (!router_) {
      const double margin_m = kCutMargin_m + kWaySlack_m;
      const std::vector<geometry::Ring> zones =
          plan_.no_fly.empty()
              ? std::vector<geometry::Ring>{}
              : geometry::grow_keeping_holes(plan_.no_fly, plan_.request.clearance_m + margin_m);
      std::vector<geometry::Ring> rings;
      for (const geometry::Ring& outer :
           plan_.fence.empty() ? std::vector<geometry::Ring>{box()} : plan_.fence)
        for (geometry::Ring& r : geometry::subtract(outer, margin_m, zones))
          rings.push_back(std::move(r));
      router_ = std::make_unique<geometry::VisibilityRouter>(
          std::move(rings), geometry::Routing::routed, steps::kCornerAllowance_m);
    }
    return *router_;
  }
  // Counter-clockwise, about the flight, home and the zones.
  geometry::Ring box() const {
    Point2 lo = home(), hi = home();
    const auto grow = [&](Point2 p) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    };
    for (const Point2& p : local_) grow(p);
    for (const geometry::Ring& zone : plan_.no_fly)
      for (const Point2& p : zone) grow(p);
    lo = {lo.x - kOpenBox_m, lo.y - kOpenBox_m};
    hi = {hi.x + kOpenBox_m, hi.y + kOpenBox_m};
    return {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
  }
  const SurveyPlan& plan_;
  const Flight& flight_;
  const std::vector<missions::ExportPoint>& points_;
  const std::vector<Point2>& local_;
  mutable std::unique_ptr<geometry::VisibilityRouter> router_;
};

// Rows of a way home or out: at the altitude of the point it leaves, the flight's speed, the
// camera off, each facing along the leg it starts (the last along the leg it ends).
std::vector<missions::ExportPoint> way_rows(const SurveyPlan& plan,
                                            const missions::ExportPoint& from,
                                            const std::vector<Point2>& way,
                                            const missions::ExportPoint* to) {
  std::vector<missions::ExportPoint> rows;
  for (const Point2& p : way) {
    missions::ExportPoint row;
    row.geo = files::geo(plan, p);
    row.altitude_m = from.altitude_m;
    rows.push_back(row);
  }
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const bool last = k + 1 == rows.size() && to == nullptr;
    const geometry::GeoPoint& next = k + 1 < rows.size() ? rows[k + 1].geo
                                     : to                ? to->geo
                                                         : from.geo;
    rows[k].heading_deg =
        last ? files::bearing_deg(k > 0 ? rows[k - 1].geo : from.geo, rows[k].geo, true)
             : files::bearing_deg(rows[k].geo, next, false);
  }
  return rows;
}

// Where a part ends, and the way home from there (empty: straight).
struct Cut {
  std::size_t end;  ///< one past the part's last point of the flight
  std::vector<Point2> way;
};

[[noreturn]] void refuse(const Flight& flight, std::size_t first, std::size_t last) {
  throw base::InputError(
      "--litchi: " + flight.file_stem + "'s flight cannot be cut into Litchi missions " +
      "of at most " + std::to_string(kLitchiMaxWaypoints) +
      " waypoints: from none of its waypoints " + std::to_string(first + 1) + " to " +
      std::to_string(last + 1) +
      " does a way home round the no-fly zones that keeps clear inside the fence (its legs and "
      "the stops at its bends) fit in the rows left; fewer waypoints (a larger "
      "--waypoint-spacing, or none) or a lower --speed may let it");
}

// The end of the part of at most `rows` rows that begins at point `first`: the last point a
// straight way home keeps clear from, else the last whose routed way home fits in the rows.
Cut cut_after(const PartEnds& ends, const Flight& flight, std::size_t first, std::size_t rows,
              std::size_t count) {
  const std::size_t end = first + std::min(count - first, rows);
  if (end >= count) return {end, {}};
  for (std::size_t last = end - 1; last > first; --last)
    if (ends.straight(last)) return {last + 1, {}};
  for (std::size_t last = end - 1; last > first; --last)
    if (const auto way = ends.routed(last); way && (last - first + 1) + way->size() <= rows)
      return {last + 1, *way};
  refuse(flight, first, end - 1);
}

}  // namespace

std::vector<std::string> litchi_csv(const SurveyPlan& plan, const Flight& flight) {
  missions::LitchiSettings settings;
  settings.max_rows = kLitchiMaxWaypoints;
  settings.gimbal_pitch_deg = plan.request.triggering.gimbal_pitch_deg;
  settings.speed_m_s = flight.drone->speed_m_s;
  settings.trigger = plan.request.triggering.mode;
  settings.trigger_value = files::trigger_value(flight);
  std::vector<Point2> local;
  const std::vector<missions::ExportPoint> points = files::export_points(plan, flight, &local);
  const PartEnds ends(plan, flight, points, local);
  std::vector<std::string> parts;
  // Each part after the first starts at the point the one before ended at (its actions done
  // there), after the way out to it when the one before flew a way home.
  std::vector<missions::ExportPoint> way_out;
  for (std::size_t first = 0;;) {
    if (way_out.size() + 2 > kLitchiMaxWaypoints) refuse(flight, first, first);
    const Cut cut =
        cut_after(ends, flight, first, kLitchiMaxWaypoints - way_out.size(), points.size());
    std::vector<missions::ExportPoint> part = std::move(way_out);
    const std::optional<std::size_t> resumed =
        first > 0 ? std::optional<std::size_t>(part.size()) : std::nullopt;
    part.insert(part.end(), points.begin() + first, points.begin() + cut.end);
    way_out.clear();
    if (!cut.way.empty()) {
      const missions::ExportPoint& last = points[cut.end - 1];
      part.back().photo_leg = false;  // the camera is off on the way home
      part.back().speed_m_s = 0.0;
      part.back().heading_deg =
          files::bearing_deg(last.geo, files::geo(plan, cut.way.front()), false);
      const std::vector<missions::ExportPoint> home = way_rows(plan, last, cut.way, nullptr);
      part.insert(part.end(), home.begin(), home.end());
      way_out = way_rows(plan, last, {cut.way.rbegin(), cut.way.rend()}, &last);
    }
    parts.push_back(missions::write_litchi_part(part, resumed, settings));
    if (cut.end >= points.size()) break;
    first = cut.end - 1;
  }
  return parts;
}

}  // namespace swath::planning
