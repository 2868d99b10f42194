// Step 7 of plan_survey(): battery-sized sorties (survey_steps.hpp, docs/swath-plan.md).
#include <algorithm>
#include <cmath>
#include <functional>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/planning/survey_steps.hpp"

namespace swath::planning::steps {
namespace {

using base::fixed_text;
using base::InputError;

// The part of `path` from `from_m` to `to_m` along it, a stub of a line outside the area that a
// cut in its turnaround leaves flown as a transit.
SurveyPath piece_of(const SurveyPath& path, double from_m, double to_m,
                    const std::vector<geometry::Ring>& lined) {
  std::vector<double> cuts;
  if (from_m > 0) cuts.push_back(from_m);
  if (to_m < path.length_m()) cuts.push_back(to_m);
  SurveyPath piece = cut_path(path, cuts)[from_m > 0 ? 1 : 0];
  transit_stubs_outside(piece, lined);
  return piece;
}

// A sortie's cut closer than this to a waypoint of the path is moved onto it (or this far off
// it): the cut is a waypoint of both sorties, and one a few millimetres from another (the
// bisection's millimetre landing beside a line's end) is no leg a DJI or Litchi mission takes
// (0.5 m at least between waypoints) nor any autopilot needs.
constexpr double kCutOffWaypoint_m = 0.6;

// Where along the path each of its points lies, metres, summed as cut_path() sums it (so that a
// cut there lands on the point itself).
std::vector<double> point_distances_m(const SurveyPath& path) {
  std::vector<double> at{0.0};
  double walked = 0;
  for (std::size_t i = 0; i + 1 < path.points.size(); ++i) {
    walked += geometry::distance(path.points[i], path.points[i + 1]);
    at.push_back(walked);
  }
  return at;
}

// The cut at `to_m` (after `from_m`) moved off the path's points nearby: back onto a point
// just before it; forward onto one just after it where the sortie still `fits` to there, else
// back to kCutOffWaypoint_m before that one (onto the point before where the leg is short).
double cut_off_waypoints_m(double from_m, double to_m, const std::vector<double>& at,
                           const std::function<bool(double)>& fits) {
  const auto next = std::upper_bound(at.begin(), at.end(), to_m);
  if (next != at.begin() && to_m - *(next - 1) < kCutOffWaypoint_m && *(next - 1) > from_m)
    return *(next - 1);
  if (next == at.end() || *next - to_m >= kCutOffWaypoint_m) return to_m;
  if (fits(*next)) return *next;
  const double back_m = *next - kCutOffWaypoint_m;
  const double before_m = *(next - 1);
  if (back_m - before_m >= kCutOffWaypoint_m) return back_m;
  return before_m > from_m ? before_m : to_m;
}

// What one sortie may fly: the battery it takes off with (the first the charge the drone has,
// battery_level x endurance; the next a full one) less the reserve and the layers' climb, seconds.
struct SortieTimes {
  double first_s;
  double later_s;
};

SortieTimes usable_times(const SurveyPlan& plan, const DronePlan& d) {
  const double keep = 1 - plan.request.reserve;
  const double room_s = layer_room_s(plan, d);
  return {*d.endurance_s * d.battery_level * keep - room_s, *d.endurance_s * keep - room_s};
}

// Cuts one drone's survey path into sorties that each fit their usable time, exactly at the
// length where the next would not (bisection to a millimetre on the sortie's own flight time,
// which grows with its length: the way home shortens by at most what the line lengthens).
std::vector<Sortie> cut_sorties(const SurveyPlan& plan, const DronePlan& d,
                                const SortieTimes& usable, const Routes& routes,
                                const InsideTest& inside) {
  const MissionSettings settings = mission_settings(plan, d);
  const SurveyPath& path = d.work.path;
  const double total = path.length_m();
  const std::vector<geometry::Ring> lined = lined_rings(plan);
  auto sortie = [&](double from, double to) {
    return mission_for_path(d.number, d.home, piece_of(path, from, to, lined), settings,
                            routes.leg(), inside);
  };
  const std::vector<double> at = point_distances_m(path);
  std::vector<Sortie> out;
  double from = 0;
  while (from < total - 1e-6) {
    const double usable_s = out.empty() ? usable.first_s : usable.later_s;
    double lo = 0, hi = total - from;
    if (sortie(from, total).flight_time_s > usable_s) {
      if (sortie(from, from + std::min(hi, 1e-3)).flight_time_s > usable_s)
        throw InputError("drone " + d.name + " cannot fly to the survey and back within its " +
                         std::string(out.empty() && d.battery_level < 1 ? "charge" : "endurance") +
                         " less the reserve (" + duration_text(usable_s) +
                         "); it cannot fly even one metre of it per sortie");
      while (hi - lo > 1e-3) {
        const double mid = (lo + hi) / 2;
        (sortie(from, from + mid).flight_time_s <= usable_s ? lo : hi) = mid;
      }
    } else {
      lo = total - from;
    }
    double to = from + lo;
    if (lo < total - from)
      to = cut_off_waypoints_m(from, to, at, [&](double end_m) {
        return sortie(from, end_m).flight_time_s <= usable_s;
      });
    Sortie s;
    s.number = static_cast<int>(out.size() + 1);
    s.mission = sortie(from, to);
    s.resume = piece_of(path, from, to, lined).points.front();
    s.photos = planned_photos(s.mission, plan.imaging.trigger_distance_m);
    out.push_back(std::move(s));
    from = to;
    if (out.size() > 1000)
      throw InputError("drone " + d.name +
                       " would need more than 1000 sorties; check its endurance");
  }
  return out;
}

}  // namespace

double layer_room_s(const SurveyPlan& plan, const DronePlan& d) {
  // deconflict(): one layer per other drone at most.
  const double layer_m = static_cast<double>(plan.drones.size() - 1) * plan.request.layer_spacing_m;
  return layer_m * (1 / d.climb_speed_m_s + 1 / d.descent_speed_m_s);
}

void sorties(SurveyPlan& plan) {
  if (!plan.request.sorties) return;
  const Routes& routes = routes_of(plan);
  const InsideTest inside = [&routes](geometry::Point2 a, geometry::Point2 b) {
    return routes.inside.visible(a, b);
  };
  for (DronePlan& d : plan.drones) {
    if (!d.endurance_s)
      throw InputError("cutting flights into sorties needs each drone's endurance; drone " +
                           d.name + " has none",
                       {base::Remedy::endurance});
    const SortieTimes usable = usable_times(plan, d);
    if (d.mission.flight_time_s <= usable.first_s) continue;  // one flight does it
    d.sorties = cut_sorties(plan, d, usable, routes, inside);
  }
}

}  // namespace swath::planning::steps
