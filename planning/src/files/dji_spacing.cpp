// DJI's waypoint spacing for the Litchi and DJI exports (docs/swath-plan.md): DJI's waypoint
// missions, which Litchi flies on, take a waypoint only 0.5 m to 2,000 m (in three dimensions)
// from the one before it (DJIMutableWaypointMission addWaypoint). Points closer than that are
// merged, legs longer are split by points on them.
#include <algorithm>
#include <cmath>

#include "common.hpp"
#include "swath/geometry/local_frame.hpp"

namespace swath::planning::files {
namespace {

using geometry::Point2;

// The longest piece a long leg is cut into: under DJI's 2,000 m by what a distance on a sphere
// may differ from the ellipsoid's geodesic (0.5 %), as kDjiMergeBelow_m allows for.
constexpr double kLongestPiece_m = 1990.0;

double leg_m(const ExportPoint& a, const ExportPoint& b) {
  return std::hypot(geometry::geodesic_distance_m(a.geo, b.geo), b.altitude_m - a.altitude_m);
}

// A leg's speed as flown: 0 is the flight's own.
double flown_m_s(double speed_m_s, double cruise_m_s) {
  return speed_m_s > 0 ? speed_m_s : cruise_m_s;
}

// The slower of two leg speeds, 0 (the flight's own) where that is the slower or both are it.
double slower_m_s(double a_m_s, double b_m_s, double cruise_m_s) {
  return flown_m_s(a_m_s, cruise_m_s) <= flown_m_s(b_m_s, cruise_m_s) ? a_m_s : b_m_s;
}

// Point b merged into the kept point a before it (closer than DJI's least spacing). The merged
// point stands where the stop is: at a, unless only b holds or shoots. It flies b's leg onwards
// (b's photos and speed: the leg a->b it drops is under half a metre and starts or ends at rest
// or on a line, so what it set is not needed past it); standing at b, the leg into it takes the
// slower of the speeds into a and on to b, so that the approach to the stop is no faster than the
// .plan's (its overrun as the check allows).
void merge_into(std::vector<ExportPoint>& kept, std::vector<Point2>& kept_local,
                const ExportPoint& b, Point2 b_local, double cruise_m_s) {
  ExportPoint& a = kept.back();
  const bool at_b = (b.hold_s > 0 || b.shot) && !(a.hold_s > 0 || a.shot);
  ExportPoint merged = b;
  merged.hold_s = std::max(a.hold_s, b.hold_s);
  merged.shot = a.shot || b.shot;
  if (!at_b) {
    merged.geo = a.geo;
    merged.altitude_m = a.altitude_m;
  } else {
    kept_local.back() = b_local;
    if (kept.size() > 1) {
      ExportPoint& before = kept[kept.size() - 2];
      before.speed_m_s = slower_m_s(before.speed_m_s, a.speed_m_s, cruise_m_s);
    }
  }
  a = merged;
}

// The points that split the leg a->b (local positions la, lb) into pieces of at most
// kLongestPiece_m, flying it as a does: its photos and speed, no hold, no photo of their own (a
// is a copy: it is an element of `out`).
void split_leg(const SurveyPlan& plan, const ExportPoint a, Point2 la, const ExportPoint& b,
               Point2 lb, std::vector<ExportPoint>& out, std::vector<Point2>& out_local) {
  const double length_m = leg_m(a, b);
  const auto pieces = static_cast<int>(std::ceil(length_m / kLongestPiece_m));
  for (int k = 1; k < pieces; ++k) {
    const double t = static_cast<double>(k) / pieces;
    const Point2 p = la + (lb - la) * t;
    ExportPoint mid = a;
    mid.geo = geo(plan, p);
    mid.altitude_m = a.altitude_m + (b.altitude_m - a.altitude_m) * t;
    mid.hold_s = 0.0;
    mid.shot = false;
    out.push_back(mid);
    out_local.push_back(p);
  }
}

}  // namespace

void fit_dji_spacing(const SurveyPlan& plan, double cruise_m_s, std::vector<ExportPoint>& points,
                     std::vector<Point2>& local) {
  std::vector<ExportPoint> kept;
  std::vector<Point2> kept_local;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!kept.empty() && leg_m(kept.back(), points[i]) < kDjiMergeBelow_m) {
      merge_into(kept, kept_local, points[i], local[i], cruise_m_s);
      // A merged point moved to b may now stand as close to the one before it.
      while (kept.size() > 1 && leg_m(kept[kept.size() - 2], kept.back()) < kDjiMergeBelow_m) {
        const ExportPoint b = kept.back();
        const Point2 b_local = kept_local.back();
        kept.pop_back();
        kept_local.pop_back();
        merge_into(kept, kept_local, b, b_local, cruise_m_s);
      }
      continue;
    }
    if (!kept.empty() && leg_m(kept.back(), points[i]) > kLongestPiece_m)
      split_leg(plan, kept.back(), kept_local.back(), points[i], local[i], kept, kept_local);
    kept.push_back(points[i]);
    kept_local.push_back(local[i]);
  }
  points = std::move(kept);
  local = std::move(kept_local);
}

}  // namespace swath::planning::files
