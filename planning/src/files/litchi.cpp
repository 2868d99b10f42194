// Litchi mission CSV (docs/swath-plan.md), written by swath::missions (writers.hpp) from the
// flight's export points.
#include <cmath>
#include <functional>

#include "../steps/leg_within.hpp"
#include "common.hpp"
#include "swath/geometry/offset.hpp"
#include "swath/missions/stopping.hpp"

namespace swath::planning {
namespace {

using geometry::Point2;

// Beyond the clearance, for the writers' rounding and the bow of a long straight leg home (the
// plan splits legs bowing more than this; a part's way home is one leg).
constexpr double kCutMargin_m = 0.5;

// Whether a part of a split flight may end at point i and the next start there. Litchi flies
// each part as a mission of its own (docs/swath-plan.md): it stops at the part's last point and
// flies home straight from it, and flies out to it straight from home, stopping there if it
// turns sharply. Each of those legs, and each stop's overrun along the leg into it, must keep
// the clearance from every no-fly zone and stay inside the inclusion fence, as the plan's check
// asks of the part.
class PartEnds {
 public:
  /// `points` and `local` (the same points in the plan's frame) are kept by reference.
  PartEnds(const SurveyPlan& plan, const Flight& flight,
           const std::vector<missions::ExportPoint>& points, const std::vector<Point2>& local)
      : plan_(plan), flight_(flight), points_(points), local_(local) {}

  bool operator()(std::size_t i) const {
    if (i == 0 || i >= local_.size()) return false;
    const Point2 home = flight_.drone->home, at = local_[i];
    const double into_m_s = points_[i - 1].speed_m_s > 0 ? points_[i - 1].speed_m_s : cruise_m_s();
    return clear(at, home) && clear(at, overrun(local_[i - 1], at, into_m_s)) &&
           clear(at, overrun(home, at, cruise_m_s()));
  }

 private:
  double cruise_m_s() const { return flight_.drone->speed_m_s; }
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
  const SurveyPlan& plan_;
  const Flight& flight_;
  const std::vector<missions::ExportPoint>& points_;
  const std::vector<Point2>& local_;
};

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
  settings.may_end_at = std::cref(ends);
  return missions::write_litchi_csv(points, settings);
}

}  // namespace swath::planning
